#include <boost/test/unit_test.hpp>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "skyspec/render.hpp"
#include "skyspec/scene.hpp"
#include "transport/single_scattering.hpp"

BOOST_AUTO_TEST_SUITE(test_seed_agreement)

using namespace skyspec;

// The "seed" preset is the tutorial's algorithm on the RGB-fast path. Its values must agree with
// the tutorial's program run to convergence (tests/data/seed_nishita_converged.csv, produced by
// the baseline program at 2048 view / 1024 light samples; see the file's header).
BOOST_AUTO_TEST_CASE(seed_preset_matches_converged_baseline) {
  std::ifstream in(std::string(SKYSPEC_TEST_DATA_DIR) + "/seed_nishita_converged.csv");
  BOOST_REQUIRE(in.good());
  const int W = 12;
  std::string line;
  int compared = 0;
  double worst = 0.0, sum = 0.0;
  double current_elevation = -999;
  std::unique_ptr<SkyRenderer> renderer;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 's') continue;
    std::istringstream row(line);
    double el, rgb[3];
    int i, j;
    char comma;
    row >> el >> comma >> i >> comma >> j >> comma >> rgb[0] >> comma >> rgb[1] >> comma >> rgb[2];
    BOOST_REQUIRE(!row.fail());
    if (el != current_elevation) {
      SceneLoader loader("seed");
      loader.apply_override("sun.elevation_deg", std::to_string(el), "test");
      loader.apply_override("camera.width", "1", "test");
      loader.apply_override("camera.height", "1", "test");
      renderer = std::make_unique<SkyRenderer>(loader.finish());
      current_elevation = el;
    }
    // The baseline's pixel-to-direction mapping, in its frame (x east, y up, z south).
    const double x = 2.0 * (i + 0.5) / (W - 1) - 1.0, y = 2.0 * (j + 0.5) / (W - 1) - 1.0;
    const double z2 = x * x + y * y;
    const double phi = std::atan2(y, x), theta = std::acos(1 - z2);
    const Vec3 dir(std::sin(theta) * std::cos(phi), -std::sin(theta) * std::sin(phi), std::cos(theta));
    const Rgb ours = renderer->radiance_rgb(dir);
    for (int c = 0; c < 3; ++c) {
      const double rel = std::abs(ours[c] - rgb[c]) / rgb[c];
      worst = std::max(worst, rel);
      sum += rel;
      ++compared;
      BOOST_TEST(rel < 2e-3, "sun " << el << " pixel (" << i << "," << j << ") channel " << c << ": " << ours[c]
                                    << " vs baseline " << rgb[c]);
    }
  }
  BOOST_TEST(compared == 3 * 291);
  BOOST_TEST_MESSAGE("seed agreement: mean relative difference " << sum / compared << ", worst " << worst);
  BOOST_TEST(sum / compared < 3e-4);
}

BOOST_AUTO_TEST_SUITE_END()  // test_seed_agreement
