// Liquid water: its density at atmospheric pressure and its refractive index, what rain drops,
// fog and cloud droplets need for Lorenz-Mie theory (lorenz_mie.hpp).
#pragma once

namespace skyspec {

/// Real refractive index of water relative to vacuum, IAPWS R9-97 ("Release on the refractive
/// index of ordinary water substance as a function of wavelength, temperature and pressure";
/// Harvey, Gallagher & Levelt Sengers 1998, J. Phys. Chem. Ref. Data 27, 761):
///
///   (n^2 - 1) / (n^2 + 2) / rho' = a0 + a1 rho' + a2 T' + a3 lambda'^2 T' + a4 / lambda'^2
///                                 + a5 / (lambda'^2 - lambda_UV^2) + a6 / (lambda'^2 - lambda_IR^2) + a7 rho'^2
///
/// with T' = T / 273.15 K, rho' = rho / 1000 kg m^-3, lambda' = lambda / 589 nm. Used over the
/// release's range: 200-1100 nm, -12 to 500 degC (261.15-773.15 K), 0-1060 kg m^-3; outside it
/// throws InputError naming water.temperature_K, water.density_kg_per_m3 or wavelength_nm. The
/// release's stated uncertainty in the visible, for liquid water near room temperature: 1.5e-5.
double water_refractive_index(double temperature_K, double density_kg_per_m3, double wavelength_nm);

/// Density of liquid water at 101325 Pa, kg m^-3: Kell 1975 (J. Chem. Eng. Data 20, 97), eq. 16,
///   rho = (999.83952 + 16.945176 t - 7.9870401e-3 t^2 - 46.170461e-6 t^3 + 105.56302e-9 t^4
///          - 280.54253e-12 t^5) / (1 + 16.879850e-3 t),  t in degC (IPTS-68),
/// 0-150 degC (throws InputError naming water.temperature_K outside). Within 0.003 kg m^-3 of
/// IAPWS-95 at 25 degC (test_water), which changes n by less than 1e-6.
double liquid_water_density_kg_per_m3(double temperature_K);

}  // namespace skyspec
