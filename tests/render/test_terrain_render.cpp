// The renderer with terrain: directions the terrain's shadow crosses, from the sky-view table less
// the shadowed light of order 1 (render.cpp, table_less_shadows), against the same rays marched
// (render.sky_view_table = false); the sun's disk hidden behind the ridge; the camera's direct
// irradiance in its shadow.

#include <boost/test/unit_test.hpp>

#include <cstdio>

#include "scene_fixtures.hpp"
#include "skyspec/camera.hpp"
#include "skyspec/render.hpp"

BOOST_AUTO_TEST_SUITE(test_terrain_render)

using namespace skyspec;

namespace {
Scene ridge_scene(bool sky_view_table) {
  char toml[512];
  std::snprintf(toml, sizeof toml,
                "[sun]\nelevation_deg = 3\nazimuth_deg = 270\n[spectrum]\nwavelengths_nm = [450, 550, 650]\n"
                "[terrain]\nmodel = \"ridge\"\nridge.notch_spacing_m = 6000\n[ground]\nalbedo = 0.3\n"
                "[camera]\nposition_m = [0, 0, 300]\nwidth = 1\nheight = 1\n"
                "[render]\nscattering_orders = 1\nsky_view_table = %s\n",
                sky_view_table ? "true" : "false");
  return test::scene_with(toml, "default");
}
}  // namespace

BOOST_AUTO_TEST_CASE(shadowed_directions_from_the_table_match_marching) {
  const SkyRenderer table(ridge_scene(true)), marched(ridge_scene(false));
  int compared = 0;
  for (double az : {0.0, 30.0, 150.0, 200.0, 330.0})
    for (double el : {-3.0, 0.5, 2.0, 6.0}) {
      const Vec3 d = direction_from_angles(az, el);
      const Spectrum a = table.radiance(d), b = marched.radiance(d);
      for (int i = 0; i < 3; ++i) {
        // The sky-view table's own interpolation error (docs/performance.md: up to 0.66 %).
        BOOST_TEST(a[i] == b[i], boost::test_tools::tolerance(0.01f));
        ++compared;
      }
    }
  BOOST_TEST(compared == 60);
  // The shadows matter: the open sky is brighter.
  Scene open = ridge_scene(true);
  open.terrain.model = TerrainSpec::Model::None;
  const SkyRenderer sky(open);
  // South-south-west, 0.5 degrees up: past the ridge's southern end, through its shadows.
  const Vec3 past = direction_from_angles(200.0, 0.5);
  BOOST_TEST(table.radiance(past)[1] < 0.9f * sky.radiance(past)[1]);
}

BOOST_AUTO_TEST_CASE(the_ridge_hides_the_sun) {
  const SkyRenderer r(ridge_scene(true));
  BOOST_TEST(r.transmittance(r.sun_direction()).maxCoeff() == 0.0f);
  Scene open = ridge_scene(true);
  open.terrain.model = TerrainSpec::Model::None;
  const SkyRenderer sky(open);
  BOOST_TEST(sky.transmittance(sky.sun_direction()).minCoeff() > 0.0f);
}

BOOST_AUTO_TEST_SUITE_END()
