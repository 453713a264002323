#include "transport/spherical_harmonics.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "base/quadrature.hpp"
#include "skyspec/units.hpp"
#include "transport/multiple_scattering.hpp"

namespace skyspec {

namespace {
constexpr int kMaxDegree = kMaxHarmonicDegree;
// Per (l, m) at harmonic_index(l, m), computed once: K_lm (x sqrt 2 for m > 0), and the
// coefficients of the recurrence in l, P_l^m = alpha_lm x P_{l-1}^m - beta_lm P_{l-2}^m with
// alpha_lm = (2l - 1) / (l - m), beta_lm = (l + m - 1) / (l - m) (l > m + 1; for l = m + 1,
// alpha = 2m + 1 and beta = 0).
struct Coefficients {
  std::vector<double> k, alpha, beta;
};
const Coefficients& coefficients() {
  static const Coefficients c = [] {
    Coefficients v;
    const size_t n = static_cast<size_t>(harmonic_count(kMaxDegree));
    v.k.resize(n);
    v.alpha.assign(n, 0.0);
    v.beta.assign(n, 0.0);
    for (int l = 0; l <= kMaxDegree; ++l)
      for (int m = 0; m <= l; ++m) {
        double ratio = 1.0;  // (l - m)! / (l + m)!
        for (int j = l - m + 1; j <= l + m; ++j) ratio /= j;
        const size_t i = static_cast<size_t>(harmonic_index(l, m));
        v.k[i] = std::sqrt((2.0 * l + 1.0) / (4.0 * kPi) * ratio) * (m > 0 ? std::sqrt(2.0) : 1.0);
        if (l == m + 1) {
          v.alpha[i] = 2.0 * m + 1.0;
        } else if (l > m + 1) {
          v.alpha[i] = (2.0 * l - 1.0) / (l - m);
          v.beta[i] = (l + m - 1.0) / (l - m);
        }
      }
    return v;
  }();
  return c;
}
}  // namespace

void symmetric_harmonics(int degree, double mu, double cos_phi, double* out) {
  const Coefficients& co = coefficients();
  const double x = std::clamp(mu, -1.0, 1.0), s = std::sqrt(std::max(0.0, 1.0 - x * x));
  const double c = std::clamp(cos_phi, -1.0, 1.0);
  double cos_m_prev = 1.0, cos_m = 1.0;  // cos((m - 1) phi), cos(m phi) by Chebyshev's recurrence
  double pmm = 1.0;                      // P_m^m = (2m - 1)!! s^m
  for (int m = 0; m <= degree; ++m) {
    if (m == 1) {
      cos_m = c;
    } else if (m > 1) {
      const double next = 2.0 * c * cos_m - cos_m_prev;
      cos_m_prev = cos_m;
      cos_m = next;
    }
    if (m > 0) pmm *= (2.0 * m - 1.0) * s;
    // P_l^m for l = m .. degree by the three-term recurrence in l.
    double p_prev = 0.0, p = pmm;
    for (int l = m; l <= degree; ++l) {
      const int i = harmonic_index(l, m);
      if (l > m) {
        const double next = co.alpha[static_cast<size_t>(i)] * x * p - co.beta[static_cast<size_t>(i)] * p_prev;
        p_prev = p;
        p = next;
      }
      out[i] = co.k[static_cast<size_t>(i)] * p * cos_m;
    }
  }
}

std::vector<double> legendre_moments(const std::function<double(double)>& phase, int degree, int nodes) {
  // The nodes of the usual count once (every wavelength of every table asks for them).
  static const std::pair<std::vector<double>, std::vector<double>> usual = [] {
    std::pair<std::vector<double>, std::vector<double>> p;
    gauss_legendre(512, -1.0, 1.0, p.first, p.second);
    return p;
  }();
  std::vector<double> x, w, chi(static_cast<size_t>(degree) + 1, 0.0);
  if (nodes == 512) {
    x = usual.first;
    w = usual.second;
  } else {
    gauss_legendre(nodes, -1.0, 1.0, x, w);
  }
  for (size_t i = 0; i < x.size(); ++i) {
    const double f = 2.0 * kPi * w[i] * phase(x[i]);
    chi[0] += f;
    if (degree >= 1) chi[1] += f * x[i];
    double p0 = 1.0, p1 = x[i];  // P_{l-2}, P_{l-1}
    for (int l = 2; l <= degree; ++l) {
      const double pl = ((2.0 * l - 1.0) * x[i] * p1 - (l - 1.0) * p0) / l;
      chi[static_cast<size_t>(l)] += f * pl;
      p0 = p1;
      p1 = pl;
    }
  }
  return chi;
}

double skyline_hidden_share(double gamma, double theta) {
  if (theta <= gamma) return 1.0;
  if (theta >= kPi - gamma) return 0.0;
  return 1.0 - std::acos(std::clamp(std::tan(gamma) / std::tan(theta), -1.0, 1.0)) / kPi;
}

std::vector<double> skyline_legendre_moments(const std::function<double(double)>& phase, int degree, int count,
                                             double step_rad, int nodes_per_step) {
  const size_t stride = static_cast<size_t>(degree) + 1;
  std::vector<double> out(static_cast<size_t>(std::max(count, 0)) * stride, 0.0);
  std::vector<double> x, w;
  gauss_legendre(nodes_per_step, 0.0, step_rad, x, w);
  const int steps = static_cast<int>(std::lround(kPi / step_rad));
  std::vector<double> pl(stride);
  for (int k = 0; k < steps; ++k) {
    for (size_t i = 0; i < x.size(); ++i) {
      // p P_l sin(theta) at this node once, then its share under each skyline.
      const double theta = k * step_rad + x[i], mu = std::cos(theta);
      const double f = 2.0 * kPi * w[i] * std::sin(theta) * phase(mu);
      pl[0] = f;
      if (degree >= 1) pl[1] = f * mu;
      double p0 = 1.0, p1 = mu;  // P_{l-2}, P_{l-1}
      for (int l = 2; l <= degree; ++l) {
        const double p = ((2.0 * l - 1.0) * mu * p1 - (l - 1.0) * p0) / l;
        pl[static_cast<size_t>(l)] = f * p;
        p0 = p1;
        p1 = p;
      }
      for (int j = 0; j < count; ++j) {
        const double share = skyline_hidden_share(j * step_rad, theta);
        if (share == 0.0) continue;
        double* chi = &out[static_cast<size_t>(j) * stride];
        for (size_t l = 0; l < stride; ++l) chi[l] += share * pl[l];
      }
    }
  }
  return out;
}

const std::array<Eigen::Matrix3d, 3>& quadrupole_tensors() {
  // Gauss-Legendre in mu and the midpoint rule in phi, both exact for these polynomials of degree 4.
  static const std::array<Eigen::Matrix3d, 3> k = [] {
    std::array<Eigen::Matrix3d, 3> t;
    for (auto& m : t) m.setZero();
    std::vector<double> mus, weights;
    gauss_legendre(8, -1.0, 1.0, mus, weights);
    constexpr int kAzimuths = 16;
    double y[harmonic_count(2)];
    for (size_t i = 0; i < mus.size(); ++i)
      for (int j = 0; j < kAzimuths; ++j) {
        const double mu = mus[i], phi = 2.0 * kPi * (j + 0.5) / kAzimuths, s = std::sqrt(1.0 - mu * mu);
        const Eigen::Vector3d w(s * std::cos(phi), s * std::sin(phi), mu);
        symmetric_harmonics(2, mu, std::cos(phi), y);
        for (int m = 0; m <= 2; ++m)
          t[static_cast<size_t>(m)] +=
              weights[i] * (2.0 * kPi / kAzimuths) * y[harmonic_index(2, m)] * (w * w.transpose());
      }
    return t;
  }();
  return k;
}

}  // namespace skyspec
