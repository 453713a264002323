// The polynomial atan2 of the per-pixel path (src/base/fast_atan2.hpp) against libm's.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>

#include "base/fast_atan2.hpp"

BOOST_AUTO_TEST_SUITE(test_fast_atan2)

using skyspec::detail::fast_atan2;

BOOST_AUTO_TEST_CASE(within_1e9_rad_in_every_quadrant) {
  double worst = 0.0;
  const int n = 200000;
  for (int i = 0; i <= n; ++i) {  // the unit circle, finely
    const double phi = -M_PI + 2.0 * M_PI * i / n;
    const double x = std::cos(phi), y = std::sin(phi);
    worst = std::max(worst, std::abs(fast_atan2(y, x) - std::atan2(y, x)));
  }
  std::mt19937 rng(7);  // and vectors of every length and aspect
  std::uniform_real_distribution<double> u(-1, 1), e(-30, 30);
  for (int i = 0; i < 200000; ++i) {
    const double y = u(rng) * std::pow(10.0, e(rng) / 10), x = u(rng) * std::pow(10.0, e(rng) / 10);
    worst = std::max(worst, std::abs(fast_atan2(y, x) - std::atan2(y, x)));
  }
  BOOST_TEST_MESSAGE("largest error " << worst << " rad");
  BOOST_TEST(worst < 1e-9);
}

BOOST_AUTO_TEST_CASE(axes_and_diagonals_exact_enough) {
  BOOST_TEST(fast_atan2(0.0, 0.0) == 0.0);
  BOOST_TEST(fast_atan2(0.0, 1.0) == 0.0);
  BOOST_TEST(std::abs(fast_atan2(1.0, 0.0) - M_PI / 2) < 1e-15);
  BOOST_TEST(std::abs(fast_atan2(0.0, -1.0) - M_PI) < 1e-15);
  BOOST_TEST(std::abs(fast_atan2(-1.0, 0.0) + M_PI / 2) < 1e-15);
  BOOST_TEST(std::abs(fast_atan2(1.0, 1.0) - M_PI / 4) < 1e-9);
  BOOST_TEST(std::abs(fast_atan2(-1.0, -1.0) + 3 * M_PI / 4) < 1e-9);
  // Increasing along the upper half circle (the sky-view table's azimuth), at steps far below
  // the error bound.
  double prev = -1.0;
  bool monotone = true;
  for (int i = 0; i <= 100000; ++i) {
    const double phi = M_PI * i / 100000;
    const double a = fast_atan2(std::sin(phi), std::cos(phi));
    monotone = monotone && a >= prev;
    prev = a;
  }
  BOOST_TEST(monotone);
}

BOOST_AUTO_TEST_SUITE_END()  // test_fast_atan2
