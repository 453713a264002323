#include "job/job_run.hpp"

#include <chrono>
#include <filesystem>
#include <memory>
#include <thread>

#include "base/atomic_file.hpp"
#include "base/cancellation.hpp"
#include "base/output_lock.hpp"
#include "job/task_record.hpp"

namespace skyspec {
namespace {
// Whether the task's record or any of its files exists (not following a link).
bool left_behind(const JobPlan& plan, const JobTask& task) {
  std::error_code ec;
  const auto present = [&ec](const std::filesystem::path& p) {
    return std::filesystem::exists(std::filesystem::symlink_status(p, ec));
  };
  if (present(task_record_path(plan, task))) return true;
  for (const std::string& f : expected_task_files(plan, task))
    if (present(plan.job.output_directory / f)) return true;
  return false;
}
}  // namespace

LocalRunSummary run_tasks_here(const JobPlan& plan, TaskRange range, const LocalRunOptions& options) {
  ensure_writable_directory(plan.job.output_directory, "job.output");
  std::filesystem::create_directories(plan.task_directory());
  LocalRunSummary summary;
  int finished = 0;
  const auto report = [&] {
    ++finished;
    if (options.progress) options.progress(finished, range.size());
  };
  // Holding the task's lock.
  const auto run_locked = [&](const JobTask& task, bool check_again) {
    std::string why;
    if (check_again && options.keep_done && task_done(plan, task, why)) {  // finished by another run meanwhile
      ++summary.kept;
      return;
    }
    const auto record = run_task(plan, task, options.threads);
    ++summary.ran;
    if (record.value("status", "") != "ok") {
      ++summary.failed;
      const std::string error = record.value("error", std::string("(no error recorded)"));
      summary.failures.push_back(task.id() + ": " + error);
      if (options.on_failure) options.on_failure(task.id(), error);
    }
  };
  std::vector<int> held_elsewhere;
  for (int k = range.first; k < range.last; ++k) {
    throw_if_cancelled();
    const JobTask& task = plan.tasks[k];
    std::string why;
    const bool done = task_done(plan, task, why);
    if (done && options.keep_done) {
      ++summary.kept;
    } else if (const auto lock = try_lock_task(plan, task)) {
      // What an earlier run (or another program) left in the way and why it is not kept.
      if (!done && left_behind(plan, task)) summary.replaced.push_back(task.id() + ": " + why);
      run_locked(task, true);
    } else {
      held_elsewhere.push_back(k);
      continue;
    }
    report();
  }
  for (const int k : held_elsewhere) {
    const JobTask& task = plan.tasks[k];
    std::unique_ptr<OutputLock> lock;
    while (!(lock = try_lock_task(plan, task))) {
      throw_if_cancelled();
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    const int before = summary.kept;
    run_locked(task, true);
    summary.kept_from_elsewhere += summary.kept - before;
    report();
  }
  return summary;
}

}  // namespace skyspec
