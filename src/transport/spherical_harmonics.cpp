#include "transport/spherical_harmonics.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
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

std::vector<double> piecewise_linear_legendre_moments(const std::vector<double>& mu, const std::vector<double>& values,
                                                      int degree) {
  std::vector<double> x, w, chi(static_cast<size_t>(degree) + 1, 0.0);
  gauss_legendre(degree / 2 + 2, 0.0, 1.0, x, w);  // on [0, 1], mapped to each interval
  for (size_t k = 0; k + 1 < mu.size(); ++k) {
    const double a = mu[k], b = mu[k + 1], h = b - a;
    for (size_t q = 0; q < x.size(); ++q) {
      const double m = a + h * x[q];
      const double f = 2.0 * kPi * h * w[q] * (values[k] + (values[k + 1] - values[k]) * x[q]);
      chi[0] += f;
      if (degree >= 1) chi[1] += f * m;
      double p0 = 1.0, p1 = m;
      for (int l = 2; l <= degree; ++l) {
        const double pl = ((2.0 * l - 1.0) * m * p1 - (l - 1.0) * p0) / l;
        chi[static_cast<size_t>(l)] += f * pl;
        p0 = p1;
        p1 = pl;
      }
    }
  }
  return chi;
}

double skyline_hidden_share(double gamma, double theta) {
  if (theta <= gamma) return 1.0;
  if (theta >= kPi - gamma) return 0.0;
  return 1.0 - std::acos(std::clamp(std::tan(gamma) / std::tan(theta), -1.0, 1.0)) / kPi;
}

namespace {
// The scattering angles both skyline integrals are summed over (Gauss-Legendre over each step of
// [0, pi]) and, per node and skyline, the hidden share f_gamma and sin(phi_0): the same for every
// phase function, so computed once per layout (the last one asked for is kept).
struct SkylineNodes {
  int count = 0, nodes_per_step = 0;
  double step_rad = 0.0;
  std::vector<double> theta, weight;
  std::vector<double> share, sin_phi0;  // [node * count + skyline]
};

std::shared_ptr<const SkylineNodes> skyline_nodes(int count, double step_rad, int nodes_per_step) {
  static std::mutex mutex;
  static std::shared_ptr<const SkylineNodes> last;
  std::lock_guard<std::mutex> lock(mutex);
  if (last && last->count == count && last->step_rad == step_rad && last->nodes_per_step == nodes_per_step) return last;
  auto g = std::make_shared<SkylineNodes>();
  g->count = count;
  g->step_rad = step_rad;
  g->nodes_per_step = nodes_per_step;
  std::vector<double> x, w;
  gauss_legendre(nodes_per_step, 0.0, step_rad, x, w);
  const int steps = static_cast<int>(std::lround(kPi / step_rad));
  for (int k = 0; k < steps; ++k)
    for (size_t i = 0; i < x.size(); ++i) {
      const double theta = k * step_rad + x[i];
      g->theta.push_back(theta);
      g->weight.push_back(w[i]);
      for (int j = 0; j < count; ++j) {
        const double gamma = j * step_rad;
        g->share.push_back(skyline_hidden_share(gamma, theta));
        const bool between = theta > gamma && theta < kPi - gamma;
        const double c = between ? std::clamp(std::tan(gamma) / std::tan(theta), -1.0, 1.0) : 1.0;
        g->sin_phi0.push_back(std::sqrt(1.0 - c * c));
      }
    }
  last = g;
  return g;
}
}  // namespace

namespace {
// Both skyline integrals over the nodes of skyline_nodes: the moments below the skyline
// (gradient = false: 2 pi w sin(theta) p P_l, weighted by the hidden share) or their first-order
// correction (gradient = true: -4 / (l (l + 1)) w sin^2(theta) p P_l', weighted by sin(phi_0)).
std::vector<double> skyline_moments(const std::function<double(double)>& phase, int degree, int count, double step_rad,
                                    int nodes_per_step, bool gradient) {
  const size_t stride = static_cast<size_t>(degree) + 1;
  std::vector<double> out(static_cast<size_t>(std::max(count, 0)) * stride, 0.0);
  const auto g = skyline_nodes(count, step_rad, nodes_per_step);
  std::vector<double> term(stride);
  for (size_t node = 0; node < g->theta.size(); ++node) {
    const double theta = g->theta[node], mu = std::cos(theta), sin_theta = std::sin(theta);
    const double f = g->weight[node] * sin_theta * phase(mu) * (gradient ? sin_theta : 2.0 * kPi);
    // P_l by its recurrence and P_l' = P_{l-2}' + (2 l - 1) P_{l-1}, from P_0 = 1, P_1 = mu.
    double p_prev = 1.0, p_cur = mu, dp_prev = 0.0, dp_cur = 1.0;
    term[0] = gradient ? 0.0 : f;
    if (degree >= 1) term[1] = gradient ? -2.0 * f : f * mu;
    for (int l = 2; l <= degree; ++l) {
      const double dp = dp_prev + (2.0 * l - 1.0) * p_cur;
      const double p = ((2.0 * l - 1.0) * mu * p_cur - (l - 1.0) * p_prev) / l;
      term[static_cast<size_t>(l)] = gradient ? -4.0 / (l * (l + 1.0)) * f * dp : f * p;
      dp_prev = dp_cur;
      dp_cur = dp;
      p_prev = p_cur;
      p_cur = p;
    }
    const double* weight = &(gradient ? g->sin_phi0 : g->share)[node * static_cast<size_t>(count)];
    for (int j = 0; j < count; ++j) {
      if (weight[j] == 0.0) continue;
      double* chi = &out[static_cast<size_t>(j) * stride];
      for (size_t l = 0; l < stride; ++l) chi[l] += weight[j] * term[l];
    }
  }
  return out;
}
}  // namespace

std::vector<double> skyline_legendre_moments(const std::function<double(double)>& phase, int degree, int count,
                                             double step_rad, int nodes_per_step) {
  return skyline_moments(phase, degree, count, step_rad, nodes_per_step, false);
}

std::vector<double> skyline_gradient_moments(const std::function<double(double)>& phase, int degree, int count,
                                             double step_rad, int nodes_per_step) {
  return skyline_moments(phase, degree, count, step_rad, nodes_per_step, true);
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
