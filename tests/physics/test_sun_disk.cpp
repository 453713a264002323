#include <boost/test/unit_test.hpp>

#include <cmath>

#include "physics/sun_disk.hpp"
#include "skyspec/units.hpp"

BOOST_AUTO_TEST_SUITE(test_sun_disk)

using namespace skyspec;

BOOST_AUTO_TEST_CASE(angular_radius_at_one_au) {
  // 0.2666 degrees (physics.md; 959.63 arcsec in the astronomical almanac).
  BOOST_TEST(radians_to_degrees(sun_angular_radius_rad(1.0)) == 0.2666, boost::test_tools::tolerance(1e-3));
  // Perihelion (0.9833 au) makes it larger.
  BOOST_TEST(sun_angular_radius_rad(0.9833) > sun_angular_radius_rad(1.0167));
}

BOOST_AUTO_TEST_CASE(limb_darkening_exponent_branches) {
  BOOST_TEST(limb_darkening_exponent(500) == -0.023 + 0.292 / 0.5, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(limb_darkening_exponent(400) == -0.507 + 0.441 / 0.4, boost::test_tools::tolerance(1e-12));
  // Stronger darkening in the blue.
  BOOST_TEST(limb_darkening_exponent(450) > limb_darkening_exponent(700));
}

// The disk's radiance integrates over its solid angle to the irradiance (unit here).
BOOST_AUTO_TEST_CASE(disk_integrates_to_the_irradiance) {
  const WavelengthGrid grid = WavelengthGrid::from_list({380, 450, 550, 700, 830});
  const double theta = sun_angular_radius_rad(1.0);
  Spectrum sum = Spectrum::Zero(grid.size()), L;
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    const double x = (k + 0.5) / n;  // rings of the disk
    disk_radiance_per_irradiance(grid, theta, x, L);
    sum += L * static_cast<float>(2 * kPi * x * theta * theta / n);
  }
  for (int i = 0; i < grid.size(); ++i)
    BOOST_TEST(static_cast<double>(sum[i]) == 1.0, boost::test_tools::tolerance(2e-3));
  disk_radiance_per_irradiance(grid, theta, 1.5, L);
  BOOST_TEST(L.maxCoeff() == 0.0f);
}

BOOST_AUTO_TEST_SUITE_END()  // test_sun_disk
