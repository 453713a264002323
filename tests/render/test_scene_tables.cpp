// The cache key of the scattering-order tables: a hash of exactly the physical inputs they depend
// on. Changing any such input gives a new key; changing the sun, the camera, the exposure or the
// outputs does not; the key carries no build stamp (the same scene gives the same key).
#include <boost/test/unit_test.hpp>

#include <string>
#include <vector>

#include "render/scene_tables.hpp"
#include "scene_fixtures.hpp"

BOOST_AUTO_TEST_SUITE(test_scene_tables)

using namespace skyspec;

namespace {
ScatteringTablesKey key_of(const std::string& toml) { return scattering_tables_key(test::scene_with(toml)); }
}  // namespace

BOOST_AUTO_TEST_CASE(the_same_scene_gives_the_same_key) {
  const ScatteringTablesKey a = key_of(""), b = key_of("");
  BOOST_TEST(a.hash == b.hash);
  BOOST_TEST(a.inputs == b.inputs);
  BOOST_TEST(a.file_name().size() == std::string("orders-0123456789abcdef.bin").size());
  BOOST_TEST(a.inputs.find("format ") == 0u);  // the table-format version comes first
}

BOOST_AUTO_TEST_CASE(every_physical_input_changes_the_key) {
  const ScatteringTablesKey base = key_of("");
  const std::vector<std::string> changes = {
      "planet.radius_m = 6371e3",
      "atmosphere.top_altitude_m = 80e3",
      "atmosphere.rayleigh.profile = \"exponential\"",
      "atmosphere.rayleigh.co2_ppm = 280",
      "atmosphere.rayleigh.refractive_index = \"ciddor\"",
      "atmosphere.mie.scattering_per_m = 42e-6",
      "atmosphere.mie.scale_height_m = 1500",
      "atmosphere.mie.angstrom_exponent = 0.5",
      "atmosphere.mie.extinction_to_scattering = 1.2",
      "atmosphere.mie.g = 0.7",
      "atmosphere.mie.phase = \"henyey-greenstein\"",
      "atmosphere.mie.enabled = false",
      "atmosphere.ozone.enabled = false",
      "atmosphere.ozone.column_DU = 250",
      "atmosphere.ozone.peak_m = 22e3",
      "ground.albedo = 0.3",
      "spectrum.step_nm = 20",
      "spectrum.max_nm = 700",
      "render.scattering_orders = 4",
      "render.ms_altitude_samples = 24",
      "render.ms_angular_degree = 6",
      "render.ms_sun_samples = 32",
      "render.ms_view_segments = 32",
      "render.ms_higher_order_segments = 24",
      "render.table_altitude_samples = 64",
      "render.table_zenith_samples = 128",
  };
  for (const std::string& change : changes) {
    BOOST_TEST_CONTEXT(change) {
      const ScatteringTablesKey k = key_of(change);
      BOOST_TEST(k.inputs != base.inputs);
      BOOST_TEST(k.hash != base.hash);
    }
  }
}

BOOST_AUTO_TEST_CASE(sun_camera_exposure_and_outputs_leave_the_key_alone) {
  const ScatteringTablesKey base = key_of("");
  const std::vector<std::string> changes = {
      "sun.elevation_deg = 5",
      "sun.azimuth_deg = 90",
      "sun.distance_au = 1.5",
      "sun.disk = false",
      "camera.type = \"perspective\"",
      "camera.type = \"equirectangular\"\nground.albedo = 0.0",  // alone it brings a grey ground
      "camera.width = 64",
      "camera.position_m = [0, 0, 2000]",
      "location.latitude_deg = 45",
      "output.exposure_ev = 3",
      "output.name = \"other\"",
      "output.exr_compression = \"zip\"",
      "render.threads = 1",
      "render.view_segments = 32",
      "render.sky_view_table = false",
      "render.cache_tables = false",
  };
  for (const std::string& change : changes) {
    BOOST_TEST_CONTEXT(change) { BOOST_TEST(key_of(change).hash == base.hash); }
  }
}

BOOST_AUTO_TEST_SUITE_END()  // test_scene_tables
