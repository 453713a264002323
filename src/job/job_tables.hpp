// What a job's tasks ask of the scattering-order tables, before any task runs: how many distinct
// sets of tables they use (one per atmosphere and table settings: scattering_tables_key), how many
// of those must still be built, the time that takes and the bytes the disk cache gains.
//
// A job that sweeps an atmosphere key (random aerosol loads, albedos) builds a set per sample, each
// a build and a cache file (docs/jobs.md, "What a job costs before it runs"). The sun, the
// date-time, the camera and the outputs do not change the tables, so the sets are found from one
// scene per (site, parameter set) pair; the build time is measured once per distinct cost (table
// settings, wavelengths, view segments) with ScatteringOrders::estimate_build_seconds and
// multiplied.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "job/job_plan.hpp"
#include "transport/scattering_tables_key.hpp"

namespace skyspec {

struct JobTableEstimate {
  int distinct = 0;  ///< distinct sets of scattering-order tables among the tasks (0: single scattering)
  int cached = 0;    ///< of them, already in this process's memory or the disk cache
  /// Builds the job will do: one per set not cached when the disk cache is on (the tasks share it);
  /// without it (render.cache_tables = false) one per set per chunk that uses it (each chunk is a process).
  int builds = 0;
  double build_seconds = 0.0;             ///< wall time of those builds, on the threads the tasks use
  std::uint64_t cache_bytes = 0;          ///< what the disk cache gains (0 without it)
  std::filesystem::path cache_directory;  ///< empty without a disk cache
  /// "2 distinct sets (1 cached): 1 build, about 40 s, 56 MB added to ~/.cache/skyspec", or
  /// "none (single scattering)".
  std::string describe() const;
};

/// The estimate for every task of the plan (builds a few sun tables and times 16 entries per
/// distinct cost).
JobTableEstimate estimate_job_tables(const JobPlan& plan);

/// One distinct set of scattering-order tables among the plan's tasks.
struct JobTableSet {
  Scene scene;              ///< the first scene that uses it (a task's, a broadband run's or a grid atmosphere's)
  ScatteringTablesKey key;  ///< its cache key
  int chunks = 0;           ///< the chunks (processes) that use it, each building it without a disk cache
};

/// The plan's distinct sets, in a fixed order (by key): a task's scene's own tables, those of its
/// broadband irradiance's runs, or, with render.ms_tables = "interpolated", the grid's atmospheres
/// its tables are blended from (render/table_family.hpp).
std::vector<JobTableSet> job_table_sets(const JobPlan& plan);

/// The indices in job_table_sets of the sets a run should build before its tasks: not cached, and
/// kept in the disk cache once built (render.cache_tables). The Dask driver builds each as a task of
/// its own (`skyspec job run --table-set K`), so that the workers build different sets at once.
std::vector<int> job_table_sets_to_build(const JobPlan& plan);

/// Builds set `index` of job_table_sets (with `threads` threads, 0: all cores) into the disk cache,
/// unless it is cached; returns whether it built it. Throws InputError naming --table-set for an
/// index out of range.
bool build_job_table_set(const JobPlan& plan, int index, int threads);

}  // namespace skyspec
