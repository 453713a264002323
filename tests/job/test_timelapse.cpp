// The time-lapse (skyspec/timelapse.hpp) as a library function: its frames are job tasks named
// <name>_NNNN with records and a manifest, share one exposure (metered on the highest sun, or
// given), a resumed run keeps intact frames and replaces damaged ones, and bad settings are named by
// their neutral ids before anything is written.
#include <boost/test/unit_test.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "scratch_folder.hpp"
#include "skyspec/error.hpp"
#include "skyspec/timelapse.hpp"

BOOST_AUTO_TEST_SUITE(test_timelapse)

using namespace skyspec;

namespace {
Scene small_scene(const std::filesystem::path& out) {
  SceneLoader l("default");
  l.apply_toml(
      "[camera]\nwidth = 8\nheight = 8\n[render]\nscattering_orders = 1\n[location]\nlatitude_deg = 48.1\n"
      "longitude_deg = 11.6\n",
      "test");
  l.set("output.directory", out.string());
  l.set("output.name", "dusk");
  return l.finish();
}

TimelapseSettings evening() {
  TimelapseSettings s;
  s.start = "2026-06-21T20:00:00+02:00";
  s.end = "2026-06-21T20:45:00+02:00";
  s.step_minutes = 15;
  return s;
}

std::string setting_of(const Scene& scene, const TimelapseSettings& s) {
  try {
    render_timelapse(scene, s);
  } catch (const InputError& e) {
    return e.setting();
  }
  return "";
}
}  // namespace

BOOST_AUTO_TEST_CASE(frames_are_tasks_with_one_exposure_and_a_resume_keeps_intact_ones) {
  test::ScratchFolder folder("timelapse");
  const Scene scene = small_scene(folder.path);
  int calls = 0;
  const TimelapseResult r = render_timelapse(scene, evening(), [&calls](int done, int total) {
    ++calls;
    BOOST_TEST(total == 4);
    BOOST_TEST(done == calls);
  });
  BOOST_TEST(r.frames == 4);
  BOOST_TEST(r.written == 4);
  BOOST_TEST(calls == 4);
  BOOST_TEST(r.exposure.rfind("metered on frame 0", 0) == 0, r.exposure);  // the sun sinks: frame 0 is highest
  BOOST_TEST(r.files.size() == 8u);
  BOOST_TEST(r.files[0] == folder.path / "dusk_0000.exr");
  BOOST_TEST(r.files[7] == folder.path / "dusk_0003.png");
  BOOST_TEST(std::filesystem::is_regular_file(folder.path / "dusk_0002.json"));
  BOOST_TEST(std::filesystem::is_regular_file(r.manifest));
  // Every frame records the same exposure.
  for (int k = 0; k < 4; ++k) {
    const std::string record = test::read_all(folder.path / ("dusk_000" + std::to_string(k) + ".json"));
    BOOST_TEST(record.find("\"status\":\"ok\"") != std::string::npos);
  }
  const std::string first = test::read_all(folder.path / "dusk_0000.exr"),
                    last = test::read_all(folder.path / "dusk_0003.exr");
  const std::string ev = "exposure_ev = ";
  BOOST_TEST(first.substr(first.find(ev), 30) == last.substr(last.find(ev), 30));

  // A damaged frame is replaced, the others kept.
  test::write_text(folder.path / "dusk_0001.png", "garbage");
  TimelapseSettings resume = evening();
  resume.resume = true;
  const TimelapseResult again = render_timelapse(scene, resume);
  BOOST_TEST(again.written == 1);
  BOOST_TEST(again.kept == 3);
  BOOST_TEST(again.replaced.size() == 1u);
  BOOST_TEST(again.exposure_ev == r.exposure_ev);
  BOOST_TEST(test::read_all(folder.path / "dusk_0001.png") != "garbage");

  // A share of the frames, with a given exposure.
  Scene given = scene;
  given.output.exposure_ev = -10.0;
  TimelapseSettings share = evening();
  share.frames = "2-3";
  const TimelapseResult part = render_timelapse(given, share);
  BOOST_TEST(part.first == 2);
  BOOST_TEST(part.last == 4);
  BOOST_TEST(part.written == 2);
  BOOST_TEST(part.exposure == "given");
  BOOST_TEST(part.exposure_ev == -10.0);
}

BOOST_AUTO_TEST_CASE(bad_settings_are_named_before_anything_is_written) {
  test::ScratchFolder folder("timelapse-bad");
  const Scene scene = small_scene(folder.path / "out");
  TimelapseSettings s = evening();
  s.start = "";
  BOOST_TEST(setting_of(scene, s) == timelapse_setting::kStart);
  s = evening();
  s.end = "2026-06-21T19:00:00+02:00";
  BOOST_TEST(setting_of(scene, s) == timelapse_setting::kEnd);
  s = evening();
  s.end = "tomorrow";
  BOOST_TEST(setting_of(scene, s) == timelapse_setting::kEnd);
  s = evening();
  s.step_minutes = 0;
  BOOST_TEST(setting_of(scene, s) == timelapse_setting::kStepMinutes);
  s.step_minutes = 1e-6;
  BOOST_TEST(setting_of(scene, s) == timelapse_setting::kStepMinutes);
  s = evening();
  s.frames = "3-4";
  BOOST_TEST(setting_of(scene, s) == timelapse_setting::kFrames);
  BOOST_TEST(!std::filesystem::exists(folder.path / "out"));
}

BOOST_AUTO_TEST_SUITE_END()
