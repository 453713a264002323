#include "transport/scattering_tables_cache.hpp"

#include "base/atomic_file.hpp"
#include "skyspec/error.hpp"

#include <algorithm>
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

std::uint64_t table_cache_cap_bytes() {
  const char* text = std::getenv("SKYSPEC_CACHE_MAX_MB");
  if (!text || !*text) return kDefaultTableCacheCapBytes;
  const std::string value(text);
  constexpr std::uint64_t kMaxMegabytes = 1000ull * 1000 * 1000;  // a petabyte
  const auto refuse = [&value] {
    throw InputError("SKYSPEC_CACHE_MAX_MB", "\"" + value + "\"",
                     "a whole number of megabytes for the table cache, 0 to 1000000000 (0: no cap; unset: 2000)");
  };
  std::uint64_t mb = 0;
  for (char c : value) {
    if (c < '0' || c > '9' || mb > kMaxMegabytes) refuse();
    mb = mb * 10 + static_cast<std::uint64_t>(c - '0');
  }
  if (mb > kMaxMegabytes) refuse();
  return mb * 1000 * 1000;
}

std::uint64_t evict_table_cache(const std::filesystem::path& dir, std::uint64_t cap, const std::filesystem::path& keep) {
  if (cap == 0) return 0;
  struct Entry {
    std::filesystem::path path;
    std::filesystem::file_time_type used;
    std::uint64_t bytes;
  };
  std::vector<Entry> files;
  std::uint64_t total = 0;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind("orders-", 0) != 0 || name.size() < 4 || name.compare(name.size() - 4, 4, ".bin") != 0) continue;
    std::error_code e;
    if (!it->is_regular_file(e)) continue;
    const auto bytes = it->file_size(e);
    if (e) continue;
    const auto used = it->last_write_time(e);
    if (e) continue;
    files.push_back({it->path(), used, bytes});
    total += bytes;
  }
  std::sort(files.begin(), files.end(), [](const Entry& a, const Entry& b) { return a.used < b.used; });
  std::uint64_t removed = 0;
  for (const Entry& f : files) {
    if (total <= cap) break;
    if (f.path == keep) continue;
    std::error_code e;
    if (std::filesystem::remove(f.path, e)) {
      total -= f.bytes;
      removed += f.bytes;
    }
  }
  return removed;
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
  const std::uint64_t cap = path.empty() ? 0 : table_cache_cap_bytes();  // a bad value: refused before any work
  if (!path.empty() && is_regular_input(path))
    if (auto loaded = ScatteringOrders::load(path, key.inputs, integrator.atmosphere(), settings)) {
      std::error_code ec;  // used now: the last to be evicted (a read-only cache keeps its times)
      std::filesystem::last_write_time(path, std::filesystem::file_time_type::clock::now(), ec);
      return loaded;
    }
  auto built = std::make_shared<const ScatteringOrders>(integrator, settings);
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
