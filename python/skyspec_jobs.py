"""Run a skyspec job on a Dask cluster.

A job file (docs/jobs.md) expands into tasks; ``skyspec job plan --json`` lists them in chunks of
``job.tasks_per_chunk``. Each chunk becomes one Dask task, which runs
``skyspec job run JOB --tasks A-B`` in a child process: a crash of the native code ends that
process, not the Dask worker, and a worker that dies (its child goes with it) has its chunk run
again on another worker, where the tasks already done are skipped. Tasks write their files
atomically under their own names and return only paths and checksums. When every chunk has run,
``skyspec job collect`` writes the manifest and the tables.

    skyspec job run JOB.toml                              # a LocalCluster on this machine
    skyspec job run JOB.toml --scheduler tcp://HOST:8786  # a running cluster

or from Python: ``skyspec.run_job("JOB.toml")`` (the same function as ``skyspec_jobs.run_job``).
"""

import argparse
import json
import logging
import os
import shutil
import subprocess
import sys
import time
import uuid

__all__ = ["run_job", "find_skyspec", "JobFailed", "DaskMissing"]

#: Exit code of ``skyspec job`` when tasks failed or did not run (src/cli/command_job.cpp).
EXIT_TASKS_FAILED = 4


class DaskMissing(RuntimeError):
    """Dask distributed is not installed where the driver runs."""


class JobFailed(RuntimeError):
    """A job ended with tasks that failed or did not run; ``summary`` says which."""

    def __init__(self, message, summary):
        super().__init__(message)
        self.summary = summary


def find_skyspec(skyspec=None):
    """The skyspec program: the argument, $SKYSPEC_CLI, the build tree beside this module, the
    interpreter's own bin folder (where `cmake --install --component python --prefix VENV` puts it,
    whether or not the environment is activated), or PATH."""
    candidates = [skyspec, os.environ.get("SKYSPEC_CLI"),
                  os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "skyspec"),
                  os.path.join(os.path.dirname(sys.executable), "skyspec"),
                  shutil.which("skyspec")]
    for c in candidates:
        if c and os.path.isfile(c) and os.access(c, os.X_OK):
            return os.path.abspath(c)
    raise FileNotFoundError("the skyspec program was not found: pass skyspec=PATH, set SKYSPEC_CLI, or put it on PATH")


def _plan(skyspec, job, out):
    cmd = [skyspec, "job", "plan", job, "--json"] + (["--out", out] if out else [])
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise ValueError(p.stderr.strip() or f"skyspec job plan exited with {p.returncode}")
    return json.loads(p.stdout)


def _record_path(task_directory, task):
    return os.path.join(task_directory, "t%06d.json" % task)


def _write_failure(task_directory, task, error):
    """A record for a task whose process died before it wrote one (atomically, like skyspec)."""
    path = _record_path(task_directory, task)
    tmp = "%s.tmp-%d-driver" % (path, os.getpid())
    with open(tmp, "w") as f:
        json.dump({"task": task, "id": "t%06d" % task, "status": "failed", "error": error, "files": []}, f)
        f.write("\n")
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


def build_table_set(skyspec, job, out, index, threads):
    """One Dask task: builds set `index` of the scattering-order tables the job's tasks use into the
    disk cache (skyspec job run --table-set), so that the workers build different sets at once
    before the chunks read them. Returns an error text, or None."""
    cmd = [skyspec, "job", "run", job, "--out", out, "--table-set", str(index), "--threads", str(threads), "--quiet",
           "--stop-with-parent"]
    env = dict(os.environ)
    env.pop("MALLOC_TRIM_THRESHOLD_", None)
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if p.returncode != 0:
        tail = p.stderr.strip().splitlines()[-3:]
        return "table set %d: exit code %d%s" % (index, p.returncode, (": " + " / ".join(tail)) if tail else "")
    return None


def run_chunk(skyspec, job, out, task_directory, first, last, threads):
    """One Dask task: tasks [first, last) of the job in a child process. Returns, per task, its
    status, files (paths, sizes, SHA-256) and error: never pixels."""
    cmd = [skyspec, "job", "run", job, "--out", out, "--tasks", "%d-%d" % (first, last - 1),
           "--threads", str(threads), "--quiet", "--stop-with-parent"]
    started = time.monotonic()
    # Dask's nanny gives its workers MALLOC_TRIM_THRESHOLD_ (distributed.nanny.pre-spawn-environ):
    # inherited, it makes glibc hand a render's large buffers back to the kernel after every use and
    # fault them in again (docs/jobs.md has the cost). The render process runs with the machine's
    # own malloc settings.
    env = dict(os.environ)
    env.pop("MALLOC_TRIM_THRESHOLD_", None)
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if p.returncode < 0 or p.returncode not in (0, EXIT_TASKS_FAILED):
        why = ("killed by signal %d" % -p.returncode) if p.returncode < 0 else ("exit code %d" % p.returncode)
        tail = p.stderr.strip().splitlines()[-3:]
        error = "the task's process ended before it finished (%s)%s" % (why, (": " + " / ".join(tail)) if tail else "")
        for k in range(first, last):
            if not os.path.exists(_record_path(task_directory, k)):
                _write_failure(task_directory, k, error)
    results = []
    for k in range(first, last):
        try:
            with open(_record_path(task_directory, k)) as f:
                r = json.load(f)
        except (OSError, ValueError) as e:
            r = {"task": k, "status": "failed", "error": "no readable record (%s)" % e, "files": []}
        results.append({"task": k, "status": r.get("status"), "error": r.get("error"), "files": r.get("files", [])})
    return {"first": first, "last": last, "seconds": time.monotonic() - started, "tasks": results}


class _Progress:
    """done/total, failures and an ETA on stderr; silent when stderr is not a terminal or quiet."""

    def __init__(self, total, quiet, what="tasks"):
        self.total, self.done, self.failed, self.what = total, 0, 0, what
        self.active = not quiet and sys.stderr.isatty()
        self.start = time.monotonic()

    def update(self, done, failed):
        self.done += done
        self.failed += failed
        if not self.active:
            return
        elapsed = time.monotonic() - self.start
        eta = elapsed / self.done * (self.total - self.done) if self.done else float("nan")
        width = 30
        filled = int(width * self.done / max(1, self.total))
        eta_text = "--" if eta != eta else "%dm%02ds" % divmod(int(eta), 60)
        sys.stderr.write("\rjob [%s%s] %d/%d %s, %d failed, ETA %s " % (
            "#" * filled, "." * (width - filled), self.done, self.total, self.what, self.failed, eta_text))
        sys.stderr.flush()

    def finish(self):
        if self.active:
            sys.stderr.write("\n")


def run_job(job, *, out=None, scheduler=None, workers=None, threads=1, skyspec=None, quiet=False):
    """Runs the job file `job` on Dask and collects its manifest and tables.

    scheduler: a Dask scheduler address ("tcp://host:8786"); None starts a LocalCluster of
    `workers` workers (default: the cores), threads of this process, one task at a time each.
    threads: render threads per task. Returns the summary (tasks, ok, failed, output folder); raises JobFailed when tasks failed
    or did not run, ValueError for a job file with an error (before any task runs).
    """
    try:
        from dask.distributed import Client, LocalCluster, as_completed
        import cloudpickle
    except ImportError as e:
        raise DaskMissing("skyspec job run needs Dask distributed (Debian: apt-get install python3-distributed), "
                          "or runs without it in shards: skyspec job run JOB --shard 1/1 (%s)" % e) from e

    skyspec = find_skyspec(skyspec)
    job = os.path.abspath(job)
    plan = _plan(skyspec, job, os.path.abspath(out) if out else None)
    out = plan["output"]
    os.makedirs(plan["task_directory"], exist_ok=True)
    # Workers on other machines need not have this module: its functions travel by value.
    cloudpickle.register_pickle_by_value(sys.modules[__name__])
    cluster = None
    if scheduler:
        try:
            client = Client(scheduler, timeout="20s")
        except (OSError, TimeoutError) as e:
            raise ValueError("skyspec: error: --scheduler = %s: no Dask scheduler answers there (%s); start one "
                             "with `dask scheduler` (docs/jobs.md)" % (scheduler, e)) from e
    else:
        # The workers are threads of this process: each only waits for its child process, which
        # does the work, so worker processes would add start-up and heartbeats and no isolation.
        cluster = LocalCluster(n_workers=workers or os.cpu_count(), threads_per_worker=1, processes=False,
                               dashboard_address=None, silence_logs=logging.ERROR)
        client = Client(cluster)
    progress = _Progress(plan["tasks"], quiet)
    failures = []
    try:
        run = uuid.uuid4().hex[:12]  # keys of this run only: another run on a shared cluster never shares them
        # The tables first, a task per set not cached (a set failing here is built, or fails, in the
        # tasks that use it).
        builds = [client.submit(build_table_set, skyspec, job, out, k, threads,
                                key="skyspec-%s-%s-tables-%d" % (plan["name"], run, k), pure=False)
                  for k in plan.get("table_sets", [])]
        tables = _Progress(len(builds), quiet or not builds, "table sets built")
        for future in as_completed(builds):
            error = future.result()
            if error:
                failures.append(error)
            tables.update(1, error is not None)
        tables.finish()
        progress = _Progress(plan["tasks"], quiet)
        futures = [client.submit(run_chunk, skyspec, job, out, plan["task_directory"], a, b, threads,
                                 key="skyspec-%s-%s-%d-%d" % (plan["name"], run, a, b), pure=False)
                   for a, b in plan["chunks"]]
        for future in as_completed(futures):
            try:
                result = future.result()
            except Exception as e:  # the chunk's worker died too often (Dask's allowed-failures)
                failures.append(str(e))
                continue
            bad = [t for t in result["tasks"] if t["status"] != "ok"]
            progress.update(len(result["tasks"]), len(bad))
    finally:
        progress.finish()
        client.close()
        if cluster is not None:
            cluster.close()
    p = subprocess.run([skyspec, "job", "collect", job, "--out", out] + (["--quiet"] if quiet else []),
                       capture_output=True, text=True)
    if not quiet:
        sys.stdout.write(p.stdout)
    sys.stderr.write(p.stderr)
    with open(os.path.join(out, "manifest.jsonl")) as f:
        records = [json.loads(line) for line in f]
    summary = {"tasks": len(records), "ok": sum(r.get("status") == "ok" for r in records),
               "failed": sum(r.get("status") == "failed" for r in records),
               "missing": sum(r.get("status") == "missing" for r in records), "output": out,
               "engine_errors": failures}
    if p.returncode not in (0, EXIT_TASKS_FAILED):
        raise RuntimeError("skyspec job collect failed: " + p.stderr.strip())
    if summary["failed"] or summary["missing"]:
        raise JobFailed("%d of %d task(s) failed and %d did not run (manifest: %s)%s" % (
            summary["failed"], summary["tasks"], summary["missing"], os.path.join(out, "manifest.jsonl"),
            "; Dask: " + "; ".join(failures[:3]) if failures else ""), summary)
    return summary


def main(argv=None):
    parser = argparse.ArgumentParser(prog="skyspec job run", description="Run a skyspec job on Dask.")
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run")
    run.add_argument("job")
    run.add_argument("--skyspec")
    run.add_argument("--out")
    run.add_argument("--scheduler")
    run.add_argument("--workers", type=int)
    run.add_argument("--threads", type=int, default=1)
    run.add_argument("--quiet", action="store_true")
    a = parser.parse_args(argv)
    try:
        run_job(a.job, out=a.out, scheduler=a.scheduler, workers=a.workers, threads=a.threads, skyspec=a.skyspec,
                quiet=a.quiet)
    except JobFailed as e:
        print("skyspec: error: %s" % e, file=sys.stderr)
        return EXIT_TASKS_FAILED
    except ValueError as e:
        print(str(e), file=sys.stderr)
        return 2
    except DaskMissing as e:
        print("skyspec: error: %s" % e, file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("skyspec: interrupted: finished tasks are kept; run the job again to finish it", file=sys.stderr)
        return 130
    return 0


if __name__ == "__main__":
    sys.exit(main())
