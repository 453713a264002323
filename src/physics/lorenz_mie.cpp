#include "skyspec/lorenz_mie.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace skyspec {

namespace {
using complex = std::complex<double>;

// psi_n-1(z) / psi_n(z) = J_n-1/2(z) / J_n+1/2(z) for a complex z, from the continued fraction of
// the Bessel functions' ratio, r_nu = 2 nu / z - 1 / r_nu+1 (nu = n + 1/2), evaluated by the
// modified Lentz method (Lentz 1976; Thompson & Barnett 1986, J. Comput. Phys. 64, 490):
// f = b_0 - 1 / (b_1 - 1 / (b_2 - ...)), b_j = 2 (nu + j) / z.
complex bessel_ratio(int n, complex z) {
  constexpr double kTiny = 1e-300, kTolerance = 1e-15;
  const double nu = n + 0.5;
  const complex two_over_z = 2.0 / z;
  complex f = nu * two_over_z;
  if (f == 0.0) f = kTiny;
  complex c = f, d = 0.0;
  for (int j = 1; j < 10'000'000; ++j) {
    const complex b = (nu + j) * two_over_z;
    d = b - d;
    if (d == 0.0) d = kTiny;
    c = b - 1.0 / c;
    if (c == 0.0) c = kTiny;
    d = 1.0 / d;
    const complex delta = c * d;
    f *= delta;
    if (std::abs(delta - 1.0) < kTolerance) return f;
  }
  throw std::runtime_error("Lorenz-Mie: the continued fraction of D_n did not converge");
}

// D_n(z) = psi_n'(z) / psi_n(z) for n = 0 .. count (index n), downward from the exact value at
// n = count: D_n-1 = n/z - 1 / (D_n + n/z).
std::vector<complex> log_derivatives(complex z, int count) {
  std::vector<complex> d(static_cast<size_t>(count) + 1);
  d[static_cast<size_t>(count)] = bessel_ratio(count, z) - static_cast<double>(count) / z;
  for (int n = count; n >= 1; --n) {
    const complex n_over_z = static_cast<double>(n) / z;
    d[static_cast<size_t>(n) - 1] = n_over_z - 1.0 / (d[static_cast<size_t>(n)] + n_over_z);
  }
  return d;
}

void check_size_parameter(double x) {
  if (!(x > 0.0) || !(x <= kMaxMieSizeParameter))
    throw std::invalid_argument("Lorenz-Mie: size parameter " + std::to_string(x) + " outside (0, 2e4]");
}

// The Riccati-Bessel functions psi_n(x) and chi_n(x) for n = 1 .. N by upward recurrence
// f_n = (2n - 1)/x f_n-1 - f_n-2 from psi_0 = sin x, psi_-1 = cos x, chi_0 = cos x, chi_-1 = -sin x;
// `visit(n, psi_n, psi_n-1, xi_n, xi_n-1)` with xi_n = psi_n - i chi_n.
template <class Visit>
void riccati_bessel(double x, int terms, Visit visit) {
  double psi_prev = std::cos(x), psi = std::sin(x);
  double chi_prev = -std::sin(x), chi = std::cos(x);
  for (int n = 1; n <= terms; ++n) {
    const double f = (2.0 * n - 1.0) / x;
    const double psi_next = f * psi - psi_prev, chi_next = f * chi - chi_prev;
    visit(n, psi_next, psi, complex(psi_next, -chi_next), complex(psi, -chi));
    psi_prev = psi;
    psi = psi_next;
    chi_prev = chi;
    chi = chi_next;
  }
}
}  // namespace

int mie_term_count(double x) {
  const double cube_root = std::cbrt(x);
  if (x <= 8.0) return std::max(1, static_cast<int>(x + 4.0 * cube_root + 1.0));
  if (x < 4200.0) return static_cast<int>(x + 4.05 * cube_root + 2.0);
  return static_cast<int>(x + 4.0 * cube_root + 2.0);
}

MieSeries lorenz_mie(complex m, double x) {
  check_size_parameter(x);
  if (!(m.real() > 0.0) || !(m.imag() >= 0.0) || !std::isfinite(std::abs(m)))
    throw std::invalid_argument("Lorenz-Mie: refractive index (" + std::to_string(m.real()) + ", " +
                                std::to_string(m.imag()) + ") needs real > 0 and imaginary >= 0");
  MieSeries s;
  s.size_parameter = x;
  const int terms = mie_term_count(x);
  s.a.resize(static_cast<size_t>(terms));
  s.b.resize(static_cast<size_t>(terms));
  const std::vector<complex> d = log_derivatives(m * x, terms);
  riccati_bessel(x, terms, [&](int n, double psi, double psi_prev, complex xi, complex xi_prev) {
    const complex dn = d[static_cast<size_t>(n)];
    const double n_over_x = n / x;
    const complex ta = dn / m + n_over_x, tb = m * dn + n_over_x;
    s.a[static_cast<size_t>(n) - 1] = (ta * psi - psi_prev) / (ta * xi - xi_prev);
    s.b[static_cast<size_t>(n) - 1] = (tb * psi - psi_prev) / (tb * xi - xi_prev);
  });
  return s;
}

MieSeries lorenz_mie_conducting(double x) {
  check_size_parameter(x);
  MieSeries s;
  s.size_parameter = x;
  const int terms = mie_term_count(x);
  s.a.resize(static_cast<size_t>(terms));
  s.b.resize(static_cast<size_t>(terms));
  // psi_n' = psi_n-1 - n psi_n / x, and the same for xi_n.
  riccati_bessel(x, terms, [&](int n, double psi, double psi_prev, complex xi, complex xi_prev) {
    const double n_over_x = n / x;
    s.a[static_cast<size_t>(n) - 1] = (psi_prev - n_over_x * psi) / (xi_prev - n_over_x * xi);
    s.b[static_cast<size_t>(n) - 1] = psi / xi;
  });
  return s;
}

MieEfficiencies mie_efficiencies(const MieSeries& s) {
  MieEfficiencies q;
  const double x = s.size_parameter;
  double ext = 0.0, sca = 0.0, g = 0.0;
  complex back = 0.0;
  for (int n = 1; n <= s.terms(); ++n) {
    const complex a = s.a[static_cast<size_t>(n) - 1], b = s.b[static_cast<size_t>(n) - 1];
    const double w = 2.0 * n + 1.0;
    ext += w * (a.real() + b.real());
    sca += w * (std::norm(a) + std::norm(b));
    back += (n % 2 == 0 ? w : -w) * (a - b);
    g += w / (n * (n + 1.0)) * (a * std::conj(b)).real();
    if (n < s.terms()) {
      const complex a1 = s.a[static_cast<size_t>(n)], b1 = s.b[static_cast<size_t>(n)];
      g += n * (n + 2.0) / (n + 1.0) * (a * std::conj(a1) + b * std::conj(b1)).real();
    }
  }
  q.extinction = 2.0 / (x * x) * ext;
  q.scattering = 2.0 / (x * x) * sca;
  q.backscatter = std::norm(back) / (x * x);
  q.asymmetry = q.scattering > 0.0 ? 4.0 / (x * x) * g / q.scattering : 0.0;
  return q;
}

namespace {
// Adds term n of S1 and S2 at count angles and steps pi_n to pi_n+1 there (pi_0 = 0, pi_1 = 1,
// pi_n+1 = ((2n+1) mu pi_n - (n+1) pi_n-1) / n, tau_n = n mu pi_n - (n+1) pi_n-1). The weights
// (2n+1)/(n(n+1)) are in a and b. Angles are the inner loop, plain arrays, so that it vectorises.
void add_term(int n, std::complex<double> a, std::complex<double> b, int count, const double* __restrict mu,
              double* __restrict pi_prev, double* __restrict pi, double* __restrict s1_re, double* __restrict s1_im,
              double* __restrict s2_re, double* __restrict s2_im) {
  const double ar = a.real(), ai = a.imag(), br = b.real(), bi = b.imag();
  const double nn = n, n1 = n + 1.0, inv_n = 1.0 / n, two_n1 = 2.0 * n + 1.0;
  for (int j = 0; j < count; ++j) {
    const double p = pi[j], pp = pi_prev[j], c = mu[j];
    const double tau = nn * c * p - n1 * pp;
    s1_re[j] += ar * p + br * tau;
    s1_im[j] += ai * p + bi * tau;
    s2_re[j] += ar * tau + br * p;
    s2_im[j] += ai * tau + bi * p;
    pi_prev[j] = p;
    pi[j] = (two_n1 * c * p - n1 * pp) * inv_n;
  }
}
}  // namespace

std::vector<MieAmplitudes> mie_amplitudes(const MieSeries& s, const std::vector<double>& mu) {
  const int count = static_cast<int>(mu.size());
  std::vector<double> pi_prev(mu.size(), 0.0), pi(mu.size(), 1.0), s1_re(mu.size(), 0.0), s1_im(mu.size(), 0.0),
      s2_re(mu.size(), 0.0), s2_im(mu.size(), 0.0);
  for (int n = 1; n <= s.terms(); ++n) {
    const double w = (2.0 * n + 1.0) / (n * (n + 1.0));
    add_term(n, w * s.a[static_cast<size_t>(n) - 1], w * s.b[static_cast<size_t>(n) - 1], count, mu.data(),
             pi_prev.data(), pi.data(), s1_re.data(), s1_im.data(), s2_re.data(), s2_im.data());
  }
  std::vector<MieAmplitudes> out(mu.size());
  for (size_t j = 0; j < mu.size(); ++j) out[j] = {{s1_re[j], s1_im[j]}, {s2_re[j], s2_im[j]}};
  return out;
}

SphereScatteringMatrix sphere_scattering_matrix(const MieAmplitudes& s) {
  SphereScatteringMatrix m;
  const double i1 = std::norm(s.s1), i2 = std::norm(s.s2);
  const complex cross = s.s2 * std::conj(s.s1);
  m.s11 = 0.5 * (i2 + i1);
  m.s12 = 0.5 * (i2 - i1);
  m.s33 = cross.real();
  m.s34 = cross.imag();
  return m;
}

}  // namespace skyspec
