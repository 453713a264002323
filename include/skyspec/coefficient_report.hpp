// The coefficient derivation report: every step from the refractive index of air to the optical
// depth of the atmosphere, per wavelength, beside the published values it is checked against.
//
// make_coefficient_report() computes the numbers (a CoefficientReport); the writers turn them into
// Markdown (people), CSV and JSON (programs) or one self-contained HTML page with SVG plots. The
// numbers are the engine's own: the same AtmosphereModel, density profiles and column integrals
// that `skyspec render` uses, so the report documents exactly what is rendered.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "skyspec/atmosphere.hpp"
#include "skyspec/king_factor.hpp"
#include "skyspec/rayleigh.hpp"

namespace skyspec {

/// A state of the air given directly by its pressure and temperature (e.g. 250 hPa and 220 K):
/// N = P / (k T), beta = sigma N.
struct AirConditions {
  double pressure_Pa = 101325.0;
  double temperature_K = 288.15;
};

struct CoefficientReportRequest {
  AtmosphereSpec atmosphere;                ///< as a scene describes it
  std::vector<double> wavelengths_nm;       ///< the grid (strictly positive, any order)
  std::vector<double> altitudes_m{0.0};     ///< levels for beta(z) and tau(z -> top)
  std::optional<AirConditions> conditions;  ///< an extra (P, T) state
  double latitude_deg = 45.0;               ///< gravity for the hydrostatic columns
  std::string origin;                       ///< what the atmosphere came from, for the header
  int column_segments = 256;                ///< quadrature pieces of the vertical columns
};

/// A medium of the atmosphere other than the air, the aerosol and ozone (fog, ice, rain:
/// docs/bows-and-halos.md; or one a caller added) at one altitude.
struct ReportMediumLevel {
  std::string name;  ///< the medium's name in the list ("fog", "ice", "rain")
  std::vector<double> scattering_per_m, extinction_per_m;
  std::vector<double> optical_depth;  ///< vertical, z -> top of the atmosphere
};

/// One altitude of the scene's atmosphere.
struct ReportLevel {
  double altitude_m = 0.0;
  double rayleigh_number_density_per_m3 = 0.0;       ///< 0 when the coefficients are typed in
  std::optional<double> temperature_K, pressure_Pa;  ///< when the profile defines them
  std::string number_density_origin;
  std::vector<double> rayleigh_scattering_per_m;  ///< beta_R(lambda, z)
  std::vector<double> rayleigh_optical_depth;     ///< vertical, z -> top of the atmosphere
  std::vector<double> mie_scattering_per_m, mie_extinction_per_m, mie_optical_depth;
  std::vector<double> ozone_absorption_per_m, ozone_optical_depth;  ///< zeros without ozone
  std::vector<ReportMediumLevel> media;                             ///< CoefficientReport::media's, in order
  std::vector<double> total_optical_depth;                          ///< extinction of every species, z -> top
};

/// The (P, T) state of AirConditions.
struct ReportConditions {
  AirConditions air;
  double number_density_per_m3 = 0.0;             ///< P / (k T)
  double density_ratio = 0.0;                     ///< N / N_s
  std::vector<double> refractivity;               ///< (n - 1) at (P, T) = (n_s - 1) N / N_s (Lorentz-Lorenz)
  std::vector<double> rayleigh_scattering_per_m;  ///< sigma N
  /// Hydrostatic column above the level where the pressure is P (Bodhaine eq. 9), with g taken at
  /// the mass-weighted altitude of the column above the U.S. Standard Atmosphere 1976 altitude of
  /// that pressure.
  double pressure_altitude_m = 0.0;
  double column_gravity_m_per_s2 = 0.0;
  double column_molecules_per_m2 = 0.0;
  std::vector<double> rayleigh_optical_depth_above;
};

/// One comparison with a published table.
struct ReferenceComparison {
  struct Row {
    double wavelength_nm, published, skyspec, difference_percent;  ///< 100 (skyspec / published - 1)
  };
  std::string id;          ///< "bodhaine1999_table3", "bucholtz1995_king_factor", "seed_constants", ...
  std::string title;       ///< what is compared, for headings
  std::string quantity;    ///< column label, with its unit
  std::string conditions;  ///< the published conditions skyspec reproduced
  std::string source;      ///< citation and transcription
  std::string method;      ///< how the skyspec column was computed
  std::vector<Row> rows;
  double max_abs_difference_percent = 0.0;
  std::string explanation;  ///< plain language: where and why the numbers differ
};

/// A formula as written in the report.
struct ReportFormula {
  std::string quantity, formula, units, source;
};

struct CoefficientReport {
  std::string skyspec_version;
  std::string origin;
  std::vector<double> wavelengths_nm;
  double latitude_deg = 45.0;

  // Rayleigh derivation (computed for every atmosphere; used by the renderer when derived).
  bool rayleigh_derived = true;  ///< false: coefficients typed in (atmosphere.rayleigh.source = "fixed")
  ScatteringGas gas = ScatteringGas::Air;
  RefractiveIndexFormula formula = RefractiveIndexFormula::PeckReeder1972;
  double co2_ppv = 0.0;
  AirComposition composition;
  std::vector<RayleighDerivationStep> derivation;  ///< n, F, sigma per wavelength
  std::string profile_description;                 ///< the Rayleigh density profile
  double top_altitude_m = 0.0;

  // Aerosols (Angstrom law).
  bool mie_enabled = false;
  double mie_scattering_at_reference_per_m = 0.0, mie_reference_wavelength_nm = 550.0;
  double mie_angstrom_exponent = 0.0, mie_extinction_to_scattering = 1.0;
  bool mie_tabulated = false;  ///< spectral tables (Q_ext, albedo, g) replace the Angstrom law
  /// Microphysics (atmosphere.mie.model = "opac"): OPAC component -> particles per cm^3 (those
  /// above 0) and the humidity; empty for the Angstrom model.
  std::vector<std::pair<std::string, double>> mie_opac_components;
  double mie_opac_relative_humidity_percent = 0.0;
  std::string mie_profile_description;

  // Ozone (absorption only), when the atmosphere has it.
  bool ozone_enabled = false;
  double ozone_column_DU = 0.0;
  double ozone_peak_number_density_per_m3 = 0.0;
  std::vector<double> ozone_cross_section_m2;  ///< absorption cross-section per molecule
  std::string ozone_profile_description;

  // The other media (fog, ice, rain, or one a caller added), when the atmosphere has them: name and
  // density profile, in the list's order; their coefficients at each level are in ReportLevel::media.
  struct Medium {
    std::string name, profile_description;
    std::string region_description;  ///< where it is, when only in a region (Medium::region); else empty
  };
  std::vector<Medium> media;

  std::vector<ReportLevel> levels;
  std::optional<ReportConditions> conditions;
  std::vector<std::string> notes;

  std::vector<ReportFormula> formulas;
  std::vector<ReferenceComparison> references;
};

/// Computes the report. Throws InputError (setting "altitudes_m", "conditions.pressure_Pa",
/// "conditions.temperature_K", "latitude_deg", "wavelengths_nm" or a scene key) for bad requests.
CoefficientReport make_coefficient_report(const CoefficientReportRequest& request);

/// The Rayleigh derivation as columns over the wavelengths (one value per wavelength each), as
/// the JSON report and the Python module hand them out.
struct DerivationColumns {
  std::vector<double> refractivity_ref;  ///< n_s - 1 from the formula at its own CO2
  std::vector<double> refractivity;      ///< n_s - 1 at the report's CO2
  std::vector<double> king_factor_air, king_factor_n2, king_factor_o2;
  std::vector<double> cross_section_m2;
};
DerivationColumns derivation_columns(const CoefficientReport& report);

/// The comparisons with published tables alone (they do not depend on the request): Bodhaine et
/// al. 1999 Table 3 and text values, Bucholtz 1995's King factors and cross-section fit, and the
/// seed tutorial's constants against standard air.
std::vector<ReferenceComparison> published_comparisons();

enum class ReportFormat { Markdown, Csv, Json, Html };
/// "md", "csv", "json", "html"; throws InputError(setting) otherwise.
ReportFormat parse_report_format(const std::string& name, const std::string& setting = "format");
std::string to_string(ReportFormat f);

std::string report_to_markdown(const CoefficientReport& report);
/// One row per wavelength; reference comparisons are in the other formats.
std::string report_to_csv(const CoefficientReport& report);
std::string report_to_json(const CoefficientReport& report);
/// One self-contained page: the Markdown content as HTML plus SVG plots of beta(lambda), the King
/// factor and the optical depth.
std::string report_to_html(const CoefficientReport& report);
std::string format_report(const CoefficientReport& report, ReportFormat format);

}  // namespace skyspec
