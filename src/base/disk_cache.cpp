#include "base/disk_cache.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "base/cancellation.hpp"
#include "base/output_lock.hpp"
#include "base/preparation_progress.hpp"
#include "skyspec/error.hpp"

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

std::uint64_t evict_table_cache(const std::filesystem::path& dir, std::uint64_t cap,
                                const std::filesystem::path& keep) {
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
    const bool ours = name.rfind("orders-", 0) == 0 || name.rfind("aerosol-", 0) == 0;
    if (!ours || name.size() < 4 || name.compare(name.size() - 4, 4, ".bin") != 0) continue;
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
      std::filesystem::path lock = f.path;
      lock += ".lock";
      std::filesystem::remove(lock, e);  // a claim's leftover (a process killed while computing it)
      total -= f.bytes;
      removed += f.bytes;
    }
  }
  return removed;
}

void warn_cache_unusable(const std::filesystem::path& dir, const std::string& why) {
  static std::once_flag once;
  std::call_once(once, [&] {
    const char* from =
        std::getenv("SKYSPEC_CACHE_DIR") && *std::getenv("SKYSPEC_CACHE_DIR") ? " (SKYSPEC_CACHE_DIR)" : "";
    std::cerr << "skyspec: warning: tables cannot be cached in " << dir.string() << from << ": " << why
              << "; they are computed again on every run\n";
  });
}

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

void mark_cache_file_used(const std::filesystem::path& path) {
  std::error_code ec;
  std::filesystem::last_write_time(path, std::filesystem::file_time_type::clock::now(), ec);
}

CacheFileClaim::CacheFileClaim(const std::filesystem::path& file) {
  if (file.empty()) return;
  std::filesystem::path lock_path = file;
  lock_path += ".lock";
  constexpr auto kPoll = std::chrono::milliseconds(20);
  try {
    while (!(lock_ = LockFile::try_lock(lock_path))) {
      if (!waited_) plan_preparation(1, "waiting for another skyspec process to finish the same tables");
      waited_ = true;
      throw_if_cancelled();
      std::this_thread::sleep_for(kPoll);
    }
  } catch (const IoError& e) {  // computed without a claim
    warn_cache_unusable(file.parent_path(), e.what());
  }
  if (waited_) finish_preparation(1);
}

CacheFileClaim::~CacheFileClaim() = default;

}  // namespace skyspec
