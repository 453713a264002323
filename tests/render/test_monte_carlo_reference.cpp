// The renderer's multiple scattering against the Monte Carlo reference (issue 18, item 2): a fast
// subset of bench/ms_validation.py's table, with a fixed seed. A value passes within `allowed` of
// the reference plus 3 of its standard errors. The benchmark's criterion is 1 %; what the default
// quality reaches today (angular degree 6) is in docs/validation.md, and these allowances are that,
// rounded up: they catch a regression towards the isotropic approximation (errors of 10-16 % at
// the horizon in these cases), not yet the last per cent.

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>

#include "scene_fixtures.hpp"
#include "skyspec/camera.hpp"
#include "skyspec/monte_carlo_reference.hpp"
#include "skyspec/render.hpp"

BOOST_AUTO_TEST_SUITE(test_monte_carlo_reference)

using namespace skyspec;

namespace {
void check_against_reference(const std::string& preset, double sun_elevation, double allowed, std::int64_t paths) {
  char toml[256];
  std::snprintf(toml, sizeof toml,
                "[sun]\nelevation_deg = %g\n[spectrum]\nwavelengths_nm = [450, 650]\n[camera]\nwidth = 1\nheight = 1\n"
                "[render]\ncache_tables = false\n",
                sun_elevation);
  const Scene scene = test::scene_with(toml, preset);
  const std::vector<ReferenceProbe> probes = standard_reference_probes(scene);
  ReferenceSettings settings;
  settings.paths = paths;
  settings.seed = 2026;
  const ReferenceResult mc = monte_carlo_reference(scene, probes, settings);
  const SkyRenderer renderer(scene);
  for (size_t k = 0; k < probes.size(); ++k) {
    const Spectrum det = renderer.radiance(direction_from_angles(probes[k].azimuth_deg, probes[k].elevation_deg));
    for (size_t i = 0; i < mc.wavelengths_nm.size(); ++i) {
      const double ref = mc.radiance[k][i], se = mc.radiance_standard_error[k][i];
      const double value = det[static_cast<Eigen::Index>(i)];
      BOOST_TEST_MESSAGE(preset << ", sun " << sun_elevation << ", " << probes[k].label << ", " << mc.wavelengths_nm[i]
                                << " nm: renderer " << value << ", reference " << ref << " +- " << se << " ("
                                << 100.0 * (value / ref - 1.0) << " %)");
      BOOST_TEST(std::abs(value - ref) <= allowed * ref + 3.0 * se,
                 preset << " sun " << sun_elevation << " " << probes[k].label << " " << mc.wavelengths_nm[i]
                        << " nm: " << value << " vs " << ref << " +- " << se);
    }
  }
}
}  // namespace

// The physics issue's criterion: within 1 % of the reference plus 3 of its standard errors. Hazy
// air, the other suns and twilight are in bench/ms_validation.py only: their reference takes
// minutes (docs/validation.md).
BOOST_AUTO_TEST_CASE(default_air_high_and_low_sun) {
  check_against_reference("default", 30.0, 0.01, 20000);
  check_against_reference("default", 2.0, 0.01, 20000);
}

BOOST_AUTO_TEST_SUITE_END()
