// Depolarisation (King) correction factors F = (6 + 3 rho) / (6 - 7 rho) of the air's gases.
#pragma once

#include <string>

namespace skyspec {

/// Bates 1984 fits, lambda in nm (the formulas take micrometres internally).
double king_factor_n2(double lambda_nm);  ///< 1.034 + 3.17e-4 / lambda_um^2
double king_factor_o2(double lambda_nm);  ///< 1.096 + 1.385e-3 / lambda_um^2 + 1.448e-4 / lambda_um^4
constexpr double kKingFactorAr = 1.00;    ///< argon: monatomic, no depolarisation
constexpr double kKingFactorCO2 = 1.15;   ///< Bates 1984 / Bodhaine et al. 1999

/// Air mix of Bodhaine et al. 1999 eq. (23): volume-weighted mean of N2 78.084 %, O2 20.946 %,
/// Ar 0.934 % and CO2 (co2_ppv parts per volume, 3.6e-4 for 360 ppm).
double king_factor_air(double lambda_nm, double co2_ppv);

/// Pure carbon dioxide, Sneep & Ubachs 2005 eq. 14: F = 1.1364 + 25.3e-12 nu^2, nu in cm^-1
/// (Bates 1984's constant 1.15 is its value near 400 nm).
double king_factor_co2(double lambda_nm);

/// The composition used by king_factor_air, in percent by volume.
struct AirComposition {
  double n2_percent = 78.084, o2_percent = 20.946, ar_percent = 0.934, co2_percent = 0.036;
};
AirComposition bodhaine_air_composition(double co2_ppv);

}  // namespace skyspec
