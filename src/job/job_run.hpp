// Running a job's tasks in this process, one after the other: what `skyspec job run --shard` and
// `--tasks`, the Dask driver's chunks and a time-lapse do. A task is run only by the process that
// holds its lock (task_record.hpp); tasks another run holds are taken up last, once their lock is
// free: done by then (kept), or run here if that run stopped before finishing them.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "job/job_plan.hpp"

namespace skyspec {

struct LocalRunSummary {
  int ran = 0, kept = 0, failed = 0;
  int kept_from_elsewhere = 0;  ///< of `kept`: finished by another run while this one waited for them
  /// Tasks with files or a record of an earlier run that were run again, and why (task_done's answer).
  std::vector<std::string> replaced;
  std::vector<std::string> failures;  ///< "<task id>: <error>"
};

struct LocalRunOptions {
  int threads = 0;  ///< > 0: render threads instead of the scenes' render.threads
  /// Keep tasks that are done (record, scene and files checked); false runs them all again.
  bool keep_done = true;
  /// After each task: (tasks finished, tasks in the range).
  std::function<void(int done, int total)> progress;
  /// When a task fails (its record says why), as it happens.
  std::function<void(const std::string& id, const std::string& error)> on_failure;
};

/// Runs tasks [range.first, range.last) of the plan here. Polls skyspec::cancellation between
/// tasks and while waiting for a lock (Cancelled).
LocalRunSummary run_tasks_here(const JobPlan& plan, TaskRange range, const LocalRunOptions& options);

}  // namespace skyspec
