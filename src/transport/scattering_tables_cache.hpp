// Where the scattering-order tables come from: this process's last few, the disk cache, or a
// fresh build (which is then saved). Keyed by scattering_tables_key.hpp, never by build stamps or
// scene text: two builds of the same source share tables, a change of physics does not.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>

#include "transport/multiple_scattering.hpp"
#include "transport/scattering_tables_key.hpp"

namespace skyspec {

/// The disk cache's folder: $SKYSPEC_CACHE_DIR, else $XDG_CACHE_HOME/skyspec, else
/// ~/.cache/skyspec; empty when none can be named.
std::filesystem::path table_cache_directory();

/// The default cap of the disk cache: 2000 MB (about 35 sets of tables at the default settings).
inline constexpr std::uint64_t kDefaultTableCacheCapBytes = 2000ull * 1000 * 1000;
/// The disk cache's cap in bytes: $SKYSPEC_CACHE_MAX_MB megabytes (10^6 bytes; 0: no cap), else
/// kDefaultTableCacheCapBytes. InputError naming SKYSPEC_CACHE_MAX_MB for a value that is not a
/// whole number of megabytes.
std::uint64_t table_cache_cap_bytes();
/// Removes the least recently used table files of `dir` ("orders-*.bin"; a load refreshes a file's
/// modification time, so that is its last use) until they take at most `cap` bytes, never `keep`
/// (the file just written). cap 0: nothing is removed. Returns the bytes removed. A file another
/// process is reading stays readable for it (POSIX unlink).
std::uint64_t evict_table_cache(const std::filesystem::path& dir, std::uint64_t cap, const std::filesystem::path& keep);

/// The tables for the integrator's atmosphere and sun columns (whose resolution is sun_table) with
/// these settings. With use_disk_cache, a file in table_cache_directory() named by the key is used
/// when it holds exactly this key's inputs and its checksum holds (and is then marked as used);
/// otherwise the tables are built and saved there (a cache that cannot be written only costs
/// time), and the least recently used files beyond the cap are removed (table_cache_cap_bytes). The last four sets are kept
/// in memory for the process (a time-lapse changes only the sun).
std::shared_ptr<const ScatteringOrders> scattering_orders_for(const SingleScattering& integrator,
                                                              const SunColumnTable::Resolution& sun_table,
                                                              const MultipleScatteringSettings& settings,
                                                              bool use_disk_cache);

/// Whether scattering_orders_for would take the tables of `key` from memory or from the disk
/// cache rather than build them (a file of the key's name counts; its checksum is checked when it
/// is read, and a damaged file is rebuilt then).
bool scattering_orders_cached(const ScatteringTablesKey& key, bool use_disk_cache);

}  // namespace skyspec
