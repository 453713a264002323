#include "transport/scattering_tables_cache.hpp"

#include <cstdlib>
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

std::shared_ptr<const ScatteringOrders> load_or_build(const SingleScattering& integrator, const ScatteringTablesKey& key,
                                                      const MultipleScatteringSettings& settings, bool use_disk_cache) {
  const std::filesystem::path dir = use_disk_cache ? table_cache_directory() : std::filesystem::path();
  const std::string path = dir.empty() ? std::string() : (dir / key.file_name()).string();
  if (!path.empty())
    if (auto loaded = ScatteringOrders::load(path, key.inputs, integrator.atmosphere(), settings)) return loaded;
  auto built = std::make_shared<const ScatteringOrders>(integrator, settings);
  if (!path.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    built->save(path, key.inputs);
  }
  return built;
}

}  // namespace

std::shared_ptr<const ScatteringOrders> scattering_orders_for(const SingleScattering& integrator,
                                                              const SunColumnTable::Resolution& sun_table,
                                                              const MultipleScatteringSettings& settings,
                                                              bool use_disk_cache) {
  static std::mutex mutex;
  static std::vector<std::pair<std::string, std::shared_ptr<const ScatteringOrders>>> recent;
  const ScatteringTablesKey key = scattering_tables_key(integrator.atmosphere(), sun_table, settings);
  {
    std::lock_guard<std::mutex> lock(mutex);
    for (const auto& [inputs, orders] : recent)
      if (inputs == key.inputs) return orders;
  }
  auto orders = load_or_build(integrator, key, settings, use_disk_cache);
  std::lock_guard<std::mutex> lock(mutex);
  recent.emplace_back(key.inputs, orders);
  if (recent.size() > 4) recent.erase(recent.begin());
  return orders;
}

}  // namespace skyspec
