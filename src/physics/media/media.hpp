// The list of media an atmosphere may hold, and how each is built from the scene's AtmosphereSpec.
//
// Adding a medium: write its builder in a file of its own in this folder (air.cpp is the
// example), declare it below and add one entry to medium_registry() (media.cpp). Its scene keys go
// in the key registry (src/scene/key_registry.cpp) and its settings in AtmosphereSpec. Nothing in
// transport, render or the Monte Carlo changes: they iterate AtmosphereModel::media().
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "skyspec/aerosol_components.hpp"
#include "skyspec/atmosphere.hpp"
#include "skyspec/medium.hpp"

namespace skyspec {

/// What a builder reads.
struct MediumContext {
  const AtmosphereSpec& spec;
  const WavelengthGrid& grid;
  /// A medium whose optics are slow to compute (Lorenz-Mie) may take them from, and put them in,
  /// the disk cache of tables (render.cache_tables).
  bool cache_on_disk = false;
};

/// Builds the medium on the grid, or nothing when the scene turns it off. Throws InputError naming
/// the scene key when the spec cannot be evaluated.
using MediumBuilder = std::optional<Medium> (*)(const MediumContext&);

struct MediumEntry {
  const char* name;
  MediumBuilder build;
};

/// Rain's and fog's lognormal populations are cut this many spreads either side of their median
/// (SizeDistribution::lognormal_within): the far tails hold a fraction erfc(3 / sqrt 2) = 0.27 %
/// of the drops.
constexpr double kDropCutSpreads = 3.0;

/// A medium of particles: `per_particle`'s coefficients times `amount` (particles per m^3 at
/// density 1, or whatever unit per_particle is per), its tabulated matrix, density `profile`.
Medium particle_medium(const char* name, DensityProfile profile, const AerosolMixtureOptics& per_particle,
                       double amount);

/// Every medium, in the order AtmosphereModel::media() holds them (and light transport sums them).
const std::vector<MediumEntry>& medium_registry();

// The builders, one file each.
std::optional<Medium> build_air(const MediumContext& c);           // air.cpp: Rayleigh from n(lambda) and N
std::optional<Medium> build_aerosol(const MediumContext& c);       // aerosol.cpp: Angstrom law or OPAC by Lorenz-Mie
std::optional<Medium> build_ozone(const MediumContext& c);         // ozone.cpp: absorption by the ozone layer
std::optional<Medium> build_fog(const MediumContext& c);           // fog.cpp: water droplets by Lorenz-Mie
std::optional<Medium> build_ice(const MediumContext& c);           // ice.cpp: ice prisms by ray tracing (halos)
std::optional<Medium> build_rain(const MediumContext& c);          // rain.cpp: drops by geometric optics or Lorenz-Mie
std::optional<Medium> build_water_vapour(const MediumContext& c);  // water_vapour.cpp: its bands (broadband runs)

/// Air's number density at altitude 0 and how it was obtained (air.cpp; for the derivation report).
struct AirNumberDensity {
  double per_m3 = 0.0;
  std::string origin;
};
AirNumberDensity air_number_density(const RayleighSpec& r);
/// The surface's pressure over 101325 Pa (air.cpp): the air masses of the vertical column.
double relative_surface_pressure(const RayleighSpec& r);
/// One fog droplet's extinction cross-section at 550 nm, m^2, averaged over the droplets of `fog`
/// (fog.cpp: what the visibility is measured at).
double fog_extinction_cross_section_550nm_m2(const FogSpec& fog = FogSpec{});
/// The cosines the ice crystals' scattering function is tabulated at (ice.cpp): every 0.1 degree to
/// 60 degrees (the halos' edges), every 0.5 degree beyond.
const std::vector<double>& ice_scattering_cosines();
/// A cirrostratus layer's density profile (ice.cpp): 1 from base to top, edges falling by e every
/// quarter of its thickness.
DensityProfile cirrus_profile(const IceSpec& ice);
/// The rain shower's cylinder (rain.cpp; atmosphere.rain.extent = "shower").
VerticalCylinder shower_region(const AtmosphereSpec& spec);
/// Ozone's number density at the layer's peak, m^-3 (ozone.cpp; 0 without ozone).
double ozone_peak_number_density_per_m3(const OzoneSpec& o);

}  // namespace skyspec
