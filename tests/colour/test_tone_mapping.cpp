#include <boost/test/unit_test.hpp>

#include <cmath>
#include <vector>

#include "colour/exposure.hpp"
#include "colour/tone_mapping.hpp"

BOOST_AUTO_TEST_SUITE(test_tone_mapping)

using namespace skyspec;

BOOST_AUTO_TEST_SUITE(operators)

// Reinhard et al. 2002 eq. 3: 0 -> 0, 1 -> 1/2, increasing, below 1.
BOOST_AUTO_TEST_CASE(reinhard_simple) {
  BOOST_TEST(reinhard(0.0) == 0.0);
  BOOST_TEST(reinhard(1.0) == 0.5);
  BOOST_TEST(reinhard(1e6) < 1.0);
}

// Eq. 4: the white W maps to exactly 1, and W -> infinity gives back eq. 3.
BOOST_AUTO_TEST_CASE(reinhard_extended_maps_white_to_one) {
  for (double W : {1.0, 2.0, 11.2, 1000.0}) BOOST_TEST(std::abs(reinhard_extended(W, W) - 1.0) < 1e-14);
  BOOST_TEST(std::abs(reinhard_extended(3.0, 1e9) - reinhard(3.0)) < 1e-12);
}

// Hable's curve: f(0) = 0 (the -E/F term) and the linear white 11.2, after the exposure bias
// of 2, maps to 1: c = 5.6 -> 1.
BOOST_AUTO_TEST_CASE(uncharted2_white_and_black) {
  BOOST_TEST(std::abs(uncharted2_filmic(0.0)) < 1e-15);
  BOOST_TEST(std::abs(uncharted2_filmic(5.6) - 1.0) < 1e-14);
  BOOST_TEST(uncharted2_filmic(1.0) > uncharted2_filmic(0.5));
}

// Narkowicz's fit: 0 -> 0 (up to its tiny constant term), clamped at 1, and mid-grey 0.18 to
// about 0.14 display-linear (after his 0.6 pre-scale): (0.108 (2.51 0.108 + 0.03)) / (0.108 (2.43
// 0.108 + 0.59) + 0.14).
BOOST_AUTO_TEST_CASE(aces_approx_values) {
  BOOST_TEST(aces_approx_narkowicz(0.0) == 0.0);
  BOOST_TEST(aces_approx_narkowicz(1e3) == 1.0);
  const double x = 0.108;
  BOOST_TEST(std::abs(aces_approx_narkowicz(0.18) - x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14)) < 1e-15);
}

// The luminance version keeps chromaticity (channel ratios) and maps the luminance by eq. 4.
BOOST_AUTO_TEST_CASE(luminance_reinhard_keeps_ratios) {
  std::vector<float> rgb = {0.2f, 0.5f, 1.5f, 4.0f, 2.0f, 1.0f};
  const std::vector<float> before = rgb;
  const double W = apply_tone_operator(ToneOperator::ReinhardLuminance, rgb, 8.0);
  BOOST_TEST(W == 8.0);
  for (size_t p = 0; p < 2; ++p) {
    const size_t i = 3 * p;
    BOOST_TEST(std::abs(rgb[i] / rgb[i + 1] - before[i] / before[i + 1]) < 1e-5);
    BOOST_TEST(std::abs(rgb[i + 2] / rgb[i + 1] - before[i + 2] / before[i + 1]) < 1e-5);
    const double y_in = rec709_luminance(&before[i]), y_out = rec709_luminance(&rgb[i]);
    BOOST_TEST(std::abs(y_out - reinhard_extended(y_in, 8.0)) < 1e-6);
  }
}

// Without an explicit white, extended Reinhard uses the image's largest luminance: the brightest
// grey pixel becomes exactly 1. Negative components are clamped to 0 first.
BOOST_AUTO_TEST_CASE(automatic_white_and_negative_values) {
  std::vector<float> rgb = {6.0f, 6.0f, 6.0f, 1.0f, -0.5f, 2.0f};
  const double W = apply_tone_operator(ToneOperator::ReinhardExtended, rgb);
  BOOST_TEST(std::abs(W - 6.0) < 1e-6);
  BOOST_TEST(std::abs(rgb[0] - 1.0f) < 1e-6f);
  BOOST_TEST(rgb[4] == 0.0f);
}

BOOST_AUTO_TEST_CASE(names) {
  BOOST_TEST(tone_operator_names().size() == 5u);
  for (const auto& n : tone_operator_names()) BOOST_TEST(to_string(*tone_operator_from_name(n)) == n);
  BOOST_TEST(!tone_operator_from_name("filmic"));
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE_END()  // test_tone_mapping
