#include <boost/test/unit_test.hpp>

// U.S. Standard Atmosphere 1976, computed from its layer definition, against the values printed
// in the standard (NOAA/NASA/USAF 1976): Table 4 (layer bases, geopotential altitude) and the
// geometric-altitude tables of Part 4.

#include <cmath>
#include <string>

#include "skyspec/error.hpp"
#include "skyspec/standard_atmosphere.hpp"

BOOST_AUTO_TEST_SUITE(test_standard_atmosphere)

using namespace skyspec;

namespace {

/// The standard's tables print 5-7 significant figures; 1e-4 relative checks the physics, not the
/// rounding.
constexpr double kTableTolerance = 1.0e-4;

/// Effective Earth radius of the standard's geopotential, m.
constexpr double kEarthRadius_m = 6356.766e3;

double relative_error(double value, double reference) { return std::abs(value / reference - 1.0); }

/// Geometric altitude (m) of a geopotential altitude (m'): the inverse of H = r0 z / (r0 + z),
/// z = r0 H / (r0 - H).
double geometric_from_geopotential_m(double geopotential_m) {
  return kEarthRadius_m * geopotential_m / (kEarthRadius_m - geopotential_m);
}

AtmosphereState at_geopotential(double geopotential_m) {
  return us_standard_atmosphere_1976(geometric_from_geopotential_m(geopotential_m));
}

}  // namespace

BOOST_AUTO_TEST_CASE(sea_level) {
  const AtmosphereState s = us_standard_atmosphere_1976(0.0);
  BOOST_TEST(s.temperature_K == 288.15, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(s.pressure_Pa == 101325.0, boost::test_tools::tolerance(1e-12));
  // The standard prints N = 2.5470e25 m^-3 (from its own N_A and R*; skyspec uses the SI 2019 k).
  BOOST_TEST(relative_error(s.number_density_per_m3, 2.5470e25) < kTableTolerance);
}

BOOST_AUTO_TEST_CASE(geopotential_conversion) {
  BOOST_TEST(geopotential_altitude_m(0.0) == 0.0);
  // 86 km geometric is the standard's 84.852 km' (top of the defined layers).
  BOOST_TEST(geopotential_altitude_m(86000.0) == 84852.0, boost::test_tools::tolerance(1e-5));
  BOOST_TEST(geometric_from_geopotential_m(geopotential_altitude_m(12345.0)) == 12345.0,
             boost::test_tools::tolerance(1e-12));
}

// Table 4 of the standard: base temperatures and pressures of the layers (geopotential altitude).
BOOST_AUTO_TEST_CASE(layer_bases) {
  struct Base {
    double geopotential_km;
    double temperature_K;
    double pressure_Pa;
  };
  const Base bases[] = {
      {11.0, 216.65, 22632.06}, {20.0, 216.65, 5474.889}, {32.0, 228.65, 868.0187},
      {47.0, 270.65, 110.9063}, {51.0, 270.65, 66.93887}, {71.0, 214.65, 3.956420},
  };
  for (const Base& b : bases) {
    const AtmosphereState s = at_geopotential(b.geopotential_km * 1000.0);
    BOOST_TEST(relative_error(s.temperature_K, b.temperature_K) < 1e-9,
               b.geopotential_km << " km': T " << s.temperature_K);
    BOOST_TEST(relative_error(s.pressure_Pa, b.pressure_Pa) < kTableTolerance,
               b.geopotential_km << " km': P " << s.pressure_Pa << " vs " << b.pressure_Pa);
  }
}

// Geometric-altitude tables of the standard.
BOOST_AUTO_TEST_CASE(geometric_altitude_rows) {
  struct Row {
    double altitude_m;
    double temperature_K;
    double pressure_Pa;
  };
  const Row rows[] = {{5000.0, 255.676, 54048.0}, {10000.0, 223.252, 26500.0}};
  for (const Row& r : rows) {
    const AtmosphereState s = us_standard_atmosphere_1976(r.altitude_m);
    BOOST_TEST(relative_error(s.temperature_K, r.temperature_K) < kTableTolerance,
               r.altitude_m << " m: T " << s.temperature_K);
    BOOST_TEST(relative_error(s.pressure_Pa, r.pressure_Pa) < kTableTolerance,
               r.altitude_m << " m: P " << s.pressure_Pa);
  }
}

// Temperature is continuous at every layer boundary and pressure is continuous and decreasing.
BOOST_AUTO_TEST_CASE(continuity_at_layer_boundaries) {
  const double boundaries_km[] = {11.0, 20.0, 32.0, 47.0, 51.0, 71.0, 84.852};
  const double step_m = 1.0e-3;
  for (double h_km : boundaries_km) {
    const double h_m = h_km * 1000.0;
    const AtmosphereState below = at_geopotential(h_m - step_m);
    const AtmosphereState above = at_geopotential(h_m + step_m);
    BOOST_TEST(std::abs(above.temperature_K - below.temperature_K) < 1e-4, h_km << " km'");
    BOOST_TEST(relative_error(above.pressure_Pa, below.pressure_Pa) < 1e-6, h_km << " km'");
    BOOST_TEST(above.pressure_Pa < below.pressure_Pa);
  }
}

// Hydrostatic balance: dP/dH = -rho g0 = -P M0 g0 / (R* T) at an arbitrary point inside a layer.
BOOST_AUTO_TEST_CASE(hydrostatic_balance) {
  const double g0_m_per_s2 = 9.80665, molar_mass_kg_per_mol = 28.9644e-3, gas_constant = 8.31432;
  for (double h_m : {3000.0, 15000.0, 25000.0, 40000.0, 49000.0, 60000.0, 80000.0}) {
    const double dh_m = 1.0;
    const AtmosphereState s = at_geopotential(h_m);
    const double dp_dh =
        (at_geopotential(h_m + dh_m).pressure_Pa - at_geopotential(h_m - dh_m).pressure_Pa) / (2.0 * dh_m);
    const double expected = -s.pressure_Pa * molar_mass_kg_per_mol * g0_m_per_s2 / (gas_constant * s.temperature_K);
    BOOST_TEST(relative_error(dp_dh, expected) < 1e-6, h_m << " m'");
  }
}

BOOST_AUTO_TEST_CASE(range_ends_and_outside) {
  BOOST_CHECK_NO_THROW(us_standard_atmosphere_1976(-5000.0));
  BOOST_CHECK_NO_THROW(us_standard_atmosphere_1976(100000.0));
  // Below sea level the first layer continues: warmer, denser.
  BOOST_TEST(us_standard_atmosphere_1976(-1000.0).temperature_K > 288.15);
  // Above 84.852 km' the last layer (-2 K/km') continues.
  BOOST_TEST(us_standard_atmosphere_1976(100000.0).temperature_K < us_standard_atmosphere_1976(86000.0).temperature_K);
  for (double bad : {-5000.5, 100000.5, std::nan("")}) {
    try {
      us_standard_atmosphere_1976(bad);
      BOOST_FAIL("altitude " << bad << " was accepted");
    } catch (const InputError& e) {
      BOOST_TEST(e.setting() == "altitude_m");
      BOOST_TEST(e.allowed() == "-5000 to 100000 m");
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()  // test_standard_atmosphere
