#include <boost/test/unit_test.hpp>

#include <cmath>
#include <set>
#include <vector>

#include "colour/exposure.hpp"
#include "skyspec/error.hpp"

BOOST_AUTO_TEST_SUITE(test_exposure)

using namespace skyspec;

BOOST_AUTO_TEST_SUITE(camera)

// EV100 = log2(N^2 / t * 100 / S): f/8, 1/250 s, ISO 400 is 11.9657842 (the value colour-hdri's
// exposure_value_100 documents); f/1, 1 s, ISO 100 is EV 0 by definition.
BOOST_AUTO_TEST_CASE(ev100_of_known_settings) {
  BOOST_TEST(std::abs(camera_ev100(8, 1.0 / 250, 400) - 11.9657842) < 1e-7);
  BOOST_TEST(std::abs(camera_ev100(1, 1, 100)) < 1e-15);
  BOOST_TEST(std::abs(camera_ev100(16, 1.0 / 125, 100) - std::log2(256.0 * 125.0)) < 1e-12);  // "sunny 16"
}

// ISO 12232 saturation-based sensitivity: L_max = 78 / (S q) N^2 / t with q = 0.65; the scale is
// 1 / L_max. At EV100 = 0 that is 1 / 1.2.
BOOST_AUTO_TEST_CASE(saturating_luminance_maps_to_one) {
  BOOST_TEST(std::abs(camera_exposure_scale(1, 1, 100) - 1.0 / 1.2) < 1e-15);
  const double N = 5.6, t = 1.0 / 500, S = 200;
  const double L_max = 78.0 / (S * 0.65) * N * N / t;
  BOOST_TEST(std::abs(camera_exposure_scale(N, t, S) * L_max - 1.0) < 1e-12);
}

BOOST_AUTO_TEST_CASE(bad_camera_settings_name_the_flag) {
  BOOST_CHECK_THROW(camera_ev100(0, 1, 100), InputError);
  try {
    camera_ev100(8, -1, 100);
    BOOST_FAIL("no error");
  } catch (const InputError& e) {
    BOOST_TEST(e.setting() == display_setting::kShutter);
  }
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(automatic)

// A uniform image of luminance L is metered to 0.18 / L; the rule ignores pixels darker than
// 1/100 of the 90th percentile (a black ground half does not change it).
BOOST_AUTO_TEST_CASE(key_value_of_uniform_and_half_black_images) {
  const int w = 40, h = 30;
  std::vector<float> rgb(static_cast<size_t>(w) * h * 3, 5.0f);
  BOOST_TEST(std::abs(metered_exposure_scale(rgb, w, h) - 0.18 / 5.0) < 1e-12);
  for (size_t i = rgb.size() / 2; i < rgb.size(); ++i) rgb[i] = 0.0f;
  BOOST_TEST(std::abs(metered_exposure_scale(rgb, w, h) - 0.18 / 5.0) < 1e-12);
  // log-average, not mean: half at 1, half at 100 -> key 10.
  std::vector<double> y(100, 1.0);
  for (size_t i = 50; i < 100; ++i) y[i] = 100.0;
  BOOST_TEST(std::abs(key_exposure_scale(y) - 0.018) < 1e-12);
  BOOST_TEST(key_exposure_scale({0.0, -1.0}) == 1.0);
}

// At most 64 x 64 metered pixels, spread over the whole image; every pixel for small images.
BOOST_AUTO_TEST_CASE(metering_grid) {
  BOOST_TEST(metering_pixels(8, 8).size() == 64u);
  const auto big = metering_pixels(512, 256);
  BOOST_TEST(big.size() == 64u * 32u);
  std::set<int> columns;
  for (const auto& p : big) columns.insert(p.first);
  BOOST_TEST(*columns.begin() == 4);
  BOOST_TEST(*columns.rbegin() == 508);
  BOOST_TEST(metering_pixels(1000, 10).size() <= 64u * 64u);
}

BOOST_AUTO_TEST_CASE(resolved_descriptions) {
  ExposureSettings s;
  s.mode = ExposureSettings::Mode::Manual;
  s.ev = -3;
  const auto r = resolve_exposure(s, 99.0);
  BOOST_TEST(r.scale == 0.125);
  BOOST_TEST(r.ev == -3.0);
  BOOST_TEST(r.description.find("manual") == 0u);
  s.mode = ExposureSettings::Mode::Automatic;
  BOOST_TEST(resolve_exposure(s, 0.5).scale == 0.5);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE_END()  // test_exposure
