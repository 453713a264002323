// A job: one base scene swept over sites, date-times and scene parameters, one task per
// combination (docs/jobs.md). This file is the job file's schema and its reader; job_plan.hpp
// turns a JobSpec into tasks.
//
//   [job]    name, scene (a preset or a scene file), quality, produce, output, tasks_per_chunk,
//            min_sun_elevation_deg, tile_rows (giant images: each frame in strips, merged)
//   [scene]  scene keys for every task (any key of docs/scene-keys.md but the ones the job sets)
//   [[site]] name, latitude_deg, longitude_deg, altitude_m
//   [[time]] start, end (ISO 8601 with UTC offset, or TOML offset date-times), step_minutes
//   [axes]   scene key = [values] or { start, stop, count }: every combination
//   [random] seed, samples, and [random.axes] scene key = { min, max }: a seeded random design
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "physics/date_time.hpp"

namespace skyspec {

struct JobSite {
  std::string name;  ///< letters, digits, '-', '_' (it names files)
  double latitude_deg = 0.0, longitude_deg = 0.0;
  double altitude_m = 0.0;  ///< added to the camera's height (the ground stays at sea level)
};

struct JobTimeRange {
  DateTime start, end;
  double step_minutes = 60.0;
};

/// A swept scene key and its values as TOML value text ("2e-05", "\"fisheye\"", "[1, 2, 3]").
struct JobAxis {
  std::string key;
  std::vector<std::string> values;
};

/// A key of the random design: values uniform in [min, max] (whole numbers when both are).
struct JobRandomAxis {
  std::string key;
  double min = 0.0, max = 0.0;
  bool integer = false;
};

struct JobSpec {
  std::filesystem::path file;  ///< the job file (absolute)
  std::string name;
  std::string preset = "default";    ///< job.scene when it names a preset
  std::filesystem::path scene_file;  ///< job.scene when it names a file (absolute)
  std::string quality;
  std::string scene_toml;           ///< the [scene] table, as TOML text applied over the preset and file
  std::vector<JobSite> sites;       ///< empty: the scene's own location
  std::vector<JobTimeRange> times;  ///< empty: the scene's own sun
  std::optional<double> min_sun_elevation_deg;
  std::vector<JobAxis> axes;
  std::uint64_t random_seed = 0;
  int random_samples = 0;
  std::vector<JobRandomAxis> random_axes;
  bool exr = true, png = true, irradiance = false;  ///< job.produce
  int tasks_per_chunk = 24;
  /// When > 0, each frame is rendered in strips of at most this many rows (one task each, with
  /// pixel bounds) and `job collect` merges them into <output>/frames/f<frame>.exr.
  int tile_rows = 0;
  std::filesystem::path output_directory;  ///< job.output (absolute; relative to the working folder)
  /// How tasks are named and where their files go: "<task_prefix><index in task_digits digits>" in
  /// <output>/<task_folder> ("" = the output folder itself). A job file's tasks are "t000012" in
  /// tasks/; a time-lapse's frames "<output.name>_0012" beside its manifest (skyspec/timelapse.hpp).
  std::string task_prefix = "t";
  int task_digits = 6;
  std::string task_folder = "tasks";
  /// When set, every task's output.exposure_ev: one exposure for all (a time-lapse's).
  std::optional<double> exposure_ev;
};

/// Reads and checks a job file. InputError names the key (e.g. "time[1].step_minutes") with the
/// file:line:column, the value and what is allowed; unknown keys are refused. Scene keys are
/// checked by the scene loader when the plan is made (plan_job).
JobSpec read_job_file(const std::filesystem::path& path);
/// The same from TOML text; `origin` names it in messages, `base` resolves relative paths.
JobSpec parse_job(const std::string& text, const std::string& origin, const std::filesystem::path& base);

/// Scene keys a job sets itself (per task): not allowed in [scene], [axes] or [random.axes].
bool job_owned_scene_key(const std::string& key);

}  // namespace skyspec
