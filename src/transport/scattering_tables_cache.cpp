#include "transport/scattering_tables_cache.hpp"

#include "base/atomic_file.hpp"

#include <cstdlib>
#include <iostream>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace skyspec {

std::filesystem::path table_cache_directory() {
  if (const char* d = std::getenv("SKYSPEC_CACHE_DIR"); d && *d) return d;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::filesystem::path(x) / "skyspec";
  if (const char* h = std::getenv("HOME"); h && *h) return std::filesystem::path(h) / ".cache" / "skyspec";
  return {};
}

namespace {

std::mutex g_mutex;
// The last few tables of this process, by their key's inputs.
std::vector<std::pair<std::string, std::shared_ptr<const ScatteringOrders>>> g_recent;

// A cache that cannot be used only costs time, but the user should know why every run rebuilds
// the tables: said once per process, on stderr.
void warn_cache_unusable(const std::filesystem::path& dir, const std::string& why) {
  static std::once_flag once;
  std::call_once(once, [&] {
    const char* from =
        std::getenv("SKYSPEC_CACHE_DIR") && *std::getenv("SKYSPEC_CACHE_DIR") ? " (SKYSPEC_CACHE_DIR)" : "";
    std::cerr << "skyspec: warning: the scattering tables cannot be cached in " << dir.string() << from << ": " << why
              << "; they are built again on every run\n";
  });
}

// Whether `dir` can hold cache files, creating it if needed; warns (once) when it cannot.
bool usable_cache_directory(const std::filesystem::path& dir) {
  std::error_code ec;
  if (std::filesystem::is_directory(dir, ec)) return true;
  if (std::filesystem::exists(dir, ec)) {
    warn_cache_unusable(dir, "it exists and is not a folder");
    return false;
  }
  if (!std::filesystem::create_directories(dir, ec) && ec) {
    warn_cache_unusable(dir, ec.message());
    return false;
  }
  return true;
}

std::shared_ptr<const ScatteringOrders> load_or_build(const SingleScattering& integrator,
                                                      const ScatteringTablesKey& key,
                                                      const MultipleScatteringSettings& settings, bool use_disk_cache) {
  const std::filesystem::path dir = use_disk_cache ? table_cache_directory() : std::filesystem::path();
  const std::string path = dir.empty() ? std::string() : (dir / key.file_name()).string();
  // Only a regular file is read: a FIFO or a device under the cache file's name would block the
  // reader or feed it anything (it is then rebuilt, and replacing it is refused with a message).
  if (!path.empty() && is_regular_input(path))
    if (auto loaded = ScatteringOrders::load(path, key.inputs, integrator.atmosphere(), settings)) return loaded;
  auto built = std::make_shared<const ScatteringOrders>(integrator, settings);
  if (!path.empty() && usable_cache_directory(dir) && !built->save(path, key.inputs))
    warn_cache_unusable(dir, "the table file could not be written");
  return built;
}

}  // namespace

std::shared_ptr<const ScatteringOrders> scattering_orders_for(const SingleScattering& integrator,
                                                              const SunColumnTable::Resolution& sun_table,
                                                              const MultipleScatteringSettings& settings,
                                                              bool use_disk_cache) {
  const ScatteringTablesKey key = scattering_tables_key(integrator.atmosphere(), sun_table, settings);
  {
    std::lock_guard<std::mutex> lock(g_mutex);
    for (const auto& [inputs, orders] : g_recent)
      if (inputs == key.inputs) return orders;
  }
  auto orders = load_or_build(integrator, key, settings, use_disk_cache);
  std::lock_guard<std::mutex> lock(g_mutex);
  g_recent.emplace_back(key.inputs, orders);
  if (g_recent.size() > 4) g_recent.erase(g_recent.begin());
  return orders;
}

bool scattering_orders_cached(const ScatteringTablesKey& key, bool use_disk_cache) {
  {
    std::lock_guard<std::mutex> lock(g_mutex);
    for (const auto& entry : g_recent)
      if (entry.first == key.inputs) return true;
  }
  const std::filesystem::path dir = use_disk_cache ? table_cache_directory() : std::filesystem::path();
  std::error_code ec;
  return !dir.empty() && std::filesystem::is_regular_file(dir / key.file_name(), ec);
}

}  // namespace skyspec
