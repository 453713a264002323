// King (depolarisation) correction factors of the gases of dry air.
//
// F = (6 + 3 rho) / (6 - 7 rho) multiplies the Rayleigh cross-section of an isotropic molecule to
// account for the anisotropy of real ones (rho: depolarisation ratio). Bates 1984 (Planet. Space
// Sci. 32, 785) fitted F(lambda) for N2 and O2; Bodhaine et al. 1999 (J. Atmos. Oceanic Technol. 16,
// 1854) eq. (23) mixes them by volume into F(air).
#include "skyspec/king_factor.hpp"

#include <cmath>
#include <sstream>

#include "base/text_format.hpp"
#include "skyspec/error.hpp"
#include "skyspec/units.hpp"

namespace skyspec {
namespace {

constexpr double kPercentPerPartPerVolume = 100.0;

/// Bates 1984 fit for N2: F = 1.034 + 3.17e-4 / lambda_um^2.
constexpr double kN2KingConstant = 1.034;
constexpr double kN2KingInverseSquare_um2 = 3.17e-4;

/// Bates 1984 fit for O2: F = 1.096 + 1.385e-3 / lambda_um^2 + 1.448e-4 / lambda_um^4.
constexpr double kO2KingConstant = 1.096;
constexpr double kO2KingInverseSquare_um2 = 1.385e-3;
constexpr double kO2KingInverseFourth_um4 = 1.448e-4;

/// 1 / lambda_um^2, um^-2.
double inverse_wavelength_squared_per_um2(double lambda_nm) {
  if (!std::isfinite(lambda_nm) || lambda_nm <= 0.0)
    throw InputError("wavelength_nm", format_number(lambda_nm), "a positive wavelength in nm");
  const double lambda_um = lambda_nm / kNanometresPerMicrometre;
  return 1.0 / (lambda_um * lambda_um);
}

}  // namespace

// Bates 1984: F(N2) = 1.034 + 3.17e-4 / lambda_um^2.
double king_factor_n2(double lambda_nm) {
  const double inv_lambda2_per_um2 = inverse_wavelength_squared_per_um2(lambda_nm);
  return kN2KingConstant + kN2KingInverseSquare_um2 * inv_lambda2_per_um2;
}

// Bates 1984: F(O2) = 1.096 + 1.385e-3 / lambda_um^2 + 1.448e-4 / lambda_um^4.
double king_factor_o2(double lambda_nm) {
  const double inv_lambda2_per_um2 = inverse_wavelength_squared_per_um2(lambda_nm);
  return kO2KingConstant + kO2KingInverseSquare_um2 * inv_lambda2_per_um2 +
         kO2KingInverseFourth_um4 * inv_lambda2_per_um2 * inv_lambda2_per_um2;
}

// Bodhaine et al. 1999 air: N2 78.084 %, O2 20.946 %, Ar 0.934 % (the AirComposition defaults) and
// CO2 in percent by volume, C_percent = 100 * co2_ppv (0.036 % for 360 ppm).
AirComposition bodhaine_air_composition(double co2_ppv) {
  if (!std::isfinite(co2_ppv) || co2_ppv < 0.0 || co2_ppv > 1.0)
    throw InputError("co2_ppv", format_number(co2_ppv), "a CO2 mole fraction from 0 to 1 (360 ppm = 3.6e-4)");
  AirComposition air;
  air.co2_percent = co2_ppv * kPercentPerPartPerVolume;
  return air;
}

// Bodhaine et al. 1999 eq. (23), the volume-weighted mean of the component factors:
//   F(air) = (78.084 F(N2) + 20.946 F(O2) + 0.934 F(Ar) + C F(CO2)) / (78.084 + 20.946 + 0.934 + C)
// with C the CO2 content in percent by volume.
double king_factor_air(double lambda_nm, double co2_ppv) {
  const AirComposition air = bodhaine_air_composition(co2_ppv);
  const double weighted_sum = air.n2_percent * king_factor_n2(lambda_nm) + air.o2_percent * king_factor_o2(lambda_nm) +
                              air.ar_percent * kKingFactorAr + air.co2_percent * kKingFactorCO2;
  const double total_percent = air.n2_percent + air.o2_percent + air.ar_percent + air.co2_percent;
  return weighted_sum / total_percent;
}

double king_factor_co2(double lambda_nm) {
  const double nu_per_cm = 1e7 / lambda_nm;
  return 1.1364 + 25.3e-12 * nu_per_cm * nu_per_cm;
}

}  // namespace skyspec
