#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "colour/chromatic_adaptation.hpp"
#include "colour/ciede2000.hpp"
#include "skyspec/colour.hpp"

BOOST_AUTO_TEST_SUITE(test_ciede2000)

using namespace skyspec;

namespace {

struct Pair {
  int index;
  Lab lab1, lab2;
  double delta_E;
};

/// tests/data/ciede2000_sharma2005.csv: Sharma, Wu & Dalal 2005, Table 1.
std::vector<Pair> sharma_pairs() {
  std::ifstream in(std::string(SKYSPEC_TEST_DATA_DIR) + "/ciede2000_sharma2005.csv");
  BOOST_REQUIRE(in);
  std::vector<Pair> pairs;
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) {
      header = false;
      continue;
    }
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream fields(line);
    Pair p{};
    fields >> p.index >> p.lab1.L >> p.lab1.a >> p.lab1.b >> p.lab2.L >> p.lab2.a >> p.lab2.b >> p.delta_E;
    BOOST_REQUIRE(fields);
    pairs.push_back(p);
  }
  return pairs;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(sharma_wu_dalal_2005)

// Every published pair to 1e-4 (the table's own rounding is 5e-5), in both orders: the formula
// is symmetric, and several pairs sit on the hue-angle discontinuities it has to get right.
BOOST_AUTO_TEST_CASE(all_34_pairs_match_the_published_values) {
  const auto pairs = sharma_pairs();
  BOOST_REQUIRE_EQUAL(pairs.size(), 34u);
  double worst = 0.0;
  for (const auto& p : pairs) {
    const double forward = ciede2000(p.lab1, p.lab2);
    const double backward = ciede2000(p.lab2, p.lab1);
    BOOST_TEST_CONTEXT("pair " << p.index) {
      BOOST_TEST(std::abs(forward - p.delta_E) <= 1e-4);
      BOOST_TEST(std::abs(backward - p.delta_E) <= 1e-4);
    }
    worst = std::max({worst, std::abs(forward - p.delta_E), std::abs(backward - p.delta_E)});
  }
  BOOST_TEST_MESSAGE("largest difference from Sharma et al. Table 1: " << worst);
}

BOOST_AUTO_TEST_CASE(identical_colours_differ_by_zero) {
  for (const auto& p : sharma_pairs()) BOOST_TEST(ciede2000(p.lab1, p.lab1) == 0.0);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(cielab)

// The white itself is L* = 100, a* = b* = 0; black is 0; 18 % grey is L* = 49.5 (CIE 015 formula).
BOOST_AUTO_TEST_CASE(white_grey_and_black) {
  const Eigen::Vector3d white = linear_rec709_to_xyz() * Eigen::Vector3d::Ones();
  const Lab w = xyz_to_lab(white, white);
  BOOST_TEST(std::abs(w.L - 100.0) < 1e-12);
  BOOST_TEST(std::abs(w.a) < 1e-12);
  BOOST_TEST(std::abs(w.b) < 1e-12);
  const Lab grey = xyz_to_lab(0.18 * white, white);
  BOOST_TEST(std::abs(grey.L - (116.0 * std::cbrt(0.18) - 16.0)) < 1e-12);
  BOOST_TEST(std::abs(grey.L - 49.496) < 1e-3);
  BOOST_TEST(std::abs(xyz_to_lab(Eigen::Vector3d::Zero(), white).L) < 1e-12);
}

// The two branches of f meet continuously at (6/29)^3.
BOOST_AUTO_TEST_CASE(lab_function_is_continuous) {
  const Eigen::Vector3d white(1, 1, 1);
  const double t0 = std::pow(6.0 / 29.0, 3);
  const double below = xyz_to_lab(Eigen::Vector3d::Constant(t0 * (1 - 1e-9)), white).L;
  const double above = xyz_to_lab(Eigen::Vector3d::Constant(t0 * (1 + 1e-9)), white).L;
  BOOST_TEST(std::abs(below - above) < 1e-6);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(bradford)

// Adaptation maps the source white onto the destination white, and is the identity between equal
// whites.
BOOST_AUTO_TEST_CASE(white_maps_to_white) {
  const Eigen::Vector3d e = xyz_from_xy(1.0 / 3.0, 1.0 / 3.0);
  const Eigen::Vector3d d65 = xyz_from_xy(0.3127, 0.3290);
  const Eigen::Vector3d mapped = bradford_adaptation(e, d65) * e;
  BOOST_TEST((mapped - d65).norm() < 1e-12);
  BOOST_TEST((bradford_adaptation(d65, d65) - Eigen::Matrix3d::Identity()).norm() < 1e-12);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE_END()  // test_ciede2000
