#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "render/render_budget.hpp"
#include "scene_fixtures.hpp"
#include "skyspec/display.hpp"
#include "skyspec/error.hpp"
#include "skyspec/render.hpp"
#include "skyspec/scene.hpp"

BOOST_AUTO_TEST_SUITE(test_render_budget)

using namespace skyspec;
using skyspec::test::contains;
using skyspec::test::scene_with;

namespace {

// The message of the InputError the estimate is refused with ("" if it is not).
std::string refusal(const RenderEstimate& e) {
  try {
    refuse_if_over_budget(e);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}
}  // namespace

BOOST_AUTO_TEST_CASE(file_size_bounds) {
  // 512 x 512 pixels x (41 wavelengths + R, G, B) floats, an 8-byte offset per scan line, 64 KiB of header.
  BOOST_TEST(spectral_exr_bytes(512, 512, 41) == 512ull * 512 * 44 * 4 + 512 * 8 + 65536);
  BOOST_TEST(rgb_exr_bytes(100, 50) == 100ull * 50 * 3 * 4 + 50 * 8 + 65536);
  BOOST_TEST(png_bytes(100, 50, 8) == 100ull * 50 * 3 + 50 + 65536);
  BOOST_TEST(png_bytes(100, 50, 16) == 100ull * 50 * 6 + 50 + 65536);
  // No overflow at the largest image a scene allows (1e9 pixels) with 1024 wavelengths.
  BOOST_TEST(spectral_exr_bytes(40000, 25000, 1024) == 1000000000ull * 1027 * 4 + 25000 * 8 + 65536);
}

BOOST_AUTO_TEST_CASE(plan_of_a_scene) {
  const Scene s = scene_with("[camera]\nwidth = 300\nheight = 200\n[render]\nthreads = 1\nview_segments = 32\n");
  DisplaySettings display;
  display.exr_space = "ACEScg";  // the working-space EXR too
  display.png_bit_depth = 16;
  RenderPlan p = RenderPlan::for_scene(s, display, 5);
  BOOST_TEST(p.outputs == (std::vector<std::string>{"spectral_exr", "png", "working_exr"}),
             boost::test_tools::per_element());
  BOOST_TEST(p.wavelengths == 41);
  BOOST_TEST(p.threads == 1);
  BOOST_TEST(p.output_bytes() ==
             5 * (spectral_exr_bytes(300, 200, 41) + png_bytes(300, 200, 16) + rgb_exr_bytes(300, 200)));
  BOOST_TEST(p.settings() == "41 wavelengths, 32 view segments, 300x200, 1 thread, 5 frames");
  // Memory: a band per thread (whole PIZ line blocks of about 4 MiB: 64 rows of 52.8 kB here,
  // spectral + RGB), then the larger of the spectral EXR's part (each thread's encoder holds three
  // buffers of a band, and two encoded bands per thread wait to be written) and the display's (70 bytes per pixel for
  // an 8-bit PNG, 3 more for 16 bits; 70 for a working-space EXR): the per-pixel figures measured in
  // docs/reliability.md, "Memory estimates". Plus the multiple-scattering tables: 16 x 72 entries x 41 wavelengths of
  // floats, times the harmonics of the sum (degree 10: 66) and of orders 2-6 (degrees 10, 9, 8, 7, 6: 66 + 55 + 45 + 36
  // + 28).
  const std::uint64_t band = 64ull * 300 * 44 * 4, px = 300ull * 200;
  BOOST_TEST(render_band_rows(300, 41, 32, 200) == 64);
  BOOST_TEST(p.table_bytes == 16ull * 72 * 41 * 4 * (66 + 66 + 55 + 45 + 36 + 28));
  BOOST_TEST(p.peak_memory_bytes() == band + std::max(5 * band, px * 73) + p.table_bytes);
  p.threads = 2;  // two of each
  BOOST_TEST(p.peak_memory_bytes() == 2 * band + std::max(10 * band, px * 73) + p.table_bytes);
  p.threads = 1;
  p.outputs.clear();
  p.table_bytes = 0;
  BOOST_TEST(p.peak_memory_bytes() == band);  // without the EXR, 1-row blocks: 64 rows still
  p.extra_bytes_per_pixel = 10;
  p.extra_output_bytes = 7;
  BOOST_TEST(p.peak_memory_bytes() == band + px * 10);
  // Wide images take fewer rows per band, at least one line block.
  p.width = 65536;
  p.height = 1000;
  BOOST_TEST(p.peak_memory_bytes() == 65536ull * 44 * 4 + 65536ull * 1000 * 10);
  BOOST_TEST(render_band_rows(65536, 41, 32, 1000) == 32);
  BOOST_TEST(render_band_rows(65536, 41, 16, 1000) == 16);
  BOOST_TEST(render_band_rows(100, 41, 32, 20) == 20);    // never more than the image
  BOOST_TEST(render_band_rows(1000, 41, 1, 5000) == 23);  // 4 MiB / 176 kB
  BOOST_TEST(p.output_bytes() == 5u * 7u);
}

// The bytes come from the outputs list (render_outputs.cpp): every file a render writes, each
// row's own bound; a tile writes neither the PNG (render --pixel-bounds turns it off) nor the
// polarisation EXR, so its plan counts neither.
BOOST_AUTO_TEST_CASE(bytes_follow_the_outputs_list) {
  const Scene s =
      scene_with("[camera]\nwidth = 64\nheight = 32\n[output]\npolarisation = true\npolarisation_png = true\n");
  const RenderPlan whole = RenderPlan::for_scene(s);
  BOOST_TEST(whole.outputs == (std::vector<std::string>{"spectral_exr", "png", "polarisation_exr", "polarisation_png"}),
             boost::test_tools::per_element());
  BOOST_TEST(whole.output_bytes() ==
             spectral_exr_bytes(64, 32, 41 * 4) + png_bytes(64, 32, 8) + rgb_exr_bytes(64, 32) + png_bytes(64, 32, 8));
  Scene tile_scene = s;
  tile_scene.output.png = false;
  RenderPlan tile = RenderPlan::for_scene(tile_scene, DisplaySettings{}, 1, true);
  tile.width = 16;
  BOOST_TEST(tile.outputs == (std::vector<std::string>{"spectral_exr"}), boost::test_tools::per_element());
  BOOST_TEST(tile.output_bytes() == spectral_exr_bytes(16, 32, 41 * 4));
}

BOOST_AUTO_TEST_CASE(limits_and_messages) {
  RenderEstimate e;
  e.plan =
      RenderPlan::for_scene(scene_with("[camera]\nwidth = 16384\nheight = 8192\n[output]\ndirectory = \"/data\"\n"));
  e.output_bytes = 41'000'000'000ull;
  e.peak_memory_bytes = 2'000'000'000ull;
  e.disk_available_bytes = 12'000'000'000ull;
  e.memory_available_bytes = 8'000'000'000ull;
  const std::string disk = refusal(e);
  BOOST_TEST(contains(disk, "this render would write up to 41 GB"));
  BOOST_TEST(contains(disk, "but /data has 12 GB free"));
  BOOST_TEST(contains(disk, "(use budget.force to render anyway)"));
  BOOST_TEST(!contains(disk, "memory"));

  e.disk_available_bytes = 50'000'000'000ull;
  BOOST_TEST(refusal(e).empty());
  e.seconds = 3.2 * 86400;
  const std::string slow = refusal(e);
  BOOST_TEST(
      contains(slow, "would take about 3.2 days at these settings (41 wavelengths, 64 view segments, 16384x8192"));
  BOOST_TEST(contains(slow, kForceSetting));
  e.seconds = 23.0 * 3600;
  BOOST_TEST(refusal(e).empty());

  e.memory_available_bytes = 1'000'000'000ull;
  BOOST_TEST(contains(refusal(e), "would need about 2.0 GB of memory but 1.0 GB is available"));
  // Unknown disk or memory: not checked.
  e.memory_available_bytes.reset();
  e.disk_available_bytes.reset();
  BOOST_TEST(refusal(e).empty());
}

BOOST_AUTO_TEST_CASE(formatting) {
  BOOST_TEST(format_bytes(512) == "512 bytes");
  BOOST_TEST(format_bytes(720'000) == "720 kB");
  BOOST_TEST(format_bytes(46'200'000) == "46 MB");
  BOOST_TEST(format_bytes(1'500'000'000) == "1.5 GB");
  BOOST_TEST(format_duration(2.1) == "2.1 s");
  BOOST_TEST(format_duration(720) == "12 min");
  BOOST_TEST(format_duration(5 * 3600) == "5.0 h");
  BOOST_TEST(format_duration(3.2 * 86400) == "3.2 days");
}

BOOST_AUTO_TEST_CASE(the_machine_is_read) {
  BOOST_TEST(available_memory_bytes().value_or(0) > 0u);
  // A folder that does not exist yet is on the file system of its nearest existing parent.
  BOOST_TEST(available_disk_bytes("/tmp/skyspec-no-such-folder/a/b").value_or(0) > 0u);
}

BOOST_AUTO_TEST_CASE(measured_time_scales_with_pixels_frames_and_threads) {
  const Scene s = scene_with("[camera]\nwidth = 64\nheight = 64\n[render]\nscattering_orders = 1\n");
  const SkyRenderer r(s);
  RenderPlan p = RenderPlan::for_scene(s);
  p.threads = 1;
  const double one = measure_render_seconds(r, p);
  BOOST_TEST(one > 0.0);
  BOOST_TEST(one < 60.0);
  p.frames = 1000;
  p.threads = 2;
  const double many = measure_render_seconds(r, p);
  // Two independent samples of the same work: the same per-pixel cost within a factor of 3.
  BOOST_TEST(many / one > 500.0 / 3);
  BOOST_TEST(many / one < 500.0 * 3);
}

BOOST_AUTO_TEST_SUITE_END()  // test_render_budget
