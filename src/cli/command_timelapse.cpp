// `skyspec timelapse`: one image per time step between a start and an end date-time at a place,
// the sun placed by the NREL solar position algorithm, with one exposure for every frame: the
// library's render_timelapse (skyspec/timelapse.hpp), whose frames are the tasks of a job.

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "physics/date_time.hpp"
#include "progress.hpp"
#include "scene_options.hpp"
#include "skyspec/error.hpp"
#include "skyspec/timelapse.hpp"

namespace skyspec::cli {
namespace {

std::vector<KeyFlag> timelapse_flags() {
  std::vector<KeyFlag> flags = output_flags();
  append_flags(flags, camera_flags(true));
  append_flags(
      flags,
      {
          {"--latitude", "location.latitude_deg", "latitude, degrees north", {}, false},
          {"--longitude", "location.longitude_deg", "longitude, degrees east", {}, false},
          {"--threads", "render.threads", "worker threads (0: all cores)", {}, false},
          {"--exposure", "output.exposure_ev", "exposure in EV for every frame (default: metered once)", {}, false},
      });
  append_flags(flags, spectrum_flags());
  return flags;
}

struct TimelapseOptions {
  SceneOptions scene{"default", {}, {}, timelapse_flags()};
  TimelapseSettings settings;
  bool quiet = false;
};

int run(TimelapseOptions& o) {
  const Scene scene = load_scene(o.scene);
  ProgressBar bar("time-lapse", o.quiet);
  bar.watch_preparation();
  const TimelapseResult r =
      render_timelapse(scene, o.settings, [&bar](int done, int total) { bar.update(done, total); });
  bar.finish();
  if (r.removed_temporaries > 0 && !o.quiet)
    std::cout << "removed " << r.removed_temporaries << " temporary file(s) of an earlier run\n";
  for (const auto& why : r.replaced) std::cerr << "skyspec: frame rendered again: " << why << "\n";
  for (const auto& f : r.failures) std::cerr << "skyspec: frame failed: " << f << "\n";
  if (!o.quiet)
    std::cout << "exposure " << r.exposure_ev << " EV for every frame, " << r.exposure << "\n"
              << "wrote " << r.written << " frame(s)"
              << (r.kept ? ", kept " + std::to_string(r.kept) + " finished" : "")
              << (r.replaced.empty() ? "" : ", replaced " + std::to_string(r.replaced.size()) + " damaged or foreign")
              << (r.failed ? ", " + std::to_string(r.failed) + " failed" : "") << " in " << scene.output.directory
              << " (manifest: " << r.manifest.string() << ")\n";
  return r.failed ? kExitTasksFailed : kExitOk;
}

}  // namespace

Command add_timelapse_command(CLI::App& app) {
  auto o = std::make_shared<TimelapseOptions>();
  auto* cmd = app.add_subcommand("timelapse", "Render one image per time step at a place, the sun from date and time");
  cmd->footer(
      "Example:\n"
      "  skyspec timelapse --latitude 48.14 --longitude 11.58 --start 2026-06-21T19:00:00+02:00 \\\n"
      "      --end 2026-06-21T22:30:00+02:00 --step-minutes 15 --out sunset\n"
      "Frames are <name>_0000.exr/.png ... with a record each (<name>_0000.json) and manifest.jsonl (the frames'\n"
      "times and sun angles); all share one exposure (--exposure, or metered once on the frame with the highest\n"
      "sun). Frames are written atomically; --resume keeps those whose record, scene and files check out.");
  add_scene_options(*cmd, o->scene);
  add_quality_option(*cmd, o->scene);
  cmd->add_option("--start", o->settings.start,
                  "first frame, ISO 8601 with UTC offset (e.g. 2026-06-21T19:00:00+02:00)");
  cmd->add_option("--end", o->settings.end, "last frame at or before this time");
  cmd->add_option("--step-minutes", o->settings.step_minutes, "time between frames, minutes");
  cmd->add_option("--frames", o->settings.frames,
                  "render only frames A-B (inclusive, 0-based) of the sequence, e.g. one machine's share; the "
                  "exposure is still metered on the whole sequence, so the shares match");
  cmd->add_flag("--resume", o->settings.resume,
                "keep the frames an earlier run finished: those whose record names this frame's scene and whose "
                "files have their recorded sizes and SHA-256 (others are rendered again; without it every frame is)");
  cmd->add_flag("--force", o->settings.force,
                "render even if the frames exceed the free disk, a frame needs more memory than is available or "
                "the estimated time exceeds 24 hours");
  cmd->add_flag("-q,--quiet", o->quiet, "no progress bar and no summary");
  return {cmd, [o] { return run(*o); },
          [o] {  // run's checks of the times and the scene, without rendering (Command::validate)
            const std::string when =
                o->settings.start.empty() ? "" : to_iso8601(parse_iso8601(o->settings.start, "--start"));
            if (!o->settings.end.empty()) parse_iso8601(o->settings.end, "--end");
            load_scene(o->scene, [&](SceneLoader& l) {
              if (!when.empty()) l.apply_override("sun.date_time", "\"" + when + "\"", "--start/--step-minutes");
            });
          }};
}

}  // namespace skyspec::cli
