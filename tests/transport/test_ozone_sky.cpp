#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>

#include "physics/ozone.hpp"
#include "skyspec/colour.hpp"
#include "skyspec/render.hpp"
#include "skyspec/scene.hpp"
#include "skyspec/units.hpp"
#include "transport/optical_depth.hpp"

BOOST_AUTO_TEST_SUITE(test_ozone_sky)

using namespace skyspec;

namespace {
Scene twilight_scene(bool ozone, double sun_elevation_deg) {
  SceneLoader l("default");
  l.apply_override("atmosphere.ozone.enabled", ozone ? "true" : "false", "test");
  l.apply_override("sun.elevation_deg", std::to_string(sun_elevation_deg), "test");
  l.apply_override("render.scattering_orders", "1", "test");
  l.apply_override("camera.width", "1", "test");
  l.apply_override("camera.height", "1", "test");
  return l.finish();
}
}  // namespace

// The engine's vertical ozone optical depth is the cross-section times the column: the tent
// profile holds exactly column_DU.
BOOST_AUTO_TEST_CASE(vertical_ozone_optical_depth_is_sigma_times_column) {
  const Scene s = twilight_scene(true, 30);
  const WavelengthGrid grid = make_wavelength_grid(s);
  const AtmosphereModel atm(s.atmosphere, grid);
  const Columns c = columns_to_top_m(atm, atm.planet_radius_m(), 1.0, 512);
  BOOST_TEST(atm.media().size() == 3u);  // air, aerosol, ozone: ozone's column is the third
  BOOST_TEST(atm.media()[2].name == "ozone");
  const SpectrumD expected = ozone_vertical_optical_depth_on_grid(grid, 300.0);
  for (int i = 0; i < grid.size(); ++i)
    BOOST_TEST(atm.medium("ozone")->extinction_per_m[i] * c[2] == expected[i], boost::test_tools::tolerance(1e-6));
  // Chappuis band: about 0.04 at 600 nm for 300 DU.
  const int i600 = grid.index_of(600);
  BOOST_TEST(expected[i600] > 0.03);
  BOOST_TEST(expected[i600] < 0.05);
}

// Without ozone a twilight zenith is grey-yellow; ozone's Chappuis absorption along the long,
// grazing sun paths keeps it blue (Hulburt 1953).
BOOST_AUTO_TEST_CASE(ozone_keeps_the_twilight_zenith_blue) {
  for (double el : {-2.0, -4.0}) {
    const SkyRenderer with(twilight_scene(true, el)), without(twilight_scene(false, el));
    const WavelengthGrid& grid = with.grid();
    const Spectrum a = with.radiance(Vec3(0, 0, 1)), b = without.radiance(Vec3(0, 0, 1));
    const SpectrumToXyz xyz(grid);
    const Eigen::Vector2d xy_with = xy_chromaticity(xyz(a));
    const Eigen::Vector2d xy_without = xy_chromaticity(xyz(b));
    BOOST_TEST_MESSAGE("sun " << el << " deg: zenith xy with ozone " << xy_with.transpose() << ", without "
                              << xy_without.transpose());
    BOOST_TEST(xy_with.x() < xy_without.x() - 0.01);
    BOOST_TEST(xy_with.y() < xy_without.y());
    // Absorption only removes light.
    for (Eigen::Index i = 0; i < a.size(); ++i) BOOST_TEST(a[i] <= b[i] * 1.0001f);
  }
}

BOOST_AUTO_TEST_SUITE_END()  // test_ozone_sky
