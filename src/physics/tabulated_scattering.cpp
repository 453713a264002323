#include "skyspec/tabulated_scattering.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>

#include "skyspec/units.hpp"

namespace skyspec {

TabulatedScatteringMatrix::TabulatedScatteringMatrix(std::vector<double> mu, std::vector<std::vector<double>> a1,
                                                     std::vector<std::vector<double>> b1,
                                                     std::vector<std::vector<double>> a3,
                                                     std::vector<std::vector<double>> b2)
    : mu_(std::move(mu)), a1_(std::move(a1)), b1_(std::move(b1)), a3_(std::move(a3)), b2_(std::move(b2)) {
  const size_t n = mu_.size();
  if (n < 2 || mu_.front() != -1.0 || mu_.back() != 1.0)
    throw std::invalid_argument("tabulated scattering matrix: the cosines must run from -1 to 1");
  for (size_t k = 1; k < n; ++k)
    if (!(mu_[k] > mu_[k - 1])) throw std::invalid_argument("tabulated scattering matrix: cosines not increasing");
  if (b1_.size() != a1_.size() || a3_.size() != a1_.size() || b2_.size() != a1_.size() || a1_.empty())
    throw std::invalid_argument("tabulated scattering matrix: one row of each element per wavelength");
  cdf_.resize(a1_.size());
  g_.resize(a1_.size());
  for (size_t i = 0; i < a1_.size(); ++i) {
    for (const auto* row : {&a1_[i], &b1_[i], &a3_[i], &b2_[i]}) {
      if (row->size() != n)
        throw std::invalid_argument("tabulated scattering matrix: a row's length is not the cosines'");
      for (double v : *row)
        if (!std::isfinite(v)) throw std::invalid_argument("tabulated scattering matrix: a value is not finite");
    }
    // The trapezoidal rule is exact for the piecewise-linear a1; so is its first moment's rule
    // integral of (p_k (1 - t) + p_k+1 t) mu dmu over an interval, mu linear in t.
    std::vector<double>& c = cdf_[i];
    c.assign(n, 0.0);
    double g = 0.0;
    for (size_t k = 0; k + 1 < n; ++k) {
      const double h = mu_[k + 1] - mu_[k], p0 = a1_[i][k], p1 = a1_[i][k + 1];
      if (p0 < 0.0 || p1 < 0.0) throw std::invalid_argument("tabulated scattering matrix: a negative phase function");
      c[k + 1] = c[k] + 0.5 * h * (p0 + p1);
      g += h * (p0 * (2.0 * mu_[k] + mu_[k + 1]) + p1 * (mu_[k] + 2.0 * mu_[k + 1])) / 6.0;
    }
    const double total = c.back();
    if (!(total > 0.0)) throw std::invalid_argument("tabulated scattering matrix: a phase function that is zero");
    const double scale = 1.0 / (2.0 * kPi * total);
    for (auto* row : {&a1_[i], &b1_[i], &a3_[i], &b2_[i]})
      for (double& v : *row) v *= scale;
    for (double& v : c) v /= total;
    c.back() = 1.0;
    g_[i] = g / total;
  }
  // The rows by node, and their integrals by the trapezoidal rule again (on the normalised rows).
  const size_t w = a1_.size();
  for (auto [rows, by_node, integrals] :
       {std::tuple{&a1_, &a1_by_node_, &a1_integral_}, std::tuple{&b1_, &b1_by_node_, &b1_integral_}}) {
    by_node->assign(n * w, 0.0);
    integrals->assign(n * w, 0.0);
    for (size_t i = 0; i < w; ++i)
      for (size_t k = 0; k < n; ++k) {
        (*by_node)[k * w + i] = (*rows)[i][k];
        if (k > 0)
          (*integrals)[k * w + i] =
              (*integrals)[(k - 1) * w + i] + 0.5 * (mu_[k] - mu_[k - 1]) * ((*rows)[i][k - 1] + (*rows)[i][k]);
      }
  }
}

// On [mu_k, mu_k+1] an element is r_k + (r_k+1 - r_k) t with t = (mu - mu_k) / h: its integral from
// -1 to mu_k + t h is I_k + h t (r_k + t (r_k+1 - r_k) / 2).
void TabulatedScatteringMatrix::add_means(const std::vector<double>& by_node, const std::vector<double>& integrals,
                                          Position lo, Position hi, double weight, float* out) const {
  const size_t w = a1_.size();
  const double width = cosine(hi) - cosine(lo);
  const double* r_lo = by_node.data() + static_cast<size_t>(lo.k) * w;
  if (!(width > 1e-12)) {
    for (size_t i = 0; i < w; ++i) out[i] += static_cast<float>(weight * (r_lo[i] * (1.0 - lo.w) + r_lo[i + w] * lo.w));
    return;
  }
  const double* r_hi = by_node.data() + static_cast<size_t>(hi.k) * w;
  const double* i_lo = integrals.data() + static_cast<size_t>(lo.k) * w;
  const double* i_hi = integrals.data() + static_cast<size_t>(hi.k) * w;
  const double h_lo = (mu_[static_cast<size_t>(lo.k) + 1] - mu_[static_cast<size_t>(lo.k)]) * lo.w,
               h_hi = (mu_[static_cast<size_t>(hi.k) + 1] - mu_[static_cast<size_t>(hi.k)]) * hi.w;
  const double s = weight / width, half_lo = 0.5 * lo.w, half_hi = 0.5 * hi.w;
  for (size_t i = 0; i < w; ++i) {
    const double below_hi = i_hi[i] + h_hi * (r_hi[i] + half_hi * (r_hi[i + w] - r_hi[i]));
    const double below_lo = i_lo[i] + h_lo * (r_lo[i] + half_lo * (r_lo[i + w] - r_lo[i]));
    out[i] += static_cast<float>(s * (below_hi - below_lo));
  }
}

TabulatedScatteringMatrix::Position TabulatedScatteringMatrix::locate(double mu) const {
  mu = std::clamp(mu, -1.0, 1.0);
  const auto it = std::upper_bound(mu_.begin(), mu_.end(), mu);
  int k = static_cast<int>(it - mu_.begin()) - 1;
  k = std::clamp(k, 0, static_cast<int>(mu_.size()) - 2);
  const double w = (mu - mu_[static_cast<size_t>(k)]) / (mu_[static_cast<size_t>(k) + 1] - mu_[static_cast<size_t>(k)]);
  return {k, std::clamp(w, 0.0, 1.0)};
}

SphereMatrixElements TabulatedScatteringMatrix::elements(int i, double mu) const {
  const Position p = locate(mu);
  const size_t s = static_cast<size_t>(i);
  return {lerp(a1_[s], p), lerp(b1_[s], p), lerp(a3_[s], p), lerp(b2_[s], p)};
}

double TabulatedScatteringMatrix::sample_mu(int i, double u) const {
  const std::vector<double>& c = cdf_[static_cast<size_t>(i)];
  const std::vector<double>& p = a1_[static_cast<size_t>(i)];
  const auto it = std::upper_bound(c.begin(), c.end(), u);
  size_t k =
      static_cast<size_t>(std::clamp<long>(static_cast<long>(it - c.begin()) - 1, 0, static_cast<long>(c.size()) - 2));
  while (k + 2 < c.size() && c[k + 1] <= c[k]) ++k;  // skip intervals of zero probability
  // On [mu_k, mu_k+1] the density is p_k + s t (t = mu - mu_k, s the slope); the probability
  // below mu_k + t is c_k + 2 pi (p_k t + s t^2 / 2), solved for t (the root that stays finite
  // as s -> 0).
  const double h = mu_[k + 1] - mu_[k], s = (p[k + 1] - p[k]) / h;
  const double target = std::max(0.0, (u - c[k]) / (2.0 * kPi));
  const double disc = std::max(0.0, p[k] * p[k] + 2.0 * s * target);
  const double denom = p[k] + std::sqrt(disc);
  const double t = denom > 0.0 ? 2.0 * target / denom : h * (u - c[k]) / std::max(c[k + 1] - c[k], 1e-300);
  return std::clamp(mu_[k] + std::clamp(t, 0.0, h), -1.0, 1.0);
}

TruncatedScatteringMatrix truncate_forward_peak(const TabulatedScatteringMatrix& m, double cone_rad) {
  if (!(cone_rad > 0.0 && cone_rad < kPi))
    throw std::invalid_argument("forward-peak truncation: the cone must be between 0 and pi radians");
  const double mu_c = std::cos(cone_rad);
  const std::vector<double>& mu = m.mu();
  const TabulatedScatteringMatrix::Position edge = m.locate(mu_c);
  // The new cosines: the old ones up to the edge, the edge itself (unless it is a node), the old
  // ones after it.
  const size_t inside = static_cast<size_t>(edge.k) + 1;  // nodes at or below the edge's interval start
  std::vector<double> cut_mu(mu.begin(), mu.begin() + static_cast<long>(inside));
  if (cut_mu.back() < mu_c) cut_mu.push_back(mu_c);
  const size_t edge_node = cut_mu.size() - 1;
  cut_mu.insert(cut_mu.end(), std::upper_bound(mu.begin(), mu.end(), mu_c), mu.end());
  if (cut_mu.back() != 1.0) cut_mu.push_back(1.0);
  TruncatedScatteringMatrix out;
  const int n = m.wavelengths();
  std::vector<std::vector<double>> a1(n), b1(n), a3(n), b2(n);
  out.removed.resize(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const size_t w = static_cast<size_t>(i);
    for (const double c : cut_mu) {
      const SphereMatrixElements e = m.elements(i, c);
      a1[w].push_back(e.a1);
      b1[w].push_back(e.b1);
      a3[w].push_back(e.a3);
      b2[w].push_back(e.b2);
    }
    const double a1_edge = a1[w][edge_node];
    for (size_t k = edge_node + 1; k < cut_mu.size(); ++k) {
      const double ratio = a1[w][k] > 0.0 ? a1_edge / a1[w][k] : 0.0;
      a1[w][k] = a1_edge;
      b1[w][k] *= ratio;
      a3[w][k] *= ratio;
      b2[w][k] *= ratio;
    }
    // What is left of the normalised phase function's integral (trapezoidal: exact for the
    // piecewise-linear interpolant).
    double kept = 0.0;
    for (size_t k = 0; k + 1 < cut_mu.size(); ++k)
      kept += 0.5 * (cut_mu[k + 1] - cut_mu[k]) * (a1[w][k] + a1[w][k + 1]);
    out.removed[w] = std::clamp(1.0 - 2.0 * kPi * kept, 0.0, 1.0 - 1e-12);
  }
  out.matrix = std::make_shared<const TabulatedScatteringMatrix>(std::move(cut_mu), std::move(a1), std::move(b1),
                                                                 std::move(a3), std::move(b2));
  return out;
}

}  // namespace skyspec
