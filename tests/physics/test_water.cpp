// Water: IAPWS R9-97's own check value of the refractive index, its dispersion and temperature
// dependence, Kell's density of liquid water, and values outside the formulas' ranges.

#include <boost/test/unit_test.hpp>

#include <cmath>

#include "skyspec/error.hpp"
#include "skyspec/water.hpp"

BOOST_AUTO_TEST_SUITE(test_water)

using namespace skyspec;

// The release's verification value (IAPWS R9-97, Table 3): T = 298.15 K, rho = 997.047435 kg m^-3,
// lambda = 589.3 nm -> n = 1.3328581926.
BOOST_AUTO_TEST_CASE(iapws_check_value) {
  BOOST_TEST(std::abs(water_refractive_index(298.15, 997.047435, 589.3) - 1.3328581926) < 1e-9);
}

// Normal dispersion across the visible (n falls from about 1.343 at 400 nm to 1.331 at 700 nm),
// and n falls as warm water expands.
BOOST_AUTO_TEST_CASE(dispersion_and_temperature) {
  const double rho = liquid_water_density_kg_per_m3(293.15);
  double previous = 10.0;
  for (double nm = 400.0; nm <= 700.0; nm += 50.0) {
    const double n = water_refractive_index(293.15, rho, nm);
    BOOST_TEST(n < previous);
    previous = n;
  }
  BOOST_TEST(std::abs(water_refractive_index(293.15, rho, 400.0) - 1.343) < 2e-3);
  BOOST_TEST(std::abs(water_refractive_index(293.15, rho, 700.0) - 1.331) < 2e-3);
  BOOST_TEST(water_refractive_index(353.15, liquid_water_density_kg_per_m3(353.15), 550.0) <
             water_refractive_index(283.15, liquid_water_density_kg_per_m3(283.15), 550.0));
}

// Kell 1975: 999.8395 kg m^-3 at 0 degC, the maximum 999.972 at 4 degC; at 25 degC within
// 0.003 of IAPWS-95's 997.047 (the check value's density above).
BOOST_AUTO_TEST_CASE(density_of_liquid_water) {
  BOOST_TEST(std::abs(liquid_water_density_kg_per_m3(273.15) - 999.8395) < 1e-4);
  const double at4 = liquid_water_density_kg_per_m3(277.13);
  BOOST_TEST(std::abs(at4 - 999.972) < 1e-3);
  BOOST_TEST(at4 > liquid_water_density_kg_per_m3(276.15));
  BOOST_TEST(at4 > liquid_water_density_kg_per_m3(278.15));
  BOOST_TEST(std::abs(liquid_water_density_kg_per_m3(298.15) - 997.047435) < 3e-3);
}

BOOST_AUTO_TEST_CASE(outside_the_ranges) {
  BOOST_CHECK_THROW(water_refractive_index(200.0, 1000.0, 550.0), InputError);
  BOOST_CHECK_THROW(water_refractive_index(293.15, 1100.0, 550.0), InputError);
  BOOST_CHECK_THROW(water_refractive_index(293.15, 998.0, 1500.0), InputError);
  BOOST_CHECK_THROW(liquid_water_density_kg_per_m3(263.15), InputError);
  try {
    water_refractive_index(293.15, 998.0, 150.0);
    BOOST_FAIL("no error");
  } catch (const InputError& e) {
    BOOST_TEST(e.setting() == "wavelength_nm");
  }
}

BOOST_AUTO_TEST_SUITE_END()
