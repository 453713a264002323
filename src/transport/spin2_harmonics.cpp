#include "transport/spin2_harmonics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "base/quadrature.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

namespace {

// d^l_{m1,m2}(theta) = sum_k c_k cos(theta / 2)^(2l + m2 - m1 - 2k) sin(theta / 2)^(m1 - m2 + 2k),
// c_k = (-1)^(m1 - m2 + k) sqrt((l + m1)! (l - m1)! (l + m2)! (l - m2)!) /
//       ((l + m2 - k)! k! (m1 - m2 + k)! (l - m1 - k)!), k from max(0, m2 - m1) to min(l + m2, l - m1).
struct Term {
  double c;
  int cos_power, sin_power;
};

double factorial(int n) {
  double f = 1.0;
  for (int i = 2; i <= n; ++i) f *= i;
  return f;
}

std::vector<Term> wigner_terms(int l, int m1, int m2) {
  std::vector<Term> terms;
  const double root = std::sqrt(factorial(l + m1) * factorial(l - m1) * factorial(l + m2) * factorial(l - m2));
  for (int k = std::max(0, m2 - m1); k <= std::min(l + m2, l - m1); ++k) {
    const double sign = ((m1 - m2 + k) % 2 == 0) ? 1.0 : -1.0;
    const double c =
        sign * root / (factorial(l + m2 - k) * factorial(k) * factorial(m1 - m2 + k) * factorial(l - m1 - k));
    terms.push_back({c, 2 * l + m2 - m1 - 2 * k, m1 - m2 + 2 * k});
  }
  return terms;
}

double sum_terms(const std::vector<Term>& terms, const double* cos_powers, const double* sin_powers) {
  double d = 0.0;
  for (const Term& t : terms)
    d += t.c * cos_powers[static_cast<size_t>(t.cos_power)] * sin_powers[static_cast<size_t>(t.sin_power)];
  return d;
}

// cos(theta / 2)^j and sin(theta / 2)^j for j = 0..2 kMaxSpin2Degree.
struct HalfAnglePowers {
  double c[2 * kMaxSpin2Degree + 1], s[2 * kMaxSpin2Degree + 1];
  explicit HalfAnglePowers(double mu) {
    const double x = std::clamp(mu, -1.0, 1.0);
    const double ch = std::sqrt(0.5 * (1.0 + x)), sh = std::sqrt(0.5 * (1.0 - x));
    c[0] = s[0] = 1.0;
    for (int j = 1; j <= 2 * kMaxSpin2Degree; ++j) {
      c[j] = c[j - 1] * ch;
      s[j] = s[j - 1] * sh;
    }
  }
};

// The harmonics' theta parts lambda_lm = sqrt((2l + 1) / (4 pi)) d^l_{m,-2}, as Wigner sums, at
// spin2_harmonic_index(l, m); computed once.
struct Spin2Terms {
  std::vector<std::vector<Term>> lambda;
  Spin2Terms() : lambda(static_cast<size_t>(spin2_harmonic_count(kMaxSpin2Degree))) {
    for (int l = 2; l <= kMaxSpin2Degree; ++l)
      for (int m = -l; m <= l; ++m) {
        std::vector<Term> t = wigner_terms(l, m, -2);
        for (Term& term : t) term.c *= std::sqrt((2.0 * l + 1.0) / (4.0 * kPi));
        lambda[static_cast<size_t>(spin2_harmonic_index(l, m))] = std::move(t);
      }
  }
};
const Spin2Terms& spin2_terms() {
  static const Spin2Terms t;
  return t;
}

void check_degree(int l, const char* what) {
  if (l < 0 || l > kMaxSpin2Degree)
    throw std::invalid_argument(std::string(what) + ": degree " + std::to_string(l) + " is outside 0-" +
                                std::to_string(kMaxSpin2Degree));
}

}  // namespace

double wigner_d(int l, int m1, int m2, double mu) {
  check_degree(l, "wigner_d");
  if (std::abs(m1) > l || std::abs(m2) > l) return 0.0;
  const HalfAnglePowers p(mu);
  return sum_terms(wigner_terms(l, m1, m2), p.c, p.s);
}

void spin2_harmonics(int degree, double mu, double cos_phi, double sin_phi, double* q, double* u) {
  check_degree(degree, "spin2_harmonics");
  const Spin2Terms& terms = spin2_terms();
  const HalfAnglePowers p(mu);
  // cos(m phi), sin(m phi) for m = 0..degree by the angle-sum recurrence.
  double cm[kMaxSpin2Degree + 1], sm[kMaxSpin2Degree + 1];
  cm[0] = 1.0;
  sm[0] = 0.0;
  for (int m = 1; m <= degree; ++m) {
    cm[m] = cm[m - 1] * cos_phi - sm[m - 1] * sin_phi;
    sm[m] = sm[m - 1] * cos_phi + cm[m - 1] * sin_phi;
  }
  for (int l = 2; l <= degree; ++l)
    for (int m = -l; m <= l; ++m) {
      const int i = spin2_harmonic_index(l, m);
      const double lambda = sum_terms(terms.lambda[static_cast<size_t>(i)], p.c, p.s);
      const int a = std::abs(m);
      q[i] = lambda * cm[a];
      u[i] = lambda * (m < 0 ? -sm[a] : sm[a]);
    }
}

std::vector<double> spin2_moments(const std::function<double(double)>& phase, int degree, int nodes) {
  check_degree(degree, "spin2_moments");
  std::vector<double> mu, w;
  gauss_legendre(nodes, -1.0, 1.0, mu, w);
  std::vector<std::vector<Term>> d22(static_cast<size_t>(degree + 1));
  for (int l = 2; l <= degree; ++l) d22[static_cast<size_t>(l)] = wigner_terms(l, 2, 2);
  std::vector<double> beta(static_cast<size_t>(degree + 1), 0.0);
  for (size_t k = 0; k < mu.size(); ++k) {
    const HalfAnglePowers p(mu[k]);
    const double pw = w[k] * phase(mu[k]);
    for (int l = 2; l <= degree; ++l)
      beta[static_cast<size_t>(l)] += pw * sum_terms(d22[static_cast<size_t>(l)], p.c, p.s);
  }
  for (double& b : beta) b *= 2.0 * kPi;
  return beta;
}

std::vector<double> piecewise_linear_spin_moments(const std::vector<double>& mu, const std::vector<double>& values,
                                                  int degree, int m1, int m2) {
  check_degree(degree, "piecewise_linear_spin_moments");
  if (mu.size() != values.size() || mu.size() < 2)
    throw std::invalid_argument("piecewise_linear_spin_moments: need as many values as cosines, two or more");
  for (size_t k = 0; k + 1 < mu.size(); ++k)
    if (!(mu[k + 1] > mu[k])) throw std::invalid_argument("piecewise_linear_spin_moments: the cosines must ascend");
  std::vector<std::vector<Term>> d(static_cast<size_t>(degree + 1));
  for (int l = std::max(std::abs(m1), std::abs(m2)); l <= degree; ++l)
    d[static_cast<size_t>(l)] = wigner_terms(l, m1, m2);
  // d^l_{m1,m2} is a polynomial of degree l in mu when m1 and m2 are even; times a linear function,
  // degree + 1 at most: (degree + 2) / 2 + 1 Gauss-Legendre nodes per interval are exact.
  std::vector<double> x, w;
  gauss_legendre((degree + 2) / 2 + 1, 0.0, 1.0, x, w);
  std::vector<double> moments(static_cast<size_t>(degree + 1), 0.0);
  for (size_t k = 0; k + 1 < mu.size(); ++k) {
    const double width = mu[k + 1] - mu[k];
    for (size_t j = 0; j < x.size(); ++j) {
      const double m = mu[k] + x[j] * width;
      const double f = values[k] + x[j] * (values[k + 1] - values[k]);
      const HalfAnglePowers p(m);
      for (int l = 0; l <= degree; ++l)
        if (!d[static_cast<size_t>(l)].empty())
          moments[static_cast<size_t>(l)] += w[j] * width * f * sum_terms(d[static_cast<size_t>(l)], p.c, p.s);
    }
  }
  for (double& v : moments) v *= 2.0 * kPi;
  return moments;
}

}  // namespace skyspec
