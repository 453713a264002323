#include <boost/test/unit_test.hpp>

// Correlated colour temperature from its CIE definition: the Planckian locus recovers its own
// temperatures; the CIE illuminants D65, D50 and A get their published CCTs (6504 K, 5003 K and
// 2856 K, CIE 015:2004) and D65 its distance above the locus (Duv +0.0032).

#include <cmath>

#include "colour/colour_temperature.hpp"

BOOST_AUTO_TEST_SUITE(test_colour_temperature)

using namespace skyspec;

namespace {
/// XYZ (Y = 1) of a CIE 1931 chromaticity x, y.
Eigen::Vector3d xyz_of_xy(double x, double y) { return {x / y, 1.0, (1.0 - x - y) / y}; }
/// XYZ (Y = 1) of a CIE 1960 chromaticity u, v.
Eigen::Vector3d xyz_of_uv(const Eigen::Vector2d& uv) {
  const double d = 2.0 * uv[0] - 8.0 * uv[1] + 4.0;
  return xyz_of_xy(3.0 * uv[0] / d, 2.0 * uv[1] / d);
}
}  // namespace

BOOST_AUTO_TEST_CASE(planckian_radiators_get_their_own_temperature) {
  for (double t : {1500.0, 2856.0, 4000.0, 6500.0, 10000.0, 25000.0, 100000.0}) {
    const auto c = correlated_colour_temperature(xyz_of_uv(planckian_uv_1960(t)));
    BOOST_REQUIRE(c.has_value());
    BOOST_TEST(std::abs(c->cct_K / t - 1.0) < 1e-6, t << " K: " << c->cct_K);
    BOOST_TEST(std::abs(c->duv) < 1e-9);
  }
}

BOOST_AUTO_TEST_CASE(cie_daylight_illuminants) {
  // CIE 015:2004: D65 x = 0.31271, y = 0.32902, CCT 6504 K; D50 x = 0.34567, y = 0.35850, 5003 K;
  // illuminant A (a Planckian radiator at 2856 K) x = 0.44757, y = 0.40745.
  const auto d65 = correlated_colour_temperature(xyz_of_xy(0.31271, 0.32902));
  const auto d50 = correlated_colour_temperature(xyz_of_xy(0.34567, 0.35850));
  BOOST_REQUIRE(d65.has_value());
  BOOST_REQUIRE(d50.has_value());
  BOOST_TEST(std::abs(d65->cct_K - 6504.0) < 3.0, d65->cct_K);
  BOOST_TEST(std::abs(d50->cct_K - 5003.0) < 3.0, d50->cct_K);
  const auto a = correlated_colour_temperature(xyz_of_xy(0.44757, 0.40745));
  BOOST_REQUIRE(a.has_value());
  BOOST_TEST(std::abs(a->cct_K - 2856.0) < 2.0, a->cct_K);
  BOOST_TEST(std::abs(a->duv) < 1e-4, a->duv);
  // Daylight lies above (on the green side of) the Planckian locus: D65 by about 0.0032.
  BOOST_TEST(d65->duv > 0.0030, d65->duv);
  BOOST_TEST(d65->duv < 0.0034, d65->duv);
  // Scale does not matter.
  BOOST_TEST(std::abs(correlated_colour_temperature(1e4 * xyz_of_xy(0.31271, 0.32902))->cct_K - d65->cct_K) < 1e-6);
}

BOOST_AUTO_TEST_CASE(no_colour_or_far_from_the_locus) {
  BOOST_TEST(!correlated_colour_temperature(Eigen::Vector3d::Zero()).has_value());
  BOOST_TEST(!correlated_colour_temperature(Eigen::Vector3d(NAN, 1.0, 1.0)).has_value());
  BOOST_TEST(!correlated_colour_temperature(xyz_of_xy(0.30, 0.60)).has_value());  // saturated green
}

BOOST_AUTO_TEST_SUITE_END()
