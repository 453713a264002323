#include "transport/scattering_tables_cache.hpp"

#include "base/atomic_file.hpp"
#include "base/disk_cache.hpp"
#include "base/recent_values.hpp"
#include "skyspec/error.hpp"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <string>

namespace skyspec {

namespace {

// The last four sets of tables of this process, by their key's inputs.
RecentValues<ScatteringOrders> g_recent(3, std::numeric_limits<std::size_t>::max(),
                                        [](const ScatteringOrders&) { return std::size_t{0}; });

std::shared_ptr<const ScatteringOrders> load_or_build(const AtmosphereModel& atmosphere, const ScatteringTablesKey& key,
                                                      const MultipleScatteringSettings& settings, bool use_disk_cache,
                                                      const TablesBuild& build) {
  const std::filesystem::path dir = use_disk_cache ? table_cache_directory() : std::filesystem::path();
  const std::string path = dir.empty() ? std::string() : (dir / key.file_name()).string();
  // Only a regular file is read: a FIFO or a device under the cache file's name would block the
  // reader or feed it anything (it is then rebuilt, and replacing it is refused with a message).
  const std::uint64_t cap = path.empty() ? 0 : table_cache_cap_bytes();  // a bad value: refused before any work
  const auto load = [&]() -> std::unique_ptr<ScatteringOrders> {
    if (path.empty() || !is_regular_input(path)) return nullptr;
    auto loaded = ScatteringOrders::load(path, key.inputs, atmosphere, settings);
    if (loaded) mark_cache_file_used(path);
    return loaded;
  };
  if (auto loaded = load()) return loaded;
  // Built by one process at a time: another that is building these tables now is waited for.
  const CacheFileClaim claim(path.empty() || !usable_cache_directory(dir) ? std::filesystem::path()
                                                                          : std::filesystem::path(path));
  if (claim.waited())
    if (auto loaded = load()) return loaded;
  std::shared_ptr<const ScatteringOrders> built = build();
  if (!path.empty() && usable_cache_directory(dir)) {
    if (built->save(path, key.inputs))
      evict_table_cache(dir, cap, path);
    else
      warn_cache_unusable(dir, "the table file could not be written");
  }
  return built;
}

}  // namespace

std::shared_ptr<const ScatteringOrders> scattering_orders_for(const SingleScattering& integrator,
                                                              const SunColumnTable::Resolution& sun_table,
                                                              const MultipleScatteringSettings& settings,
                                                              bool use_disk_cache) {
  return scattering_orders_for(integrator.atmosphere(), sun_table, settings, use_disk_cache,
                               [&] { return std::make_shared<const ScatteringOrders>(integrator, settings); });
}

std::shared_ptr<const ScatteringOrders> scattering_orders_for(const AtmosphereModel& atmosphere,
                                                              const SunColumnTable::Resolution& sun_table,
                                                              const MultipleScatteringSettings& settings,
                                                              bool use_disk_cache, const TablesBuild& build) {
  const ScatteringTablesKey key = scattering_tables_key(atmosphere, sun_table, settings);
  return g_recent.get(key.inputs, [&] { return load_or_build(atmosphere, key, settings, use_disk_cache, build); });
}

bool scattering_orders_cached(const ScatteringTablesKey& key, bool use_disk_cache) {
  if (g_recent.find(key.inputs)) return true;
  const std::filesystem::path dir = use_disk_cache ? table_cache_directory() : std::filesystem::path();
  std::error_code ec;
  return !dir.empty() && std::filesystem::is_regular_file(dir / key.file_name(), ec);
}

}  // namespace skyspec
