#include "skyspec/timelapse.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>

#include "base/atomic_file.hpp"
#include "base/output_lock.hpp"
#include "job/job_collect.hpp"
#include "job/job_plan.hpp"
#include "job/job_run.hpp"
#include "job/task_record.hpp"
#include "physics/date_time.hpp"
#include "render/render_budget.hpp"
#include "skyspec/error.hpp"
#include "skyspec/render.hpp"

namespace skyspec {
namespace {

namespace ts = timelapse_setting;
constexpr int kMaxFrames = 100000;

// The job of a time-lapse: the scene (every key, as TOML) at its own place, one time range, the
// frames named <output.name>_NNNN in output.directory.
JobSpec timelapse_job(const Scene& scene, const DateTime& start, const DateTime& end, double step_minutes) {
  JobSpec job;
  job.name = scene.output.name;
  job.preset = "default";
  Scene recorded = scene;
  recorded.sun.date_time.clear();  // set per frame
  job.scene_toml = scene_to_toml(recorded);
  job.times.push_back({start, end, step_minutes});
  job.exr = scene.output.exr;
  job.png = scene.output.png;
  job.tasks_per_chunk = 24;
  job.output_directory = std::filesystem::absolute(scene.output.directory).lexically_normal();
  job.task_prefix = scene.output.name + "_";
  job.task_digits = 4;
  job.task_folder = "";
  return job;
}

// The automatic exposure of the frame with the highest sun, metered on a 64-pixel-wide render of
// it, in EV clamped to output.exposure_ev's range and rounded to 6 decimals (what the frames'
// scenes record).
double metered_exposure_ev(const JobPlan& plan, int& frame) {
  frame = 0;
  for (const JobTask& t : plan.tasks)
    if (t.sun_elevation_deg > plan.tasks[static_cast<size_t>(frame)].sun_elevation_deg) frame = t.index;
  Scene meter = task_scene(plan, plan.tasks[static_cast<size_t>(frame)]);
  const double aspect = static_cast<double>(meter.camera.height) / meter.camera.width;
  meter.camera.width = 64;
  meter.camera.height = std::max(1, static_cast<int>(std::lround(64 * aspect)));
  const SpectralImageBuffer image = render_to_memory(meter);
  const double ev = std::clamp(std::log2(image.metered_exposure_scale), -64.0, 64.0);
  char text[64];
  std::snprintf(text, sizeof text, "%.6f", ev);
  return std::stod(text);
}

}  // namespace

TimelapseResult render_timelapse(const Scene& scene, const TimelapseSettings& settings,
                                 const TimelapseProgress& progress) {
  if (settings.start.empty()) throw InputError(ts::kStart, "(missing)", "an ISO 8601 date-time with UTC offset");
  if (settings.end.empty()) throw InputError(ts::kEnd, "(missing)", "an ISO 8601 date-time with UTC offset");
  const DateTime start = parse_iso8601(settings.start, ts::kStart), end = parse_iso8601(settings.end, ts::kEnd);
  const double span_s = seconds_between(start, end);
  if (span_s < 0)
    throw InputError(ts::kEnd, "\"" + settings.end + "\"", "a time not before the start (" + settings.start + ")");
  if (!(settings.step_minutes > 0.0) || !std::isfinite(settings.step_minutes))
    throw InputError(ts::kStepMinutes, std::to_string(settings.step_minutes), "a number of minutes > 0");
  const double frames_d = std::floor(span_s / (settings.step_minutes * 60.0) + 1e-9) + 1;
  if (frames_d > kMaxFrames)
    throw InputError(ts::kStepMinutes, std::to_string(settings.step_minutes),
                     "a step giving at most " + std::to_string(kMaxFrames) + " frames (this gives " +
                         std::to_string(static_cast<long>(frames_d)) + ")");
  if (!scene.output.exr && !scene.output.png)
    throw InputError("output.exr and output.png", "false", "at least one output to be true");
  JobPlan plan = plan_job(timelapse_job(scene, start, end, settings.step_minutes));
  TimelapseResult result;
  result.frames = static_cast<int>(plan.tasks.size());
  // frames: this call renders only those; the exposure is still the whole sequence's.
  const TaskRange mine = settings.frames.empty() ? TaskRange{0, result.frames}
                                                 : parse_task_range(settings.frames, result.frames, ts::kFrames);
  result.first = mine.first;
  result.last = mine.last;

  // Absurd requests are refused up front (render_budget.hpp): all frames' files and one frame's
  // memory, the tables, then the time of all frames measured on a light renderer of the first.
  const Scene first = task_scene(plan, plan.tasks[static_cast<size_t>(mine.first)]);
  const RenderPlan budget = RenderPlan::for_scene(first, mine.size());
  ensure_writable_directory(first.output.directory, "output.directory");
  RenderEstimate estimate = estimate_render(budget);
  if (!settings.force) {
    refuse_if_over_budget(estimate);
    refuse_if_tables_over_budget(first, estimate);
  }

  if (scene.output.exposure_ev) {
    result.exposure_ev = *scene.output.exposure_ev;
    result.exposure = "given";
  } else {
    int frame = 0;
    result.exposure_ev = metered_exposure_ev(plan, frame);
    std::ostringstream what;
    what << "metered on frame " << frame << " (sun " << std::fixed << std::setprecision(2)
         << plan.tasks[static_cast<size_t>(frame)].sun_elevation_deg << " deg)";
    result.exposure = what.str();
  }
  plan.job.exposure_ev = result.exposure_ev;
  if (!settings.force) {
    const SkyRenderer light(scene_for_estimate(task_scene(plan, plan.tasks[static_cast<size_t>(mine.first)])));
    estimate.seconds = measure_render_seconds(light, budget);
    refuse_if_over_budget(estimate);
  }

  // Temporary files of a run that was killed (SIGKILL leaves them).
  result.removed_temporaries = remove_stale_temporaries(plan.task_directory(), plan.job.task_prefix);
  LocalRunOptions run;
  run.keep_done = settings.resume;
  run.progress = progress;
  const LocalRunSummary s = run_tasks_here(plan, mine, run);
  result.written = s.ran - s.failed;
  result.failed = s.failed;
  result.kept = s.kept;
  result.replaced = s.replaced;
  result.failures = s.failures;
  collect_job(plan);
  result.manifest = plan.job.output_directory / "manifest.jsonl";
  for (int k = mine.first; k < mine.last; ++k)
    for (const std::string& f : expected_task_files(plan, plan.tasks[static_cast<size_t>(k)]))
      result.files.push_back(plan.job.output_directory / f);
  return result;
}

}  // namespace skyspec
