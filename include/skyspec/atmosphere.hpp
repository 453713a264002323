// The atmosphere: a planet, a spherical shell of air, and the species in it.
//
// AtmosphereSpec is what a user describes (scale heights, pressure, CO2, aerosol load, ...);
// AtmosphereModel is the same atmosphere evaluated on a wavelength grid: its media (medium.hpp),
// each with volume scattering and extinction coefficients at relative density 1, a density
// profile and a phase function, which is all light transport needs.
#pragma once

#include <string>
#include <vector>

#include <memory>
#include <optional>

#include "skyspec/aerosol_components.hpp"
#include "skyspec/density_profile.hpp"
#include "skyspec/medium.hpp"
#include "skyspec/phase_function.hpp"
#include "skyspec/rayleigh.hpp"
#include "skyspec/spectrum.hpp"

namespace skyspec {

enum class ProfileKind { Exponential, UsStandard1976, Constant };
std::string to_string(ProfileKind k);

struct RayleighSpec {
  /// Derived: beta(lambda) = sigma(lambda) N(0) from the refractive index and the number density.
  /// Fixed: beta(lambda) typed in per wavelength (the seed tutorial's constants), kept so that the
  /// classic RGB-fast literature can be reproduced; every grid wavelength must be listed.
  enum class Source { Derived, Fixed };
  Source source = Source::Derived;
  ProfileKind profile = ProfileKind::UsStandard1976;
  double scale_height_m = 8000.0;         ///< exponential profile
  double surface_pressure_Pa = 101325.0;  ///< exponential/constant profile: N(0) = P / (k T)
  double surface_temperature_K = 288.15;
  /// Refractive index formula and CO2 (420 ppm, present-day air; the derivation's own default is
  /// Bodhaine et al.'s 360 ppm, at which their tables are computed).
  RayleighDerivationInput derivation{ScatteringGas::Air, RefractiveIndexFormula::PeckReeder1972,
                                     420 * 1e-6};  // as the reader stores 420 ppm
  std::vector<double> fixed_wavelengths_nm;        ///< Fixed source
  std::vector<double> fixed_beta_per_m;            ///< Fixed source, at altitude 0
};

struct MieSpec {
  /// Angstrom: the Angstrom law (or the optional tables below) and an analytic phase function that
  /// does not polarise. Opac: OPAC components by Lorenz-Mie theory (aerosol_components.hpp):
  /// extinction, scattering and the full scattering matrix per wavelength from the mixture's number
  /// concentrations and humidity; the Angstrom model's amount, exponent, ratio, phase and tables
  /// are then not used.
  enum class Model { Angstrom, Opac };
  Model model = Model::Angstrom;
  AerosolMixture opac = AerosolMixture::continental_average();
  bool enabled = true;
  ProfileKind profile = ProfileKind::Exponential;
  double scale_height_m = 1200.0;
  /// Aerosol scattering coefficient at altitude 0 and the reference wavelength, m^-1, and the
  /// Angstrom law beta(lambda) = beta_ref (lambda / lambda_ref)^-alpha.
  double scattering_per_m = 21e-6;
  double reference_wavelength_nm = 550.0;
  double angstrom_exponent = 1.3;  ///< continental aerosol, Angstrom's typical value
  /// beta_extinction = ratio * beta_scattering (the seed's 1.1: 10 % absorption).
  double extinction_to_scattering = 1.1;
  AerosolPhase phase;
  /// Optional spectral single-scattering properties (e.g. a published dust model), linearly
  /// interpolated; when given they replace the Angstrom law, the ratio and g:
  ///   beta_sca(lambda) = scattering_per_m Q(lambda) w(lambda) / (Q(lambda_ref) w(lambda_ref)),
  ///   beta_ext = beta_sca / w, g = g(lambda), with Q the extinction efficiency (any scale) and w
  ///   the single-scattering albedo.
  std::vector<double> table_wavelengths_nm, table_extinction_efficiency, table_single_scattering_albedo, table_g;
};

/// An absorbing ozone layer: a tent profile holding a given column.
struct OzoneSpec {
  bool enabled = true;
  double column_DU = 300.0;  ///< total column, Dobson units (1 DU = 2.6867e20 molecules m^-2)
  double bottom_m = 10e3, peak_m = 25e3, top_m = 40e3;
  /// Absorption cross-sections (m^2 per molecule) at these wavelengths, linearly interpolated; when
  /// empty, the built-in laboratory table (233 K, 230-1060 nm: Serdyuchenko et al. 2014 and Bogumil
  /// et al. 2003; data/ozone/) is used.
  std::vector<double> cross_section_wavelengths_nm, cross_section_m2;
};

/// Fog: droplets of liquid water near the ground, with OPAC's fog size distribution (a modified
/// gamma distribution, mode radius 8.06 um; Hess, Koepke & Schult 1998) and water's refractive
/// index at 10 degC (IAPWS R9-97), by Lorenz-Mie theory; off by default.
struct FogSpec {
  bool enabled = false;
  /// Meteorological optical range (WMO): the distance over which light at 550 nm falls to 5 %,
  /// so beta_ext(550 nm) = ln 20 / V at the ground. Fog by definition: V < 1 km.
  double visibility_m = 500.0;
  double scale_height_m = 100.0;  ///< density exp(-z / H) above the ground
  /// OPAC: OPAC's fog droplets (a broad modified gamma distribution, mode radius 8 um).
  /// Lognormal: droplets of about one size (a cloud's, whose corona shows coloured rings).
  enum class Droplets { Opac, Lognormal };
  Droplets droplets = Droplets::Opac;
  double median_radius_um = 6.0;  ///< lognormal: the number distribution's median radius
  double radius_spread = 1.1;     ///< lognormal: its geometric standard deviation
};

/// Ice crystals: randomly oriented hexagonal prisms of ice (ice_crystals.hpp), whose geometric
/// optics give the 22 and 46 degree halos, near the ground (diamond dust) or in a cloud layer aloft
/// (cirrostratus); off by default.
struct IceSpec {
  bool enabled = false;
  /// Ground: density exp(-z / scale_height_m), visibility_m at the ground. Cloud: a layer
  /// (DensityProfile::layer) from base_m to top_m whose edges fall by e every quarter of its
  /// thickness, holding a vertical optical depth optical_depth at 550 nm.
  enum class Layer { Ground, Cloud };
  Layer layer = Layer::Ground;
  /// Meteorological optical range at the ground, 550 nm: the crystals' whole extinction
  /// (refraction, reflection and diffraction: efficiency 2) is ln 20 / V.
  double visibility_m = 5000.0;
  double scale_height_m = 200.0;  ///< density exp(-z / H) above the ground
  double base_m = 8000.0;         ///< cloud: the layer's base
  double top_m = 10000.0;         ///< cloud: the layer's top
  /// Cloud: the layer's whole vertical optical depth at 550 nm (diffraction included, like
  /// visibility_m), from the ground to the top of the atmosphere.
  double optical_depth = 0.3;
  double aspect_ratio = 2.0;  ///< the prisms' length over their width (columns > 1, plates < 1)
};

/// Rain: water drops falling through the air near the ground; off by default. Either Marshall &
/// Palmer's sizes for a rain rate, by geometric optics (drop_optics.hpp: the primary and secondary
/// rainbows, no supernumeraries), or drops of about one size (a narrow lognormal distribution) by
/// Lorenz-Mie theory (sphere_ensemble.hpp: the bows with their supernumeraries), as many as carry
/// the rain rate at their fall speed (media/rain.cpp).
struct RainSpec {
  bool enabled = false;
  enum class Drops { MarshallPalmer, Lognormal };
  Drops drops = Drops::MarshallPalmer;
  double rate_mm_per_h = 2.0;      ///< R: the drops' number (and, Marshall-Palmer, their sizes)
  double scale_height_m = 1500.0;  ///< density exp(-z / H) above the ground
  double median_radius_mm = 0.25;  ///< lognormal: the number distribution's median radius
  double radius_spread = 1.1;      ///< lognormal: its geometric standard deviation
  /// Everywhere: a layer over the whole planet. Shower: only in a vertical cylinder (Medium::region)
  /// of radius shower_radius_m whose axis stands shower_distance_m from the reference point (east =
  /// north = 0) towards shower_azimuth_deg (clockwise from north).
  enum class Extent { Everywhere, Shower };
  Extent extent = Extent::Everywhere;
  double shower_distance_m = 8000.0;
  double shower_azimuth_deg = 0.0;
  double shower_radius_m = 3000.0;
};

/// The planet's surface: Lambertian, with a constant or a spectral albedo.
struct GroundSpec {
  double albedo = 0.0;                                       ///< used when albedo_values is empty
  std::vector<double> albedo_wavelengths_nm, albedo_values;  ///< spectral albedo, linearly interpolated
};

/// Water vapour: its column and profile. Only the broadband irradiance (irradiance.broadband) models
/// the gases' absorption bands (water vapour's, and the mixed gases' in the air: gas_bands.hpp);
/// spectral images name the bands they do not model in their files.
struct WaterVapourSpec {
  double column_cm = 1.42;         ///< precipitable water, cm (ASTM G173-03's reference atmosphere: 1.4164 cm)
  double scale_height_m = 2000.0;  ///< density exp(-z / H) above the ground
};

struct AtmosphereSpec {
  double planet_radius_m = 6360e3;
  double top_altitude_m = 60e3;  ///< thickness of the shell
  RayleighSpec rayleigh;
  MieSpec mie;
  OzoneSpec ozone;
  FogSpec fog;
  IceSpec ice;
  RainSpec rain;
  GroundSpec ground;
  WaterVapourSpec water_vapour;
  /// Not a scene key: set by the broadband irradiance for each of its runs (broadband_irradiance.hpp),
  /// the exponential term of the gas bands the run takes (gas_bands.hpp), with air's Rayleigh
  /// coefficients continued as lambda^-4 beyond its refractive index's range and no ozone
  /// absorption beyond its table's (both stated in docs/physics.md, "Gas bands"). -1 for every other
  /// use: no gas bands, and every table's range enforced.
  int gas_band_term = -1;
};

/// The atmosphere on a wavelength grid: its media (medium.hpp), the ground, and what the Rayleigh
/// derivation report shows.
class AtmosphereModel {
 public:
  /// Builds every medium of the list (src/physics/media/) that the spec turns on. Throws
  /// InputError naming the scene key when the spec cannot be evaluated on the grid.
  /// cache_on_disk: a microphysical aerosol's optics come from / go to the disk cache of tables
  /// (aerosol_components.hpp; a scene's render.cache_tables).
  AtmosphereModel(const AtmosphereSpec& spec, const WavelengthGrid& grid, bool cache_on_disk = false);

  const AtmosphereSpec& spec() const { return spec_; }
  const WavelengthGrid& grid() const { return grid_; }
  double planet_radius_m() const { return spec_.planet_radius_m; }
  double top_radius_m() const { return spec_.planet_radius_m + spec_.top_altitude_m; }

  /// The media present, in the list's order (air first; "aerosol" and "ozone" when the scene has
  /// them). Light transport sums over these and nothing else.
  const std::vector<Medium>& media() const { return media_; }
  /// The medium of that name, or null when the scene has none.
  const Medium* medium(const std::string& name) const;
  /// Adds a medium of the caller's own (after the list's): light transport and the Monte Carlo
  /// then sum over it as over the others. Throws InputError naming "medium.<name>.<field>" when it
  /// does not fit: an empty or taken name, spectra not of the grid's size, a coefficient negative
  /// or not finite, extinction below scattering, a phase function missing its parameters or with
  /// |g| >= 1, a scatterer whose density is not positive everywhere, more than kMaxMedia media.
  /// Call it before building anything on the atmosphere (tables and integrators keep references).
  void add_medium(Medium medium);

  /// The same atmosphere with the forward peak of every medium whose scattering matrix is tabulated
  /// cut off inside the cone of scattering angles below cone_rad (truncate_forward_peak): its
  /// scattering coefficient becomes (1 - f) beta_sca and its extinction beta_ext - f beta_sca, f
  /// the cut share per wavelength, its phase function the cut matrix. The light of the peak, which
  /// leaves within a few degrees of its way in, then travels on with the unscattered light: the
  /// "delta-M" scaling of radiative transfer (Wiscombe 1977; Nakajima & Tanaka 1988). Other media
  /// are unchanged. Empty when no medium has a tabulated matrix (nothing to cut).
  std::optional<AtmosphereModel> with_forward_peaks_truncated(double cone_rad) const;

  /// Whether a medium is confined to a region (Medium::region).
  bool has_regional_media() const;
  /// The atmosphere whose light field the scattering-order tables hold when some medium is confined
  /// to a region: each such medium spread everywhere again but vanishingly thin (its coefficients
  /// times kProbeDensity), so that it takes no part in the field while the tables still give its
  /// in-scattering source J_s (a source per unit scattering coefficient: the light of the rest of
  /// the atmosphere, all orders, scattered once by it). Light scattered twice or more by a regional
  /// medium is left out of the renderer's higher orders (docs/bows-and-halos.md measures what that
  /// misses). Empty when no medium is regional.
  std::optional<AtmosphereModel> with_regional_media_as_probes() const;
  static constexpr double kProbeDensity = 1e-12;

  /// Lambertian albedo of the ground on the grid.
  const SpectrumD& ground_albedo() const { return ground_albedo_; }

  /// Molecular number density at altitude 0, m^-3, and how it was obtained (0 and why for typed-in
  /// coefficients).
  double rayleigh_number_density_per_m3() const { return rayleigh_n0_per_m3_; }
  const std::string& rayleigh_number_density_origin() const { return rayleigh_n0_origin_; }
  /// The derivation (empty for the Fixed source and a broadband irradiance's run).
  const std::vector<RayleighDerivationStep>& rayleigh_derivation() const { return derivation_; }
  /// Number density of ozone at the layer's peak, m^-3 (0 without ozone).
  double ozone_peak_number_density_per_m3() const { return ozone_peak_per_m3_; }

 private:
  AtmosphereSpec spec_;
  WavelengthGrid grid_;
  std::vector<Medium> media_;
  SpectrumD ground_albedo_;
  double rayleigh_n0_per_m3_ = 0.0;
  std::string rayleigh_n0_origin_;
  std::vector<RayleighDerivationStep> derivation_;
  double ozone_peak_per_m3_ = 0.0;
};

/// Piecewise-linear interpolation of (x, y) samples at x0, constant beyond the ends.
double interpolate_linear(const std::vector<double>& x, const std::vector<double>& y, double x0);

/// A surface's albedo at each wavelength of a grid: albedo_values interpolated linearly (constant
/// beyond their ends), or `albedo` everywhere when there are none.
SpectrumD albedo_on_grid(const GroundSpec& surface, const WavelengthGrid& grid);

/// Build the density profile of a kind (exponential needs its scale height).
DensityProfile make_profile(ProfileKind kind, double scale_height_m, double top_altitude_m);

}  // namespace skyspec
