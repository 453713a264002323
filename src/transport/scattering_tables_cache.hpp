// Where the scattering-order tables come from: this process's last few, the disk cache, or a
// fresh build (which is then saved). Keyed by scattering_tables_key.hpp, never by build stamps or
// scene text: two builds of the same source share tables, a change of physics does not.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>

#include "base/disk_cache.hpp"  // the folder, its cap and eviction
#include "transport/multiple_scattering.hpp"
#include "transport/scattering_tables_key.hpp"

namespace skyspec {

/// The tables for the integrator's atmosphere and sun columns (whose resolution is sun_table) with
/// these settings. With use_disk_cache, a file in table_cache_directory() named by the key is used
/// when it holds exactly this key's inputs and its checksum holds (and is then marked as used);
/// otherwise the tables are built and saved there (a cache that cannot be written only costs
/// time), and the least recently used files beyond the cap are removed (table_cache_cap_bytes). The last four sets are
/// kept in memory for the process (a time-lapse changes only the sun).
std::shared_ptr<const ScatteringOrders> scattering_orders_for(const SingleScattering& integrator,
                                                              const SunColumnTable::Resolution& sun_table,
                                                              const MultipleScatteringSettings& settings,
                                                              bool use_disk_cache);

/// Builds tables when neither this process nor the disk cache has them.
using TablesBuild = std::function<std::shared_ptr<const ScatteringOrders>()>;

/// The same for `atmosphere`, whose tables, when they must be built, build() makes (so that the
/// integrator, and the sun table it needs, are made only then: render/table_family.cpp reads many
/// atmospheres' tables, most of them cached).
std::shared_ptr<const ScatteringOrders> scattering_orders_for(const AtmosphereModel& atmosphere,
                                                              const SunColumnTable::Resolution& sun_table,
                                                              const MultipleScatteringSettings& settings,
                                                              bool use_disk_cache, const TablesBuild& build);

/// Whether scattering_orders_for would take the tables of `key` from memory or from the disk
/// cache rather than build them (a file of the key's name counts; its checksum is checked when it
/// is read, and a damaged file is rebuilt then).
bool scattering_orders_cached(const ScatteringTablesKey& key, bool use_disk_cache);

}  // namespace skyspec
