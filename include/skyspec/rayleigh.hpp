// Rayleigh scattering by air molecules, derived from the refractive index and the number density.
//
//   sigma(lambda) = 24 pi^3 (n_s^2 - 1)^2 / (lambda^4 N_s^2 (n_s^2 + 2)^2) * F_air(lambda)
//   beta(lambda, z) = sigma(lambda) N(z)
//
// with n_s the refractive index at the conditions where the number density is N_s (standard air,
// 288.15 K and 101325 Pa, N_s = 2.546899e25 m^-3) and F_air the King factor. Sources: Bodhaine,
// Wood, Dutton & Slusser 1999 (J. Atmos. Oceanic Technol. 16, 1854), eqs. (2), (18)-(23).
#pragma once

#include <string>
#include <vector>

#include "skyspec/refractive_index.hpp"

namespace skyspec {

/// The scattering gas: Earth's dry air, or pure carbon dioxide (Mars, Venus).
enum class ScatteringGas { Air, CarbonDioxide };
std::string to_string(ScatteringGas g);

struct RayleighDerivationInput {
  ScatteringGas gas = ScatteringGas::Air;
  RefractiveIndexFormula formula = RefractiveIndexFormula::PeckReeder1972;  ///< air only
  double co2_ppv = 3.6e-4;  ///< CO2 mole fraction, parts per volume (Bodhaine's 360 ppm)
};

/// Every intermediate quantity of the derivation at one wavelength (the coefficient report prints
/// them, the tests check them).
struct RayleighDerivationStep {
  double lambda_nm;
  double refractivity_ref;       ///< (n - 1) from the formula at its own CO2
  double refractivity;           ///< (n - 1) corrected to the requested CO2 (= n_s - 1)
  double king_factor;            ///< F_air
  double king_n2, king_o2;       ///< component King factors (air; 0 for CO2)
  double number_density_per_m3;  ///< N_s the index is paired with
  double cross_section_m2;       ///< sigma
};

/// Derive sigma(lambda) for each wavelength (nm).
std::vector<RayleighDerivationStep> derive_rayleigh(const std::vector<double>& lambda_nm,
                                                    const RayleighDerivationInput& in);
/// The cross-section alone, m^2.
double rayleigh_cross_section_m2(double lambda_nm, const RayleighDerivationInput& in);

/// Mean molecular weight of dry air, g mol^-1, Bodhaine eq. (17): 15.0556 C + 28.9595 (C in ppv).
double mean_molecular_weight_air_g_per_mol(double co2_ppv);

/// Acceleration of gravity, m s^-2, at latitude (deg) and altitude (m above sea level): List 1968 as
/// used by Bodhaine et al. 1999 eqs. (10)-(11). For the weight of an air column pass the column's
/// mass-weighted altitude (mass_weighted_column_altitude_m), as Bodhaine's tables do.
double gravity_m_per_s2(double latitude_deg, double altitude_m);

/// Mass-weighted altitude (m) of the air column above a station at station_altitude_m, Bodhaine
/// et al. 1999 (fit to the U.S. Standard Atmosphere): z_c = 0.73737 z + 5517.56. (Added by the
/// physics module: Bodhaine's Table 3 evaluates g at z_c, 5517.56 m for a sea-level station.)
double mass_weighted_column_altitude_m(double station_altitude_m);

/// Vertical Rayleigh optical depth of the whole air column above a station (station altitude in m)
/// from the hydrostatic relation, Bodhaine eq. (9): tau = sigma P N_A / (m_a g), with g taken at
/// the column's mass-weighted altitude. Reproduces Bodhaine's Table 3 (0.09707 at 550 nm).
double rayleigh_optical_depth_hydrostatic(double cross_section_m2, double surface_pressure_Pa, double latitude_deg,
                                          double altitude_m, double co2_ppv);

}  // namespace skyspec
