// `skyspec job plan|run|collect`: a job file (job/job_spec.hpp) swept into tasks, run on this
// machine in shards, or on a Dask cluster through the Python driver (python/skyspec_jobs.py),
// which runs chunks of tasks with `skyspec job run --tasks A-B` in child processes.

#include <sys/prctl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstring>

#include <cstdlib>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "base/atomic_file.hpp"
#include "base/output_lock.hpp"
#include "commands.hpp"
#include "interrupt.hpp"
#include "job/job_collect.hpp"
#include "job/job_plan.hpp"
#include "job/job_run.hpp"
#include "job/job_tables.hpp"
#include "job/task_record.hpp"
#include "progress.hpp"
#include "render/render_budget.hpp"
#include "skyspec/error.hpp"
#include "skyspec/render.hpp"
#include "transport/scattering_tables_cache.hpp"

#ifndef SKYSPEC_PYTHON_EXECUTABLE
#define SKYSPEC_PYTHON_EXECUTABLE "/usr/bin/python3"
#endif

namespace skyspec::cli {
namespace {

struct JobOptions {
  std::string job_file, out;
  // plan
  bool json = false;
  int print_scene = -1;
  // run
  // Optional, not empty strings: `--shard ''` (an unset variable in a Slurm array script) is an
  // error, not "no shard", which would run every task on every node.
  std::optional<std::string> shard, tasks;
  std::optional<int> table_set;
  std::string scheduler;
  int threads = 0, workers = 0;
  bool quiet = false, no_collect = false, stop_with_parent = false;
};

JobPlan load_plan(const JobOptions& o) {
  JobSpec spec = read_job_file(o.job_file);
  if (!o.out.empty()) spec.output_directory = std::filesystem::absolute(o.out).lexically_normal();
  return plan_job(spec);
}

std::string produce_list(const JobSpec& job) {
  std::string s;
  if (job.exr) s += "exr ";
  if (job.png) s += "png ";
  if (job.irradiance) s += "irradiance ";
  if (!s.empty()) s.pop_back();
  return s;
}

int run_plan(const JobOptions& o) {
  const JobPlan plan = load_plan(o);
  if (o.print_scene >= 0) {
    if (o.print_scene >= static_cast<int>(plan.tasks.size()))
      throw InputError("--print-scene", std::to_string(o.print_scene),
                       "a task index from 0 to " + std::to_string(plan.tasks.size() - 1));
    std::cout << scene_to_toml(task_scene(plan, plan.tasks[o.print_scene]));
    return kExitOk;
  }
  if (o.json) {  // for the Dask driver: the chunks and where they write
    nlohmann::json j = {{"name", plan.job.name},
                        {"tasks", plan.tasks.size()},
                        {"output", plan.job.output_directory.string()},
                        {"task_directory", plan.task_directory().string()},
                        {"tasks_per_chunk", plan.job.tasks_per_chunk},
                        {"chunks", nlohmann::json::array()},
                        {"table_sets", job_table_sets_to_build(plan)}};
    for (int k = 0; k < plan.chunk_count(); ++k) j["chunks"].push_back({plan.chunk(k).first, plan.chunk(k).last});
    std::cout << j.dump() << "\n";
    return kExitOk;
  }
  const JobSpec& job = plan.job;
  std::cout << "job " << job.name << ": " << plan.tasks.size() << " task(s) = ";
  std::cout << (job.sites.empty() ? 1 : job.sites.size()) << " site(s) x " << plan.combinations.size()
            << " parameter set(s) x frames";
  if (job.min_sun_elevation_deg) std::cout << " with the sun at or above " << *job.min_sun_elevation_deg << " deg";
  if (job.tile_rows > 0)
    std::cout << " x strips: " << plan.frame_tasks.size() << " frame(s) in strips of up to " << job.tile_rows
              << " rows, merged into " << (job.output_directory / "frames").string();
  std::cout << "\n";
  if (!job.sites.empty()) {
    std::vector<int> per_site(job.sites.size(), 0);
    for (const auto& t : plan.tasks) ++per_site[t.site];
    for (std::size_t s = 0; s < job.sites.size(); ++s)
      std::cout << "  " << job.sites[s].name << ": " << per_site[s] << " task(s)\n";
  }
  std::cout << "chunks: " << plan.chunk_count() << " of up to " << job.tasks_per_chunk << " task(s)\n"
            << "produces: " << produce_list(job) << " per task, in " << plan.task_directory().string() << "\n";
  // The budget of render --dry-run for the first task's scene, times the tasks.
  const Scene first = task_scene(plan, plan.tasks.front());
  RenderPlan rp = RenderPlan::for_scene(first, static_cast<int>(plan.tasks.size()));
  if (const auto& tile = plan.tasks.front().tile) {  // strips, and the merged frames besides them
    rp.height = tile->y1 - tile->y0;
    rp.extra_output_bytes = spectral_exr_bytes(first.camera.width, first.camera.height, rp.wavelengths) *
                            plan.frame_tasks.size() / plan.tasks.size();
  }
  RenderEstimate estimate = estimate_render(rp);
  // Every distinct atmosphere builds its scattering-order tables once (cached), every task its
  // atmosphere, sun table and sky-view table.
  const JobTableEstimate tables = estimate_job_tables(plan);
  std::cout << "tables: " << tables.describe() << "\n";
  estimate.table_seconds = tables.build_seconds;
  if (job.exr || job.png) {
    const SkyRenderer light(scene_for_estimate(first));
    *estimate.table_seconds += estimate_frame_table_seconds(first, light) * static_cast<double>(plan.tasks.size());
    estimate.seconds = measure_render_seconds(light, rp);
  }
  std::cout << "estimate: " << estimate.describe() << " (" << rp.settings() << ")\n";
  if (!tables.cache_directory.empty()) {
    const auto cap = table_cache_cap_bytes();  // the cache never holds more than that
    const std::uint64_t held = cap > 0 ? std::min<std::uint64_t>(tables.cache_bytes, cap) : tables.cache_bytes;
    if (const auto free = available_disk_bytes(tables.cache_directory); free && held > *free)
      std::cout << "warning: the tables would add " << format_bytes(held) << " to " << tables.cache_directory.string()
                << " but it has " << format_bytes(*free) << " free\n";
    if (cap > 0 && tables.cache_bytes > cap)
      std::cout << "warning: the tables (" << format_bytes(tables.cache_bytes) << ") exceed the table cache's cap ("
                << format_bytes(cap) << ", SKYSPEC_CACHE_MAX_MB): the least recently used are removed as new "
                << "ones are written, and a second run of the job builds them again\n";
  }
  for (const auto& p : estimate.problems()) std::cout << "warning: " << p << "\n";
  return kExitOk;
}

// The tasks of [range] one after the other in this process (job/job_run.hpp), with a progress bar.
int run_here(const JobOptions& o, const JobPlan& plan, TaskRange range, bool collect) {
  ProgressBar bar("job " + plan.job.name, o.quiet);
  LocalRunOptions run;
  run.threads = o.threads;
  run.progress = [&bar](int done, int total) { bar.update(done, total); };
  run.on_failure = [](const std::string& id, const std::string& error) {
    std::cerr << "skyspec: task " << id << " failed: " << error << "\n";
  };
  const LocalRunSummary s = run_tasks_here(plan, range, run);
  bar.finish();
  if (!o.quiet)
    std::cout << (range.size() > 0 ? "tasks " + std::to_string(range.first) + "-" + std::to_string(range.last - 1)
                                   : std::string("no tasks (this shard is empty: the job has fewer tasks than shards)"))
              << ": ran " << s.ran << ", " << s.kept << " already done"
              << (s.kept_from_elsewhere ? " (" + std::to_string(s.kept_from_elsewhere) + " by another run meanwhile)"
                                        : std::string())
              << ", " << s.failed << " failed\n";
  if (collect) {
    const JobSummary summary = collect_job(plan);
    if (!o.quiet)
      std::cout << summary.describe() << "\nmanifest: " << (plan.job.output_directory / "manifest.jsonl").string()
                << "\n";
    return summary.failed || summary.missing || summary.damaged ? kExitTasksFailed : kExitOk;
  }
  return s.failed ? kExitTasksFailed : kExitOk;
}

// This program's own path, for the driver's workers.
std::string self_path() {
  std::error_code ec;
  const auto p = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string("skyspec") : p.string();
}

// `job run` without --shard or --tasks: the Dask driver (python/skyspec_jobs.py) takes over this
// process. It is found beside this program (<dir>/python/, the build tree) or on Python's path.
[[noreturn]] void exec_driver(const JobOptions& o) {
  const char* env_python = std::getenv("SKYSPEC_PYTHON");
  const std::string python = env_python && *env_python ? env_python : SKYSPEC_PYTHON_EXECUTABLE;
  const std::string self = self_path();
  const auto beside = std::filesystem::path(self).parent_path() / "python";
  if (std::filesystem::exists(beside / "skyspec_jobs.py")) {
    const char* old = std::getenv("PYTHONPATH");
    const std::string path = beside.string() + (old && *old ? ":" + std::string(old) : "");
    setenv("PYTHONPATH", path.c_str(), 1);
  }
  std::vector<std::string> args = {python, "-m", "skyspec_jobs", "run", o.job_file, "--skyspec", self};
  if (!o.out.empty()) args.insert(args.end(), {"--out", std::filesystem::absolute(o.out).string()});
  if (!o.scheduler.empty()) args.insert(args.end(), {"--scheduler", o.scheduler});
  if (o.workers > 0) args.insert(args.end(), {"--workers", std::to_string(o.workers)});
  if (o.threads > 0) args.insert(args.end(), {"--threads", std::to_string(o.threads)});
  if (o.quiet) args.push_back("--quiet");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::cout.flush();
  execv(python.c_str(), argv.data());
  throw IoError("skyspec job run: cannot start the Dask driver with " + python + " (" + std::strerror(errno) +
                "): install python3-distributed, set SKYSPEC_PYTHON, or run here without Dask with --shard 1/1");
}

int run_job(const JobOptions& o) {
  if (o.threads < 0 || o.threads > 1024)
    throw InputError("--threads", std::to_string(o.threads), "0 (the scene's render.threads) to 1024");
  if (o.workers < 0 || o.workers > 4096)
    throw InputError("--workers", std::to_string(o.workers), "0 (one per core) to 4096");
  if (o.shard && o.tasks) throw InputError("--tasks", "\"" + *o.tasks + "\"", "either --shard or --tasks, not both");
  if (o.table_set && (o.shard || o.tasks))
    throw InputError("--table-set", std::to_string(*o.table_set), "no --shard or --tasks (it runs no task)");
  if (!o.shard && !o.tasks && !o.table_set) {
    if (o.no_collect)
      throw InputError("--no-collect", "(given)", "--shard or --tasks (the Dask driver always collects)");
    load_plan(o);  // a job with an error is refused here, before Python starts
    exec_driver(o);
  }
  if (!o.scheduler.empty())
    throw InputError("--scheduler", o.scheduler, "no --shard or --tasks (they run here, without Dask)");
  if (o.workers > 0)
    throw InputError("--workers", std::to_string(o.workers), "no --shard or --tasks (they run here, in this process)");
  if (o.stop_with_parent) {  // a driver's child: SIGTERM (a clean stop) when the worker that started it dies
    const pid_t parent = getppid();
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) throw Interrupted(SIGTERM);
  }
  const JobPlan plan = load_plan(o);
  if (o.table_set) {
    const auto start = std::chrono::steady_clock::now();
    const bool built = build_job_table_set(plan, *o.table_set, o.threads);
    if (!o.quiet)
      std::cout << "table set " << *o.table_set << ": "
                << (built ? "built in " +
                                format_duration(
                                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count())
                          : std::string("cached already"))
                << "\n";
    return kExitOk;
  }
  if (o.tasks)
    return run_here(o, plan, parse_task_range(*o.tasks, static_cast<int>(plan.tasks.size()), "--tasks"), false);
  const auto [i, n] = parse_shard(*o.shard, "--shard");
  const int rc = run_here(o, plan, plan.shard(i, n), n == 1 && !o.no_collect);
  if (n > 1 && !o.quiet) std::cout << "after the last shard: skyspec job collect " << o.job_file << "\n";
  return rc;
}

int run_collect(const JobOptions& o) {
  const JobPlan plan = load_plan(o);
  const int stale = remove_stale_temporaries(plan.task_directory(), plan.job.task_prefix);
  if (stale > 0 && !o.quiet) std::cout << "removed " << stale << " temporary file(s) of killed tasks\n";
  const JobSummary summary = collect_job(plan);
  if (!o.quiet) {
    std::cout << summary.describe() << "\nmanifest: " << (plan.job.output_directory / "manifest.jsonl").string()
              << "\n";
    for (const auto& t : summary.tables) std::cout << "table: " << t.string() << "\n";
  }
  if (summary.missing)
    std::cerr << "skyspec: " << summary.missing << " task(s) have not run: run the job (or the shard) again; finished "
              << "tasks are kept\n";
  if (summary.damaged) {
    std::cerr << "skyspec: " << summary.damaged << " task record(s) are damaged or their files are gone; running the "
              << "job again renders those tasks:\n";
    for (const auto& d : summary.damaged_records) std::cerr << "  " << d << "\n";
  }
  return summary.failed || summary.missing || summary.damaged ? kExitTasksFailed : kExitOk;
}

}  // namespace

Command add_job_command(CLI::App& app) {
  auto o = std::make_shared<JobOptions>();
  auto* cmd = app.add_subcommand("job", "Run a job: one scene swept over sites, times and parameters (Dask, shards)");
  cmd->require_subcommand(1);
  cmd->footer(
      "Examples:\n"
      "  skyspec job plan data/jobs/week-two-sites.toml        # tasks, chunks, estimate\n"
      "  skyspec job run data/jobs/week-two-sites.toml         # on a local Dask cluster (all cores)\n"
      "  skyspec job run JOB.toml --scheduler tcp://HOST:8786  # on a running Dask cluster\n"
      "  skyspec job run JOB.toml --shard 3/8                  # the third of 8 parts, here, without Dask\n"
      "  skyspec job collect JOB.toml                          # manifest and tables after the shards\n"
      "Job files: docs/jobs.md. Finished tasks are kept: running a job again runs only what is missing.");
  const auto common = [&](CLI::App* sub) {
    sub->add_option("JOB", o->job_file, "the job file (TOML)")->required();
    sub->add_option("--out", o->out, "output folder (default: job.output, else the job's name)");
  };
  auto* plan = cmd->add_subcommand("plan", "Print the tasks, chunks and estimated cost of a job; check it");
  common(plan);
  plan->add_flag("--json", o->json, "machine-readable: task count, chunks and output folder");
  plan->add_option("--print-scene", o->print_scene, "print the scene of task K (as TOML, for skyspec render --scene)");
  auto* run = cmd->add_subcommand("run", "Run a job's tasks (Dask by default; --shard or --tasks: here)");
  common(run);
  run->add_option("--shard", o->shard, "run only the I-th of N contiguous parts (I/N, 1-based), here without Dask");
  run->add_option("--tasks", o->tasks, "run only tasks A-B (inclusive), here without Dask");
  run->add_option("--scheduler", o->scheduler, "address of a running Dask scheduler (default: a local cluster)");
  run->add_option("--workers", o->workers, "local cluster: worker processes (default: the cores)");
  run->add_option("--threads", o->threads, "threads per render (default: all cores here; 1 per worker under Dask)");
  run->add_option("--table-set", o->table_set,
                  "build only the K-th set of scattering-order tables the job's tasks use into the disk cache, here "
                  "(skyspec job plan JOB --json lists those not cached; the Dask driver runs each as a task)");
  run->add_flag("--no-collect", o->no_collect, "with --shard 1/1: do not write the manifest and tables");
  run->add_flag("--stop-with-parent", o->stop_with_parent,
                "stop (as on SIGTERM) when the process that started this one ends (for drivers such as Dask's)");
  run->add_flag("-q,--quiet", o->quiet, "no progress bar and no summary");
  auto* collect =
      cmd->add_subcommand("collect", "Write the manifest and the irradiance tables from the tasks' records");
  common(collect);
  collect->add_flag("-q,--quiet", o->quiet, "no summary");
  return {cmd,
          [o, plan, run, collect]() -> int {
            if (plan->parsed()) return run_plan(*o);
            if (run->parsed()) return run_job(*o);
            if (collect->parsed()) return run_collect(*o);
            return kExitBadInput;
          },
          [o, run] {  // the checks before any work (Command::validate)
            JobSpec spec = read_job_file(o->job_file);
            const JobPlan p = plan_job(spec);
            if (run->parsed() && o->shard) parse_shard(*o->shard, "--shard");
            if (run->parsed() && o->tasks) parse_task_range(*o->tasks, static_cast<int>(p.tasks.size()), "--tasks");
          }};
}

}  // namespace skyspec::cli
