// Physical constants and unit conventions used throughout skyspec.
//
// The engine works in SI: metres, m^-1 for volume coefficients, m^2 for cross-sections, kelvin,
// pascal. Wavelengths are carried in nanometres (the unit people label spectra with) and converted
// at the formula that needs another unit. Every variable that holds a dimensioned number says its
// unit in its name (altitude_m, beta_per_m, lambda_nm, ...).
#pragma once

namespace skyspec {

constexpr double kPi = 3.14159265358979323846;

namespace constants {
/// Boltzmann constant, J K^-1 (exact, SI 2019).
constexpr double kBoltzmann_J_per_K = 1.380649e-23;
/// Avogadro constant, mol^-1 (exact, SI 2019).
constexpr double kAvogadro_per_mol = 6.02214076e23;
/// Standard air: 15 degC and one standard atmosphere (Peck & Reeder 1972; Bodhaine et al. 1999).
constexpr double kStandardTemperature_K = 288.15;
constexpr double kStandardPressure_Pa = 101325.0;
/// Molecular number density of standard air, m^-3 (Bodhaine et al. 1999, N_s = 2.546899e19 cm^-3).
constexpr double kStandardNumberDensity_per_m3 = 2.546899e25;
/// Maximum luminous efficacy for photopic vision, lm W^-1 (CIE).
constexpr double kMaxLuminousEfficacy_lm_per_W = 683.0;
/// One Dobson unit in molecules per square metre.
constexpr double kDobsonUnit_per_m2 = 2.6867e20;
}  // namespace constants

/// Length units of wavelengths: the dispersion formulas take micrometres, the rest nanometres.
constexpr double kNanometresPerMicrometre = 1000.0;

constexpr double degrees_to_radians(double deg) { return deg * kPi / 180.0; }
constexpr double radians_to_degrees(double rad) { return rad * 180.0 / kPi; }

}  // namespace skyspec
