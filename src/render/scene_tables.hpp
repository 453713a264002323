// What a scene asks of the precomputed tables: the sun table's resolution, the scattering-order
// tables' settings, and the key that names those tables (transport/scattering_tables_key.hpp).
#pragma once

#include "skyspec/scene.hpp"
#include "transport/multiple_scattering.hpp"
#include "transport/optical_depth.hpp"
#include "transport/scattering_tables_key.hpp"

namespace skyspec {

/// render.table_altitude_samples x render.table_zenith_samples, 64 pieces per entry.
SunColumnTable::Resolution sun_table_resolution(const Scene& scene);
/// render.scattering_orders, render.ms_altitude_samples, render.ms_sun_samples, render.ms_angular_degree,
/// output.polarisation.
MultipleScatteringSettings multiple_scattering_settings(const Scene& scene);
/// The key of the scene's scattering-order tables (builds the scene's atmosphere on its grid).
ScatteringTablesKey scattering_tables_key(const Scene& scene);

}  // namespace skyspec
