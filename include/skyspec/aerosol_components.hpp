// Aerosols from their microphysics: OPAC's components (Hess, Koepke & Schult 1998, "Optical
// Properties of Aerosols and Clouds: The Software Package OPAC", BAMS 79, 831), each a lognormal
// number size distribution of spheres with a spectral refractive index, at eight relative
// humidities for the components that take up water (data/aerosols/opac_components.csv, from OPAC
// 3.1's files; data/README.md). A mixture is a number concentration per component (particles per
// cm^3, OPAC's unit); its optical properties on a wavelength grid are Lorenz-Mie theory integrated
// over each component's distribution (sphere_ensemble.hpp) and added in proportion to number:
//
//   beta_ext(lambda) = sum_c N_c <C_ext,c>(lambda),  beta_sca likewise,
//   P_ij(mu, lambda) = sum_c N_c <C_sca,c> P_ij,c(mu) / beta_sca   (external mixture).
//
// Approximations, each measured in docs/validation.md (test_aerosol_components):
// - the refractive index between OPAC's wavelengths (every 50 nm from 250 to 800 nm, then 900, 1000,
//   1250 nm ...) is linear in wavelength;
// - between OPAC's humidities (0, 50, 70, 80, 90, 95, 98, 99 %) the wet mode radius and the
//   refractive index are linear in humidity; at those humidities they are OPAC's own;
// - the scattering matrix is tabulated at kScatteringAngles cosines (0.05 deg steps up to 2 deg from
//   the forward direction, 0.25 deg to 10 deg, 0.5 deg beyond) and is linear in mu between them
//   (tabulated_scattering.hpp).
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "skyspec/spectrum.hpp"
#include "skyspec/tabulated_scattering.hpp"

namespace skyspec {

/// OPAC's component names, in the order of its Table 1c: inso, waso, soot, ssam, sscm, minm, miam,
/// micm, mitr, suso.
constexpr int kAerosolComponentCount = 10;
const std::array<const char*, kAerosolComponentCount>& aerosol_component_names();
/// "water-soluble" for "waso", ...
std::string aerosol_component_description(int component);

/// The wavelengths OPAC's refractive indices cover here (250-2500 nm).
struct AerosolComponentWavelengths {
  double min_nm, max_nm;
};
AerosolComponentWavelengths aerosol_component_wavelengths();

/// A component at a relative humidity: its size distribution (number, lognormal, OPAC's radius
/// range) and refractive index at a wavelength, interpolated as stated above.
struct AerosolComponentState {
  double median_radius_m = 0.0;  ///< OPAC's wet "Rmod"
  double geometric_standard_deviation = 0.0;
  double min_radius_m = 0.0, max_radius_m = 0.0;
  double m_real = 0.0, m_imag = 0.0;  ///< m = m_real + i m_imag, m_imag >= 0 (absorbing)
};
/// Throws InputError naming `setting` when the wavelength is outside OPAC's 250-2500 nm here or
/// the humidity outside 0-99 %.
AerosolComponentState aerosol_component_state(int component, double relative_humidity_percent, double wavelength_nm,
                                              const std::string& setting);

/// The share of the untruncated lognormal that lies between the minimum and maximum radius. OPAC
/// counts the number concentration over all radii and integrates the optics over its range, so a
/// concentration N_c gives N_c times this share of particles in the range.
double aerosol_component_fraction_in_range(const AerosolComponentState& state);

/// OPAC's own optical properties of a component at one of its humidities and wavelengths (the
/// check values): extinction for one particle per cm^3 (km^-1), single-scattering albedo, g.
struct OpacPublishedOptics {
  double extinction_per_km = 0.0, single_scattering_albedo = 0.0, asymmetry = 0.0;
};
/// nullopt-like: returns false when OPAC's table has no row for it.
bool opac_published_optics(int component, int relative_humidity_percent, double wavelength_nm,
                           OpacPublishedOptics& out);

struct AerosolMixture {
  std::array<double, kAerosolComponentCount> number_per_cm3{};  ///< at relative density 1
  double relative_humidity_percent = 70.0;
  /// OPAC's "continental average" (Hess et al. 1998, Table 4): 7000 water-soluble, 0.4 insoluble,
  /// 8300 soot particles per cm^3.
  static AerosolMixture continental_average();
};

/// The cosines of the scattering angle at which mixtures are tabulated (increasing, -1 to 1).
const std::vector<double>& aerosol_scattering_cosines();

/// A mixture on a wavelength grid: volume coefficients (m^-1, at the concentrations given) and the
/// normalised scattering matrix.
struct AerosolMixtureOptics {
  SpectrumD scattering_per_m, extinction_per_m;
  std::shared_ptr<const TabulatedScatteringMatrix> matrix;
};
/// Computes (Lorenz-Mie per component, wavelength and radius node, on all threads; polls
/// cancellation). `setting` is the prefix of the mixture's keys that errors name
/// (setting.relative_humidity_percent, setting.*_per_cm3). Results are kept in memory per
/// (mixture, grid) for the process's life, so that a scene's renderer, tables and Monte Carlo
/// share one computation; with use_disk_cache also in the disk cache of tables (render.cache_tables;
/// "aerosol-<hash>.bin" beside the scattering-order tables, under the same cap), named by a hash of
/// exactly what they depend on and checked when read back.
AerosolMixtureOptics aerosol_mixture_optics(const AerosolMixture& mixture, const WavelengthGrid& grid,
                                            const std::string& setting, bool use_disk_cache = false);

}  // namespace skyspec
