#include <boost/test/unit_test.hpp>

#include <fstream>
#include <iterator>
#include <string>

#include "base/embedded_data.hpp"
#include "render/scene_provenance.hpp"
#include "scene_fixtures.hpp"
#include "skyspec/scene.hpp"

BOOST_AUTO_TEST_SUITE(test_provenance)

using namespace skyspec;
using skyspec::test::contains;
using skyspec::test::scene_with;

BOOST_AUTO_TEST_CASE(data_tables_are_described_from_their_embedded_bytes) {
  // FNV-1a 64 test vectors (Fowler, Noll, Vo: "" and "a").
  BOOST_TEST(fnv1a64("") == 0xcbf29ce484222325ull);
  BOOST_TEST(fnv1a64("a") == 0xaf63dc4c8601ec8cull);
  const EmbeddedTableInfo cie = embedded_table_info("cie/cie1931_2deg_5nm.csv");
  BOOST_TEST(cie.bytes == embedded_file("cie/cie1931_2deg_5nm.csv").size());
  BOOST_TEST(cie.fnv1a64 == fnv1a64(embedded_file("cie/cie1931_2deg_5nm.csv")));
  BOOST_TEST(contains(cie.source, "CIE 015:2004"));
  // The embedded bytes are the bytes of the file in data/.
  std::ifstream in(std::string(SKYSPEC_TEST_DATA_DIR) + "/../../data/cie/cie1931_2deg_5nm.csv", std::ios::binary);
  const std::string on_disk((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  BOOST_TEST(fnv1a64(on_disk) == cie.fnv1a64);

  // Which tables a render reads follows the scene; every one listed has a source.
  const Scene d = scene_with("");
  const std::string text = data_tables_text(d, true);
  for (const char* table : {"cie/", "solar/astm_g173_etr.csv", "ozone/", "ocio/config.ocio"})
    BOOST_TEST(contains(text, table));
  BOOST_TEST(!contains(text, "solar_position/"));
  const Scene seed = scene_with("", "seed");
  BOOST_TEST(!contains(data_tables_text(seed, false), "cie/"));
  const Scene dated = scene_with("[sun]\ndate_time = \"2026-06-21T12:00:00+02:00\"\n");
  BOOST_TEST(contains(data_tables_text(dated, false), "solar_position/spa_nutation_terms.csv"));
  for (const auto& path : data_tables_used(dated, true)) BOOST_TEST(!embedded_table_info(path).source.empty());
}

BOOST_AUTO_TEST_CASE(scene_text_reads_back_exactly) {
  // scene_to_toml must give the same Scene bit for bit, so that --from reproduces a render.
  const Scene s = scene_with(
      "[sun]\nelevation_deg = 12.3456789012345\nazimuth_deg = 0.1\n[atmosphere.rayleigh]\nco2_ppm = 412.345678901\n"
      "[atmosphere.mie]\ng = 0.7000000000000001\n[camera]\nposition_m = [0.1, 0.2, 1.2345678901234567]\n");
  SceneLoader again("default");
  again.apply_toml(scene_to_toml(s), "again");
  const Scene t = again.finish();
  BOOST_TEST(scene_to_toml(t) == scene_to_toml(s));
  BOOST_TEST(t.sun.elevation_deg == s.sun.elevation_deg);
  BOOST_TEST(t.atmosphere.rayleigh.derivation.co2_ppv == s.atmosphere.rayleigh.derivation.co2_ppv);
  BOOST_TEST(t.atmosphere.mie.phase.g == s.atmosphere.mie.phase.g);
  BOOST_TEST(t.camera.position_m.z() == s.camera.position_m.z());
  // Short values stay short.
  BOOST_TEST(contains(scene_to_toml(s), "azimuth_deg = 0.1\n"));
}

BOOST_AUTO_TEST_SUITE_END()  // test_provenance
