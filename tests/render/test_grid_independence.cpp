// A wavelength's radiance does not depend on which other wavelengths are computed: every sample
// stands for its own band (WavelengthGrid::bandwidth_nm), so the solar spectrum and the ozone
// cross-sections it gets are the same on any grid, as Rayleigh and Mie, evaluated at the
// wavelength itself, always were. The physics issue's example: the default scene at a 5 degree
// sun, a 64 x 32 panorama (here 32 x 16, for time), 440 nm with and without 400 nm in the grid,
// 680 nm with and without 600 nm (what the cell averages before did: docs/physics.md).
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "scene_fixtures.hpp"
#include "skyspec/render.hpp"
#include "skyspec/scene.hpp"

BOOST_AUTO_TEST_SUITE(test_grid_independence)

using namespace skyspec;

namespace {
// One wavelength's channel of a render of the default scene at a 5 degree sun on a grid (list).
std::vector<float> channel(const std::string& grid, double nm, int orders) {
  const Scene scene = test::scene_with(
      "camera.type = \"equirectangular\"\ncamera.width = 32\ncamera.height = 16\nsun.elevation_deg = 5\n"
      "spectrum.wavelengths_nm = [" +
      grid + "]\nrender.scattering_orders = " + std::to_string(orders) +
      "\nrender.cache_tables = false\nrender.ms_altitude_samples = 8\nrender.ms_sun_samples = 8\n");
  const SpectralImageBuffer image = render_to_memory(scene);
  int k = 0;
  while (image.wavelengths_nm[static_cast<size_t>(k)] != nm) ++k;
  const size_t n = image.wavelengths_nm.size();
  std::vector<float> out;
  for (size_t p = 0; p < static_cast<size_t>(image.width) * image.height; ++p)
    out.push_back(image.spectral[p * n + static_cast<size_t>(k)]);
  return out;
}

double largest_relative_difference(const std::vector<float>& a, const std::vector<float>& b) {
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i] > 0.0f) worst = std::max(worst, std::abs(static_cast<double>(b[i]) / a[i] - 1.0));
  return worst;
}
}  // namespace

BOOST_AUTO_TEST_CASE(adding_or_removing_samples_changes_no_other_sample) {
  for (int orders : {1, 2}) {
    BOOST_TEST_CONTEXT(orders << " scattering order(s)") {
      BOOST_TEST(largest_relative_difference(channel("440, 550, 680", 440.0, orders),
                                             channel("400, 440, 550, 680", 440.0, orders)) < 1e-6);
      BOOST_TEST(largest_relative_difference(channel("440, 550, 680", 680.0, orders),
                                             channel("440, 550, 600, 680", 680.0, orders)) < 1e-6);
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()  // test_grid_independence
