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

/// (n - 1) of pure carbon dioxide at 288.15 K and 101325 Pa, lambda in nm: Sneep & Ubachs 2005
/// (JQSRT 92, 293), eq. 13, after Bideau-Mehu et al. 1973, with nu = 1/lambda in cm^-1:
///   n - 1 = 1.1427e3 [5799.25 / (128908.9^2 - nu^2) + 120.05 / (89223.8^2 - nu^2)
///                     + 5.3334 / (75037.5^2 - nu^2) + 4.3244 / (67837.7^2 - nu^2)
///                     + 1.218145e-7 / (2418.136^2 - nu^2)]
/// (the last numerator as corrected by Kitzmann et al. 2017; it contributes ~1e-10 in the visible).
double refractivity_co2(double lambda_nm);

/// The wavelengths over which a formula is used, nm, and why there: Peck & Reeder measured
/// 230-1690 nm ("Dispersion of air", J. Opt. Soc. Am. 62, 958, 1972); Ciddor's equations cover the
/// same range (230-1690 nm as catalogued by refractiveindex.info); Edlen 1966 is accepted over the
/// same range. refractivity_standard_air() throws InputError("wavelength_nm", ...) outside it.
struct RefractiveIndexValidity {
  double min_nm = 0.0, max_nm = 0.0;
  std::string reason;  ///< e.g. "the range of Peck & Reeder's measurements (1972)"
};
RefractiveIndexValidity validity(RefractiveIndexFormula f);

/// A one-line statement of the formula with its source, for reports.
std::string describe(RefractiveIndexFormula f);

}  // namespace skyspec
