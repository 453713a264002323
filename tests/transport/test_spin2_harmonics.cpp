// The spin-2 harmonics of the tables' polarised fields: Wigner's functions against closed forms,
// orthonormal, the degree-2 E and B modes of a constant tensor at degree 2 alone, and a sphere's
// matrix on a smooth field (the unit matrix carrying each arriving polarisation along the great
// circle, the mirrored alpha_- term, b1 from intensity to polarisation and back) against
// brute-force integrals over the sphere. Those, some hundred thousand rotations each, run in the
// release stage only (release_stage.hpp).

#include <boost/test/unit_test.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "base/quadrature.hpp"
#include "release_stage.hpp"
#include "skyspec/phase_function.hpp"
#include "skyspec/units.hpp"
#include "transport/spherical_harmonics.hpp"
#include "transport/spin2_harmonics.hpp"

BOOST_AUTO_TEST_SUITE(test_spin2_harmonics)

using namespace skyspec;

namespace {

using V3 = Eigen::Vector3d;
using M3 = Eigen::Matrix3d;

struct Frame {
  V3 w, e_theta, e_phi;
  double mu, cos_phi, sin_phi;
};
Frame frame_of(double mu, double phi) {
  const double s = std::sqrt(std::max(0.0, 1.0 - mu * mu)), c = std::cos(phi), n = std::sin(phi);
  return {V3(s * c, s * n, mu), V3(mu * c, mu * n, -s), V3(-n, c, 0.0), mu, c, n};
}

// Q and U relative to (e_theta, e_phi) of a polarisation tensor C (transverse to w): Q = a^T C a -
// b^T C b, U = 2 a^T C b.
void stokes_of(const M3& c, const Frame& f, double& q, double& u) {
  q = f.e_theta.dot(c * f.e_theta) - f.e_phi.dot(c * f.e_phi);
  u = 2.0 * f.e_theta.dot(c * f.e_phi);
}

// Projects a field (Q, U as functions of the frame) on the harmonics up to `degree`.
template <class Field>
std::vector<double> project(const Field& field, int degree, int n_mu = 48, int n_phi = 96) {
  const int n = spin2_harmonic_count(degree);
  std::vector<double> mu, w, c(static_cast<size_t>(n), 0.0), bq(static_cast<size_t>(n)), bu(static_cast<size_t>(n));
  gauss_legendre(n_mu, -1.0, 1.0, mu, w);
  for (size_t i = 0; i < mu.size(); ++i)
    for (int j = 0; j < n_phi; ++j) {
      const Frame f = frame_of(mu[i], (j + 0.5) * 2.0 * kPi / n_phi);
      double q = 0, u = 0;
      field(f, q, u);
      spin2_harmonics(degree, f.mu, f.cos_phi, f.sin_phi, bq.data(), bu.data());
      const double weight = w[i] * 2.0 * kPi / n_phi;
      for (int k = 0; k < n; ++k)
        c[static_cast<size_t>(k)] += weight * (q * bq[static_cast<size_t>(k)] + u * bu[static_cast<size_t>(k)]);
    }
  return c;
}

// A smooth polarised field of every degree: exp(1.5 w . a) times the degree-2 E mode of a constant
// tensor symmetric about the x-z plane.
M3 smooth_tensor_field(const Frame& f) {
  M3 m;
  m << 0.5, 0.0, 0.4, 0.0, 0.1, 0.0, 0.4, 0.0, -0.6;
  const V3 a(0.6, 0.0, 0.8);
  const M3 p = M3::Identity() - f.w * f.w.transpose();
  const M3 t = p * m * p;
  return std::exp(1.5 * f.w.dot(a)) * (t - 0.5 * t.trace() * p);
}

// 2 pi int f d^l_{m1,m2} for f linear between 2001 even cosines: close to f's own moments.
template <class Function>
std::vector<double> tabulated_moments(const Function& f, int degree, int m1, int m2) {
  std::vector<double> mu(2001), values(mu.size());
  for (size_t k = 0; k < mu.size(); ++k) {
    mu[k] = -1.0 + 2.0 * static_cast<double>(k) / static_cast<double>(mu.size() - 1);
    values[k] = f(mu[k]);
  }
  return piecewise_linear_spin_moments(mu, values, degree, m1, m2);
}

}  // namespace

BOOST_AUTO_TEST_CASE(wigner_functions_match_closed_forms) {
  for (double mu : {-0.9, -0.3, 0.0, 0.4, 0.95}) {
    const double s = std::sqrt(1.0 - mu * mu);
    BOOST_TEST(wigner_d(2, 2, 2, mu) == (1.0 + mu) * (1.0 + mu) / 4.0, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(wigner_d(2, 2, -2, mu) == (1.0 - mu) * (1.0 - mu) / 4.0, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(wigner_d(1, 1, 0, mu) == -s / std::sqrt(2.0), boost::test_tools::tolerance(1e-12));
    BOOST_TEST(wigner_d(2, 0, 0, mu) == 0.5 * (3.0 * mu * mu - 1.0), boost::test_tools::tolerance(1e-12));
    BOOST_TEST(wigner_d(3, 2, 2, mu) == (1.0 + mu) * (1.0 + mu) / 4.0 * (3.0 * mu - 2.0),
               boost::test_tools::tolerance(1e-12));
  }
}

BOOST_AUTO_TEST_CASE(harmonics_are_orthonormal) {
  const int degree = kMaxSpin2Degree, n = spin2_harmonic_count(degree), n_phi = 40;
  std::vector<double> mu, w, q(static_cast<size_t>(n)), u(static_cast<size_t>(n));
  gauss_legendre(24, -1.0, 1.0, mu, w);
  std::vector<double> gram(static_cast<size_t>(n * n), 0.0);
  for (size_t i = 0; i < mu.size(); ++i)
    for (int j = 0; j < n_phi; ++j) {
      const double phi = (j + 0.5) * 2.0 * kPi / n_phi;
      spin2_harmonics(degree, mu[i], std::cos(phi), std::sin(phi), q.data(), u.data());
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b)
          gram[static_cast<size_t>(a * n + b)] += w[i] * 2.0 * kPi / n_phi *
                                                  (q[static_cast<size_t>(a)] * q[static_cast<size_t>(b)] +
                                                   u[static_cast<size_t>(a)] * u[static_cast<size_t>(b)]);
    }
  double worst = 0.0;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) worst = std::max(worst, std::abs(gram[static_cast<size_t>(a * n + b)] - (a == b)));
  BOOST_TEST(worst < 1e-10);
}

// A constant traceless tensor M seen across the sky (C(w) = P M P less its trace) is the
// polarisation's degree-2 E mode (what Rayleigh scattering of the sun makes), and turned by 45
// degrees its B mode: both lie at l = 2 alone. This fixes the spin's sign (with P = Q + i U
// relative to (e_theta, e_phi) the field is sY_lm with d^l_{m,-2}).
BOOST_AUTO_TEST_CASE(constant_tensors_are_degree_two) {
  M3 even;  // symmetric about the x-z plane: no xy, yz
  even << 0.7, 0.0, 0.3, 0.0, -0.2, 0.0, 0.3, 0.0, -0.5;
  M3 odd;  // only xy and yz: its 45-degree turn is symmetric
  odd << 0.0, 0.4, 0.0, 0.4, 0.0, -0.6, 0.0, -0.6, 0.0;
  const auto e_mode = [&](const Frame& f, double& q, double& u) { stokes_of(even, f, q, u); };
  const auto b_mode = [&](const Frame& f, double& q, double& u) {
    double q0 = 0, u0 = 0;
    stokes_of(odd, f, q0, u0);
    q = -u0;
    u = q0;
  };
  for (int mode = 0; mode < 2; ++mode) {
    const std::vector<double> c = mode == 0 ? project(e_mode, 6) : project(b_mode, 6);
    double inside = 0.0, outside = 0.0;
    for (int l = 2; l <= 6; ++l)
      for (int m = -l; m <= l; ++m)
        (l == 2 ? inside : outside) +=
            c[static_cast<size_t>(spin2_harmonic_index(l, m))] * c[static_cast<size_t>(spin2_harmonic_index(l, m))];
    BOOST_TEST_MESSAGE("mode " << mode << ": power at l = 2 " << inside << ", above " << outside);
    BOOST_TEST(inside > 0.1);
    BOOST_TEST(outside < 1e-20);
  }
}

namespace {
// A field's Q, U at three directions by brute force over the sphere (tensor(w', w) is what the light
// from w' adds at w, its weight included) against the harmonics' sum (expected(frame)).
template <class Brute, class Expected>
void check_against_brute_force(const Brute& contribution, const Expected& expected) {
  std::vector<double> mu, w;
  gauss_legendre(128, -1.0, 1.0, mu, w);
  const int n_phi = 256;
  double worst = 0.0, largest = 0.0;
  for (const auto& [mu_out, phi_out] : std::vector<std::pair<double, double>>{{0.8, 0.3}, {0.1, 1.9}, {-0.5, 2.8}}) {
    const Frame fo = frame_of(mu_out, phi_out);
    M3 sum = M3::Zero();
    for (size_t i = 0; i < mu.size(); ++i)
      for (int j = 0; j < n_phi; ++j) {
        const Frame fi = frame_of(mu[i], (j + 0.5) * 2.0 * kPi / n_phi);
        if (fi.w.cross(fo.w).norm() < 1e-12) continue;
        sum += w[i] * 2.0 * kPi / n_phi * contribution(fi, fo);
      }
    double q_brute = 0, u_brute = 0, q = 0, u = 0;
    stokes_of(sum, fo, q_brute, u_brute);
    expected(fo, q, u);
    BOOST_TEST_MESSAGE("mu " << mu_out << ": Q " << q << " (brute force " << q_brute << "), U " << u << " (" << u_brute
                             << ")");
    worst = std::max({worst, std::abs(q - q_brute), std::abs(u - u_brute)});
    largest = std::max({largest, std::abs(q_brute), std::abs(u_brute)});
  }
  BOOST_TEST(largest > 0.01);
  BOOST_TEST(worst < 2e-3 * largest);
}
}  // namespace

// A smooth polarised field of every degree, f(w) times a degree-2 E mode, scattered by a
// Henyey-Greenstein particle with the unit matrix: the brute-force integral over the sphere of
// p(w . w') R C(w') R^T (R the rotation about w' x w that takes w' to w) against
// sum_l beta_l c_lm of the field's harmonics.
BOOST_AUTO_TEST_CASE(unit_matrix_scales_each_degree_by_its_moment,
                     *boost::unit_test::precondition(test::not_in_sanitizer_stage)) {
  const double g = 0.6;
  const auto tensor_field = smooth_tensor_field;
  const auto field = [&](const Frame& f, double& q, double& u) { stokes_of(tensor_field(f), f, q, u); };
  const int degree = kMaxSpin2Degree, n = spin2_harmonic_count(degree);
  const std::vector<double> c = project(field, degree, 64, 128);
  const std::vector<double> beta = spin2_moments([&](double mu) { return henyey_greenstein_phase(mu, g); }, degree);
  // beta_2 and beta_3 from Henyey-Greenstein's moments <mu> = g, <mu^2> = (1 + 2 g^2) / 3,
  // <mu^3> = (3 g + 2 g^3) / 5 (its Legendre moments g^l): d^2_22 = (1 + mu)^2 / 4,
  // d^3_22 = (1 + mu)^2 (3 mu - 2) / 4.
  const double m1 = g, m2 = (1.0 + 2.0 * g * g) / 3.0, m3 = (3.0 * g + 2.0 * g * g * g) / 5.0;
  BOOST_TEST(beta[2] == (1.0 + 2.0 * m1 + m2) / 4.0, boost::test_tools::tolerance(1e-10));
  BOOST_TEST(beta[3] == (3.0 * m3 + 4.0 * m2 - m1 - 2.0) / 4.0, boost::test_tools::tolerance(1e-10));

  check_against_brute_force(
      [&](const Frame& fi, const Frame& fo) -> M3 {
        const V3 axis = fi.w.cross(fo.w).normalized();
        const double cos_t = std::clamp(fi.w.dot(fo.w), -1.0, 1.0);
        const M3 r = Eigen::AngleAxisd(std::acos(cos_t), axis).toRotationMatrix();
        return henyey_greenstein_phase(cos_t, g) * (r * tensor_field(fi) * r.transpose());
      },
      [&](const Frame& fo, double& q, double& u) {
        std::vector<double> bq(static_cast<size_t>(n)), bu(static_cast<size_t>(n));
        spin2_harmonics(degree, fo.mu, fo.cos_phi, fo.sin_phi, bq.data(), bu.data());
        for (int l = 2; l <= degree; ++l)
          for (int mm = -l; mm <= l; ++mm) {
            const size_t k = static_cast<size_t>(spin2_harmonic_index(l, mm));
            q += beta[static_cast<size_t>(l)] * c[k] * bq[k];
            u += beta[static_cast<size_t>(l)] * c[k] * bu[k];
          }
      });
}

// The sphere's alpha_- term: the arriving polarisation mirrored in the scattering plane (U -> -U
// there), carried to w and weighted by alpha_-(mu): c_l,-m -> (-1)^m beta-_l c_lm.
BOOST_AUTO_TEST_CASE(mirrored_polarisation_maps_m_to_minus_m,
                     *boost::unit_test::precondition(test::not_in_sanitizer_stage)) {
  const auto alpha = [](double mu) { return (0.3 + 0.5 * mu - 0.4 * mu * mu * mu) / (4.0 * kPi); };
  const auto tensor_field = smooth_tensor_field;
  const int degree = kMaxSpin2Degree, n = spin2_harmonic_count(degree);
  const std::vector<double> c =
      project([&](const Frame& f, double& q, double& u) { stokes_of(tensor_field(f), f, q, u); }, degree, 64, 128);
  const std::vector<double> beta = tabulated_moments(alpha, degree, 2, -2);
  check_against_brute_force(
      [&](const Frame& fi, const Frame& fo) -> M3 {
        const V3 axis = fi.w.cross(fo.w).normalized();
        const double cos_t = std::clamp(fi.w.dot(fo.w), -1.0, 1.0);
        const M3 r = Eigen::AngleAxisd(std::acos(cos_t), axis).toRotationMatrix();
        const M3 mirror = M3::Identity() - 2.0 * axis * axis.transpose();
        return alpha(cos_t) * (r * mirror * tensor_field(fi) * mirror * r.transpose());
      },
      [&](const Frame& fo, double& q, double& u) {
        std::vector<double> bq(static_cast<size_t>(n)), bu(static_cast<size_t>(n));
        spin2_harmonics(degree, fo.mu, fo.cos_phi, fo.sin_phi, bq.data(), bu.data());
        for (int l = 2; l <= degree; ++l)
          for (int mm = -l; mm <= l; ++mm) {
            const double sign = mm % 2 == 0 ? 1.0 : -1.0;
            const double coefficient =
                sign * beta[static_cast<size_t>(l)] * c[static_cast<size_t>(spin2_harmonic_index(l, mm))];
            q += coefficient * bq[static_cast<size_t>(spin2_harmonic_index(l, -mm))];
            u += coefficient * bu[static_cast<size_t>(spin2_harmonic_index(l, -mm))];
          }
      });
}

// The sphere's b1 term: unpolarised light from w' polarised relative to the scattering plane,
// Q = b1(mu) I (e_par, the plane's direction perpendicular to w, against its normal): from the
// field's real harmonics a_lm, c_l0 = gamma_l a_l0, c_l,+-m = ((-1)^m or 1) gamma_l a_lm / sqrt 2.
BOOST_AUTO_TEST_CASE(b1_polarises_the_intensity_harmonics,
                     *boost::unit_test::precondition(test::not_in_sanitizer_stage)) {
  const auto b1 = [](double mu) { return -0.2 * (1.0 - mu * mu) * (1.0 + 0.6 * mu) / (4.0 * kPi); };
  const V3 a = V3(0.6, 0.0, 0.8);
  const auto intensity = [&](const Frame& f) { return std::exp(1.5 * f.w.dot(a)); };
  const int degree = kMaxSpin2Degree, n = spin2_harmonic_count(degree), nc = harmonic_count(degree);
  // The intensity's real harmonics.
  std::vector<double> coefficients(static_cast<size_t>(nc), 0.0), y(static_cast<size_t>(nc)), mu, w;
  gauss_legendre(64, -1.0, 1.0, mu, w);
  for (size_t i = 0; i < mu.size(); ++i)
    for (int j = 0; j < 128; ++j) {
      const Frame f = frame_of(mu[i], (j + 0.5) * 2.0 * kPi / 128);
      symmetric_harmonics(degree, f.mu, f.cos_phi, y.data());
      for (int k = 0; k < nc; ++k)
        coefficients[static_cast<size_t>(k)] += w[i] * 2.0 * kPi / 128 * intensity(f) * y[static_cast<size_t>(k)];
    }
  const std::vector<double> gamma = tabulated_moments(b1, degree, 2, 0);
  check_against_brute_force(
      [&](const Frame& fi, const Frame& fo) -> M3 {
        const double cos_t = std::clamp(fi.w.dot(fo.w), -1.0, 1.0);
        const V3 e_par = (fi.w - cos_t * fo.w).normalized(), normal = fo.w.cross(e_par);
        return 0.5 * b1(cos_t) * intensity(fi) * (e_par * e_par.transpose() - normal * normal.transpose());
      },
      [&](const Frame& fo, double& q, double& u) {
        std::vector<double> bq(static_cast<size_t>(n)), bu(static_cast<size_t>(n));
        spin2_harmonics(degree, fo.mu, fo.cos_phi, fo.sin_phi, bq.data(), bu.data());
        for (int l = 2; l <= degree; ++l)
          for (int mm = 0; mm <= l; ++mm) {
            const double g = gamma[static_cast<size_t>(l)] * coefficients[static_cast<size_t>(harmonic_index(l, mm))];
            if (mm == 0) {
              q += g * bq[static_cast<size_t>(spin2_harmonic_index(l, 0))];
              u += g * bu[static_cast<size_t>(spin2_harmonic_index(l, 0))];
              continue;
            }
            const double sign = mm % 2 == 0 ? 1.0 : -1.0;
            const size_t plus = static_cast<size_t>(spin2_harmonic_index(l, mm)),
                         minus = static_cast<size_t>(spin2_harmonic_index(l, -mm));
            q += g / std::sqrt(2.0) * (sign * bq[plus] + bq[minus]);
            u += g / std::sqrt(2.0) * (sign * bu[plus] + bu[minus]);
          }
      });
}

// And back: polarised light from w' adds b1(mu) Q' to the intensity scattered to w (Q' relative
// to the scattering plane at w'): the transpose of the b1 term, a_l0 = gamma_l c_l0 and
// a_lm = gamma_l ((-1)^m c_lm + c_l,-m) / sqrt 2 (SourceTable's polarising share).
BOOST_AUTO_TEST_CASE(b1_turns_the_polarisation_into_intensity,
                     *boost::unit_test::precondition(test::not_in_sanitizer_stage)) {
  const auto b1 = [](double mu) { return -0.2 * (1.0 - mu * mu) * (1.0 + 0.6 * mu) / (4.0 * kPi); };
  const auto tensor_field = smooth_tensor_field;
  const int degree = kMaxSpin2Degree, nc = harmonic_count(degree);
  const std::vector<double> c =
      project([&](const Frame& f, double& q, double& u) { stokes_of(tensor_field(f), f, q, u); }, degree, 64, 128);
  const std::vector<double> gamma = tabulated_moments(b1, degree, 2, 0);
  std::vector<double> mu, w, y(static_cast<size_t>(nc));
  gauss_legendre(128, -1.0, 1.0, mu, w);
  const int n_phi = 256;
  double worst = 0.0, largest = 0.0;
  for (const auto& [mu_out, phi_out] : std::vector<std::pair<double, double>>{{0.8, 0.3}, {0.1, 1.9}, {-0.5, 2.8}}) {
    const Frame fo = frame_of(mu_out, phi_out);
    double brute = 0.0;
    for (size_t i = 0; i < mu.size(); ++i)
      for (int j = 0; j < n_phi; ++j) {
        const Frame fi = frame_of(mu[i], (j + 0.5) * 2.0 * kPi / n_phi);
        const double cos_t = std::clamp(fi.w.dot(fo.w), -1.0, 1.0);
        const V3 along = fo.w - cos_t * fi.w;
        if (along.norm() < 1e-12) continue;
        const V3 e_par = along.normalized(), normal = fi.w.cross(e_par);
        const M3 t = tensor_field(fi);
        brute += w[i] * 2.0 * kPi / n_phi * b1(cos_t) * (e_par.dot(t * e_par) - normal.dot(t * normal));
      }
    symmetric_harmonics(degree, fo.mu, fo.cos_phi, y.data());
    double sum = 0.0;
    for (int l = 2; l <= degree; ++l)
      for (int mm = -l; mm <= l; ++mm) {
        const int am = std::abs(mm);
        const double weight = mm == 0 ? 1.0 : ((mm > 0 && am % 2 == 1) ? -1.0 : 1.0) / std::sqrt(2.0);
        sum += gamma[static_cast<size_t>(l)] * weight * c[static_cast<size_t>(spin2_harmonic_index(l, mm))] *
               y[static_cast<size_t>(harmonic_index(l, am))];
      }
    BOOST_TEST_MESSAGE("mu " << mu_out << ": I " << sum << " (brute force " << brute << ")");
    worst = std::max(worst, std::abs(sum - brute));
    largest = std::max(largest, std::abs(brute));
  }
  BOOST_TEST(largest > 0.005);
  BOOST_TEST(worst < 2e-3 * largest);
}

BOOST_AUTO_TEST_SUITE_END()
