// The name of a set of precomputed scattering-order tables: exactly the physical inputs they
// depend on, and a hash of them that names the cache file.
//
// The tables (multiple_scattering.hpp) are a function of the atmosphere as evaluated on the
// wavelength grid (planet and top radii, each species' scattering and extinction coefficients and
// density profile, the aerosol phase function and its asymmetry per wavelength, the ground albedo),
// of the sun-column table they integrate with (its resolution) and of their own sample counts.
// They do not depend on the sun, the camera, the exposure or the outputs. The coefficients are
// taken after derivation, so a change anywhere upstream (refractive index, CO2, number density,
// aerosol model) changes the key without this file knowing about it. What the key cannot see is
// the integrator's code: kScatteringTablesFormat is bumped whenever the method or the file layout
// changes what a table holds.
#pragma once

#include <cstdint>
#include <string>

#include "transport/multiple_scattering.hpp"
#include "transport/optical_depth.hpp"

namespace skyspec {

/// Version of the tables' method and file layout (not of the program): bump it when the
/// integrator, its quadrature or the cache file's layout changes.
inline constexpr int kScatteringTablesFormat = 7;

/// Significant digits of every number in the key. Builds that differ only in the last bits of a
/// derived coefficient (another compiler, optimisation level or instruction set: a few parts in
/// 1e16) name the same tables; any physical change, and the tables' own accuracy (about 1e-3),
/// are many orders of magnitude larger.
inline constexpr int kKeySignificantDigits = 12;

struct ScatteringTablesKey {
  std::string inputs;  ///< the inputs, one per line, numbers to kKeySignificantDigits digits
  std::uint64_t hash;  ///< FNV-1a 64 of `inputs`
  /// "orders-<16 hex digits>.bin": the cache file's name.
  std::string file_name() const;
};

ScatteringTablesKey scattering_tables_key(const AtmosphereModel& atmosphere,
                                          const SunColumnTable::Resolution& sun_table,
                                          const MultipleScatteringSettings& settings);

}  // namespace skyspec
