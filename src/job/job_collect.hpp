// After a job's tasks: the manifest (one JSON line per task, in task order) and one irradiance
// table per site, assembled from the tasks' records. Run by `skyspec job run` at its end and by
// `skyspec job collect` (the step after the shards of a farm or a Slurm array).
//
//   <output>/manifest.jsonl         every task's record; tasks without one: {"status": "missing"}
//   <output>/irradiance_<site>.csv  one row per task of the site that succeeded (job.produce has
//                                   "irradiance"): time, sun, parameters, broadband values, then
//                                   the spectral global horizontal, diffuse horizontal and direct
//                                   normal irradiance per wavelength
//   <output>/frames/f000003.exr     with job.tile_rows: a frame's strips merged (io/exr_merge.hpp)
//                                   once all of them succeeded, with its record f000003.json (the
//                                   strips' checksums and its own); frames.jsonl lists them
#pragma once

#include <string>
#include <vector>

#include "job/job_plan.hpp"

namespace skyspec {

struct JobSummary {
  int ok = 0, failed = 0, missing = 0;
  int damaged = 0;                           ///< records that are not valid for their task, or whose files are gone
  std::vector<std::string> damaged_records;  ///< "t000012: <what is wrong>" for the first few
  int frames_merged = 0, frames_kept = 0, frames_incomplete = 0;  ///< job.tile_rows
  std::vector<std::string> failures;                              ///< "t000012: <error>" for the first few failed tasks
  std::vector<std::filesystem::path> tables;                      ///< the irradiance tables written
  std::string describe() const;
};

/// Writes the manifest and the tables (atomically, replacing earlier ones) from the records found.
JobSummary collect_job(const JobPlan& plan);

}  // namespace skyspec
