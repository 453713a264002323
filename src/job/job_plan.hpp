// A job's tasks: every site x parameter combination x date-time of a JobSpec, in that order (so
// that consecutive tasks are consecutive frames of one site and one set of parameters), with the
// scene each task renders. The order and the scenes depend on the job file alone, never on who
// runs the tasks: shards, chunks and task ids are the same on every machine.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "job/job_spec.hpp"
#include "skyspec/render.hpp"
#include "skyspec/scene.hpp"

namespace skyspec {

/// (scene key, TOML value text) of one task's swept parameters.
using JobParameters = std::vector<std::pair<std::string, std::string>>;

struct JobTask {
  int index = 0;
  int site = -1;                    ///< into JobSpec::sites; -1: the scene's own location
  std::optional<DateTime> time;     ///< none: the scene's own sun
  int combination = 0;              ///< into JobPlan::combinations
  double sun_elevation_deg = 0.0;   ///< apparent (refracted), at the site and time; the scene's without a time
  int frame = 0;                    ///< the image it renders (or a strip of): its index among the job's frames
  std::optional<PixelBounds> tile;  ///< with job.tile_rows: the strip of the frame it renders
  std::string name;                 ///< JobSpec's task_prefix and index
  /// "t000012" (a time-lapse: "sky_0012"): names the task's files and its record.
  const std::string& id() const { return name; }
};

/// A half-open range of task indices [first, last).
struct TaskRange {
  int first = 0, last = 0;
  int size() const { return last - first; }
};

struct JobPlan {
  JobSpec job;
  std::vector<JobParameters> combinations;  ///< [axes] x [random] samples; one empty set without either
  std::vector<JobTask> tasks;
  /// The tasks of each frame (one each, or its strips with job.tile_rows): frame_tasks[f].
  std::vector<TaskRange> frame_tasks;

  /// Chunks of job.tasks_per_chunk consecutive tasks: the unit a cluster runs in one process.
  int chunk_count() const;
  TaskRange chunk(int k) const;
  /// The i-th (1-based) of n shards: contiguous, balanced; all shards together are every task once.
  TaskRange shard(int i, int n) const;
  /// The folder of the tasks' files (<output>/tasks; a time-lapse's: <output>).
  std::filesystem::path task_directory() const;
  /// The site's name, or "scene" for the scene's own location.
  std::string site_name(const JobTask& task) const;
  /// "f000003": names a merged frame's files (job.tile_rows), <output>/frames/f000003.exr.
  static std::string frame_id(int frame);
};

/// Expands the job into tasks and checks every scene key and value it uses (the base scene, each
/// site, each swept value, each random range's ends) with the scene loader, so that a job with an
/// error is refused before any task runs: InputError names the job key ("axes.ground.albedo").
/// Frames with the sun below job.min_sun_elevation_deg are left out.
JobPlan plan_job(const JobSpec& job);

/// The scene of one task: the job's scene, the site, the date-time, the parameters, and outputs
/// named by the task id in task_directory().
Scene task_scene(const JobPlan& plan, const JobTask& task);

/// Parses "I/N" (1 <= I <= N); InputError naming `setting` otherwise.
std::pair<int, int> parse_shard(const std::string& text, const std::string& setting);
/// Parses "A-B" or "A" (indices of tasks or frames, inclusive) within [0, count); InputError naming `setting`.
TaskRange parse_task_range(const std::string& text, int count, const std::string& setting);

}  // namespace skyspec
