// The gases' absorption bands in the near infrared (water vapour, and the uniformly mixed gases:
// oxygen, carbon dioxide, ...), for the broadband irradiance (render/broadband_irradiance.hpp).
//
// Band model (Bird & Riordan 1986, "Simple solar spectral model for direct and diffuse irradiance
// on horizontal and tilted planes at the earth's surface for cloudless atmospheres", J. Climate
// Appl. Meteor. 25, 87-97, eqs. 2-8 and 2-11; coefficients from Leckner 1978): along a path with
// absorber amount u, the transmittance of the band at wavelength lambda is
//
//   T = exp(-c1 x / (1 + c2 x)^0.45),   x = a(lambda) u,                               (1)
//   water vapour:  u in precipitable centimetres,  c1 = 0.2385, c2 = 20.07;
//   mixed gases:   u in air masses (the path's air column over a vertical column at 101325 Pa),
//                  c1 = 1.41,   c2 = 118.93.
//
// (1) is not Beer-Lambert's law: lines saturate, so doubling the path does not square T. Light
// transport needs Beer-Lambert, so (1) is written as an exponential sum (data/gases/, fitted by
// make_exponential_sums.py),
//
//   T(x) = sum_i w_i exp(-k_i x),   sum_i w_i = 1,                                      (2)
//
// within 0.0024 of (1) for every x (measured: test_gas_bands). Each term is a Beer-Lambert problem
// (extinction k_i a(lambda) times the gas's density): light transport is solved once per term and
// the results summed with weights w_i. This is the correlated-k method: the band is a mixture of
// spectral points whose absorption coefficients have the distribution (2), the same at every
// altitude (no change of line width with pressure), each carried by light transport on its own.
// Along any straight path it reproduces (1) to the fit's error.
//
// Where both gases absorb at one wavelength, the one with the larger band optical depth on the
// reference path (1.5 air masses: ASTM G173's) takes the sum (2), and the other Beer-Lambert's law
// with the coefficient that gives (1)'s transmittance on that path (an approximation; its error is
// measured in docs/physics.md, "Gas bands").
#pragma once

#include <vector>

namespace skyspec {

enum class GasBand { WaterVapour, MixedGases };

/// Eq. (1): the band transmittance at x = a u.
double band_transmittance(GasBand gas, double x);

/// One term of eq. (2).
struct ExponentialTerm {
  double k = 0.0, weight = 0.0;
};
/// Eq. (2)'s terms (data/gases/exponential_sums.csv), k ascending; the same count for both gases.
const std::vector<ExponentialTerm>& exponential_sum(GasBand gas);
/// The number of terms of eq. (2).
int exponential_term_count();

/// Bird & Riordan's wavelengths, nm: 122 from 300 to 4000 nm (data/gases/bird_riordan1986_bands.csv).
const std::vector<double>& band_model_wavelengths_nm();
/// The band coefficient a(lambda) (water vapour: per precipitable cm; mixed gases: per air mass),
/// linear between Bird & Riordan's wavelengths, 0 outside 300-4000 nm.
double band_coefficient(GasBand gas, double lambda_nm);

/// The reference path the gases' overlap is resolved on, in air masses.
constexpr double kGasReferenceAirMasses = 1.5;

/// What a gas contributes to one exponential term at one wavelength: the absorption coefficient per
/// unit absorber amount (per precipitable cm, per air mass) in the term, and the term's weight
/// (the same for both gases at a wavelength; 1 where no gas absorbs, so every term there is the same).
struct GasTermCoefficients {
  double water_vapour_per_cm = 0.0, mixed_gases_per_air_mass = 0.0, weight = 1.0;
  /// False where no gas absorbs: the terms are identical and term 0 alone (weight 1) is enough.
  bool absorbs = false;
};
/// The coefficients of term `term` (0 <= term < exponential_term_count()) at lambda_nm, with
/// water_vapour_cm of precipitable water and the surface's pressure over 101325 Pa (air masses of
/// the vertical column); see the file comment for where both gases absorb.
GasTermCoefficients gas_term_coefficients(int term, double lambda_nm, double water_vapour_cm,
                                          double relative_surface_pressure);

}  // namespace skyspec
