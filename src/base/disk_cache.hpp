// The disk cache of tables that take long to compute and are named by a hash of exactly their
// inputs: the scattering-order tables ("orders-<hash>.bin", transport/scattering_tables_cache.hpp)
// and the optics of microphysical aerosols ("aerosol-<hash>.bin", physics/aerosol_components.cpp).
// One folder and one cap for both; the least recently used files go first.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

namespace skyspec {

class LockFile;  // base/output_lock.hpp

/// The disk cache's folder: $SKYSPEC_CACHE_DIR, else $XDG_CACHE_HOME/skyspec, else
/// ~/.cache/skyspec; empty when none can be named.
std::filesystem::path table_cache_directory();

/// The default cap of the disk cache: 2000 MB (about 35 sets of tables at the default settings).
inline constexpr std::uint64_t kDefaultTableCacheCapBytes = 2000ull * 1000 * 1000;
/// The disk cache's cap in bytes: $SKYSPEC_CACHE_MAX_MB megabytes (10^6 bytes; 0: no cap), else
/// kDefaultTableCacheCapBytes. InputError naming SKYSPEC_CACHE_MAX_MB for a value that is not a
/// whole number of megabytes.
std::uint64_t table_cache_cap_bytes();
/// Removes the least recently used cache files of `dir` ("orders-*.bin" and "aerosol-*.bin"; a
/// load refreshes a file's modification time, so that is its last use) until they take at most
/// `cap` bytes, never `keep` (the file just written). cap 0: nothing is removed. Returns the bytes
/// removed. A file another process is reading stays readable for it (POSIX unlink).
std::uint64_t evict_table_cache(const std::filesystem::path& dir, std::uint64_t cap, const std::filesystem::path& keep);

/// Whether `dir` can hold cache files, creating it if needed; when it cannot, says so once per
/// process on stderr (a cache that cannot be used only costs time, but the user should know why
/// every run computes its tables again).
bool usable_cache_directory(const std::filesystem::path& dir);
/// The same warning for a cache file that could not be written.
void warn_cache_unusable(const std::filesystem::path& dir, const std::string& why);
/// Marks a cache file as used now (its modification time), so that it is the last to be evicted;
/// a read-only cache keeps its times.
void mark_cache_file_used(const std::filesystem::path& path);

/// The right to compute one cache file, shared by every process that uses the folder: an exclusive
/// lock on "<file>.lock" (base/output_lock.hpp's LockFile). A process that finds the file missing
/// takes the claim before computing it; a second process that wants the same file meanwhile (two
/// renders of one atmosphere, a job's tasks on one machine, the viewer and a render) waits for the
/// first, then reads the file it wrote instead of computing it too. Waiting polls for cancellation
/// (base/cancellation.hpp) and shows as the preparation phase "waiting for another skyspec process
/// to finish the same tables". A lock that cannot be made (a read-only folder, a file system without
/// flock, a link planted under the lock's name) gives no claim: the process computes the file
/// itself, which costs only time; the reason is reported once (warn_cache_unusable).
class CacheFileClaim {
 public:
  /// Takes the claim on `file` (no claim for an empty path), waiting while another process holds it.
  explicit CacheFileClaim(const std::filesystem::path& file);
  ~CacheFileClaim();
  CacheFileClaim(const CacheFileClaim&) = delete;
  CacheFileClaim& operator=(const CacheFileClaim&) = delete;
  /// Whether another process held the claim when this one asked: the file may be there now.
  bool waited() const { return waited_; }
  /// Whether this process holds the claim (false without a lock, see above).
  bool held() const { return lock_ != nullptr; }

 private:
  std::unique_ptr<LockFile> lock_;
  bool waited_ = false;
};

}  // namespace skyspec
