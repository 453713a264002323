// Camera heights at the edges of the geometry, as properties (issue 42, item 1): exactly on the
// ground (0, -0, 1e-300 m, which is 0 once added to the planet's radius), a nanometre above it,
// the top of the atmosphere and above it, for every camera type, with the higher orders and their
// sky-view table: every render is finite (a camera at height 0 used to crash in the tables'
// look-up: its rays below the horizontal entered the planet at t = 0 and ran through it), the
// ground seen from height 0 is the ground seen from 1 mm, and a camera inside the planet is refused.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>
#include <string>

#include "check_helpers.hpp"
#include "scene_fixtures.hpp"
#include "skyspec/camera_spec.hpp"
#include "skyspec/error.hpp"
#include "skyspec/geometry.hpp"
#include "skyspec/render.hpp"
#include "skyspec/scene.hpp"

BOOST_AUTO_TEST_SUITE(test_camera_heights)

using namespace skyspec;

namespace {
Scene small_scene(const std::string& type, const std::string& height) {
  SceneLoader l;
  l.apply_quality("draft");
  l.apply_override("camera.type", "\"" + type + "\"", "test");
  l.apply_override("camera.width", "8", "test");
  l.apply_override("camera.height", "6", "test");
  l.apply_override("camera.position_m", "[0, 0, " + height + "]", "test");
  if (type == "perspective") l.apply_override("camera.look_at_m", "[0, 1000, -100]", "test");  // down a little
  l.apply_override("sun.elevation_deg", "20", "test");
  return l.finish();
}
}  // namespace

BOOST_AUTO_TEST_CASE(every_camera_at_the_edges_of_the_air_renders_finite_values) {
  for (const char* height : {"0.0", "-0.0", "1e-300", "1e-9", "60000.0", "100000.0"})
    for (const auto& type : camera_types()) {
      BOOST_TEST_CONTEXT(type.name << " at " << height << " m") {
        const SpectralImageBuffer image = render_to_memory(small_scene(type.name, height));
        bool finite = true;
        for (float v : image.spectral) finite = finite && std::isfinite(v) && v >= 0.0f;
        BOOST_TEST(finite);
      }
    }
}

BOOST_AUTO_TEST_CASE(the_ground_from_height_zero_is_the_ground_from_a_millimetre) {
  const SpectralImageBuffer at0 = render_to_memory(small_scene("equirectangular", "0.0"));
  const SpectralImageBuffer at1mm = render_to_memory(small_scene("equirectangular", "0.001"));
  double worst = 0.0;
  for (size_t i = 0; i < at0.spectral.size(); ++i)
    worst = std::max(
        worst, std::abs(double(at0.spectral[i]) - at1mm.spectral[i]) / std::max(1e-12, double(at1mm.spectral[i])));
  BOOST_TEST(worst < 1e-4);
  // The bottom row looks at the ground: it is lit (the sun is up, the default ground reflects).
  BOOST_TEST(at0.spectral[(5 * 8 + 3) * at0.wavelengths_nm.size() + 20] > 0.0f);
}

BOOST_AUTO_TEST_CASE(a_camera_inside_the_planet_is_refused) {
  try {
    small_scene("fisheye", "-1e-3");
    BOOST_FAIL("no error");
  } catch (const InputError& e) {
    BOOST_TEST(e.setting() == "camera.position_m");
    BOOST_TEST(test::contains(e.what(), "below it"));
  }
}

BOOST_AUTO_TEST_CASE(rays_from_the_ground_enter_it_at_once_when_they_point_down) {
  const double R = 6360e3;
  const Vec3 on(0.0, 0.0, R);
  const double inf = std::numeric_limits<double>::infinity();
  BOOST_TEST(sphere_entry_distance(on, Vec3(0.0, 0.6, -0.8), R) == 0.0);
  BOOST_TEST(sphere_entry_distance(on, Vec3(0.0, 0.6, 0.8), R) == inf);
  BOOST_TEST(sphere_entry_distance(on, Vec3(0.0, 1.0, 0.0), R) == inf);  // along the horizontal
  BOOST_TEST(std::abs(sphere_entry_distance(Vec3(0.0, 0.0, R + 10.0), Vec3(0.0, 0.0, -1.0), R) - 10.0) < 1e-6);
  BOOST_TEST(sphere_entry_distance(Vec3(0.0, 0.0, R - 1.0), Vec3(0.0, 0.0, 1.0), R) == 0.0);  // inside
}

BOOST_AUTO_TEST_SUITE_END()
