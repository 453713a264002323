// The spin-2 harmonics of the tables' polarised fields: Wigner's functions against closed forms,
// orthonormal, the degree-2 E and B modes of a constant tensor at degree 2 alone, and the scattering
// by a unit matrix (each arriving polarisation carried along the great circle, weighted by the
// phase function) against a brute-force integral over the sphere: each degree scaled by beta_l.

#include <boost/test/unit_test.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "base/quadrature.hpp"
#include "skyspec/phase_function.hpp"
#include "skyspec/units.hpp"
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
  BOOST_TEST(worst < 1e-12);
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

// A smooth polarised field of every degree, f(w) times a degree-2 E mode, scattered by a
// Henyey-Greenstein particle with the unit matrix: the brute-force integral over the sphere of
// p(w . w') R C(w') R^T (R the rotation about w' x w that takes w' to w) against
// sum_l beta_l c_lm of the field's harmonics.
BOOST_AUTO_TEST_CASE(unit_matrix_scales_each_degree_by_its_moment) {
  const double g = 0.6;
  M3 m;
  m << 0.5, 0.0, 0.4, 0.0, 0.1, 0.0, 0.4, 0.0, -0.6;
  const V3 a = V3(0.6, 0.0, 0.8);
  const auto tensor_field = [&](const Frame& f) -> M3 {
    const M3 p = M3::Identity() - f.w * f.w.transpose();
    const M3 t = p * m * p;
    return std::exp(1.5 * f.w.dot(a)) * (t - 0.5 * t.trace() * p);
  };
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

  std::vector<double> mu, w, bq(static_cast<size_t>(n)), bu(static_cast<size_t>(n));
  gauss_legendre(160, -1.0, 1.0, mu, w);
  const int n_phi = 320;
  double worst = 0.0, largest = 0.0;
  for (const auto& [mu_out, phi_out] : std::vector<std::pair<double, double>>{{0.8, 0.3}, {0.1, 1.9}, {-0.5, 2.8}}) {
    const Frame fo = frame_of(mu_out, phi_out);
    M3 sum = M3::Zero();
    for (size_t i = 0; i < mu.size(); ++i)
      for (int j = 0; j < n_phi; ++j) {
        const Frame fi = frame_of(mu[i], (j + 0.5) * 2.0 * kPi / n_phi);
        const V3 axis = fi.w.cross(fo.w);
        const double cos_t = std::clamp(fi.w.dot(fo.w), -1.0, 1.0);
        if (axis.norm() < 1e-12) continue;
        const M3 r = Eigen::AngleAxisd(std::acos(cos_t), axis.normalized()).toRotationMatrix();
        sum += w[i] * 2.0 * kPi / n_phi * henyey_greenstein_phase(cos_t, g) * (r * tensor_field(fi) * r.transpose());
      }
    double q_brute = 0, u_brute = 0;
    stokes_of(sum, fo, q_brute, u_brute);
    spin2_harmonics(degree, fo.mu, fo.cos_phi, fo.sin_phi, bq.data(), bu.data());
    double q = 0, u = 0;
    for (int l = 2; l <= degree; ++l)
      for (int mm = -l; mm <= l; ++mm) {
        const size_t k = static_cast<size_t>(spin2_harmonic_index(l, mm));
        q += beta[static_cast<size_t>(l)] * c[k] * bq[k];
        u += beta[static_cast<size_t>(l)] * c[k] * bu[k];
      }
    BOOST_TEST_MESSAGE("mu " << mu_out << ": Q " << q << " (brute force " << q_brute << "), U " << u << " (" << u_brute
                             << ")");
    worst = std::max({worst, std::abs(q - q_brute), std::abs(u - u_brute)});
    largest = std::max({largest, std::abs(q_brute), std::abs(u_brute)});
  }
  BOOST_TEST(largest > 0.05);
  BOOST_TEST(worst < 2e-3 * largest);
}

BOOST_AUTO_TEST_SUITE_END()
