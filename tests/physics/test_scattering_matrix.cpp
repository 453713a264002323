// Scattering matrices and Stokes frame rotations, checked against their definitions: the Rayleigh
// matrix's phase function, normalisation and degree of polarisation in closed form, physical
// realisability, and the rotation against Stokes vectors computed from a polarised field.

#include <boost/test/unit_test.hpp>

#include <cmath>

#include "physics/scattering_matrix.hpp"
#include "skyspec/phase_function.hpp"

BOOST_AUTO_TEST_SUITE(test_scattering_matrix)

using namespace skyspec;

namespace {
// Air's depolarisation at 550 nm (Bates 1984 via Bodhaine et al. 1999: F = 1.0477) and none.
const double kGammas[] = {0.0, rayleigh_gamma_from_depolarisation(depolarisation_ratio_from_king_factor(1.0477))};
}  // namespace

BOOST_AUTO_TEST_CASE(rayleigh_phase_element_is_the_phase_function) {
  for (double gamma : kGammas)
    for (double mu = -1.0; mu <= 1.0; mu += 0.125)
      BOOST_TEST(rayleigh_scattering_matrix(mu, gamma).a1 == rayleigh_phase(mu, gamma),
                 boost::test_tools::tolerance(1e-14));
}

BOOST_AUTO_TEST_CASE(rayleigh_phase_element_integrates_to_one) {
  for (double gamma : kGammas) {
    // 2 pi * integral over mu of a quadratic: Simpson's rule is exact.
    const int n = 64;
    double sum = 0.0;
    for (int i = 0; i <= n; ++i) {
      const double mu = -1.0 + 2.0 * i / n;
      const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
      sum += w * rayleigh_scattering_matrix(mu, gamma).a1;
    }
    BOOST_TEST(2.0 * kPi * sum * (2.0 / n) / 3.0 == 1.0, boost::test_tools::tolerance(1e-12));
  }
}

// P(Theta) = (1 - cos^2) / (1 + cos^2 + 2 rho / (1 - rho)) (Chandrasekhar 1950; the form in
// docs/physics.md), rho the depolarisation ratio: 0.9457 at 90 degrees for rho = 0.0279.
BOOST_AUTO_TEST_CASE(rayleigh_degree_of_polarisation_matches_the_closed_form) {
  for (double gamma : kGammas) {
    const double rho = 2.0 * gamma / (1.0 + gamma);  // gamma = rho / (2 - rho) inverted
    for (double mu = -1.0; mu <= 1.0; mu += 0.0625) {
      const ScatteringMatrix f = rayleigh_scattering_matrix(mu, gamma);
      const double expected = (1.0 - mu * mu) / (1.0 + mu * mu + 2.0 * rho / (1.0 - rho));
      BOOST_TEST(-f.b1 / f.a1 == expected, boost::test_tools::tolerance(1e-12));
    }
  }
  const double rho = depolarisation_ratio_from_king_factor(1.0477);
  const ScatteringMatrix f = rayleigh_scattering_matrix(0.0, rayleigh_gamma_from_depolarisation(rho));
  BOOST_TEST(-f.b1 / f.a1 == 1.0 / (1.0 + 2.0 * rho / (1.0 - rho)), boost::test_tools::tolerance(1e-12));
  BOOST_TEST(-f.b1 / f.a1 < 0.95);
  BOOST_TEST(-f.b1 / f.a1 > 0.94);
  // Without depolarisation, light scattered at 90 degrees is fully polarised, and V keeps its
  // sign only forwards (a4 = a3 = 3/(8 pi) mu).
  const ScatteringMatrix g = rayleigh_scattering_matrix(0.0, 0.0);
  BOOST_TEST(-g.b1 / g.a1 == 1.0, boost::test_tools::tolerance(1e-14));
  const ScatteringMatrix h = rayleigh_scattering_matrix(0.5, 0.0);
  BOOST_TEST(h.a4 == h.a3, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(h.a3 == 3.0 / (8.0 * kPi) * 0.5, boost::test_tools::tolerance(1e-14));
}

// Any fully polarised input leaves with a degree of polarisation of at most 1.
BOOST_AUTO_TEST_CASE(matrices_are_physically_realisable) {
  for (double gamma : kGammas)
    for (double mu = -1.0; mu <= 1.0; mu += 0.125)
      for (int a = 0; a < 12; ++a)
        for (int b = -3; b <= 3; ++b) {
          const double chi = kPi * a / 12.0, eps = kPi / 4.0 * b / 3.0;  // orientation and ellipticity
          const Stokes in(1.0, std::cos(2 * eps) * std::cos(2 * chi), std::cos(2 * eps) * std::sin(2 * chi),
                          std::sin(2 * eps));
          for (const ScatteringMatrix& f :
               {rayleigh_scattering_matrix(mu, gamma), non_polarising_scattering_matrix(0.3)}) {
            const Stokes out = f.matrix() * in;
            BOOST_TEST(out[0] >= 0.0);
            BOOST_TEST(out.tail<3>().norm() <= out[0] * (1.0 + 1e-12));
          }
        }
}

// Linear polarisation at angle alpha from e1 has Q = cos 2 alpha, U = sin 2 alpha. In the frame
// turned by psi (e1' = cos psi e1 + sin psi e2) its angle is alpha - psi.
BOOST_AUTO_TEST_CASE(rotation_matches_the_stokes_vector_of_a_turned_frame) {
  for (double alpha = 0.0; alpha < kPi; alpha += kPi / 7.0)
    for (double psi = -kPi; psi <= kPi; psi += kPi / 9.0) {
      const Stokes in(1.0, std::cos(2 * alpha), std::sin(2 * alpha), 0.25);
      const Stokes expected(1.0, std::cos(2 * (alpha - psi)), std::sin(2 * (alpha - psi)), 0.25);
      const Stokes out = stokes_rotation(std::cos(psi), std::sin(psi)) * in;
      BOOST_TEST((out - expected).norm() < 1e-14);
    }
  // Turning by 180 degrees is no change; by 90 degrees swaps the signs of Q and U.
  const Stokes s(1.0, 0.3, -0.2, 0.1);
  BOOST_TEST((stokes_rotation(-1.0, 0.0) * s - s).norm() < 1e-15);
  BOOST_TEST((stokes_rotation(0.0, 1.0) * s - Stokes(1.0, -0.3, 0.2, 0.1)).norm() < 1e-15);
}

BOOST_AUTO_TEST_SUITE_END()
