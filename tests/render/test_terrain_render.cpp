// The renderer with terrain: directions the terrain's shadow crosses, from the sky-view table less
// the shadowed light of order 1 (render.cpp, table_less_shadows), against the same rays marched
// (render.sky_view_table = false); the sun's disk hidden behind the ridge; the camera's direct
// irradiance in its shadow.

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstdio>

#include "render/surface_pass.hpp"
#include "scene/scene_terrain.hpp"
#include "scene_fixtures.hpp"
#include "skyspec/camera.hpp"
#include "skyspec/geometry.hpp"
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

// output.surface (render/surface_pass.hpp): each pixel's distance to the surface its ray ends on
// and which surface that is, against the terrain's and the sphere's own intersections; the sky 0.
BOOST_AUTO_TEST_CASE(surface_channels_give_distance_and_masks) {
  Scene scene = ridge_scene(true);
  scene.camera.type = CameraSpec::Type::Equirectangular;
  scene.camera.width = 72;
  scene.camera.height = 36;
  const std::vector<float> c = surface_channels(scene);
  const auto camera = make_camera(scene);
  const auto terrain = scene_terrain(scene);
  const Vec3 o = camera->origin_m();
  int on_terrain = 0, on_ground = 0, sky = 0;
  for (int y = 0; y < 36; ++y)
    for (int x = 0; x < 72; ++x) {
      Vec3 d;
      BOOST_REQUIRE(camera->direction(x + 0.5, y + 0.5, d));
      const float* px = &c[(static_cast<size_t>(y) * 72 + static_cast<size_t>(x)) * 3];
      const double ground = sphere_entry_distance(o, d, scene.atmosphere.planet_radius_m);
      const double t = terrain->intersect(o, d, 0.0, std::isfinite(ground) ? ground : 4.0e6);
      BOOST_TEST_CONTEXT("pixel " << x << ", " << y) {
        if (std::isfinite(t)) {
          ++on_terrain;
          BOOST_TEST(px[0] == t, boost::test_tools::tolerance(1e-6));
          BOOST_TEST((px[1] == 1.0f && px[2] == 0.0f));
        } else if (std::isfinite(ground)) {
          ++on_ground;
          BOOST_TEST(px[0] == ground, boost::test_tools::tolerance(1e-6));
          BOOST_TEST((px[1] == 0.0f && px[2] == 1.0f));
        } else {
          ++sky;
          BOOST_TEST((px[0] == 0.0f && px[1] == 0.0f && px[2] == 0.0f));
        }
      }
    }
  // The ridge 20 km west fills a few pixels; the ground the lower half; the sky the upper.
  BOOST_TEST(on_terrain > 0);
  BOOST_TEST(on_ground > 0);
  BOOST_TEST(sky > 0);
  // Looking straight at the ridge: about 20 km less its half-width.
  const Vec3 west = direction_from_angles(270.0, 1.0);
  const double t = terrain->intersect(o, west, 0.0, 4.0e6);
  BOOST_TEST((t > 15000.0 && t < 21000.0));
}

BOOST_AUTO_TEST_SUITE_END()
