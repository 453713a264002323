// One task of a job run to the end: its files written atomically under deterministic names, then
// its record, <output>/tasks/<id>.json (parameters, files with sizes and SHA-256, irradiance,
// timing, software version, or the error that stopped it), also written atomically and last. A
// task whose record says "ok", records this task's scene and whose files still have the recorded
// sizes and checksums is done: runs after a crash or a cancelled allocation skip it.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

#include "job/job_plan.hpp"

namespace skyspec {

/// Where a task's record lives.
std::filesystem::path task_record_path(const JobPlan& plan, const JobTask& task);

/// Renders the task's outputs (job.produce) and writes its record. A task that fails (bad input
/// its scene only shows now, a render or write error) gets a record with "status": "failed" and
/// the error, and no output files; the record is returned either way. Throws only when even the
/// record cannot be written (IoError) or when the run is cancelled (skyspec::Cancelled). `threads`
/// > 0 renders on that many threads (render and EXR compression) instead of the scene's.
nlohmann::json run_task(const JobPlan& plan, const JobTask& task, int threads = 0);

/// Whether the task is done (see above); `why` says what is missing or wrong otherwise.
bool task_done(const JobPlan& plan, const JobTask& task, std::string& why);

/// The record a task left, or null when there is none or it is not valid JSON.
nlohmann::json read_task_record(const JobPlan& plan, const JobTask& task);

/// SHA-256 of the task's scene as TOML (render.threads left out): what its files are a render of.
std::string task_scene_digest(const Scene& scene);

}  // namespace skyspec
