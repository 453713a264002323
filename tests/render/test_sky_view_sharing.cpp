// Renders share a sky-view table when its entries would be the same (render.cpp,
// sky_view_table_for): the same air, camera radius and sun zenith angle. A render that changes
// anything else the table depends on must get a table of its own: after a render of one scene, a
// render of a scene that differs in one such input agrees with the same scene marched pixel by
// pixel (no table), and not with the first scene. A render with the sun at another azimuth is the
// first one turned.
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "scene_fixtures.hpp"
#include "skyspec/render.hpp"

BOOST_AUTO_TEST_SUITE(test_sky_view_sharing)

using namespace skyspec;

namespace {
// A small full-sphere panorama, single scattering (no scattering-order tables to build).
const std::string kBase =
    "[camera]\ntype = \"equirectangular\"\nwidth = 24\nheight = 12\nmin_elevation_deg = -90\n"
    "[render]\nscattering_orders = 1\n[sun]\nelevation_deg = 20\nazimuth_deg = 90\ndisk = false\n";

using Changes = std::vector<std::pair<std::string, std::string>>;  // key, TOML value

std::vector<float> spectral(const Changes& changes) {
  SceneLoader loader("default");
  loader.apply_toml(kBase, "test.toml");
  for (const auto& [key, value] : changes) loader.apply_override(key, value, "test");
  return render_to_memory(loader.finish()).spectral;
}

// The largest difference relative to the largest value.
double relative_difference(const std::vector<float>& a, const std::vector<float>& b) {
  BOOST_REQUIRE(a.size() == b.size());
  double largest = 0.0, worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    largest = std::max(largest, static_cast<double>(std::abs(b[i])));
    worst = std::max(worst, static_cast<double>(std::abs(a[i] - b[i])));
  }
  return worst / largest;
}
}  // namespace

BOOST_AUTO_TEST_CASE(a_changed_input_gets_a_table_of_its_own) {
  const std::vector<float> first = spectral({});
  const Changes changes = {{"atmosphere.mie.scattering_per_m", "60e-6"},
                           {"ground.albedo", "0.6"},
                           {"camera.position_m", "[0, 0, 3000]"},
                           {"sun.elevation_deg", "21"},
                           {"render.view_segments", "1"}};
  for (const auto& change : changes) {
    BOOST_TEST_CONTEXT(change.first << " = " << change.second) {
      const std::vector<float> tabled = spectral({change});
      const std::vector<float> marched = spectral({change, {"render.sky_view_table", "false"}});
      BOOST_TEST(relative_difference(tabled, marched) < 2e-3);
      BOOST_TEST(relative_difference(tabled, first) > 1e-2);
    }
  }
}

BOOST_AUTO_TEST_CASE(the_sun_at_another_azimuth_turns_the_sky) {
  const std::vector<float> east = spectral({}), later = spectral({{"sun.azimuth_deg", "120"}});
  const std::vector<float> marched = spectral({{"sun.azimuth_deg", "120"}, {"render.sky_view_table", "false"}});
  BOOST_TEST(relative_difference(later, marched) < 2e-3);
  BOOST_TEST(relative_difference(later, east) > 1e-2);
}

BOOST_AUTO_TEST_SUITE_END()
