// The harmonics the multiple-scattering tables are made of: orthonormal, the addition theorem,
// and the Legendre moments of the phase functions against their closed forms.

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <vector>

#include "base/quadrature.hpp"
#include "skyspec/phase_function.hpp"
#include "skyspec/units.hpp"
#include "transport/multiple_scattering.hpp"
#include "transport/spherical_harmonics.hpp"

BOOST_AUTO_TEST_SUITE(test_spherical_harmonics)

using namespace skyspec;

namespace {
double legendre(int l, double x) {
  double p0 = 1.0, p1 = x;
  if (l == 0) return p0;
  for (int k = 2; k <= l; ++k) {
    const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
    p0 = p1;
    p1 = p2;
  }
  return p1;
}
}  // namespace

// integral over the sphere of Y_a Y_b = delta_ab (Gauss-Legendre in mu, midpoint rule in phi:
// exact for these polynomials).
BOOST_AUTO_TEST_CASE(harmonics_are_orthonormal) {
  const int degree = 8, n = harmonic_count(degree), n_phi = 64;
  std::vector<double> mu, w, y(static_cast<size_t>(n));
  gauss_legendre(24, -1.0, 1.0, mu, w);
  std::vector<double> gram(static_cast<size_t>(n * n), 0.0);
  for (size_t i = 0; i < mu.size(); ++i)
    for (int j = 0; j < n_phi; ++j) {
      const double phi = (j + 0.5) * 2.0 * kPi / n_phi;
      symmetric_harmonics(degree, mu[i], std::cos(phi), y.data());
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b)
          gram[static_cast<size_t>(a * n + b)] +=
              w[i] * 2.0 * kPi / n_phi * y[static_cast<size_t>(a)] * y[static_cast<size_t>(b)];
    }
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      BOOST_TEST(gram[static_cast<size_t>(a * n + b)] == (a == b ? 1.0 : 0.0), boost::test_tools::tolerance(1e-10));
}

// For w' in the x-z plane (phi' = 0) the sine harmonics vanish there, so the cosine ones alone
// satisfy the addition theorem: sum_m Y_lm(w) Y_lm(w') = (2 l + 1) / (4 pi) P_l(w . w').
BOOST_AUTO_TEST_CASE(addition_theorem) {
  const int degree = 10;
  std::vector<double> a(static_cast<size_t>(harmonic_count(degree))), b(a.size());
  for (double mu1 : {-0.9, -0.2, 0.3, 0.99})
    for (double mu2 : {-0.7, 0.0, 0.5})
      for (double phi : {0.0, 0.7, 2.0, 3.1}) {
        symmetric_harmonics(degree, mu1, std::cos(phi), a.data());
        symmetric_harmonics(degree, mu2, 1.0, b.data());
        const double cos_angle = mu1 * mu2 + std::sqrt((1 - mu1 * mu1) * (1 - mu2 * mu2)) * std::cos(phi);
        for (int l = 0; l <= degree; ++l) {
          double sum = 0.0;
          for (int m = 0; m <= l; ++m)
            sum += a[static_cast<size_t>(harmonic_index(l, m))] * b[static_cast<size_t>(harmonic_index(l, m))];
          BOOST_TEST(sum == (2.0 * l + 1.0) / (4.0 * kPi) * legendre(l, cos_angle), boost::test_tools::tolerance(1e-9));
        }
      }
}

// Henyey-Greenstein: chi_l = g^l; Rayleigh with depolarisation: chi_0 = 1,
// chi_2 = (1 - gamma) / (10 (1 + 2 gamma)), every other moment 0; Cornette-Shanks: chi_0 = 1.
BOOST_AUTO_TEST_CASE(legendre_moments_of_the_phase_functions) {
  const std::vector<double> hg = legendre_moments([](double mu) { return henyey_greenstein_phase(mu, 0.7); }, 12);
  for (int l = 0; l <= 12; ++l)
    BOOST_TEST(hg[static_cast<size_t>(l)] == std::pow(0.7, l), boost::test_tools::tolerance(1e-9));
  for (double gamma : {0.0, 0.0142, 0.1}) {
    const std::vector<double> r = legendre_moments([gamma](double mu) { return rayleigh_phase(mu, gamma); }, 6);
    BOOST_TEST(r[0] == 1.0, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(r[2] == (1.0 - gamma) / (10.0 * (1.0 + 2.0 * gamma)), boost::test_tools::tolerance(1e-12));
    for (int l : {1, 3, 4, 5, 6}) BOOST_TEST(std::abs(r[static_cast<size_t>(l)]) < 1e-13);
  }
  const std::vector<double> cs = legendre_moments([](double mu) { return cornette_shanks_phase(mu, 0.76); }, 4);
  BOOST_TEST(cs[0] == 1.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(cs[1] > 0.6);  // forward scattering
}

// Moments of a tabulated (piecewise-linear) phase function, exact: a linear function a + b mu on
// uneven intervals gives chi_0 = 4 pi a, chi_1 = 4 pi b / 3 and nothing else; a spike 0.1 degree wide
// holding 30 % of the light over an isotropic rest keeps chi_0 = 1 and puts 0.3 in every moment,
// where 512 Gauss-Legendre nodes (0.27 degree apart at the forward end) miss it.
BOOST_AUTO_TEST_CASE(legendre_moments_of_a_tabulated_phase_function) {
  const std::vector<double> mu = {-1.0, -0.3, 0.1, 0.2, 0.75, 1.0};
  std::vector<double> linear;
  for (double m : mu) linear.push_back(0.05 + 0.02 * m);
  const std::vector<double> chi = piecewise_linear_legendre_moments(mu, linear, 12);
  BOOST_TEST(chi[0] == 4.0 * kPi * 0.05, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(chi[1] == 4.0 * kPi * 0.02 / 3.0, boost::test_tools::tolerance(1e-12));
  for (int l = 2; l <= 12; ++l) BOOST_TEST(std::abs(chi[static_cast<size_t>(l)]) < 1e-13);

  const double m0 = std::cos(degrees_to_radians(0.1)), spike = 0.3, rest = (1.0 - spike) / (4.0 * kPi);
  // The rest is isotropic up to m0; the spike's triangle rises from rest at m0 to its peak at 1.
  const double peak = rest + 2.0 * spike / (2.0 * kPi * (1.0 - m0));
  const std::vector<double> spiked_mu = {-1.0, m0, 1.0}, spiked = {rest, rest, peak};
  const std::vector<double> exact = piecewise_linear_legendre_moments(spiked_mu, spiked, 16);
  BOOST_TEST(exact[0] == 1.0, boost::test_tools::tolerance(1e-9));
  for (int l = 1; l <= 16; ++l) BOOST_TEST(exact[static_cast<size_t>(l)] == spike, boost::test_tools::tolerance(1e-3));
  const auto table = [&](double m) { return m <= m0 ? rest : rest + (peak - rest) * (m - m0) / (1.0 - m0); };
  BOOST_TEST(legendre_moments(table, 2)[0] < 0.8);
}

// What a straight skyline hides (skyline_legendre_moments): always half the sphere, so an isotropic
// phase function gives chi_0 = 1/2 for every skyline and chi_1 = sin(gamma) / 4 (the first moment of
// a hemisphere is pi times its pole, here sin(gamma) from the view direction); a skyline through the
// view direction (gamma = 0) hides half of every ring, so chi_l(0) = chi_l / 2 for any phase
// function; a skyline 90 degrees up hides the hemisphere about the view direction.
BOOST_AUTO_TEST_CASE(moments_below_a_skyline) {
  const double step = kPi / 90.0;
  const std::vector<double> iso = skyline_legendre_moments([](double) { return 1.0 / (4.0 * kPi); }, 4, 46, step);
  for (int j = 0; j < 46; ++j) {
    const double gamma = j * step;
    BOOST_TEST_CONTEXT("gamma " << gamma) {
      BOOST_TEST(iso[static_cast<size_t>(j * 5)] == 0.5, boost::test_tools::tolerance(2e-4));
      BOOST_TEST(std::abs(iso[static_cast<size_t>(j * 5 + 1)] - std::sin(gamma) / 4.0) < 2e-4);
    }
  }
  const auto hg = [](double mu) { return henyey_greenstein_phase(mu, 0.8); };
  const std::vector<double> all = legendre_moments(hg, 10);
  const std::vector<double> below = skyline_legendre_moments(hg, 10, 46, step);
  for (int l = 0; l <= 10; ++l)
    BOOST_TEST(below[static_cast<size_t>(l)] == all[static_cast<size_t>(l)] / 2.0, boost::test_tools::tolerance(1e-4));
  const double forward = 2.0 * kPi * [&] {
    std::vector<double> x, w;
    gauss_legendre(512, 0.0, 1.0, x, w);
    double sum = 0.0;
    for (size_t i = 0; i < x.size(); ++i) sum += w[i] * hg(x[i]);
    return sum;
  }();
  BOOST_TEST(below[45 * 11] == forward, boost::test_tools::tolerance(1e-4));
  BOOST_TEST(skyline_hidden_share(0.3, 0.2) == 1.0);
  BOOST_TEST(skyline_hidden_share(0.3, kPi - 0.2) == 0.0);
  BOOST_TEST(skyline_hidden_share(0.0, 1.0) == 0.5, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(skyline_hidden_share(0.4, 0.5 * kPi) == 0.5, boost::test_tools::tolerance(1e-9));
}

// For a field of degree 1, L(w) = a + b w.u, the moments below a skyline and their first-order
// correction give the integral of p(d.w) L(w) over the hidden half of the sphere exactly (the
// rings about d carry no Fourier terms beyond cos(phi)): against a brute-force quadrature over
// that half, {w : w.n < 0} with n = cos(gamma) e - sin(gamma) d (e up, perpendicular to d).
BOOST_AUTO_TEST_CASE(gradient_moments_below_a_skyline) {
  const auto hg = [](double mu) { return henyey_greenstein_phase(mu, 0.6); };
  const double step = kPi / 180.0;
  const std::vector<double> below = skyline_legendre_moments(hg, 1, 91, step);
  const std::vector<double> delta = skyline_gradient_moments(hg, 1, 91, step);
  const Eigen::Vector3d d(1.0, 0.0, 0.0), e(0.0, 0.0, 1.0), y = e.cross(d);
  const Eigen::Vector3d u = Eigen::Vector3d(0.3, -0.2, 0.9).normalized();
  const double a = 0.7, b = 0.5;
  for (int j : {0, 10, 40, 90}) {
    const double gamma = j * step;
    const Eigen::Vector3d n = std::cos(gamma) * e - std::sin(gamma) * d;
    // Brute force: Gauss-Legendre in cos(theta) about d, midpoint in phi, v = x d + st (cos phi e + sin phi y)
    // with its dot products by components (plain arithmetic: the sanitizer build runs this at -O0).
    std::vector<double> x, w;
    gauss_legendre(2000, -1.0, 1.0, x, w);
    const int n_phi = 2000;
    std::vector<double> cos_phi(n_phi), sin_phi(n_phi);
    for (int k = 0; k < n_phi; ++k) {
      cos_phi[static_cast<size_t>(k)] = std::cos((k + 0.5) * 2.0 * kPi / n_phi);
      sin_phi[static_cast<size_t>(k)] = std::sin((k + 0.5) * 2.0 * kPi / n_phi);
    }
    const double dn = d.dot(n), en = e.dot(n), yn = y.dot(n), du = d.dot(u), eu = e.dot(u), yu = y.dot(u);
    double brute = 0.0;
    for (size_t i = 0; i < x.size(); ++i) {
      const double st = std::sqrt(1.0 - x[i] * x[i]);
      double ring = 0.0;
      for (size_t k = 0; k < static_cast<size_t>(n_phi); ++k) {
        const double vn = x[i] * dn + st * (cos_phi[k] * en + sin_phi[k] * yn);
        if (vn < 0.0) ring += a + b * (x[i] * du + st * (cos_phi[k] * eu + sin_phi[k] * yu));
      }
      brute += w[i] * hg(x[i]) * ring * 2.0 * kPi / n_phi;
    }
    const double formula = below[static_cast<size_t>(2 * j)] * a +
                           below[static_cast<size_t>(2 * j + 1)] * b * d.dot(u) +
                           delta[static_cast<size_t>(2 * j + 1)] * b * e.dot(u);
    BOOST_TEST_CONTEXT("gamma " << j << " degrees") {
      BOOST_TEST(formula == brute, boost::test_tools::tolerance(2e-3));
    }
  }
}

// The quadrupole tensors K_m = integral Y_2m(w) w w^T dw: for a field of two equal narrow beams
// from u and its mirror image u' = (ux, -uy, uz) (symmetric about the xz plane, as the basis
// assumes), a_lm = Y_lm(u) and the second moments are (u u^T + u' u'^T) / 2; the mean's share is
// 1 / 3, so sum_m Y_2m(u) K_m = (u u^T + u' u'^T) / 2 - 1 / 3. And K_0's zz is sqrt(5 / (4 pi)) 8 pi / 15.
BOOST_AUTO_TEST_CASE(quadrupole_tensors_give_the_second_moments) {
  const auto& K = quadrupole_tensors();
  BOOST_TEST(K[0](2, 2) == std::sqrt(5.0 / (4.0 * kPi)) * 8.0 * kPi / 15.0, boost::test_tools::tolerance(1e-12));
  for (const Eigen::Vector3d& v :
       {Eigen::Vector3d(0.3, 0.5, 0.8), Eigen::Vector3d(-0.7, 0.1, -0.2), Eigen::Vector3d(0, 0, 1)}) {
    const Eigen::Vector3d u = v.normalized(), mirror(u.x(), -u.y(), u.z());
    const double cos_phi = std::hypot(u.x(), u.y()) > 0 ? u.x() / std::hypot(u.x(), u.y()) : 1.0;
    double y[harmonic_count(2)];
    symmetric_harmonics(2, u.z(), cos_phi, y);
    Eigen::Matrix3d t = Eigen::Matrix3d::Zero();
    for (int m = 0; m <= 2; ++m) t += y[harmonic_index(2, m)] * K[static_cast<size_t>(m)];
    const Eigen::Matrix3d expected =
        0.5 * (u * u.transpose() + mirror * mirror.transpose()) - Eigen::Matrix3d::Identity() / 3.0;
    BOOST_TEST((t - expected).cwiseAbs().maxCoeff() < 1e-12);
  }
  for (const auto& k : K) BOOST_TEST(std::abs(k.trace()) < 1e-12);
}

BOOST_AUTO_TEST_SUITE_END()
