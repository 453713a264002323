// Panorama conventions (camera.hpp, PanoramaConvention): a panorama in the Blender convention puts
// a direction where Cycles' own mapping formula reads it, and one in the OpenEXR convention where
// OpenEXR's LatLongMap (the library's own code) reads it; a rendered sun lands there.
#include <boost/test/unit_test.hpp>

#include <ImfEnvmap.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <string>

#include "skyspec/camera.hpp"
#include "skyspec/render.hpp"
#include "skyspec/scene.hpp"
#include "skyspec/units.hpp"

BOOST_AUTO_TEST_SUITE(test_panorama_conventions)

using namespace skyspec;

namespace {
const Vec3 kOrigin(0.0, 0.0, 6360e3 + 1.0);
constexpr double kPi = 3.14159265358979323846;

// Cycles, intern/cycles/kernel/camera/projection.h: direction_to_equirectangular(dir) =
// direction_to_equirectangular_range(dir, (-2 pi, pi, -pi, pi)), that is
//   u = (atan2(dir.y, dir.x) - pi) / (-2 pi),  v = (acos(dir.z / |dir|) - pi) / (-pi),
// with v = 0 at the bottom row of the image. In Blender's world frame north is +Y, east +X, up +Z
// (the Sun Position add-on with north offset 0), which is skyspec's east-north-up frame as it is.
struct UV {
  double u, v;
};
UV cycles_direction_to_equirectangular(const Vec3& dir) {
  const double range_x = -2.0 * kPi, range_y = kPi, range_z = -kPi, range_w = kPi;
  return {(std::atan2(dir.y(), dir.x()) - range_y) / range_x, (std::acos(dir.z() / dir.norm()) - range_w) / range_z};
}

// skyspec's east-north-up direction in OpenEXR's lat-long frame: up +Y, east +X, north -Z.
IMATH_NAMESPACE::V3f to_openexr_frame(const Vec3& enu) {
  return IMATH_NAMESPACE::V3f(static_cast<float>(enu.x()), static_cast<float>(enu.z()), static_cast<float>(-enu.y()));
}

double angle_deg(const Vec3& a, const Vec3& b) {
  return radians_to_degrees(std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)));
}

// A small, cheap panorama: single scattering, 4 wavelengths, the sun at 0.05 au so that its disk
// (limb-darkened: brightest at its centre) is 5.3 degrees in radius and covers pixel centres.
Scene panorama_scene(const std::string& convention, double sun_azimuth_deg, double sun_elevation_deg) {
  SceneLoader loader;
  loader.apply_override("camera.type", "\"equirectangular\"", "test");
  loader.apply_override("camera.width", "96", "test");
  loader.apply_override("camera.height", "48", "test");
  loader.apply_override("camera.panorama_convention", "\"" + convention + "\"", "test");
  loader.apply_override("sun.azimuth_deg", std::to_string(sun_azimuth_deg), "test");
  loader.apply_override("sun.elevation_deg", std::to_string(sun_elevation_deg), "test");
  loader.apply_override("sun.distance_au", "0.05", "test");
  loader.apply_override("render.scattering_orders", "1", "test");
  loader.apply_override("spectrum.count", "4", "test");
  loader.apply_override("render.threads", "2", "test");
  return loader.finish();
}

// The pixel (column, row) of the largest luminance.
void brightest_pixel(const SpectralImageBuffer& image, int& column, int& row) {
  double best = -1.0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const float* rgb = &image.rgb[(static_cast<size_t>(y) * image.width + x) * 3];
      const double luminance = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
      if (luminance > best) {
        best = luminance;
        column = x;
        row = y;
      }
    }
}
}  // namespace

// Every pixel centre's direction, put through Cycles' formula, comes back as that pixel centre.
BOOST_AUTO_TEST_CASE(blender_pixels_are_where_cycles_looks_them_up) {
  const int w = 64, h = 32;
  const EquirectangularCamera camera(w, h, kOrigin, -90.0, PanoramaConvention::Blender);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      Vec3 d;
      BOOST_REQUIRE(camera.direction(x + 0.5, y + 0.5, d));
      UV uv = cycles_direction_to_equirectangular(d);
      if (uv.u < 0.0) uv.u += 1.0;
      BOOST_TEST_CONTEXT("pixel " << x << ", " << y) {
        BOOST_TEST(uv.u * w == x + 0.5, boost::test_tools::tolerance(1e-9));
        BOOST_TEST((1.0 - uv.v) * h == y + 0.5, boost::test_tools::tolerance(1e-9));
      }
    }
  // Named directions: north on +Y is a quarter of the way in, east (+X) is the centre column.
  Vec3 d;
  camera.direction(0.25 * w, 0.5 * h, d);
  BOOST_TEST(angle_deg(d, Vec3(0, 1, 0)) < 1e-9);
  camera.direction(0.5 * w, 0.5 * h, d);
  BOOST_TEST(angle_deg(d, Vec3(1, 0, 0)) < 1e-9);
}

// Every pixel centre's direction is OpenEXR's LatLongMap::direction of that pixel (in the frame
// up +Y, east +X, north -Z), and the default skyspec layout is the same map to half a pixel.
BOOST_AUTO_TEST_CASE(openexr_pixels_are_latlongmap_directions) {
  const int w = 64, h = 32;
  const EquirectangularCamera openexr(w, h, kOrigin, -90.0, PanoramaConvention::OpenExr);
  const EquirectangularCamera skyspec(w, h, kOrigin, -90.0, PanoramaConvention::Skyspec);
  const IMATH_NAMESPACE::Box2i window(IMATH_NAMESPACE::V2i(0, 0), IMATH_NAMESPACE::V2i(w - 1, h - 1));
  const double half_pixel_deg = 0.5 * 360.0 / w * 1.5;  // half a pixel along both axes, with margin
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const IMATH_NAMESPACE::V3f e = Imf::LatLongMap::direction(window, IMATH_NAMESPACE::V2f(float(x), float(y)));
      const Vec3 expected(e.x, -e.z, e.y);  // back to east-north-up
      Vec3 d, s;
      openexr.direction(x + 0.5, y + 0.5, d);
      skyspec.direction(x + 0.5, y + 0.5, s);
      BOOST_TEST_CONTEXT("pixel " << x << ", " << y) {
        BOOST_TEST(angle_deg(d, expected) < 1e-3);  // OpenEXR computes in float
        BOOST_TEST(angle_deg(s, expected) < half_pixel_deg);
      }
    }
}

BOOST_AUTO_TEST_CASE(whole_sphere_conventions_refuse_partial_panoramas) {
  for (PanoramaConvention c : {PanoramaConvention::Blender, PanoramaConvention::OpenExr})
    BOOST_CHECK_THROW(EquirectangularCamera(64, 32, kOrigin, 0.0, c), std::invalid_argument);
  BOOST_CHECK_THROW(EquirectangularCamera(1, 32, kOrigin, -90.0, PanoramaConvention::OpenExr), std::invalid_argument);
  BOOST_CHECK_NO_THROW(EquirectangularCamera(64, 16, kOrigin, 0.0, PanoramaConvention::Skyspec));
}

// The test the issue asks for: the sun of a rendered Blender-convention panorama is at the pixel
// Cycles' formula computes for the sun's direction in Blender's frame; in the skyspec convention
// it would be a quarter of the image (90 degrees) away.
BOOST_AUTO_TEST_CASE(rendered_sun_is_where_cycles_and_openexr_put_it) {
  const double azimuth = 123.0, elevation = 17.0;
  const Vec3 sun = direction_from_angles(azimuth, elevation);
  {
    const Scene scene = panorama_scene("blender", azimuth, elevation);
    const SpectralImageBuffer image = render_to_memory(scene);
    int column = -1, row = -1;
    brightest_pixel(image, column, row);
    const UV uv = cycles_direction_to_equirectangular(sun);
    const double x = (uv.u < 0.0 ? uv.u + 1.0 : uv.u) * image.width, y = (1.0 - uv.v) * image.height;
    BOOST_TEST_MESSAGE("blender: sun at pixel " << column << ", " << row << "; Cycles' formula: " << x << ", " << y);
    BOOST_TEST(std::fabs(column + 0.5 - x) <= 1.0);
    BOOST_TEST(std::fabs(row + 0.5 - y) <= 1.0);
  }
  {
    const Scene scene = panorama_scene("openexr", azimuth, elevation);
    const SpectralImageBuffer image = render_to_memory(scene);
    int column = -1, row = -1;
    brightest_pixel(image, column, row);
    const IMATH_NAMESPACE::Box2i window(IMATH_NAMESPACE::V2i(0, 0),
                                        IMATH_NAMESPACE::V2i(image.width - 1, image.height - 1));
    const IMATH_NAMESPACE::V2f p = Imf::LatLongMap::pixelPosition(window, to_openexr_frame(sun));
    BOOST_TEST_MESSAGE("openexr: sun at pixel " << column << ", " << row << "; LatLongMap: " << p.x << ", " << p.y);
    BOOST_TEST(std::fabs(column - double(p.x)) <= 1.0);
    BOOST_TEST(std::fabs(row - double(p.y)) <= 1.0);
  }
}

BOOST_AUTO_TEST_SUITE_END()  // test_panorama_conventions
