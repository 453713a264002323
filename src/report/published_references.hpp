// Published Rayleigh-scattering figures that skyspec's derivation is checked against, read from the
// tables embedded from data/reference/ (data/README.md says where each figure was transcribed
// from). Only published numbers live here; nothing in this file is computed by skyspec.
#pragma once

#include <string>
#include <vector>

namespace skyspec {

/// One tabulated value at one wavelength.
struct PublishedValue {
  double wavelength_nm;
  double value;
};

/// Bodhaine et al. 1999 (J. Atmos. Oceanic Technol. 16, 1854), Table 3: vertical Rayleigh optical
/// depth of the whole column above sea level, 1013.25 hPa, 45 degrees latitude, 360 ppm CO2.
const std::vector<PublishedValue>& bodhaine1999_table3_optical_depth();

/// Single figures stated by Bodhaine et al. 1999 for 360 ppm CO2 (SI units): the cross-section
/// at 550 nm in m^2, the King factor of air at 550 nm and the sea-level optical depth at 550 nm.
struct Bodhaine1999TextValues {
  double cross_section_550nm_m2;
  double king_factor_air_550nm;
  double optical_depth_550nm;
};
const Bodhaine1999TextValues& bodhaine1999_text_values();

/// Bodhaine et al. 1999 eqs. (29)-(30): their fits to their own cross-sections (360 ppm CO2) and
/// sea-level optical depths (1013.25 hPa, 45 degrees), ratio (a + b/l^2 + c l^2) / (1 + d/l^2 + e l^2)
/// with l in micrometres; sigma = 1e-28 cm^2 x ratio, tau = tau_scale x ratio.
struct Bodhaine1999Fit {
  double a, b, c, d, e, tau_scale;
};
const Bodhaine1999Fit& bodhaine1999_fit();
double bodhaine1999_cross_section_fit_m2(double lambda_nm);
double bodhaine1999_optical_depth_fit(double lambda_nm);
/// Bucholtz 1995 (Appl. Opt. 34, 2765): depolarization factor rho_n of standard air (288.15 K,
/// 1013.25 mb, 300 ppm CO2) as tabulated there (a fraction, not percent), 200-1000 nm.
const std::vector<PublishedValue>& bucholtz1995_depolarization();
/// The King factor of a depolarization factor: F = (6 + 3 rho) / (6 - 7 rho).
double king_factor_from_depolarization(double rho);

/// Bucholtz 1995's analytic fit to his cross-sections of standard air, sigma = A lambda_um^-(B + C
/// lambda_um + D / lambda_um), in m^2; the long-wave set applies above 500 nm with no stated upper
/// limit; used for 200-1690 nm (throws InputError outside).
double bucholtz1995_cross_section_fit_m2(double lambda_nm);
/// The wavelength (nm) where the fit switches from its short- to its long-wave coefficients.
double bucholtz1995_fit_branch_nm();

/// The CO2 content of the standard air of each source, parts per volume.
constexpr double kBodhaine1999Co2_ppv = 360.0e-6;
constexpr double kBucholtz1995Co2_ppv = 300.0e-6;
/// Bucholtz 1995's number density of standard air, m^-3 (2.54743e19 cm^-3).
constexpr double kBucholtz1995StandardNumberDensity_per_m3 = 2.54743e25;

}  // namespace skyspec
