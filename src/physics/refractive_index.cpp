// Refractive index of dry standard air: three published dispersion formulas and the CO2
// correction of Bodhaine et al. 1999.
//
// All three formulas share one shape. With the vacuum wavenumber s = 1 / lambda_um (um^-1),
//
//   (n - 1) * 1e8 = A + B1 / (C1 - s^2) + B2 / (C2 - s^2)
//
// and they differ in their coefficients and in the air they describe (see reference_co2_ppv).
#include "skyspec/refractive_index.hpp"

#include <cmath>
#include <sstream>

#include "base/text_format.hpp"
#include "skyspec/error.hpp"
#include "skyspec/units.hpp"

namespace skyspec {
namespace {

/// The formulas give the refractivity in units of 1e-8: (n - 1) * 1e8.
constexpr double kRefractivityUnit = 1.0e-8;

/// The measured range of Peck & Reeder 1972 ("Dispersion of air": 0.23-1.69 um), nm. Below it
/// every formula nears its pole (s^2 = C2, at 160-170 nm); above it none was fitted to data.
constexpr double kMeasuredMin_nm = 230.0;
constexpr double kMeasuredMax_nm = 1690.0;

/// Coefficients of (n - 1) * 1e8 = A + B1 / (C1 - s^2) + B2 / (C2 - s^2), s in um^-1.
struct DispersionCoefficients {
  double constant_term;     ///< A
  double first_numerator;   ///< B1, um^-2
  double first_pole_um2;    ///< C1, um^-2
  double second_numerator;  ///< B2, um^-2
  double second_pole_um2;   ///< C2, um^-2
};

/// Peck & Reeder 1972 (J. Opt. Soc. Am. 62, 958), as quoted by Bodhaine et al. 1999 eq. (4).
constexpr DispersionCoefficients kPeckReeder1972{8060.51, 2480990.0, 132.274, 17455.7, 39.32957};
/// Edlen 1966 (Metrologia 2, 71), dispersion of standard air.
constexpr DispersionCoefficients kEdlen1966{8342.13, 2406030.0, 130.0, 15997.0, 38.9};
/// Ciddor 1996 (Appl. Opt. 35, 1566), eq. (1): no constant term.
constexpr DispersionCoefficients kCiddor1996{0.0, 5792105.0, 238.0185, 167917.0, 57.362};

/// CO2 mole fractions (parts per volume) of each formula's standard air.
constexpr double kPeckReederReferenceCo2_ppv = 300.0e-6;  // Peck & Reeder 1972: 300 ppm
constexpr double kEdlenReferenceCo2_ppv = 300.0e-6;       // Edlen 1966: 300 ppm (0.03 %)
constexpr double kCiddorReferenceCo2_ppv = 450.0e-6;      // Ciddor 1996: 450 ppm

/// Relative change of (n - 1) per unit change of the CO2 mole fraction, Bodhaine et al. 1999
/// eq. (19) (from Edlen 1966): (n-1)_C = (n-1)_ref [1 + 0.54 (C - C_ref)].
constexpr double kCo2RefractivitySensitivity_per_ppv = 0.54;

const DispersionCoefficients& coefficients(RefractiveIndexFormula f) {
  switch (f) {
    case RefractiveIndexFormula::PeckReeder1972:
      return kPeckReeder1972;
    case RefractiveIndexFormula::Edlen1966:
      return kEdlen1966;
    case RefractiveIndexFormula::Ciddor1996:
      return kCiddor1996;
  }
  return kPeckReeder1972;  // unreachable: every enumerator is handled above
}

void check_wavelength(RefractiveIndexFormula f, double lambda_nm) {
  const RefractiveIndexValidity v = validity(f);
  if (!std::isfinite(lambda_nm) || lambda_nm < v.min_nm || lambda_nm > v.max_nm)
    throw InputError(
        "wavelength_nm", format_number(lambda_nm),
        "a wavelength from " + format_number(v.min_nm) + " to " + format_number(v.max_nm) + " nm, " + v.reason);
}

/// Squared vacuum wavenumber s^2 = 1 / lambda_um^2, um^-2.
double wavenumber_squared_per_um2(double lambda_nm) {
  const double lambda_um = lambda_nm / kNanometresPerMicrometre;
  return 1.0 / (lambda_um * lambda_um);
}

}  // namespace

std::string to_string(RefractiveIndexFormula f) {
  switch (f) {
    case RefractiveIndexFormula::PeckReeder1972:
      return "peck-reeder";
    case RefractiveIndexFormula::Edlen1966:
      return "edlen";
    case RefractiveIndexFormula::Ciddor1996:
      return "ciddor";
  }
  return "peck-reeder";  // unreachable
}

RefractiveIndexFormula parse_refractive_index_formula(const std::string& name, const std::string& setting) {
  if (name == "peck-reeder") return RefractiveIndexFormula::PeckReeder1972;
  if (name == "edlen") return RefractiveIndexFormula::Edlen1966;
  if (name == "ciddor") return RefractiveIndexFormula::Ciddor1996;
  throw InputError(setting, name, "one of: peck-reeder, edlen, ciddor");
}

double reference_co2_ppv(RefractiveIndexFormula f) {
  switch (f) {
    case RefractiveIndexFormula::PeckReeder1972:
      return kPeckReederReferenceCo2_ppv;
    case RefractiveIndexFormula::Edlen1966:
      return kEdlenReferenceCo2_ppv;
    case RefractiveIndexFormula::Ciddor1996:
      return kCiddorReferenceCo2_ppv;
  }
  return kPeckReederReferenceCo2_ppv;  // unreachable
}

// (n - 1) of the formula's standard air (15 degC, 101325 Pa, dry, its own CO2):
//   (n - 1) = 1e-8 [A + B1 / (C1 - s^2) + B2 / (C2 - s^2)],  s = 1 / lambda_um.
RefractiveIndexValidity validity(RefractiveIndexFormula f) {
  switch (f) {
    case RefractiveIndexFormula::PeckReeder1972:
      return {kMeasuredMin_nm, kMeasuredMax_nm,
              "the range of Peck & Reeder's measurements (J. Opt. Soc. Am. 62, 958, 1972) that the formula fits"};
    case RefractiveIndexFormula::Ciddor1996:
      return {kMeasuredMin_nm, kMeasuredMax_nm,
              "the range of Ciddor's equations for the visible and near infrared (Appl. Opt. 35, 1566, 1996)"};
    case RefractiveIndexFormula::Edlen1966:
      return {kMeasuredMin_nm, kMeasuredMax_nm,
              "the range of the measurements the formulas of air are checked against here (Peck & Reeder 1972)"};
  }
  return {};  // unreachable
}

double refractivity_standard_air(RefractiveIndexFormula f, double lambda_nm) {
  check_wavelength(f, lambda_nm);
  const DispersionCoefficients& c = coefficients(f);
  const double s2_per_um2 = wavenumber_squared_per_um2(lambda_nm);
  const double refractivity_1e8 = c.constant_term + c.first_numerator / (c.first_pole_um2 - s2_per_um2) +
                                  c.second_numerator / (c.second_pole_um2 - s2_per_um2);
  return refractivity_1e8 * kRefractivityUnit;
}

// Bodhaine et al. 1999 eq. (19): (n - 1)_C = (n - 1)_ref [1 + 0.54 (C - C_ref)], C in ppv.
double refractivity_with_co2(RefractiveIndexFormula f, double lambda_nm, double co2_ppv) {
  if (!std::isfinite(co2_ppv) || co2_ppv < 0.0 || co2_ppv > 1.0)
    throw InputError("co2_ppv", format_number(co2_ppv), "a CO2 mole fraction from 0 to 1 (360 ppm = 3.6e-4)");
  const double co2_excess_ppv = co2_ppv - reference_co2_ppv(f);
  return refractivity_standard_air(f, lambda_nm) * (1.0 + kCo2RefractivitySensitivity_per_ppv * co2_excess_ppv);
}

std::string describe(RefractiveIndexFormula f) {
  switch (f) {
    case RefractiveIndexFormula::PeckReeder1972:
      return "Peck & Reeder 1972: (n-1)*1e8 = 8060.51 + 2480990/(132.274 - s^2) + 17455.7/(39.32957 - s^2), "
             "s = 1/lambda_um; dry air, 15 degC, 101325 Pa, 300 ppm CO2";
    case RefractiveIndexFormula::Edlen1966:
      return "Edlen 1966: (n-1)*1e8 = 8342.13 + 2406030/(130 - s^2) + 15997/(38.9 - s^2), "
             "s = 1/lambda_um; dry air, 15 degC, 101325 Pa, 300 ppm CO2";
    case RefractiveIndexFormula::Ciddor1996:
      return "Ciddor 1996: (n-1)*1e8 = 5792105/(238.0185 - s^2) + 167917/(57.362 - s^2), "
             "s = 1/lambda_um; dry air, 15 degC, 101325 Pa, 450 ppm CO2";
  }
  return {};  // unreachable
}

double refractivity_co2(double lambda_nm) {
  if (!(lambda_nm >= 200.0) || !std::isfinite(lambda_nm))
    throw InputError("wavelength_nm", format_number(lambda_nm), "a wavelength of at least 200 nm");
  const double nu_per_cm = 1e7 / lambda_nm;
  const double nu2 = nu_per_cm * nu_per_cm;
  auto term = [nu2](double strength, double resonance_per_cm) {
    return strength / (resonance_per_cm * resonance_per_cm - nu2);
  };
  return 1.1427e3 * (term(5799.25, 128908.9) + term(120.05, 89223.8) + term(5.3334, 75037.5) + term(4.3244, 67837.7) +
                     term(1.218145e-7, 2418.136));
}

}  // namespace skyspec
