// `skyspec timelapse`: one image per time step between a start and an end date-time at a place,
// the sun placed by the NREL solar position algorithm, with one exposure for every frame.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "base/atomic_file.hpp"
#include "base/output_lock.hpp"
#include "colour/display_pipeline.hpp"
#include "colour/exposure.hpp"
#include "commands.hpp"
#include "io/exr_input.hpp"
#include "io/png_image.hpp"
#include "io/provenance.hpp"
#include "job/job_plan.hpp"
#include "physics/date_time.hpp"
#include "physics/solar_position.hpp"
#include "progress.hpp"
#include "render/render_budget.hpp"
#include "scene_options.hpp"
#include "skyspec/error.hpp"
#include "skyspec/render.hpp"

namespace skyspec::cli {
namespace {

constexpr int kMaxFrames = 100000;

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
  std::string start, end;
  double step_minutes = 0.0;
  std::string frames;  ///< --frames A-B: only these frames (a farm's share of the sequence)
  bool resume = false, quiet = false, force = false;
};

std::string frame_name(const std::string& base, int k) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "_%04d", k);
  return base + buf;
}

// Whether a frame an earlier run left can be kept by --resume: files are untrusted, so each file
// the frame's scene asks for must exist, decode completely (the EXR's pixels read through
// OpenEXR; the PNG's rows with libpng's CRC and Adler-32 checks) and record exactly this frame's
// scene (its skyspec:scene: the same place, time, size, quality, exposure and grid). `why` says
// what was wrong otherwise.
bool frame_intact(const Scene& s, std::string& why) {
  const std::filesystem::path dir(s.output.directory);
  // As the files record it (no output location, no threads: a resumed run may use other threads).
  const auto normalised = [](const Scene& scene) { return scene_to_toml(scene, SceneTomlKeys::Recorded); };
  const std::string expected = normalised(s);
  const auto same_scene = [&](const std::string& recorded) {
    try {
      SceneLoader loader;
      loader.apply_toml(recorded, "the frame's skyspec:scene");
      return normalised(loader.finish()) == expected;
    } catch (const InputError&) {
      return false;
    }
  };
  try {
    if (s.output.exr) {
      const auto exr = dir / (s.output.name + ".exr");
      if (!std::filesystem::exists(exr)) return why = exr.filename().string() + " is missing", false;
      verify_exr_pixels(exr);  // every chunk decoded, a band at a time
      if (!same_scene(read_exr_provenance(exr).scene))
        return why = exr.filename().string() + " records another scene", false;
    }
    if (s.output.png) {
      const auto png = dir / (s.output.name + ".png");
      if (!std::filesystem::exists(png)) return why = png.filename().string() + " is missing", false;
      const auto text = read_png_text_verified(png);
      const auto scene = text.find(kSceneAttribute);
      if (scene == text.end() || !same_scene(scene->second))
        return why = png.filename().string() + " records another scene", false;
    }
  } catch (const IoError& e) {
    return why = e.what(), false;
  }
  return true;
}

int run(TimelapseOptions& o) {
  if (o.start.empty()) throw InputError("--start", "(missing)", "an ISO 8601 date-time with UTC offset");
  if (o.end.empty()) throw InputError("--end", "(missing)", "an ISO 8601 date-time with UTC offset");
  const DateTime start = parse_iso8601(o.start, "--start"), end = parse_iso8601(o.end, "--end");
  const double span_s = seconds_between(start, end);
  if (span_s < 0) throw InputError("--end", "\"" + o.end + "\"", "a time not before --start (" + o.start + ")");
  if (!(o.step_minutes > 0.0) || !std::isfinite(o.step_minutes))
    throw InputError("--step-minutes", std::to_string(o.step_minutes), "a number of minutes > 0");
  const double frames_d = std::floor(span_s / (o.step_minutes * 60.0) + 1e-9) + 1;
  if (frames_d > kMaxFrames)
    throw InputError("--step-minutes", std::to_string(o.step_minutes),
                     "a step giving at most " + std::to_string(kMaxFrames) + " frames (this gives " +
                         std::to_string(static_cast<long>(frames_d)) + ")");
  const int frames = static_cast<int>(frames_d);
  // --frames: this process renders only those; the exposure is still the whole sequence's.
  const TaskRange mine = o.frames.empty() ? TaskRange{0, frames} : parse_task_range(o.frames, frames, "--frames");

  auto frame_scene = [&](int k, const std::string& extra_key = {}, const std::string& extra_value = {}) {
    const std::string when = to_iso8601(add_seconds(start, k * o.step_minutes * 60.0));
    return load_scene(o.scene, [&](SceneLoader& l) {
      l.apply_override("sun.date_time", "\"" + when + "\"", "--start/--step-minutes");
      if (!extra_key.empty()) l.apply_override(extra_key, extra_value, "timelapse");
    });
  };
  Scene first = frame_scene(0);
  // Absurd requests are refused up front (render_budget.hpp): all frames' files and one frame's
  // memory now, the time of all frames once the first frame's renderer is built.
  const RenderPlan plan = RenderPlan::for_scene(first, static_cast<int>(mine.size()));
  ensure_writable_directory(first.output.directory, "output.directory");  // its errors first
  RenderEstimate estimate = estimate_render(plan);
  if (!o.force) refuse_if_over_budget(estimate);
  if (!o.force) refuse_if_tables_over_budget(first, estimate);  // before the tables are built
  bool measured = o.force;
  // One exposure for all frames: the one given, or the automatic exposure of the frame with the
  // highest sun, metered on a 64 x 64 render of it.
  std::string ev_text;
  if (!first.output.exposure_ev) {
    int brightest = 0;
    double best = -1e9;
    for (int k = 0; k < frames; ++k) {
      const double el = frame_scene(k).sun.elevation_deg;
      if (el > best) best = el, brightest = k;
    }
    Scene meter = frame_scene(brightest);
    const double aspect = static_cast<double>(meter.camera.height) / meter.camera.width;
    meter.camera.width = 64;
    meter.camera.height = std::max(1, static_cast<int>(std::lround(64 * aspect)));
    const SpectralImageBuffer img = render_to_memory(meter);
    // Within output.exposure_ev's range: a night sky meters far above it (67.75 EV at a sun 18
    // degrees down), and a frame must record a scene that loads again.
    const double metered = std::log2(metered_exposure_scale(img.rgb, img.width, img.height));
    const double ev = std::clamp(metered, -64.0, 64.0);
    if (ev != metered && !o.quiet)
      std::cout << "metered exposure " << metered << " EV is outside -64..64 EV; using " << ev << " EV\n";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6f", ev);
    ev_text = buf;
    if (!o.quiet)
      std::cout << "exposure " << ev_text << " EV for every frame (metered on frame " << brightest << ", sun " << best
                << " deg)\n";
  }

  if (o.resume) {  // temporary files of a run that was killed (SIGKILL leaves them)
    const int stale = remove_stale_temporaries(first.output.directory, first.output.name + "_");
    if (stale > 0 && !o.quiet) std::cout << "removed " << stale << " temporary file(s) of an earlier run\n";
  }
  ProgressBar bar("time-lapse", o.quiet);
  bar.watch_preparation();
  int written = 0, skipped = 0, replaced = 0;
  for (int k = mine.first; k < mine.last; ++k) {
    Scene s = frame_scene(k, "output.name", "\"" + frame_name(first.output.name, k) + "\"");
    if (!ev_text.empty()) s.output.exposure_ev = std::stod(ev_text);
    std::string why;
    if (o.resume && frame_intact(s, why)) {
      ++skipped;
    } else {
      if (o.resume && why.find(" is missing") == std::string::npos) {
        ++replaced;
        if (!o.quiet) std::cerr << "skyspec: frame " << k << " rendered again: " << why << "\n";
      }
      render_scene_to_files(s, DisplaySettings{}, {}, [&](const SkyRenderer& r) {
        if (measured) return;
        RenderPlan rest = plan;
        rest.frames = mine.last - k;
        estimate.seconds = measure_render_seconds(r, rest);
        refuse_if_over_budget(estimate);
        measured = true;
      });
      ++written;
    }
    bar.update(k - mine.first + 1, mine.size());
  }
  bar.finish();
  if (!o.quiet)
    std::cout << "wrote " << written << " frame(s)"
              << (skipped ? ", kept " + std::to_string(skipped) + " finished" : "")
              << (replaced ? ", replaced " + std::to_string(replaced) + " damaged or foreign" : "") << " in "
              << first.output.directory << "\n";
  return kExitOk;
}

}  // namespace

Command add_timelapse_command(CLI::App& app) {
  auto o = std::make_shared<TimelapseOptions>();
  auto* cmd = app.add_subcommand("timelapse", "Render one image per time step at a place, the sun from date and time");
  cmd->footer(
      "Example:\n"
      "  skyspec timelapse --latitude 48.14 --longitude 11.58 --start 2026-06-21T19:00:00+02:00 \\\n"
      "      --end 2026-06-21T22:30:00+02:00 --step-minutes 15 --out sunset\n"
      "Frames are <name>_0000.exr/.png ...; all share one exposure (--exposure, or metered once on the frame\n"
      "with the highest sun). Finished frames are complete files (written atomically): --resume keeps them.");
  add_scene_options(*cmd, o->scene);
  add_quality_option(*cmd, o->scene);
  cmd->add_option("--start", o->start, "first frame, ISO 8601 with UTC offset (e.g. 2026-06-21T19:00:00+02:00)");
  cmd->add_option("--end", o->end, "last frame at or before this time");
  cmd->add_option("--step-minutes", o->step_minutes, "time between frames, minutes");
  cmd->add_option("--frames", o->frames,
                  "render only frames A-B (inclusive, 0-based) of the sequence, e.g. one machine's share; the "
                  "exposure is still metered on the whole sequence, so the shares match");
  cmd->add_flag("--resume", o->resume,
                "keep the frames an interrupted run finished: those whose files decode completely and record this "
                "frame's scene (others are rendered again)");
  cmd->add_flag("--force", o->force,
                "render even if the frames exceed the free disk, a frame needs more memory than is available or "
                "the estimated time exceeds 24 hours");
  cmd->add_flag("-q,--quiet", o->quiet, "no progress bar and no summary");
  return {cmd, [o] { return run(*o); },
          [o] {  // run's checks of the times and the scene, without rendering (Command::validate)
            const std::string when = o->start.empty() ? "" : to_iso8601(parse_iso8601(o->start, "--start"));
            if (!o->end.empty()) parse_iso8601(o->end, "--end");
            load_scene(o->scene, [&](SceneLoader& l) {
              if (!when.empty()) l.apply_override("sun.date_time", "\"" + when + "\"", "--start/--step-minutes");
            });
          }};
}

}  // namespace skyspec::cli
