// Rayleigh scattering by the molecules of dry air (Bodhaine, Wood, Dutton & Slusser 1999,
// J. Atmos. Oceanic Technol. 16, 1854-1861).
//
// The cross-section per molecule follows from the refractive index n_s of standard air and the
// molecular number density N_s of that same air, eq. (22) of the paper:
//
//   sigma = 24 pi^3 (n_s^2 - 1)^2 / (lambda^4 N_s^2 (n_s^2 + 2)^2) * F_air
//
// (n_s^2 - 1) / (n_s^2 + 2) is proportional to N_s (Lorentz-Lorenz), so sigma does not depend on
// which temperature and pressure define "standard", as long as n_s and N_s refer to the same one.
// Everything here is SI: lambda in metres, N_s in m^-3, sigma in m^2.
#include "skyspec/rayleigh.hpp"

#include <cmath>
#include <sstream>

#include "base/text_format.hpp"
#include "skyspec/error.hpp"
#include "skyspec/king_factor.hpp"
#include "skyspec/units.hpp"

namespace skyspec {
namespace {

constexpr double kMetresPerNanometre = 1.0e-9;
constexpr double kKilogramsPerGram = 1.0e-3;
constexpr double kMetresPerCentimetre = 1.0e-2;

/// Mean molecular weight of dry air, Bodhaine et al. 1999 eq. (17):
/// m_a = 15.0556 C + 28.9595 g/mol, C the CO2 mole fraction (ppv).
constexpr double kMolecularWeightCo2Slope_g_per_mol = 15.0556;
constexpr double kMolecularWeightCo2Free_g_per_mol = 28.9595;

/// Sea-level gravity of List 1968 (Smithsonian Meteorological Tables), Bodhaine et al. 1999
/// eq. (10): g0 = 980.6160 (1 - 0.0026373 cos 2phi + 0.0000059 cos^2 2phi), cm s^-2.
constexpr double kSeaLevelGravity45_cm_per_s2 = 980.6160;
constexpr double kGravityCos2PhiCoefficient = 0.0026373;
constexpr double kGravityCos2PhiSquaredCoefficient = 0.0000059;

/// Height dependence, Bodhaine et al. 1999 eq. (11), z in metres, g in cm s^-2:
/// g = g0 - (3.085462e-4 + 2.27e-7 cos 2phi) z + (7.254e-11 + 1e-13 cos 2phi) z^2
///        - (1.517e-17 + 6e-20 cos 2phi) z^3.
constexpr double kGravityLinear_cm_per_s2_m = 3.085462e-4;
constexpr double kGravityLinearCos2Phi_cm_per_s2_m = 2.27e-7;
constexpr double kGravityQuadratic_cm_per_s2_m2 = 7.254e-11;
constexpr double kGravityQuadraticCos2Phi_cm_per_s2_m2 = 1.0e-13;
constexpr double kGravityCubic_cm_per_s2_m3 = 1.517e-17;
constexpr double kGravityCubicCos2Phi_cm_per_s2_m3 = 6.0e-20;

/// Mass-weighted altitude of the column above a station, Bodhaine et al. 1999:
/// z_c = 0.73737 z + 5517.56 (m).
constexpr double kColumnAltitudeSlope = 0.73737;
constexpr double kColumnAltitudeOffset_m = 5517.56;

void check_latitude(double latitude_deg) {
  if (!std::isfinite(latitude_deg) || latitude_deg < -90.0 || latitude_deg > 90.0)
    throw InputError("latitude_deg", format_number(latitude_deg), "-90 to 90 degrees");
}

/// 24 pi^3 (n^2 - 1)^2 / (lambda^4 N^2 (n^2 + 2)^2) * F, m^2, from the refractivity r = n - 1.
/// n^2 - 1 is formed as r (2 + r) so that no precision is lost to the leading 1.
double cross_section_from_refractivity_m2(double lambda_nm, double refractivity, double number_density_per_m3,
                                          double king_factor) {
  const double lambda_m = lambda_nm * kMetresPerNanometre;
  const double n_squared_minus_one = refractivity * (2.0 + refractivity);
  const double n_squared_plus_two = n_squared_minus_one + 3.0;
  const double lorentz_lorenz_ratio = n_squared_minus_one / n_squared_plus_two;  // (n^2-1)/(n^2+2)
  const double lambda2_m2 = lambda_m * lambda_m;
  return 24.0 * kPi * kPi * kPi * lorentz_lorenz_ratio * lorentz_lorenz_ratio /
         (lambda2_m2 * lambda2_m2 * number_density_per_m3 * number_density_per_m3) * king_factor;
}

RayleighDerivationStep derive_one(double lambda_nm, const RayleighDerivationInput& in) {
  RayleighDerivationStep step{};
  step.lambda_nm = lambda_nm;
  if (in.gas == ScatteringGas::CarbonDioxide) {
    // Pure CO2 at the same reference conditions (288.15 K, 101325 Pa) as the number density.
    step.refractivity_ref = step.refractivity = refractivity_co2(lambda_nm);
    step.king_factor = king_factor_co2(lambda_nm);
  } else {
    step.refractivity_ref = refractivity_standard_air(in.formula, lambda_nm);
    step.refractivity = refractivity_with_co2(in.formula, lambda_nm, in.co2_ppv);
    step.king_n2 = king_factor_n2(lambda_nm);
    step.king_o2 = king_factor_o2(lambda_nm);
    step.king_factor = king_factor_air(lambda_nm, in.co2_ppv);
  }
  step.number_density_per_m3 = constants::kStandardNumberDensity_per_m3;
  step.cross_section_m2 =
      cross_section_from_refractivity_m2(lambda_nm, step.refractivity, step.number_density_per_m3, step.king_factor);
  return step;
}

}  // namespace

std::string to_string(ScatteringGas g) { return g == ScatteringGas::CarbonDioxide ? "co2" : "air"; }

std::vector<RayleighDerivationStep> derive_rayleigh(const std::vector<double>& lambda_nm,
                                                    const RayleighDerivationInput& in) {
  std::vector<RayleighDerivationStep> steps;
  steps.reserve(lambda_nm.size());
  for (double l_nm : lambda_nm) steps.push_back(derive_one(l_nm, in));
  return steps;
}

// Bodhaine et al. 1999 eq. (22) with n_s from the chosen formula at the requested CO2, N_s =
// 2.546899e25 m^-3 (288.15 K, 101325 Pa) and F_air from eq. (23).
double rayleigh_cross_section_m2(double lambda_nm, const RayleighDerivationInput& in) {
  return derive_one(lambda_nm, in).cross_section_m2;
}

// Bodhaine et al. 1999 eq. (17): m_a = 15.0556 C + 28.9595 g/mol (C in ppv).
double mean_molecular_weight_air_g_per_mol(double co2_ppv) {
  if (!std::isfinite(co2_ppv) || co2_ppv < 0.0 || co2_ppv > 1.0)
    throw InputError("co2_ppv", format_number(co2_ppv), "a CO2 mole fraction from 0 to 1 (360 ppm = 3.6e-4)");
  return kMolecularWeightCo2Slope_g_per_mol * co2_ppv + kMolecularWeightCo2Free_g_per_mol;
}

// List 1968 via Bodhaine et al. 1999 eqs. (10)-(11); the published fit is in cm s^-2 with z in m.
double gravity_m_per_s2(double latitude_deg, double altitude_m) {
  check_latitude(latitude_deg);
  if (!std::isfinite(altitude_m))
    throw InputError("altitude_m", format_number(altitude_m), "a finite altitude in metres");
  const double cos_2phi = std::cos(2.0 * degrees_to_radians(latitude_deg));
  const double sea_level_cm_per_s2 =
      kSeaLevelGravity45_cm_per_s2 *
      (1.0 - kGravityCos2PhiCoefficient * cos_2phi + kGravityCos2PhiSquaredCoefficient * cos_2phi * cos_2phi);
  const double z_m = altitude_m;
  const double g_cm_per_s2 =
      sea_level_cm_per_s2 - (kGravityLinear_cm_per_s2_m + kGravityLinearCos2Phi_cm_per_s2_m * cos_2phi) * z_m +
      (kGravityQuadratic_cm_per_s2_m2 + kGravityQuadraticCos2Phi_cm_per_s2_m2 * cos_2phi) * z_m * z_m -
      (kGravityCubic_cm_per_s2_m3 + kGravityCubicCos2Phi_cm_per_s2_m3 * cos_2phi) * z_m * z_m * z_m;
  return g_cm_per_s2 * kMetresPerCentimetre;
}

// Bodhaine et al. 1999: z_c = 0.73737 z + 5517.56 (m).
double mass_weighted_column_altitude_m(double station_altitude_m) {
  return kColumnAltitudeSlope * station_altitude_m + kColumnAltitudeOffset_m;
}

// Bodhaine et al. 1999 eq. (9): tau = sigma P N_A / (m_a g). In SI: sigma m^2, P Pa, N_A mol^-1,
// m_a kg mol^-1, g m s^-2; P / g is the column mass per area (kg m^-2), divided by m_a and times
// N_A the column number of molecules per area (m^-2).
double rayleigh_optical_depth_hydrostatic(double cross_section_m2, double surface_pressure_Pa, double latitude_deg,
                                          double altitude_m, double co2_ppv) {
  if (!std::isfinite(surface_pressure_Pa) || surface_pressure_Pa < 0.0)
    throw InputError("surface_pressure_Pa", format_number(surface_pressure_Pa), "a pressure >= 0 Pa");
  const double molar_mass_kg_per_mol = mean_molecular_weight_air_g_per_mol(co2_ppv) * kKilogramsPerGram;
  const double column_gravity_m_per_s2 = gravity_m_per_s2(latitude_deg, mass_weighted_column_altitude_m(altitude_m));
  const double column_molecules_per_m2 =
      surface_pressure_Pa * constants::kAvogadro_per_mol / (molar_mass_kg_per_mol * column_gravity_m_per_s2);
  return cross_section_m2 * column_molecules_per_m2;
}

}  // namespace skyspec
