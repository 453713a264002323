// The Monte Carlo reference integrator checked on its own: a published plane-parallel benchmark,
// energy conservation, the optically thin limit, and single scattering against the deterministic
// integrator (an independent implementation of the same equation).

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstdio>
#include <string>

#include "atmosphere_fixtures.hpp"
#include "monte_carlo_fixtures.hpp"
#include "skyspec/camera.hpp"
#include "skyspec/phase_function.hpp"
#include "transport/monte_carlo.hpp"

BOOST_AUTO_TEST_SUITE(test_monte_carlo)

using namespace skyspec;

namespace {
MonteCarloMedium slab(double tau, double single_scattering_albedo, double ground_albedo, double sun_irradiance,
                      double rayleigh_gamma = 0.0) {
  return test::rayleigh_slab(tau, single_scattering_albedo, ground_albedo, sun_irradiance, rayleigh_gamma);
}

// |mc - expected| within k standard errors plus a relative allowance for the reference's own rounding.
bool agrees(const MonteCarloValue& mc, double expected, double k_sigma, double relative) {
  const double allowed = k_sigma * mc.standard_error + relative * std::abs(expected);
  std::printf("  mc %.6g +- %.2g (%.3f %%), expected %.6g: %+.3f %% (%.2f sigma)\n", mc.mean, mc.standard_error,
              100.0 * mc.standard_error / std::abs(expected), expected, 100.0 * (mc.mean / expected - 1.0),
              (mc.mean - expected) / mc.standard_error);
  return std::abs(mc.mean - expected) <= allowed;
}
}  // namespace

// DISORT's test problem 2 (Stamnes et al. 1988; disotest.f, "Rayleigh Scattering, Beam Source",
// compared there with Sweigart 1970 / Coulson, Dave & Sekera 1960): a homogeneous plane-parallel
// layer, phase function 3/4 (1 + cos^2) per 4 pi sr, beam irradiance pi at mu0 = 0.080442, black
// ground. Radiances at the top (upwelling, mu > 0) and the bottom (downwelling, mu < 0) for the
// view cosines of its 16-stream quadrature, azimuth phi - phi0 = 0 (the scattering angle's cosine
// is -mu mu0 + sin sin0 cos(phi - phi0), DISORT's eq. STWL 4). Values: TSTUU of test cases 2A,
// 2B (tau 0.2, single-scattering albedo 0.5 and 1) and 2D (tau 5, conservative).
BOOST_AUTO_TEST_CASE(plane_parallel_rayleigh_matches_disort_test_problem_2) {
  struct Case {
    const char* name;
    double tau, omega;
    double top[3];     // mu = 0.018014, 0.538263, 0.981986 at tau = 0
    double bottom[3];  // mu = -0.981986, -0.538263, -0.018014 at tau = tau*
  };
  const Case cases[] = {
      {"2A", 0.2, 0.5, {1.61796e-01, 2.11501e-02, 7.86713e-03}, {7.71897e-03, 2.00778e-02, 2.57685e-02}},
      {"2B", 0.2, 1.0, {3.47678e-01, 4.87120e-02, 1.89387e-02}, {1.86027e-02, 4.64061e-02, 6.77603e-02}},
      {"2D", 5.0, 1.0, {3.64010e-01, 8.26993e-02, 4.92370e-02}, {1.05950e-02, 7.69337e-03, 3.79276e-03}},
  };
  const double mu0 = 0.080442, s0 = std::sqrt(1.0 - mu0 * mu0);
  const Vec3 sun(-s0, 0.0, mu0);  // towards the sun: the beam travels along (s0, 0, -mu0), azimuth 0
  const double mus[3] = {0.018014, 0.538263, 0.981986};
  MonteCarloSettings settings;
  settings.paths = 100000;
  settings.seed = 7;
  std::uint64_t stream = 0;
  for (const auto& c : cases) {
    const MonteCarloIntegrator mc(slab(c.tau, c.omega, 0.0, kPi), sun);
    const double relative = 2e-4;  // the table's 6 digits and DISORT's own accuracy
    for (int k = 0; k < 3; ++k) {
      const double mu = mus[k], s = std::sqrt(1.0 - mu * mu);
      BOOST_TEST_MESSAGE("case " << c.name << " top mu " << mu);
      // Radiance travelling along (s, 0, mu) at the top: the observer looks along (-s, 0, -mu).
      const MonteCarloValue up = mc.radiance(Vec3(0, 0, 1.0), Vec3(-s, 0, -mu), settings, ++stream);
      BOOST_TEST(agrees(up, c.top[k], 4.0, relative), "case " << c.name << " top, mu " << mu);
      // Downwelling along (s, 0, -mu) at the bottom (DISORT's mu < 0): looking along (-s, 0, mu).
      const double mu_down = mus[2 - k], s_down = std::sqrt(1.0 - mu_down * mu_down);
      const MonteCarloValue down = mc.radiance(Vec3(0, 0, 0.0), Vec3(-s_down, 0, mu_down), settings, ++stream);
      BOOST_TEST(agrees(down, c.bottom[k], 4.0, relative), "case " << c.name << " bottom, mu " << -mu_down);
    }
  }
}

// No absorption in the air: what leaves the top plus what the ground absorbs is what came in,
// mu0 E. With Rayleigh (depolarised) and a Cornette-Shanks aerosol, so that every sampler and
// phase function takes part, and a reflecting ground.
BOOST_AUTO_TEST_CASE(energy_is_conserved_without_absorption) {
  const double mu0 = 0.6, E = 2.0, albedo = 0.3, tau_r = 0.3, tau_m = 0.2;
  MonteCarloMedium m = slab(tau_r, 1.0, albedo, E, 0.0142);
  MonteCarloComponent aerosol;
  aerosol.profile = DensityProfile::constant();
  aerosol.scattering_per_m = aerosol.extinction_per_m = tau_m;
  aerosol.phase = MonteCarloComponent::Phase::CornetteShanks;
  aerosol.phase_parameter = 0.76;
  m.components.push_back(aerosol);
  const Vec3 sun(std::sqrt(1.0 - mu0 * mu0), 0.0, mu0);
  const MonteCarloIntegrator mc(m, sun);
  MonteCarloSettings settings;
  settings.paths = 2000000;
  settings.seed = 11;
  const MonteCarloValue reflected = mc.irradiance(Vec3(0, 0, 1.0), Vec3(0, 0, -1), settings, 1);
  const MonteCarloValue diffuse_down = mc.irradiance(Vec3(0, 0, 0.0), Vec3(0, 0, 1), settings, 2);
  const double direct_down = mu0 * E * std::exp(-(tau_r + tau_m) / mu0);
  MonteCarloValue balance;
  balance.mean = reflected.mean + (1.0 - albedo) * (diffuse_down.mean + direct_down);
  balance.standard_error = std::hypot(reflected.standard_error, (1.0 - albedo) * diffuse_down.standard_error);
  BOOST_TEST_MESSAGE("reflected " << reflected.mean << ", diffuse down " << diffuse_down.mean << ", direct down "
                                  << direct_down);
  BOOST_TEST(balance.standard_error < 4e-4 * mu0 * E);
  BOOST_TEST(agrees(balance, mu0 * E, 0.0, 1e-3));
}

// Drawing a share of the scatterings' directions about the sun (MonteCarloSettings::sun_peak_share)
// changes how paths are sampled, not what they estimate: with a strongly forward-scattering aerosol
// (Henyey-Greenstein, g = 0.95, optical depth 1) over a reflecting ground, energy is conserved to
// the same 1e-3, and the sky at the bottom agrees with the plain sampling's within 4 standard errors.
BOOST_AUTO_TEST_CASE(sampling_about_the_sun_keeps_the_estimate) {
  const double mu0 = 0.5, E = 1.0, albedo = 0.2;
  MonteCarloMedium m = slab(0.1, 1.0, albedo, E, 0.0142);
  MonteCarloComponent aerosol;
  aerosol.profile = DensityProfile::constant();
  aerosol.scattering_per_m = aerosol.extinction_per_m = 1.0;
  aerosol.phase = MonteCarloComponent::Phase::HenyeyGreenstein;
  aerosol.phase_parameter = 0.95;
  m.components.push_back(aerosol);
  const Vec3 sun(std::sqrt(1.0 - mu0 * mu0), 0.0, mu0);
  const MonteCarloIntegrator mc(m, sun);
  MonteCarloSettings plain, peaked;
  plain.paths = peaked.paths = 400000;
  plain.seed = peaked.seed = 13;
  peaked.sun_peak_share = 0.3;
  const MonteCarloValue reflected = mc.irradiance(Vec3(0, 0, 1.0), Vec3(0, 0, -1), peaked, 1);
  const MonteCarloValue diffuse_down = mc.irradiance(Vec3(0, 0, 0.0), Vec3(0, 0, 1), peaked, 2);
  MonteCarloValue balance;
  balance.mean = reflected.mean + (1.0 - albedo) * (diffuse_down.mean + mu0 * E * std::exp(-1.1 / mu0));
  balance.standard_error = std::hypot(reflected.standard_error, (1.0 - albedo) * diffuse_down.standard_error);
  BOOST_TEST(agrees(balance, mu0 * E, 4.0, 1e-3));
  for (const Vec3& look : {Vec3(0, 0, 1), Vec3(-0.8, 0, 0.6), Vec3(0.6, 0, 0.8)}) {  // zenith, away, towards
    const MonteCarloValue a = mc.radiance(Vec3(0, 0, 0.0), look, plain, 3);
    const MonteCarloValue b = mc.radiance(Vec3(0, 0, 0.0), look, peaked, 4);
    const double sigma = std::hypot(a.standard_error, b.standard_error);
    BOOST_TEST_MESSAGE("looking along (" << look.x() << ", " << look.z() << "): plain " << a.mean << " +- "
                                         << a.standard_error << ", about the sun " << b.mean << " +- "
                                         << b.standard_error);
    BOOST_TEST(std::abs(a.mean - b.mean) <= 4.0 * sigma);
  }
}

// An optically thin layer: all orders together are single scattering's closed form,
// L = E omega p(mu) mu0 / (mu + mu0) (1 - exp(-tau (1 / mu + 1 / mu0))) for the reflected light,
// to the second order's share, of the order of tau / mu (5e-4 here).
BOOST_AUTO_TEST_CASE(optically_thin_limit_is_single_scattering) {
  const double tau = 1e-4, omega = 0.9, gamma = 0.0142, mu0 = 0.5;
  const MonteCarloMedium m = slab(tau, omega, 0.0, 1.0, gamma);
  const Vec3 sun(std::sqrt(1.0 - mu0 * mu0), 0.0, mu0);
  const MonteCarloIntegrator mc(m, sun);
  MonteCarloSettings settings;
  settings.paths = 100000;
  settings.seed = 3;
  for (double mu : {0.2, 0.6, 1.0}) {
    for (double sign : {-1.0, 1.0}) {
      const Vec3 look(sign * std::sqrt(1.0 - mu * mu), 0.0, -mu);  // radiance travelling along -look
      const double cos_scattering = (-look).dot(-sun);             // between the beam and the light seen
      const double expected = omega * rayleigh_phase(cos_scattering, gamma) * mu0 / (mu + mu0) *
                              (1.0 - std::exp(-tau * (1.0 / mu + 1.0 / mu0)));
      BOOST_TEST(agrees(mc.radiance(Vec3(0, 0, 1.0), look, settings, 100 + static_cast<int>(10 * mu + sign)), expected,
                        4.0, 3e-3));
    }
  }
}

// Order 1 only, in the default atmosphere's physics (derived Rayleigh with its depolarisation,
// aerosol, ozone, a reflecting ground), against the deterministic single-scattering integral:
// zenith, 45 degrees up, and near the horizon towards and away from low and high suns.
BOOST_AUTO_TEST_CASE(single_scattering_matches_the_deterministic_integrator) {
  const std::vector<double>& nm = test::kOrderOneNm;
  const test::IntegratorChain chain = test::default_air_over_ground();
  const int n = static_cast<int>(nm.size());
  ScatteringWorkspace ws(n);
  Spectrum det(n);
  MonteCarloSettings settings;
  settings.paths = 20000;
  settings.seed = 5;
  settings.max_orders = 1;
  const Vec3 origin(0, 0, chain.atm.planet_radius_m() + 1.0);
  std::uint64_t stream = 0;
  for (double sun_elevation : {30.0, 2.0}) {
    const Vec3 sun = direction_from_angles(0.0, sun_elevation);
    for (auto [az, el] : {std::pair{0.0, 90.0}, {0.0, 45.0}, {0.0, 3.0}, {180.0, 3.0}, {90.0, 10.0}}) {
      const Vec3 dir = direction_from_angles(az, el);
      chain.integrator.radiance(origin, dir, sun, Spectrum::Ones(n), ws, det);
      for (int i = 0; i < n; ++i) {
        const MonteCarloIntegrator mc(MonteCarloMedium::from_atmosphere(chain.atm, i), sun);
        BOOST_TEST_MESSAGE("sun " << sun_elevation << ", view " << az << "/" << el << ", " << nm[size_t(i)] << " nm");
        BOOST_TEST(agrees(mc.radiance(origin, dir, settings, ++stream), det[i], 4.0, 2e-3),
                   "sun " << sun_elevation << " view " << az << "/" << el << " at " << nm[size_t(i)] << " nm");
      }
    }
  }
}

// The estimate depends on the seed, the stream and the number of paths, not on the threads.
BOOST_AUTO_TEST_CASE(results_do_not_depend_on_threads) {
  const MonteCarloIntegrator mc(slab(0.3, 1.0, 0.2, 1.0), Vec3(0.6, 0.0, 0.8));
  MonteCarloSettings one;
  one.paths = 20000;
  one.threads = 1;
  MonteCarloSettings two = one;
  two.threads = 2;
  const MonteCarloValue a = mc.radiance(Vec3(0, 0, 0), Vec3(0, 0, 1), one, 9);
  const MonteCarloValue b = mc.radiance(Vec3(0, 0, 0), Vec3(0, 0, 1), two, 9);
  BOOST_TEST(a.mean == b.mean);
  BOOST_TEST(a.standard_error == b.standard_error);
  MonteCarloSettings other_seed = one;
  other_seed.seed = 2;
  BOOST_TEST(mc.radiance(Vec3(0, 0, 0), Vec3(0, 0, 1), other_seed, 9).mean != a.mean);
  BOOST_TEST(mc.radiance(Vec3(0, 0, 0), Vec3(0, 0, 1), one, 10).mean != a.mean);
}

BOOST_AUTO_TEST_SUITE_END()
