// Cameras (camera.hpp): each projection maps pixels to the directions its definition gives.
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <stdexcept>

#include "skyspec/camera.hpp"
#include "skyspec/units.hpp"

BOOST_AUTO_TEST_SUITE(test_camera)

using namespace skyspec;

namespace {
const double kR = 6360e3;
const Vec3 kOrigin(0.0, 0.0, kR + 1.0);  // 1 m above the reference point: local up is +z

double elevation_deg(const Vec3& d) { return radians_to_degrees(std::asin(d.z())); }
// Clockwise from north (+y) towards east (+x).
double azimuth_deg(const Vec3& d) {
  const double a = radians_to_degrees(std::atan2(d.x(), d.y()));
  return a < 0.0 ? a + 360.0 : a;
}
}  // namespace

BOOST_AUTO_TEST_CASE(direction_from_angles_is_east_north_up) {
  BOOST_TEST((direction_from_angles(0.0, 0.0) - Vec3(0, 1, 0)).norm() < 1e-12);   // north
  BOOST_TEST((direction_from_angles(90.0, 0.0) - Vec3(1, 0, 0)).norm() < 1e-12);  // east
  BOOST_TEST((direction_from_angles(0.0, 90.0) - Vec3(0, 0, 1)).norm() < 1e-12);  // zenith
}

BOOST_AUTO_TEST_CASE(fisheye_centre_is_the_zenith_and_the_circle_the_horizon) {
  const FisheyeCamera cam(100, 100, kOrigin);
  Vec3 d;
  BOOST_TEST(cam.direction(50.0, 50.0, d));
  BOOST_TEST(elevation_deg(d) == 90.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(cam.direction(100.0 - 1e-9, 50.0, d));  // right edge of the circle: the horizon
  BOOST_TEST(std::fabs(elevation_deg(d)) < 1e-3);
  BOOST_TEST(!cam.direction(1.0, 1.0, d));  // a corner is outside the circle
  // Equal area: zenith angle acos(1 - r^2), so r^2 = 1/2 is 60 degrees from the zenith.
  BOOST_TEST(cam.direction(50.0 + 50.0 * std::sqrt(0.5), 50.0, d));
  BOOST_TEST(elevation_deg(d) == 30.0, boost::test_tools::tolerance(1e-9));
}

BOOST_AUTO_TEST_CASE(perspective_centre_looks_at_the_target) {
  const Vec3 target(0.0, 1000.0, kR + 1.0);
  const PerspectiveCamera cam(64, 48, kOrigin, target, 60.0);
  Vec3 d;
  BOOST_TEST(cam.direction(32.0, 24.0, d));
  BOOST_TEST((d - (target - kOrigin).normalized()).norm() < 1e-12);
  BOOST_TEST(cam.direction(32.0, 0.0, d));  // top edge: half the vertical field of view up
  BOOST_TEST(elevation_deg(d) == 30.0, boost::test_tools::tolerance(1e-9));
}

BOOST_AUTO_TEST_CASE(equirectangular_full_sphere_spans_plus_to_minus_90) {
  const EquirectangularCamera cam(360, 180, kOrigin);
  Vec3 d;
  BOOST_TEST(cam.direction(90.0, 0.0, d));  // top edge, a quarter of the way: zenith
  BOOST_TEST(elevation_deg(d) == 90.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(cam.direction(90.0, 90.0, d));  // middle row: the horizon, due east
  BOOST_TEST(std::fabs(elevation_deg(d)) < 1e-9);
  BOOST_TEST(azimuth_deg(d) == 90.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(cam.direction(180.0, 135.0, d));  // three quarters down: 45 degrees below, due south
  BOOST_TEST(elevation_deg(d) == -45.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(azimuth_deg(d) == 180.0, boost::test_tools::tolerance(1e-9));
}

BOOST_AUTO_TEST_CASE(equirectangular_upper_hemisphere_ends_at_the_horizon) {
  const EquirectangularCamera cam(360, 90, kOrigin, 0.0);
  Vec3 d;
  BOOST_TEST(cam.direction(0.0, 0.0, d));
  BOOST_TEST(elevation_deg(d) == 90.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(cam.direction(270.0, 45.0, d));  // halfway down: 45 degrees, due west
  BOOST_TEST(elevation_deg(d) == 45.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(azimuth_deg(d) == 270.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(cam.direction(10.0, 90.0, d));  // bottom edge: the horizon
  BOOST_TEST(std::fabs(elevation_deg(d)) < 1e-9);
  // Every pixel centre is above the horizon: one degree per row, the last centre at 0.5 degrees.
  BOOST_TEST(cam.direction(10.0, 89.5, d));
  BOOST_TEST(elevation_deg(d) == 0.5, boost::test_tools::tolerance(1e-9));
  // Rows of the same elevation in the full-sphere image have the same direction.
  const EquirectangularCamera full(360, 180, kOrigin);
  Vec3 e;
  BOOST_TEST(full.direction(123.5, 30.5, e));
  BOOST_TEST(cam.direction(123.5, 30.5, d));
  BOOST_TEST((d - e).norm() < 1e-12);
}

BOOST_AUTO_TEST_CASE(equirectangular_rejects_an_empty_elevation_range) {
  BOOST_CHECK_THROW(EquirectangularCamera(8, 8, kOrigin, 90.0), std::invalid_argument);
  BOOST_CHECK_THROW(EquirectangularCamera(8, 8, kOrigin, -91.0), std::invalid_argument);
}

// The closed-form lowest cosine to a direction u is a bound for every pixel's direction, and a
// tight one: within a pixel's angle of the lowest pixel (u vertical, tilted, upside down).
BOOST_AUTO_TEST_CASE(lowest_cosine_bounds_the_pixels) {
  const Vec3 origin(0, 0, 6360e3);
  const FisheyeCamera fisheye(96, 96, origin);
  const EquirectangularCamera hemisphere(128, 32, origin, 0.0), band(128, 48, origin, -20.0), sphere(128, 64, origin);
  const PerspectiveCamera perspective(32, 24, origin, origin + Vec3(1000, 0, 100), 60.0);
  BOOST_TEST(!perspective.lowest_cosine_to(Vec3(0, 0, 1)).has_value());
  for (const Vec3& u :
       {Vec3(0, 0, 1), Vec3(0.3, -0.2, 0.9).normalized(), Vec3(1, 0, 0), Vec3(0.1, 0.2, -0.97).normalized()})
    for (const Camera* camera : std::initializer_list<const Camera*>{&fisheye, &hemisphere, &band, &sphere}) {
      double lowest = 2.0;
      for (int y = 0; y < camera->height(); ++y)
        for (int x = 0; x < camera->width(); ++x) {
          Vec3 d;
          if (camera->direction(x + 0.5, y + 0.5, d)) lowest = std::min(lowest, d.dot(u));
        }
      const double bound = *camera->lowest_cosine_to(u);
      BOOST_TEST_CONTEXT(camera->describe() << ", u = " << u.transpose()) {
        BOOST_TEST(bound <= lowest + 1e-12);
        BOOST_TEST(bound >= lowest - 0.05);  // a pixel spans at most 3 degrees here
      }
    }
}

BOOST_AUTO_TEST_SUITE_END()  // test_camera
