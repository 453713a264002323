// The Monte Carlo reference with Stokes vectors: a published plane-parallel Rayleigh benchmark of
// I, Q and U, single scattering against the closed form of the degree of polarisation, V = 0 for
// Rayleigh air, and the frames' rotation (a camera's roll).

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstdio>
#include <string>

#include "atmosphere_fixtures.hpp"
#include "monte_carlo_fixtures.hpp"
#include "natraj_tables.hpp"
#include "physics/scattering_matrix.hpp"
#include "release_stage.hpp"
#include "skyspec/camera.hpp"
#include "skyspec/phase_function.hpp"
#include "transport/monte_carlo.hpp"
#include "transport/single_scattering.hpp"

BOOST_AUTO_TEST_SUITE(test_monte_carlo_polarisation)

using namespace skyspec;

namespace {
// A conservative Rayleigh slab of optical thickness tau.
MonteCarloMedium rayleigh_slab(double tau, double gamma, double ground_albedo, double sun_irradiance) {
  return test::rayleigh_slab(tau, 1.0, ground_albedo, sun_irradiance, gamma);
}

bool agrees(const char* what, const MonteCarloValue& mc, double expected, double k_sigma, double relative) {
  std::printf("  %s: mc %.6g +- %.2g, expected %.6g: %+.3f %% (%.2f sigma)\n", what, mc.mean, mc.standard_error,
              expected, 100.0 * (mc.mean / expected - 1.0), (mc.mean - expected) / mc.standard_error);
  return std::abs(mc.mean - expected) <= k_sigma * mc.standard_error + relative * std::abs(expected);
}
}  // namespace

// Natraj, Li & Yung 2009 (ApJ 691, 1909), the corrected Coulson, Dave & Sekera (1960) tables:
// optical thickness 0.5, black ground, mu0 = 0.2, light leaving the top at mu = 0.02, relative
// azimuth 30 degrees, and mu = 0.92, 60 degrees; incident flux pi per unit area normal to the beam.
// Values as quoted in SASKTRAN2's documentation ("Reproducing the Coulson Tables"):
// I = 0.39444956, Q = -0.06485313, U = 0.04390364 and I = 0.05643322, Q = -0.01979730, U = 0.03822653.
// The azimuth is that of DISORT's test (test_monte_carlo: the beam travels at azimuth 0, the
// emergent light at phi). The tables' Stokes frame is ours with e1 horizontal (perpendicular to the
// meridian plane) and e2 in it, read against the direction of observation: in our frame with e1 in
// the meridian plane (reference = the vertical) their Q is -Q and their U is U.
BOOST_AUTO_TEST_CASE(plane_parallel_rayleigh_matches_natraj_2009) {
  const MonteCarloIntegrator mc(rayleigh_slab(0.5, 0.0, 0.0, kPi), Vec3(-std::sqrt(1.0 - 0.04), 0.0, 0.2));
  struct Case {
    double mu, phi_deg, I, Q, U;
  };
  const Case cases[] = {{0.02, 30.0, 0.39444956, -0.06485313, 0.04390364},
                        {0.92, 60.0, 0.05643322, -0.01979730, 0.03822653}};
  MonteCarloSettings settings;
  settings.paths = 1000000;
  settings.seed = 5;
  std::uint64_t stream = 0;
  for (const Case& c : cases) {
    const double s = std::sqrt(1.0 - c.mu * c.mu), phi = c.phi_deg * kPi / 180.0;
    const Vec3 k(s * std::cos(phi), s * std::sin(phi), c.mu);  // the emergent light's direction
    const MonteCarloStokes v = mc.stokes_radiance(Vec3(0, 0, 1.0), -k, Vec3(0, 0, 1), settings, ++stream);
    BOOST_TEST_MESSAGE("mu " << c.mu << ", phi " << c.phi_deg);
    BOOST_TEST(agrees("I", v[0], c.I, 4.0, 1e-4));
    MonteCarloValue q = v[1];
    q.mean = -q.mean;
    BOOST_TEST(agrees("Q", q, c.Q, 4.0, 1e-4));
    BOOST_TEST(agrees("U", v[2], c.U, 4.0, 1e-4));
    BOOST_TEST(v[3].mean == 0.0);
  }
}

// The same tables over a ground (tests/data/natraj2009: optical thickness 0.25, albedo 0.25), at
// the top and the bottom, at geometries spread over the table (low and high sun, grazing and steep
// views, the principal plane and across it): 200 000 paths each. The case above runs the same code
// under the sanitizers.
BOOST_AUTO_TEST_CASE(plane_parallel_rayleigh_over_a_ground_matches_natraj_2009,
                     *boost::unit_test::precondition(test::not_in_sanitizer_stage)) {
  const std::string folder = std::string(SKYSPEC_TEST_DATA_DIR) + "/natraj2009/";
  struct Case {
    int sun, view, azimuth;  // indices into the tables' grid
  };
  const Case cases[] = {{1, 0, 1}, {1, 8, 3}, {4, 5, 0}, {4, 12, 6}, {6, 3, 3}};
  MonteCarloSettings settings;
  settings.paths = 200000;
  settings.seed = 11;
  std::uint64_t stream = 0;
  for (const bool up : {true, false}) {
    const std::string end = up ? "_UP_TAU_0.25" : "_DN_TAU_0.25";
    const test::NatrajTable I = test::read_natraj_table(folder + "I" + end),
                            Q = test::read_natraj_table(folder + "Q" + end),
                            U = test::read_natraj_table(folder + "U" + end);
    for (const Case& c : cases) {
      const double mu0 = test::kNatrajSunCosines[static_cast<size_t>(c.sun)];
      const MonteCarloIntegrator mc(rayleigh_slab(0.25, 0.0, 0.25, kPi), Vec3(-std::sqrt(1.0 - mu0 * mu0), 0.0, mu0));
      const double mu = I.row(1, c.sun, c.view)[1];
      const double phi = test::kNatrajAzimuthsDeg[static_cast<size_t>(c.azimuth)] * kPi / 180.0;
      const double s = std::sqrt(1.0 - mu * mu);
      // The light leaving the layer: upwards at the top, downwards at the bottom.
      const Vec3 k(s * std::cos(phi), s * std::sin(phi), up ? mu : -mu);
      const MonteCarloStokes v = mc.stokes_radiance(Vec3(0, 0, up ? 1.0 : 0.0), -k, Vec3(0, 0, 1), settings, ++stream);
      BOOST_TEST_MESSAGE((up ? "top" : "bottom") << ", mu0 " << mu0 << ", mu " << mu << ", phi "
                                                 << test::kNatrajAzimuthsDeg[static_cast<size_t>(c.azimuth)]);
      const size_t column = 2 + static_cast<size_t>(c.azimuth);
      BOOST_TEST(agrees("I", v[0], I.row(1, c.sun, c.view)[column], 4.0, 1e-4));
      MonteCarloValue q = v[1];
      q.mean = -q.mean;
      BOOST_TEST(agrees("Q", q, Q.row(1, c.sun, c.view)[column], 4.0, 1e-4));
      BOOST_TEST(agrees("U", v[2], U.row(1, c.sun, c.view)[column], 4.0, 1e-4));  // the same frames as above
    }
  }
}

// Once scattered, sunlight has the degree of polarisation of the closed form, perpendicular to the
// scattering plane: in the frame whose e1 is the plane's normal, Q / I = P(Theta) and U = 0 for
// every path (the sun's angle is the same all along a straight segment), to rounding.
BOOST_AUTO_TEST_CASE(single_scattering_has_the_closed_form_polarisation) {
  const double rho = depolarisation_ratio_from_king_factor(1.0477), gamma = rayleigh_gamma_from_depolarisation(rho);
  const Vec3 sun = Vec3(0.6, 0.0, 0.8);
  const MonteCarloIntegrator mc(rayleigh_slab(0.05, gamma, 0.0, 1.0), sun);
  MonteCarloSettings settings;
  settings.paths = 4096;
  settings.max_orders = 1;
  int stream = 0;
  for (double az : {0.0, 40.0, 90.0, 135.0, 180.0}) {
    const double a = az * kPi / 180.0;
    const Vec3 look = Vec3(0.5 * std::cos(a), 0.5 * std::sin(a), std::sqrt(0.75));  // 60 degrees up
    const double mu = look.dot(sun);
    const Vec3 normal = sun.cross(look);
    if (normal.norm() < 1e-6) continue;
    const MonteCarloStokes v = mc.stokes_radiance(Vec3(0, 0, 0), look, normal, settings, ++stream);
    const double expected = (1.0 - mu * mu) / (1.0 + mu * mu + 2.0 * rho / (1.0 - rho));
    BOOST_TEST(v[0].mean > 0.0);
    BOOST_TEST(v[1].mean / v[0].mean == expected, boost::test_tools::tolerance(1e-10));
    BOOST_TEST(std::abs(v[2].mean) < 1e-12 * v[0].mean);
    BOOST_TEST(v[3].mean == 0.0);
  }
}

// Rayleigh's matrix does not couple V to I, Q, U: unpolarised sunlight never gains circular
// polarisation, whatever the orders and the ground.
BOOST_AUTO_TEST_CASE(rayleigh_air_has_no_circular_polarisation) {
  const MonteCarloIntegrator mc(rayleigh_slab(0.8, 0.015, 0.3, 1.0), Vec3(0.0, 0.5, std::sqrt(0.75)));
  MonteCarloSettings settings;
  settings.paths = 20000;
  const MonteCarloStokes v =
      mc.stokes_radiance(Vec3(0, 0, 0), Vec3(0.3, -0.2, 0.5).normalized(), Vec3(0, 0, 1), settings, 1);
  BOOST_TEST(v[0].mean > 0.0);
  BOOST_TEST(std::abs(v[1].mean) + std::abs(v[2].mean) > 1e-3 * v[0].mean);  // but it is polarised
  BOOST_TEST(v[3].mean == 0.0);
  BOOST_TEST(v[3].standard_error == 0.0);
}

// Turning the reference axis by chi about the line of sight (a camera's roll) turns (Q, U) by
// 2 chi and leaves I and V: the same paths, so to rounding.
BOOST_AUTO_TEST_CASE(roll_turns_q_and_u_by_twice_the_angle) {
  const MonteCarloIntegrator mc(rayleigh_slab(0.3, 0.015, 0.2, 1.0), Vec3(0.3, 0.4, std::sqrt(0.75)).normalized());
  MonteCarloSettings settings;
  settings.paths = 8192;
  const Vec3 look = Vec3(-0.4, 0.1, 0.6).normalized();
  const Vec3 up(0, 0, 1);
  const Vec3 e1 = (up - up.dot(look) * look).normalized();
  const Vec3 k = -look;  // the light's direction
  const MonteCarloStokes v0 = mc.stokes_radiance(Vec3(0, 0, 0), look, e1, settings, 3);
  for (double chi : {0.3, 1.0, 2.5}) {
    const Vec3 e1_turned = std::cos(chi) * e1 + std::sin(chi) * k.cross(e1);
    const MonteCarloStokes v = mc.stokes_radiance(Vec3(0, 0, 0), look, e1_turned, settings, 3);
    const double I = v0[0].mean;
    BOOST_TEST(std::abs(v[0].mean - I) <= 1e-12 * I);
    BOOST_TEST(std::abs(v[1].mean - (v0[1].mean * std::cos(2 * chi) + v0[2].mean * std::sin(2 * chi))) <= 1e-9 * I);
    BOOST_TEST(std::abs(v[2].mean - (-v0[1].mean * std::sin(2 * chi) + v0[2].mean * std::cos(2 * chi))) <= 1e-9 * I);
  }
}

// The scalar and the vector transport share their paths: with polarisation ignored after the first
// scattering (one order) they give the same intensity; over all orders the vector intensity differs
// by the coupling of Q into I, a few percent in this slab and not more than 15 %.
BOOST_AUTO_TEST_CASE(vector_intensity_is_the_scalar_one_for_one_order) {
  const MonteCarloIntegrator mc(rayleigh_slab(0.5, 0.015, 0.0, 1.0), Vec3(-0.6, 0.0, 0.8));
  MonteCarloSettings settings;
  settings.paths = 50000;
  const Vec3 look = Vec3(0.5, 0.5, 0.3).normalized();
  settings.max_orders = 1;
  const MonteCarloValue scalar1 = mc.radiance(Vec3(0, 0, 0), look, settings, 9);
  const MonteCarloStokes vector1 = mc.stokes_radiance(Vec3(0, 0, 0), look, Vec3(0, 0, 1), settings, 9);
  BOOST_TEST(vector1[0].mean == scalar1.mean, boost::test_tools::tolerance(1e-12));
  settings.max_orders = 0;
  const MonteCarloValue scalar = mc.radiance(Vec3(0, 0, 0), look, settings, 9);
  const MonteCarloStokes vector = mc.stokes_radiance(Vec3(0, 0, 0), look, Vec3(0, 0, 1), settings, 9);
  BOOST_TEST(std::abs(vector[0].mean / scalar.mean - 1.0) < 0.15);
  BOOST_TEST(std::abs(vector[0].mean / scalar.mean - 1.0) > 1e-4);
}

// The deterministic integrator's single-scattering polarisation (SingleScattering::stokes) against
// the vector Monte Carlo limited to one order, in the default atmosphere's physics (depolarised
// Rayleigh, non-polarising aerosol, ozone, a depolarising ground of albedo 0.3): Q and U in the
// frame of the vertical through the line of sight, for suns at 30 and 2 degrees.
BOOST_AUTO_TEST_CASE(deterministic_single_scattering_polarisation_matches_the_monte_carlo) {
  const std::vector<double>& nm = test::kOrderOneNm;
  const test::IntegratorChain chain = test::default_air_over_ground();
  const int n = static_cast<int>(nm.size());
  ScatteringWorkspace ws(n);
  RadianceParts parts(n);
  Spectrum I(n), Q(n), U(n);
  MonteCarloSettings settings;
  settings.paths = 20000;
  settings.seed = 8;
  settings.max_orders = 1;
  const Vec3 origin(0, 0, chain.atm.planet_radius_m() + 1.0);
  const Vec3 up(0, 0, 1);
  std::uint64_t stream = 0;
  for (double sun_elevation : {30.0, 2.0}) {
    const Vec3 sun = direction_from_angles(0.0, sun_elevation);
    for (auto [az, el] : {std::pair{0.0, 60.0}, {120.0, 45.0}, {90.0, 10.0}, {250.0, 20.0}}) {
      const Vec3 dir = direction_from_angles(az, el);
      const Vec3 e1 = (up - up.dot(dir) * dir).normalized();
      chain.integrator.radiance_parts(origin, dir, sun, ScatteringSources{}, ws, parts);
      chain.integrator.stokes(parts, dir, sun, e1, Spectrum::Ones(n), ws, I, Q, U);
      for (int i = 0; i < n; ++i) {
        const MonteCarloIntegrator mc(MonteCarloMedium::from_atmosphere(chain.atm, i), sun);
        const MonteCarloStokes v = mc.stokes_radiance(origin, dir, up, settings, ++stream);
        BOOST_TEST_MESSAGE("sun " << sun_elevation << ", view " << az << "/" << el << ", " << nm[size_t(i)] << " nm");
        BOOST_TEST(agrees("I", v[0], I[i], 4.0, 2e-3));
        // Q and U against the intensity's scale: they may be near 0.
        BOOST_TEST(std::abs(v[1].mean - Q[i]) <= 4.0 * v[1].standard_error + 2e-3 * I[i]);
        BOOST_TEST(std::abs(v[2].mean - U[i]) <= 4.0 * v[2].standard_error + 2e-3 * I[i]);
        std::printf("  Q %.5g / %.5g, U %.5g / %.5g (MC / deterministic)\n", v[1].mean, Q[i], v[2].mean, U[i]);
      }
      BOOST_TEST(std::hypot(Q[0], U[0]) > 0.05 * I[0]);  // polarised: the comparison is not of zeros
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
