#include "job/job_tables.hpp"

#include <map>
#include <set>
#include <tuple>
#include <utility>

#include <tbb/task_arena.h>

#include "render/broadband_irradiance.hpp"
#include "render/render_budget.hpp"
#include "render/scene_tables.hpp"
#include "render/table_family.hpp"
#include "skyspec/error.hpp"
#include "transport/scattering_tables_cache.hpp"

namespace skyspec {
namespace {

// What a build's time depends on besides the atmosphere's values: the tables' settings, the sun
// table's resolution, the wavelengths, the view segments and the threads.
using BuildCost = std::tuple<int, int, int, int, int, int, bool, int, int, int, int, int, int>;

BuildCost build_cost(const Scene& scene) {
  const auto ms = multiple_scattering_settings(scene);
  const auto sun = sun_table_resolution(scene);
  return {ms.orders,
          ms.altitude_samples,
          ms.sun_samples,
          ms.view_segments,
          ms.higher_order_segments,
          ms.angular_degree,
          ms.polarisation,
          sun.n_r,
          sun.n_mu,
          sun.segments,
          make_wavelength_grid(scene).size(),
          scene.render.view_segments,
          scene.render.threads};
}

std::string plural(int n, const std::string& one, const std::string& many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

}  // namespace

std::string JobTableEstimate::describe() const {
  if (distinct == 0) return "none (single scattering)";
  std::string text = plural(distinct, "distinct set", "distinct sets") + " of scattering-order tables (" +
                     std::to_string(cached) + " cached): ";
  if (builds == 0) return text + "nothing to build";
  text += plural(builds, "build", "builds") + ", about " + format_duration(build_seconds);
  if (cache_directory.empty())
    text += ", not kept (render.cache_tables = false)";
  else
    text += ", " + format_bytes(cache_bytes) + " added to " + cache_directory.string();
  return text;
}

std::vector<JobTableSet> job_table_sets(const JobPlan& plan) {
  // One scene per (site, parameter set): the tables do not depend on the date-time or the sun.
  // A task's scenes: its own, and with irradiance.broadband in an irradiance job the broadband
  // irradiance's runs (broadband_irradiance.hpp), each with tables of its own.
  const auto scenes_of = [&plan](const JobTask& task) {
    std::vector<Scene> scenes{task_scene(plan, task)};
    if (plan.job.irradiance && scenes.front().irradiance.broadband)
      for (Scene& run : broadband_run_scenes(scenes.front())) scenes.push_back(std::move(run));
    return scenes;
  };
  std::map<std::pair<int, int>, std::vector<std::pair<std::uint64_t, bool>>> keys_of;  // -> (key hash, disk cache on)
  std::map<std::uint64_t, JobTableSet> sets;
  std::set<std::pair<int, std::uint64_t>> chunk_sets;  // (chunk, set) without a disk cache
  for (const JobTask& task : plan.tasks) {
    const auto pair = std::make_pair(task.site, task.combination);
    auto found = keys_of.find(pair);
    if (found == keys_of.end()) {
      found = keys_of.emplace(pair, std::vector<std::pair<std::uint64_t, bool>>{}).first;
      for (const Scene& task_scene : scenes_of(task))
        for (Scene& scene : scenes_of_tables(task_scene)) {  // its own, or the grid's it interpolates
          ScatteringTablesKey key = scattering_tables_key(scene);
          found->second.emplace_back(key.hash, scene.render.cache_tables);
          sets.emplace(key.hash, JobTableSet{std::move(scene), std::move(key)});
        }
    }
    for (const auto& [hash, disk] : found->second)
      if (!disk && chunk_sets.emplace(task.index / plan.job.tasks_per_chunk, hash).second) ++sets.at(hash).chunks;
  }
  std::vector<JobTableSet> out;
  for (auto& [hash, set] : sets) out.push_back(std::move(set));
  return out;
}

std::vector<int> job_table_sets_to_build(const JobPlan& plan) {
  const std::vector<JobTableSet> sets = job_table_sets(plan);
  std::vector<int> out;
  for (size_t k = 0; k < sets.size(); ++k)
    if (sets[k].scene.render.cache_tables && !scattering_orders_cached(sets[k].key, true))
      out.push_back(static_cast<int>(k));
  return out;
}

bool build_job_table_set(const JobPlan& plan, int index, int threads) {
  const std::vector<JobTableSet> sets = job_table_sets(plan);
  if (index < 0 || index >= static_cast<int>(sets.size()))
    throw InputError("--table-set", std::to_string(index),
                     sets.empty() ? std::string("no value: the job's tasks use no scattering-order tables")
                                  : "a set from 0 to " + std::to_string(sets.size() - 1) +
                                        " (skyspec job plan JOB --json lists those to build)");
  const JobTableSet& set = sets[static_cast<size_t>(index)];
  if (scattering_orders_cached(set.key, set.scene.render.cache_tables)) return false;
  Scene scene = set.scene;
  if (threads > 0) scene.render.threads = threads;
  tbb::task_arena arena(scene.render.threads > 0 ? scene.render.threads : tbb::this_task_arena::max_concurrency());
  arena.execute([&] { scene_scattering_orders(scene); });
  return true;
}

JobTableEstimate estimate_job_tables(const JobPlan& plan) {
  JobTableEstimate out;
  const std::vector<JobTableSet> sets = job_table_sets(plan);
  out.distinct = static_cast<int>(sets.size());
  std::map<BuildCost, double> seconds_of;  // measured once per distinct cost
  for (const JobTableSet& set : sets) {
    const Scene& scene = set.scene;
    if (scattering_orders_cached(set.key, scene.render.cache_tables)) {
      ++out.cached;
      continue;
    }
    int builds = 1;
    if (scene.render.cache_tables) {
      out.cache_directory = table_cache_directory();
      out.cache_bytes += scattering_tables_file_bytes(scene, set.key);
    } else {
      builds = set.chunks;
    }
    const auto cost = build_cost(scene);
    auto measured = seconds_of.find(cost);
    if (measured == seconds_of.end())
      measured = seconds_of.emplace(cost, estimate_scattering_orders_seconds(scene)).first;
    out.builds += builds;
    out.build_seconds += builds * measured->second;
  }
  return out;
}

}  // namespace skyspec
