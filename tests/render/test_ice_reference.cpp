// The renderer with ice crystals (diamond dust, media/ice.cpp) against the Monte Carlo reference,
// which samples the same ray-traced scattering function (issue 39): single scattering inside and
// outside the 22 degree halo and near the 46 degree halo, within 2 % + 3 standard errors.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "scene_fixtures.hpp"
#include "skyspec/camera.hpp"
#include "skyspec/error.hpp"
#include "skyspec/monte_carlo_reference.hpp"
#include "skyspec/render.hpp"

BOOST_AUTO_TEST_SUITE(test_ice_reference)

using namespace skyspec;

namespace {
const char* const kScene =
    "[sun]\nelevation_deg = 25\nazimuth_deg = 180\n[spectrum]\nwavelengths_nm = [450, 650]\n"
    "[atmosphere.ice]\nenabled = true\nvisibility_m = 5000\nscale_height_m = 200\n"
    "[camera]\nposition_m = [0, 0, 2]\nwidth = 1\nheight = 1\n"
    "[render]\ncache_tables = false\nscattering_orders = 1\n";
}  // namespace

BOOST_AUTO_TEST_CASE(single_scattering_agrees_with_the_reference) {
  const Scene scene = test::scene_with(kScene, "default");
  // Along the sun's vertical: 15 degrees from the sun (inside the halo), 22.5 (on it), 30, 47 (the
  // 46 degree halo) and 60.
  const std::vector<ReferenceProbe> probes = {{"inside the halo", 180.0, 40.0},
                                              {"on the 22 degree halo", 180.0, 47.5},
                                              {"between the halos", 180.0, 55.0},
                                              {"on the 46 degree halo", 180.0, 72.0},
                                              {"beyond", 0.0, 85.0}};
  ReferenceSettings settings;
  settings.paths = 20000;
  settings.seed = 39;
  settings.max_orders = 1;
  const ReferenceResult mc = monte_carlo_reference(scene, probes, settings);
  const SkyRenderer renderer(scene);
  double halo = 0.0, inside = 0.0, between = 0.0;
  for (size_t k = 0; k < probes.size(); ++k) {
    const Spectrum det = renderer.radiance(direction_from_angles(probes[k].azimuth_deg, probes[k].elevation_deg));
    for (size_t i = 0; i < mc.wavelengths_nm.size(); ++i) {
      const double ref = mc.radiance[k][i], se = mc.radiance_standard_error[k][i];
      const double value = det[static_cast<Eigen::Index>(i)];
      BOOST_TEST_MESSAGE(probes[k].label << ", " << mc.wavelengths_nm[i] << " nm: renderer " << value << ", reference "
                                         << ref << " +- " << se << " (" << 100.0 * (value / ref - 1.0) << " %)");
      BOOST_TEST(std::abs(value - ref) <= 0.02 * ref + 3.0 * se,
                 probes[k].label << " " << mc.wavelengths_nm[i] << " nm: " << value << " vs " << ref << " +- " << se);
    }
    if (k == 0) inside = det[0];
    if (k == 1) halo = det[0];
    if (k == 2) between = det[0];
  }
  // The halo is there: brighter than the sky 7 degrees closer to the sun (where the aerosol's
  // forward scattering is stronger) and than the sky between the halos.
  BOOST_TEST(halo > 1.3 * inside);
  BOOST_TEST(halo > 2.0 * between);
}

BOOST_AUTO_TEST_SUITE_END()
