// The scattering-order tables of an atmosphere blended from those of atmospheres on a grid
// (render.ms_tables = "interpolated"): a dataset of many skies whose aerosol amount, Angstrom
// exponent and ozone column vary builds the grid's tables once, not a set per sky.
//
// Why a blend per wavelength: the tables at a wavelength depend on the atmosphere only through
// its optical properties at that wavelength. With the Angstrom aerosol (an analytic phase function,
// the same at every amount; a fixed extinction-to-scattering ratio) those are, besides what the
// grid's atmospheres share with the scene's, the aerosol's scattering coefficient at the ground,
// beta(lambda) = beta_ref (lambda / lambda_ref)^-alpha, and the ozone column. The grid's
// atmospheres (the members) are the scene's with the aerosol's exponent 0 (the same coefficient
// at every wavelength) at the amounts of kAerosolNodes_per_m and the ozone columns at multiples
// of kOzoneStep_DU; at each wavelength the scene's tables are the members' blended by Lagrange
// weights, cubic in ln(beta(lambda) + kAerosolOffset_per_m) over the four nearest amounts, and then geometrically
// between the two nearest columns (the ozone's absorption along the light's paths is exponential in the column;
// SourceTable::set_geometric_blend). docs/jobs.md, "Tables shared between atmospheres", measures what the blend errs.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "skyspec/atmosphere.hpp"
#include "skyspec/scene.hpp"
#include "transport/multiple_scattering.hpp"

namespace skyspec {

/// The aerosol scattering coefficients at the ground (m^-1) of the grid's atmospheres: 0 and a
/// doubling from 2.5e-6 (an optical depth of 0.003 at a scale height of 1200 m) to 6.4e-4 (0.77).
inline constexpr double kAerosolNodes_per_m[] = {0.0, 2.5e-6, 5e-6, 1e-5, 2e-5, 4e-5, 8e-5, 1.6e-4, 3.2e-4, 6.4e-4};
/// The aerosol's weights are cubic in ln(beta + this) (table_family.cpp).
inline constexpr double kAerosolOffset_per_m = 2.5e-6;
/// The grid's ozone columns: multiples of this up to kOzoneLast_DU.
inline constexpr double kOzoneStep_DU = 100.0;
inline constexpr double kOzoneLast_DU = 1000.0;

struct TableFamily {
  /// The grid's atmospheres the blend reads at one ozone column, with their weights per wavelength.
  struct Group {
    std::vector<Scene> members;               ///< weights not all zero
    std::vector<std::vector<float>> weights;  ///< [member][wavelength]
  };
  Group lower;        ///< at the column at or below the scene's (or the only group)
  Group upper;        ///< at the column above it (empty where the column is on the grid or there is no ozone)
  float ozone_t = 0;  ///< upper's weight in the geometric blend of the two
  /// Every member, lower's first.
  std::vector<Scene> members() const;
};

/// The grid's atmospheres and weights for the scene's tables; nullopt (and the reason in *why_not)
/// where the scene's atmosphere is not on the grid: another aerosol model or spectral aerosol
/// tables, a coefficient or column beyond the grid, nothing that varies, or single scattering.
std::optional<TableFamily> table_family(const Scene& scene, std::string* why_not = nullptr);

/// The scene's tables blended from its family's (each member's from this process, the disk cache,
/// or built and cached, render.cache_tables permitting), or null where table_family() is nullopt
/// (*why_not says why). `atmosphere` is the scene's.
std::shared_ptr<const ScatteringOrders> interpolated_scattering_orders(const Scene& scene,
                                                                       const AtmosphereModel& atmosphere,
                                                                       std::string* why_not = nullptr);

/// The scenes whose scattering-order tables a render of `scene` builds or reads: with
/// render.ms_tables = "interpolated" and a family, its members; otherwise the scene itself (none
/// with single scattering). Job plans and time estimates count these.
std::vector<Scene> scenes_of_tables(const Scene& scene);

/// Whether interpolated_scattering_orders(scene) would return this process's blend without
/// blending (or loading) anything: false for a scene without a family.
bool interpolated_tables_in_memory(const Scene& scene);

/// The scene's own tables (never interpolated): from this process, the disk cache, or built (with
/// the scene's own sun table) and cached, render.cache_tables permitting. For builds that are not a
/// render's (a job's table sets); a render builds its tables with its own integrator.
std::shared_ptr<const ScatteringOrders> scene_scattering_orders(const Scene& scene);

/// Whether every one of scenes_of_tables(scene) has its tables in this process (those the blends
/// read, or scattering_orders_cached's) or the disk cache: a render then builds none.
bool scene_tables_cached(const Scene& scene);

}  // namespace skyspec
