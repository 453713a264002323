// One task of a job run to the end: its files written atomically under deterministic names, then
// its record, <output>/tasks/<id>.json (parameters, files with sizes and SHA-256, irradiance,
// timing, software version, or the error that stopped it), also written atomically and last. A
// task whose record says "ok", records this task's scene and whose files still have the recorded
// sizes and checksums is done: runs after a crash or a cancelled allocation skip it.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "base/output_lock.hpp"
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

/// The lock a run holds on a task while it runs and records it ("<task folder>/.<id>.task.lock"),
/// or null when another process holds it: two runs of the same tasks at once (a resubmitted array
/// job, a second `job run`) each run a task only when they hold its lock, and take up the tasks the
/// other holds last (waiting for its lock: done by then, or run again if the other died).
std::unique_ptr<OutputLock> try_lock_task(const JobPlan& plan, const JobTask& task);

/// Whether the task is done (see above); `why` says what is missing or wrong otherwise.
bool task_done(const JobPlan& plan, const JobTask& task, std::string& why);

/// The record a task left, or null when there is none or it is not valid. Records are untrusted
/// input (a crash, a full disk or another hand may have left anything): `damaged`, when given, says
/// why a record that exists was not taken (record_problem, or it is not a regular file or not JSON).
nlohmann::json read_task_record(const JobPlan& plan, const JobTask& task, std::string* damaged = nullptr);

/// What is wrong with a task record read from disk, or "" when it is well formed for this task:
/// "task" and "id" are this task's; "status" is "ok" or "failed"; every file entry has a relative
/// "path" inside the job's folder (no "..", not absolute), whole "bytes" and a 64-digit hex
/// "sha256"; a "date_time" reads as ISO 8601; an ok record's sun angles are finite and, with
/// "irradiance", its wavelengths are the task scene's grid, every spectral array has one finite
/// value per wavelength and every broadband value is finite.
std::string record_problem(const JobPlan& plan, const JobTask& task, const nlohmann::json& record);

/// The files a task's record must list to be done: its scene's render outputs, relative to the
/// job's folder (none when the job renders no images).
std::vector<std::string> expected_task_files(const JobPlan& plan, const JobTask& task);

/// SHA-256 of the task's scene as TOML (render.threads left out): what its files are a render of.
std::string task_scene_digest(const Scene& scene);

}  // namespace skyspec
