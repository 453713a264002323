#include <boost/test/unit_test.hpp>

#include <cmath>
#include <memory>
#include <random>
#include <utility>
#include <vector>

#include "atmosphere_fixtures.hpp"
#include "skyspec/rayleigh.hpp"
#include "skyspec/standard_atmosphere.hpp"
#include "skyspec/units.hpp"
#include "transport/optical_depth.hpp"

BOOST_AUTO_TEST_SUITE(test_optical_depth)

using namespace skyspec;

namespace {
constexpr double R = 6360e3, top = 60e3;
}

// Vertical column of an exponential atmosphere from the ground: H (1 - exp(-top / H)).
BOOST_AUTO_TEST_CASE(vertical_column_of_exponential_profile) {
  for (double H : {8000.0, 1200.0, 7994.0}) {
    const DensityProfile p = DensityProfile::exponential(H);
    const double expected = H * (1 - std::exp(-top / H));
    BOOST_TEST(column_to_top_m(p, R, R + top, R, 1.0, 16) == expected, boost::test_tools::tolerance(1e-10));
    // From altitude z: H exp(-z/H) (1 - exp(-(top - z) / H)).
    const double z = 3000;
    const double from_z = H * std::exp(-z / H) * (1 - std::exp(-(top - z) / H));
    BOOST_TEST(column_to_top_m(p, R, R + top, R + z, 1.0, 16) == from_z, boost::test_tools::tolerance(1e-10));
  }
}

// A homogeneous shell: the column is the geometric path length.
BOOST_AUTO_TEST_CASE(constant_profile_column_is_path_length) {
  const DensityProfile p = DensityProfile::constant();
  const double horizontal = std::sqrt((R + top) * (R + top) - R * R);
  BOOST_TEST(column_to_top_m(p, R, R + top, R, 0.0, 64) == horizontal, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(column_to_top_m(p, R, R + top, R + 500, 1.0, 4) == top - 500, boost::test_tools::tolerance(1e-12));
}

// Along a slanted path the rule converges: 64 and 4096 segments agree to 1e-6 even for a ray
// that descends to its lowest point first.
BOOST_AUTO_TEST_CASE(slant_column_converges) {
  const DensityProfile p = DensityProfile::exponential(8000);
  for (double mu : {0.5, 0.05, 0.0, -0.02}) {
    const double r = R + 2000;
    const double coarse = column_to_top_m(p, R, R + top, r, mu, 64);
    const double fine = column_to_top_m(p, R, R + top, r, mu, 4096);
    BOOST_TEST(coarse == fine, boost::test_tools::tolerance(1e-5));
  }
}

// A cloud layer (DensityProfile::layer: 1 from 8 to 10 km, edges falling by e every 500 m): ln rho
// piecewise linear; its vertical columns in closed form with a few segments (the rays are split at
// the base and the top), slanted and grazing columns converged with 64 segments (1e-4).
BOOST_AUTO_TEST_CASE(layer_profile_columns) {
  const double b = 8000, t = 10000, w = 500;
  const DensityProfile p = DensityProfile::layer(b, t, w);
  BOOST_TEST(p.log_relative(b - w) == -1.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(p.log_relative(t + 2 * w) == -2.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(p.log_relative(9000) == 0.0);
  BOOST_TEST(p.relative(9500) == 1.0);
  BOOST_TEST(p.positive_everywhere());
  const double above = w * -std::expm1(-(top - t) / w);
  BOOST_TEST(column_to_top_m(p, R, R + top, R, 1.0, 16) == w * -std::expm1(-b / w) + (t - b) + above,
             boost::test_tools::tolerance(1e-10));
  BOOST_TEST(p.layer_column_m() == w * -std::expm1(-b / w) + (t - b) + w, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(column_to_top_m(p, R, R + top, R + 9000, 1.0, 16) == (t - 9000) + above,
             boost::test_tools::tolerance(1e-10));
  // From the ground, from inside (level and descending: it crosses the layer's base twice ahead)
  // and from above it.
  const std::pair<double, double> rays[] = {{0.0, 0.5}, {0.0, 0.05}, {9000.0, 0.0}, {9000.0, -0.03}, {20000.0, -0.06}};
  for (const auto& [z, mu] : rays) {
    const double coarse = column_to_top_m(p, R, R + top, R + z, mu, 64);
    const double fine = column_to_top_m(p, R, R + top, R + z, mu, 16384);
    BOOST_TEST(coarse == fine, boost::test_tools::tolerance(1e-4));
    BOOST_TEST(fine > 1000.0);
  }
}

// The table reproduces direct integration wherever the sun is above the horizon.
BOOST_AUTO_TEST_CASE(table_matches_direct_integration) {
  const AtmosphereModel atm(test::simple_atmosphere(ProfileKind::Exponential, top, {550}, {13.5e-6}, 21e-6),
                            WavelengthGrid::from_list({550}));
  const SunColumnTable table(atm, {256, 512, 128});
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  double worst_transmittance_error = 0;
  for (int i = 0; i < 2000; ++i) {
    const double r = R + top * u(rng) * u(rng);  // denser near the ground
    const double mu_horizon = -std::sqrt(1 - (R / r) * (R / r));
    const double mu = mu_horizon + (1 - mu_horizon) * u(rng);
    const Columns direct = columns_to_top_m(atm, r, mu, 2048);
    const Columns tab = table.lookup(r, mu);
    // Compare what matters: the transmittance at the most extinguished wavelength.
    const double tau_direct = 13.5e-6 * direct[0] + 23.1e-6 * direct[1];
    const double tau_table = 13.5e-6 * tab[0] + 23.1e-6 * tab[1];
    worst_transmittance_error =
        std::max(worst_transmittance_error, std::abs(std::exp(-tau_direct) - std::exp(-tau_table)));
  }
  BOOST_TEST(worst_transmittance_error < 1e-3);
}

// The Rayleigh optical depth of the U.S. Standard Atmosphere column at 550 nm lands near
// Bodhaine et al.'s hydrostatic 0.09707. The standard's column is integrated over geometric
// altitude with a gravity that falls with height, so its column is ~0.3 % larger than a
// constant-g hydrostatic column; the 0.1 % check of the cross-section itself is in test_rayleigh.
BOOST_AUTO_TEST_CASE(us1976_vertical_optical_depth_near_bodhaine) {
  const DensityProfile p = DensityProfile::us_standard_1976(100e3);
  const double n0 = us_standard_atmosphere_1976(0).number_density_per_m3;
  const double column_per_m2 = n0 * column_to_top_m(p, R, R + 100e3, R, 1.0, 4000);
  RayleighDerivationInput bodhaine;
  bodhaine.co2_ppv = 3.6e-4;
  const double sigma = rayleigh_cross_section_m2(550, bodhaine);
  BOOST_TEST(sigma * column_per_m2 == 0.09707, boost::test_tools::tolerance(5e-3));
  // And the column itself is what the standard's sea-level pressure holds up: P0 N_A / (M0 g0).
  const double hydrostatic = 101325.0 * constants::kAvogadro_per_mol / (28.9644e-3 * 9.80665);
  BOOST_TEST(column_per_m2 > hydrostatic);
  BOOST_TEST(column_per_m2 < hydrostatic * 1.005);
}

BOOST_AUTO_TEST_CASE(log_mean_limits) {
  BOOST_TEST(log_mean(2.0, 2.0, 0.0) == 2.0);
  const double a = 3.0, b = 1.0;
  BOOST_TEST(log_mean(a, b, std::log(a / b)) == (a - b) / std::log(a / b), boost::test_tools::tolerance(1e-14));
  const double c = 1.0 + 1e-5;
  BOOST_TEST(log_mean(c, 1.0, std::log(c)) == (c - 1.0) / std::log(c), boost::test_tools::tolerance(1e-12));
}

// A table restricted to the sun angles met in the air a camera sees, a band that widens with
// altitude: the same values as the whole table wherever a ray from the camera goes (it is the
// same grid), a fraction of the entries (cameras at 1 m and 2 km: 3 % for a sun at 30 degrees,
// 12-18 % at 10, half to three quarters at 2: the rows crowd towards the horizon), and look-ups
// outside the band computed directly rather than read from missing entries.
BOOST_AUTO_TEST_CASE(banded_table_serves_the_camera_exactly) {
  const AtmosphereModel atm(test::simple_atmosphere(ProfileKind::Exponential, top, {550}, {13.5e-6}, 21e-6),
                            WavelengthGrid::from_list({550}));
  const SunColumnTable::Resolution res{128, 256, 64};
  const SunColumnTable whole(atm, res);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  for (double height : {1.0, 2000.0})
    for (double sun_el : {30.0, 10.0, 2.0, -3.0}) {
      const Vec3 o(0, 0, R + height);
      const double e = degrees_to_radians(sun_el);
      const Vec3 s(std::cos(e), 0, std::sin(e));
      const SunColumnTable banded(atm, res, SunColumnTable::band_seen_from(atm, o, s));
      BOOST_TEST_MESSAGE("camera " << height << " m, sun " << sun_el << " deg: " << banded.computed_entries() << " of "
                                   << whole.computed_entries() << " entries");
      // The table's rows crowd towards the horizon, so a low sun's band still holds most of them.
      BOOST_TEST(banded.computed_entries() <
                 (sun_el >= 10.0 ? whole.computed_entries() / 2 : whole.computed_entries()));
      int differ = 0, points = 0;
      for (int i = 0; i < 3000; ++i) {  // points along random rays from the camera, up to the ground or the top
        const double z = 2 * u(rng) - 1, phi = 2 * M_PI * u(rng);
        const Vec3 d(std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z);
        const SphereHit ground = intersect_sphere(o, d, R), sky = intersect_sphere(o, d, R + top);
        const double t_end = ground.hit && ground.t_near_m > 0 ? ground.t_near_m : sky.t_far_m;
        const Vec3 p = o + u(rng) * t_end * d;
        const double r = p.norm(), mu = p.dot(s) / r;
        const Columns a = banded.lookup(r, mu), b = whole.lookup(r, mu);
        differ += a != b;
        ++points;
      }
      BOOST_TEST(differ == 0, differ << " of " << points << " look-ups differ from the whole table's");
      // Out of the band (the sun overhead at the camera's foot): integrated directly, close to the table.
      const Columns direct = columns_to_top_m(atm, R, 1.0, 64), out_of_band = banded.lookup(R, 1.0);
      for (int k = 0; k < 2; ++k) BOOST_TEST(out_of_band[k] == direct[k], boost::test_tools::tolerance(1e-12));
    }
}

// Renders of the same air share one table (SunColumnTable::shared), and a shared table keeps what
// it integrates with: a banded table's look-ups out of its band still work after the atmosphere it
// was built from is gone.
BOOST_AUTO_TEST_CASE(shared_tables_are_one_per_air_and_outlive_their_atmosphere) {
  const WavelengthGrid grid = WavelengthGrid::from_list({550});
  const SunColumnTable::Resolution res{32, 64, 32};
  const Vec3 o(0, 0, R + 1.0), s(std::cos(0.5), 0, std::sin(0.5));
  std::shared_ptr<const SunColumnTable> banded, whole;
  {
    const AtmosphereModel atm(test::simple_atmosphere(ProfileKind::Exponential, top, {550}, {13.5e-6}, 21e-6), grid);
    banded = SunColumnTable::shared(atm, res, SunColumnTable::band_seen_from(atm, o, s));
    whole = SunColumnTable::shared(atm, res, SunColumnTable::MuBand{});
    BOOST_TEST(banded != whole);
    BOOST_TEST(banded.get() == SunColumnTable::shared(atm, res, SunColumnTable::band_seen_from(atm, o, s)).get());
    BOOST_TEST(whole.get() == SunColumnTable::shared(atm, res, SunColumnTable::MuBand{}).get());
    const SunColumnTable fresh(atm, res);
    BOOST_TEST(whole->lookup(R + 500.0, 0.3) == fresh.lookup(R + 500.0, 0.3));
    BOOST_TEST(whole.get() != SunColumnTable::shared(atm, SunColumnTable::Resolution{32, 64, 16}, {}).get());
  }
  const AtmosphereModel same(test::simple_atmosphere(ProfileKind::Exponential, top, {550}, {13.5e-6}, 21e-6), grid);
  BOOST_TEST(whole.get() == SunColumnTable::shared(same, res, SunColumnTable::MuBand{}).get());
  const Columns out_of_band = banded->lookup(R, 1.0), direct = columns_to_top_m(same, R, 1.0, res.segments);
  for (int k = 0; k < 2; ++k) BOOST_TEST(out_of_band[k] == direct[k], boost::test_tools::tolerance(1e-12));
  const AtmosphereModel other(test::simple_atmosphere(ProfileKind::Constant, top, {550}, {13.5e-6}, 21e-6), grid);
  BOOST_TEST(whole.get() != SunColumnTable::shared(other, res, SunColumnTable::MuBand{}).get());
}

// The batched look-up (vectorised coordinates, then interpolation) gives lookup()'s values, in
// the band, out of it (computed directly) and below the horizon, across its chunks of 64 points:
// the same to rounding (the compiler may fuse multiply-adds differently in vector code).
BOOST_AUTO_TEST_CASE(lookup_many_equals_lookup) {
  const AtmosphereModel atm(test::simple_atmosphere(ProfileKind::Exponential, top, {550}, {13.5e-6}, 21e-6),
                            WavelengthGrid::from_list({550}));
  const Vec3 o(0, 0, R + 1.0);
  const double e = degrees_to_radians(10.0);
  const SunColumnTable banded(atm, SunColumnTable::Resolution{128, 256, 64},
                              SunColumnTable::band_seen_from(atm, o, Vec3(std::cos(e), 0, std::sin(e))));
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  const int n = 200;  // three full chunks and a partial one
  std::vector<double> r(n), mu(n);
  for (int i = 0; i < n; ++i) {
    r[i] = R - 10.0 + (top + 20.0) * u(rng);  // a little outside [R, R_t] too (clamped)
    mu[i] = 2 * u(rng) - 1;                   // in and out of the band, below the horizon too
  }
  std::vector<Columns> many(n);
  banded.lookup_many(n, r.data(), mu.data(), many.data());
  double worst = 0.0;
  for (int i = 0; i < n; ++i) {
    const Columns one = banded.lookup(r[i], mu[i]);
    for (int k = 0; k < 2; ++k) worst = std::max(worst, std::abs(many[i][k] - one[k]) / one[k]);
  }
  BOOST_TEST_MESSAGE("batched vs single look-ups: largest relative difference " << worst);
  BOOST_TEST(worst < 1e-12);
}

BOOST_AUTO_TEST_SUITE_END()  // test_optical_depth
