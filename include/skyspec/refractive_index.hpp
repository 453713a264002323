// Refractive index of dry air as a function of wavelength.
//
// Each formula gives (n - 1) at its own reference conditions (temperature, pressure, CO2); the
// Rayleigh cross-section only needs n at the same conditions as the number density it is paired
// with (see rayleigh.hpp), so no density scaling happens here.
#pragma once

#include <string>

namespace skyspec {

enum class RefractiveIndexFormula {
  PeckReeder1972,  ///< standard air: 15 degC, 101325 Pa, 300 ppm CO2
  Edlen1966,       ///< standard air: 15 degC, 101325 Pa, 300 ppm CO2
  Ciddor1996,      ///< standard air: 15 degC, 101325 Pa, 450 ppm CO2
};

/// "peck-reeder", "edlen", "ciddor"; parse throws InputError(setting) listing the allowed names.
std::string to_string(RefractiveIndexFormula f);
RefractiveIndexFormula parse_refractive_index_formula(const std::string& name,
                                                      const std::string& setting = "refractive_index");

/// CO2 mole fraction (parts per volume) at which a formula's coefficients are stated.
double reference_co2_ppv(RefractiveIndexFormula f);

/// (n - 1) of dry standard air from the formula itself (its own CO2 content), lambda in nm.
double refractivity_standard_air(RefractiveIndexFormula f, double lambda_nm);

/// (n - 1) corrected to a CO2 mole fraction co2_ppv (parts per volume, 360 ppm = 3.6e-4) with
/// Bodhaine et al. 1999 eq. (19): (n-1)_C = (n-1)_ref [1 + 0.54 (C - C_ref)].
double refractivity_with_co2(RefractiveIndexFormula f, double lambda_nm, double co2_ppv);

/// A one-line statement of the formula with its source, for reports.
std::string describe(RefractiveIndexFormula f);

}  // namespace skyspec
