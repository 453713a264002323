// The coefficient derivation report: computation (the writers are in coefficient_report_writers.cpp).
//
// Rayleigh, per wavelength (Bodhaine, Wood, Dutton & Slusser 1999, J. Atmos. Oceanic Technol. 16,
// 1854, eqs. 2, 9, 17-23):
//   (n_s - 1)   from the chosen dispersion formula, corrected to the CO2 content (eq. 19)
//   F_air       volume-weighted King factors of N2, O2, Ar, CO2 (eq. 23, Bates 1984)
//   sigma       24 pi^3 (n_s^2 - 1)^2 / (lambda^4 N_s^2 (n_s^2 + 2)^2) F_air (eq. 2), independent of
//               the air's density because (n^2 - 1) / (n^2 + 2) is proportional to N
//   beta(z)     sigma N(z), N from the density profile (or P / kT for given conditions)
//   tau(z)      integral of beta from z to the top of the atmosphere (the engine's column integral),
//               or sigma P N_A / (m_a g) for the hydrostatic column above a pressure level (eq. 9)
// Aerosols: beta(lambda) = beta_ref (lambda / lambda_ref)^-alpha (Angstrom 1929).
#include "skyspec/coefficient_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>

#include "base/text_format.hpp"
#include "physics/ozone.hpp"
#include "report/published_references.hpp"
#include "skyspec/aerosol_components.hpp"
#include "skyspec/error.hpp"
#include "skyspec/refractive_index.hpp"
#include "skyspec/scene.hpp"
#include "skyspec/standard_atmosphere.hpp"
#include "skyspec/units.hpp"
#include "skyspec/version.hpp"
#include "transport/optical_depth.hpp"

namespace skyspec {
namespace {

constexpr double kKilogramsPerGram = 1.0e-3;
constexpr double kPercent = 100.0;
/// The range of altitudes over which the U.S. Standard Atmosphere 1976 is evaluated here, m.
constexpr double kStandardAtmosphereLowest_m = -5000.0;
constexpr double kStandardAtmosphereHighest_m = 100000.0;
/// Wavelength range of the comparisons with published tables, nm (Bodhaine's Table 3 range).
constexpr double kComparisonMin_nm = 350.0;
constexpr double kComparisonMax_nm = 850.0;
constexpr double kComparisonStep_nm = 50.0;
/// Wavelength ranges of the comparisons with published fits, nm: Bodhaine's eqs. (29)-(30) from
/// the ultraviolet to 1 um; Bucholtz's fit over the whole range of the refractive index (its long-wave
/// branch has no stated upper limit).
constexpr double kBodhaineFitMin_nm = 250.0;
constexpr double kBodhaineFitMax_nm = 1000.0;
constexpr double kBucholtzFitMin_nm = 250.0;
constexpr double kBucholtzFitMax_nm = 1650.0;

std::string fmt(const char* pattern, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, pattern, v);
  return buf;
}

double percent_difference(double value, double reference) { return kPercent * (value / reference - 1.0); }

void finish_comparison(ReferenceComparison& c) {
  c.max_abs_difference_percent = 0.0;
  for (const auto& r : c.rows)
    c.max_abs_difference_percent = std::max(c.max_abs_difference_percent, std::abs(r.difference_percent));
}

RayleighDerivationInput peck_reeder_at(double co2_ppv) {
  RayleighDerivationInput in;
  in.formula = RefractiveIndexFormula::PeckReeder1972;
  in.co2_ppv = co2_ppv;
  return in;
}

/// Altitude (m) at which the U.S. Standard Atmosphere 1976 has pressure P, by bisection (pressure
/// falls monotonically with altitude); clamped to the range the standard is evaluated over.
double standard_atmosphere_pressure_altitude_m(double pressure_Pa) {
  double lo = kStandardAtmosphereLowest_m, hi = kStandardAtmosphereHighest_m;
  if (pressure_Pa >= us_standard_atmosphere_1976(lo).pressure_Pa) return lo;
  if (pressure_Pa <= us_standard_atmosphere_1976(hi).pressure_Pa) return hi;
  for (int i = 0; i < 100 && hi - lo > 1e-6; ++i) {
    const double mid = 0.5 * (lo + hi);
    (us_standard_atmosphere_1976(mid).pressure_Pa > pressure_Pa ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

std::vector<double> scaled(const std::vector<double>& s, double factor) {
  std::vector<double> v(s.size());
  for (size_t i = 0; i < s.size(); ++i) v[i] = s[i] * factor;
  return v;
}

std::vector<double> scaled(const SpectrumD& s, double factor) {
  std::vector<double> v(static_cast<size_t>(s.size()));
  for (Eigen::Index i = 0; i < s.size(); ++i) v[static_cast<size_t>(i)] = s[i] * factor;
  return v;
}

std::vector<ReportFormula> report_formulas(const CoefficientReport& r) {
  std::vector<ReportFormula> f;
  if (r.gas == ScatteringGas::CarbonDioxide) {
    f.push_back({"refractive index of CO2 (288.15 K, 101325 Pa)",
                 "n - 1 = 1.1427e3 [5799.25 / (128908.9^2 - nu^2) + 120.05 / (89223.8^2 - nu^2) + 5.3334 / "
                 "(75037.5^2 - nu^2) + 4.3244 / (67837.7^2 - nu^2) + 1.218145e-7 / (2418.136^2 - nu^2)]",
                 "nu = 1 / lambda in cm^-1", "Sneep & Ubachs 2005 eq. (13), after Bideau-Mehu et al. 1973"});
    f.push_back(
        {"King factor of CO2", "F(CO2) = 1.1364 + 25.3e-12 nu^2", "nu in cm^-1", "Sneep & Ubachs 2005 eq. (14)"});
  }
  if (r.gas == ScatteringGas::Air) {
    f.push_back({"refractive index of standard air, n_s", describe(r.formula), "n dimensionless; lambda in micrometres",
                 "as named; quoted by Bodhaine et al. 1999 eqs. (4)-(5)"});
    f.push_back({"CO2 correction", "(n_s - 1)_C = (n_s - 1)_ref [1 + 0.54 (C - C_ref)]",
                 "C, C_ref: CO2 mole fractions (parts per volume)", "Bodhaine et al. 1999 eq. (19), after Edlen 1966"});
    f.push_back({"King factor of N2", "F(N2) = 1.034 + 3.17e-4 / lambda^2", "lambda in micrometres",
                 "Bates 1984 (Planet. Space Sci. 32, 785)"});
    f.push_back({"King factor of O2", "F(O2) = 1.096 + 1.385e-3 / lambda^2 + 1.448e-4 / lambda^4",
                 "lambda in micrometres", "Bates 1984"});
    f.push_back({"King factor of air",
                 "F(air) = (78.084 F(N2) + 20.946 F(O2) + 0.934 F(Ar) + C F(CO2)) / (78.084 + 20.946 + 0.934 + C), "
                 "F(Ar) = 1.00, F(CO2) = 1.15",
                 "C: CO2 in percent by volume", "Bodhaine et al. 1999 eq. (23)"});
  }
  f.push_back({"Rayleigh cross-section",
               "sigma = 24 pi^3 (n_s^2 - 1)^2 / (lambda^4 N_s^2 (n_s^2 + 2)^2) F(air), N_s = 2.546899e25 m^-3 "
               "(288.15 K, 101325 Pa)",
               "sigma in m^2, lambda in m, N_s in m^-3", "Bodhaine et al. 1999 eq. (2); Bucholtz 1995 eq. (1)"});
  f.push_back({"number density", "N = P / (k T), k = 1.380649e-23 J/K", "N in m^-3, P in Pa, T in K",
               "ideal gas law; U.S. Standard Atmosphere 1976 for P(z), T(z)"});
  f.push_back({"volume scattering coefficient", "beta_R(lambda, z) = sigma(lambda) N(z)", "beta in m^-1",
               "Bodhaine et al. 1999; Bucholtz 1995 eq. (9)"});
  f.push_back({"refractivity at other conditions", "(n - 1) = (n_s - 1) N / N_s",
               "first order of the Lorentz-Lorenz relation (n^2 - 1)/(n^2 + 2) ~ N", "Lorentz-Lorenz"});
  f.push_back({"vertical optical depth", "tau(lambda, z) = integral from z to the top of beta_ext(lambda, z') dz'",
               "dimensionless; the engine integrates rho(z') exactly for exponential pieces (column_to_top_m)",
               "Beer-Lambert; Nishita et al. 1993"});
  f.push_back({"hydrostatic column above a pressure level",
               "tau = sigma P N_A / (m_a g), m_a = 15.0556 C + 28.9595 g/mol",
               "P in Pa, m_a in kg/mol, g in m s^-2 at the column's mass-weighted altitude (List 1968)",
               "Bodhaine et al. 1999 eqs. (9)-(11), (17)"});
  if (r.ozone_enabled)
    f.push_back(
        {"ozone absorption",
         "beta_O3(lambda, z) = sigma_O3(lambda) N_peak rho_O3(z), N_peak = column / (area of the "
         "profile), 1 DU = 2.6867e20 molecules m^-2",
         "sigma_O3 in m^2 per molecule, column in Dobson units",
         "the scene's table, or the built-in one (233 K: Serdyuchenko et al. 2014, 360-840 nm; Bogumil et al. 2003, "
         "230-360 and 840-1060 nm; data/ozone/)"});
  if (!r.mie_opac_components.empty())
    f.push_back({"aerosol (microphysics)",
                 "beta_ext(lambda) = sum_c N_c f_c <C_ext,c>(lambda), beta_sca likewise, "
                 "P_ij = sum_c N_c f_c <C_sca,c> P_ij,c / beta_sca; <C> = integral C(r) dN/dr dr by Lorenz-Mie",
                 "N_c particles per m^3 of component c, f_c its share between OPAC's minimum and maximum radius",
                 "Hess, Koepke & Schult 1998 (OPAC 3.1 size distributions and refractive indices, "
                 "data/aerosols/); Wiscombe 1980 (Lorenz-Mie)"});
  else if (r.mie_tabulated)
    f.push_back({"aerosol (tabulated)",
                 "beta_sca(lambda) = beta_ref Q(lambda) w(lambda) / (Q(lambda_ref) w(lambda_ref)), "
                 "beta_ext = beta_sca / w",
                 "Q: extinction efficiency, w: single-scattering albedo", "the scene's aerosol tables"});
  else
    f.push_back({"aerosol (Angstrom law)",
                 "beta_M(lambda, z) = beta_ref (lambda / lambda_ref)^-alpha rho_M(z), "
                 "beta_ext = ratio * beta_sca",
                 "beta in m^-1", "Angstrom 1929; extinction/scattering ratio as in the seed tutorial"});
  return f;
}

}  // namespace

std::vector<ReferenceComparison> published_comparisons() {
  std::vector<ReferenceComparison> out;
  const RayleighDerivationInput bodhaine_air = peck_reeder_at(kBodhaine1999Co2_ppv);
  const RayleighDerivationInput bucholtz_air = peck_reeder_at(kBucholtz1995Co2_ppv);
  constexpr double kBodhaineLatitude_deg = 45.0;
  constexpr double kSeaLevel_m = 0.0;
  // Bodhaine's method at his conditions: tau = sigma P N_A / (m_a g) for the sea-level column.
  const auto bodhaine_sea_level_tau = [&](double lambda_nm) {
    return rayleigh_optical_depth_hydrostatic(rayleigh_cross_section_m2(lambda_nm, bodhaine_air),
                                              constants::kStandardPressure_Pa, kBodhaineLatitude_deg, kSeaLevel_m,
                                              kBodhaine1999Co2_ppv);
  };

  {  // Bodhaine et al. 1999 Table 3.
    ReferenceComparison c;
    c.id = "bodhaine1999_table3";
    c.title = "Rayleigh optical depth of the sea-level column (Bodhaine et al. 1999, Table 3)";
    c.quantity = "vertical optical depth";
    c.conditions = "sea level, 1013.25 hPa, 45 deg latitude, dry air with 360 ppm CO2";
    c.source =
        "Bodhaine, Wood, Dutton & Slusser 1999, J. Atmos. Oceanic Technol. 16, 1854, Table 3 "
        "(secondary transcription, data/reference/bodhaine1999_table3_optical_depth.csv)";
    c.method =
        "sigma from Peck & Reeder (360 ppm) and Bates/Bodhaine King factors; tau = sigma P N_A / (m_a g), "
        "g (List 1968) at the column's mass-weighted altitude 5517.56 m";
    for (const auto& p : bodhaine1999_table3_optical_depth()) {
      const double tau = bodhaine_sea_level_tau(p.wavelength_nm);
      c.rows.push_back({p.wavelength_nm, p.value, tau, percent_difference(tau, p.value)});
    }
    finish_comparison(c);
    c.explanation =
        "Same method as the paper (its equations, constants and conditions), so the only differences are the "
        "rounding of the published figures to 5 decimals (up to " +
        fmt("%.3f", kPercent * 0.5e-5 / c.rows.back().published) +
        " % for the smallest value) and of the constants. Because tau = sigma x (one wavelength-independent column), "
        "this table also checks the shape of sigma(lambda) to the same accuracy.";
    out.push_back(c);
  }
  {  // Bodhaine et al. 1999 eq. (30), the fit to their optical depths.
    ReferenceComparison c;
    c.id = "bodhaine1999_fit";
    c.title = "Rayleigh optical depth of the sea-level column, ultraviolet to 1 um (Bodhaine et al. 1999, eq. 30)";
    c.quantity = "vertical optical depth";
    c.conditions = "sea level, 1013.25 hPa, 45 deg latitude, dry air with 360 ppm CO2";
    c.source =
        "Bodhaine et al. 1999, eq. (30): their fit to their own optical depths, tau = 0.0021520 (1.0455996 - "
        "341.29061 l^-2 - 0.90230850 l^2) / (1 + 0.0027059889 l^-2 - 85.968563 l^2), l in um "
        "(data/reference/bodhaine1999_fit.csv)";
    c.method = "as for Table 3 above";
    for (double l = kBodhaineFitMin_nm; l <= kBodhaineFitMax_nm + 1e-9; l += kComparisonStep_nm) {
      const double published = bodhaine1999_optical_depth_fit(l);
      const double tau = bodhaine_sea_level_tau(l);
      c.rows.push_back({l, published, tau, percent_difference(tau, published)});
    }
    finish_comparison(c);
    c.explanation = "The paper's own fit to the calculation skyspec repeats, so the differences (largest " +
                    fmt("%.3f", c.max_abs_difference_percent) +
                    " %) are those of the fit; this extends the check of Table 3 into the ultraviolet (300 nm: " +
                    fmt("%+.3f", c.rows[1].difference_percent) + " %) and to 1 um.";
    out.push_back(c);
  }
  const Bodhaine1999TextValues& text = bodhaine1999_text_values();
  {
    ReferenceComparison c;
    c.id = "bodhaine1999_cross_section_550nm";
    c.title = "Rayleigh cross-section at 550 nm (Bodhaine et al. 1999, text)";
    c.quantity = "sigma, m^2";
    c.conditions = "dry air with 360 ppm CO2 (sigma does not depend on pressure or temperature)";
    c.source = "Bodhaine et al. 1999: 4.51e-27 cm^2 (data/reference/bodhaine1999_text_values.csv)";
    c.method = "Peck & Reeder at 360 ppm, Bates/Bodhaine King factor, N_s = 2.546899e25 m^-3";
    const double s = rayleigh_cross_section_m2(550.0, bodhaine_air);
    c.rows.push_back({550.0, text.cross_section_550nm_m2, s, percent_difference(s, text.cross_section_550nm_m2)});
    finish_comparison(c);
    c.explanation = "The published figure has 3 significant digits (+-0.11 %); the difference is within its rounding.";
    out.push_back(c);
  }
  {
    ReferenceComparison c;
    c.id = "bodhaine1999_king_factor_550nm";
    c.title = "King factor of air at 550 nm (Bodhaine et al. 1999, text)";
    c.quantity = "F(air)";
    c.conditions = "360 ppm CO2";
    c.source = "Bodhaine et al. 1999: 1.0488 (data/reference/bodhaine1999_text_values.csv)";
    c.method = "Bodhaine eq. (23) with the Bates 1984 fits";
    const double f = king_factor_air(550.0, kBodhaine1999Co2_ppv);
    c.rows.push_back({550.0, text.king_factor_air_550nm, f, percent_difference(f, text.king_factor_air_550nm)});
    finish_comparison(c);
    c.explanation = "Same formula; the published figure has 4 decimals (+-0.005 %).";
    out.push_back(c);
  }
  {  // Bucholtz 1995 depolarization -> King factor.
    ReferenceComparison c;
    c.id = "bucholtz1995_king_factor";
    c.title = "King factor of standard air (Bucholtz 1995, depolarization table)";
    c.quantity = "F(air) = (6 + 3 rho) / (6 - 7 rho)";
    c.conditions = "standard air, 300 ppm CO2";
    c.source =
        "Bucholtz 1995, Appl. Opt. 34, 2765: rho_n per wavelength (after Bates 1984), secondary "
        "transcription in data/reference/bucholtz1995_depolarization.csv";
    c.method = "Bodhaine eq. (23) with the Bates 1984 fits at 300 ppm CO2";
    for (const auto& p : bucholtz1995_depolarization()) {
      if (p.wavelength_nm < kComparisonMin_nm - 1e-9 || p.wavelength_nm > kComparisonMax_nm + 1e-9) continue;
      const double published = king_factor_from_depolarization(p.value);
      const double f = king_factor_air(p.wavelength_nm, kBucholtz1995Co2_ppv);
      c.rows.push_back({p.wavelength_nm, published, f, percent_difference(f, published)});
    }
    finish_comparison(c);
    c.explanation =
        "Bucholtz tabulates rho_n to 4 digits, and the same value repeats over several wavelengths (e.g. 2.786 % "
        "from 600 to 750 nm), so his F is a staircase while skyspec's follows Bates's smooth fits; the difference "
        "(largest " +
        fmt("%.3f", c.max_abs_difference_percent) + " %) is that staircase, not a different physics.";
    out.push_back(c);
  }
  {  // Bucholtz 1995 cross-section fit.
    ReferenceComparison c;
    c.id = "bucholtz1995_cross_section_fit";
    c.title = "Rayleigh cross-section of standard air (Bucholtz 1995, analytic fit)";
    c.quantity = "sigma, m^2";
    c.conditions = "standard air, 288.15 K, 1013.25 hPa, 300 ppm CO2";
    c.source =
        "Bucholtz 1995, Appl. Opt. 34, 2765: sigma = A lambda^-(B + C lambda + D/lambda), two coefficient "
        "sets split at 0.5 um (data/reference/bucholtz1995_cross_section_fit.csv). Bucholtz's table of "
        "cross-sections itself was not available to transcribe; this is his fit to it";
    c.method = "Peck & Reeder at 300 ppm, Bates/Bodhaine King factor, N_s = 2.546899e25 m^-3";
    for (double l = kBucholtzFitMin_nm; l <= kBucholtzFitMax_nm + 1e-9; l += kComparisonStep_nm) {
      const double published = bucholtz1995_cross_section_fit_m2(l);
      const double s = rayleigh_cross_section_m2(l, bucholtz_air);
      c.rows.push_back({l, published, s, percent_difference(s, published)});
    }
    finish_comparison(c);
    const double branch_nm = bucholtz1995_fit_branch_nm();
    const double below = bucholtz1995_cross_section_fit_m2(branch_nm);
    const double above = bucholtz1995_cross_section_fit_m2(branch_nm + 1e-9);
    c.explanation =
        "A fit, not the table: its two branches disagree by " +
        fmt("%.2f", std::abs(percent_difference(above, below))) + " % where they meet at " + fmt("%.0f", branch_nm) +
        " nm, so the fit itself is no closer than about that to his table. Bucholtz also uses his own King factors "
        "(the staircase above) and pairs "
        "n_s with N_s = 2.54743e25 m^-3 where skyspec uses Bodhaine's 2.546899e25 (sigma ~ 1/N_s^2 for a given "
        "n_s: 0.04 %). The largest difference is " +
        fmt("%.2f", c.max_abs_difference_percent) + " %.";
    out.push_back(c);
  }
  {  // The seed tutorial's constants against standard air.
    const Scene seed = SceneLoader("seed").finish();
    const auto& nm = seed.atmosphere.rayleigh.fixed_wavelengths_nm;
    const auto& beta = seed.atmosphere.rayleigh.fixed_beta_per_m;
    ReferenceComparison c;
    c.id = "seed_constants";
    c.title = "The seed tutorial's sea-level coefficients vs standard air";
    c.quantity = "beta_R at sea level, m^-1";
    c.conditions =
        "not stated by the tutorial (sea level); skyspec's column is standard air: 288.15 K, 101325 Pa, "
        "360 ppm CO2";
    c.source =
        "Scratchapixel, Simulating the Colors of the Sky (after Nishita et al. 1993): typed-in constants "
        "(data/scenes/seed.toml, atmosphere.rayleigh.beta_per_m)";
    c.method =
        "beta = sigma N_s, N_s = 2.546899e25 m^-3, with Peck & Reeder at 360 ppm and the Bates/Bodhaine "
        "King factor";
    for (size_t i = 0; i < nm.size() && i < beta.size(); ++i) {
      const double b = rayleigh_cross_section_m2(nm[i], bodhaine_air) * constants::kStandardNumberDensity_per_m3;
      c.rows.push_back({nm[i], beta[i], b, percent_difference(b, beta[i])});
    }
    std::sort(c.rows.begin(), c.rows.end(),
              [](const auto& a, const auto& b) { return a.wavelength_nm < b.wavelength_nm; });
    finish_comparison(c);
    // The facts that explain the difference, measured here.
    double ratio_min = 1e300, ratio_max = 0.0, k_min = 1e300, k_max = 0.0;
    for (const auto& r : c.rows) {
      const double ratio = r.published / r.skyspec;
      ratio_min = std::min(ratio_min, ratio);
      ratio_max = std::max(ratio_max, ratio);
      const double lambda_um = r.wavelength_nm * 1e-3;
      const double k = r.published * std::pow(lambda_um, 4.0);
      k_min = std::min(k_min, k);
      k_max = std::max(k_max, k);
    }
    std::string slope;
    if (c.rows.size() >= 2) {
      const auto& a = c.rows.front();
      const auto& b = c.rows.back();
      const double exponent = std::log(a.skyspec / b.skyspec) / std::log(b.wavelength_nm / a.wavelength_nm);
      const double seed_exponent = std::log(a.published / b.published) / std::log(b.wavelength_nm / a.wavelength_nm);
      slope = " Between " + fmt("%.0f", a.wavelength_nm) + " and " + fmt("%.0f", b.wavelength_nm) +
              " nm the derived beta falls as lambda^-" + fmt("%.3f", exponent) +
              " (n - 1 and the King factor both rise towards the blue); the seed's as lambda^-" +
              fmt("%.3f", seed_exponent) +
              ": its three numbers follow one lambda^-4 law, beta lambda^4 = " + fmt("%.4g", k_min) + " to " +
              fmt("%.4g", k_max) + " m^-1 um^4.";
    }
    c.explanation =
        "The seed's constants are " + fmt("%.1f", (ratio_min - 1.0) * kPercent) + " to " +
        fmt("%.1f", (ratio_max - 1.0) * kPercent) +
        " % larger than the derivation for standard air. A different air density would scale all three by the "
        "same factor, but the ratio changes with wavelength, so no single pressure and temperature (no single "
        "(n, N) pair) reproduces them; the tutorial does not say where they come from." +
        slope +
        " The graphics literature's 8 pi^3 (n^2 - 1)^2 / (3 N lambda^4) (no King factor, (n^2 + 2)^2 ~ 9) is about "
        "5 % below the derivation, so it does not explain the seed's values either; its listing also types "
        "3.8e-6 for red where the text says 5.8e-6.";
    out.push_back(c);
  }
  return out;
}

namespace {
/// Which report wavelengths the scene's ozone cross-sections cover: all of them for a scene's own
/// table (checked by the model) or no ozone; the built-in table's range otherwise.
struct OzoneCoverage {
  std::vector<double> covered_nm, missing_nm;
  std::vector<size_t> covered_index;  ///< index in the report's grid of each covered_nm
  std::string table_range;
};
OzoneCoverage ozone_coverage(const AtmosphereSpec& spec, const WavelengthGrid& grid) {
  OzoneCoverage c;
  const bool built_in = spec.ozone.enabled && spec.ozone.cross_section_m2.empty();
  const TabulatedSpectrum& table = ozone_cross_section_table();
  c.table_range = format_number(table.min_nm()) + "-" + format_number(table.max_nm()) + " nm";
  for (int i = 0; i < grid.size(); ++i) {
    const double nm = grid.nm(i);
    if (built_in && (nm < table.min_nm() || nm > table.max_nm())) {
      c.missing_nm.push_back(nm);
    } else {
      c.covered_nm.push_back(nm);
      c.covered_index.push_back(static_cast<size_t>(i));
    }
  }
  return c;
}
}  // namespace

CoefficientReport make_coefficient_report(const CoefficientReportRequest& req) {
  if (req.wavelengths_nm.empty()) throw InputError("wavelengths_nm", "[]", "at least one wavelength");
  const WavelengthGrid grid = WavelengthGrid::from_list(req.wavelengths_nm);
  if (!std::isfinite(req.latitude_deg) || req.latitude_deg < -90.0 || req.latitude_deg > 90.0)
    throw InputError("latitude_deg", format_number(req.latitude_deg), "-90 to 90 degrees");
  if (req.column_segments < 1 || req.column_segments > 1 << 16)
    throw InputError("column_segments", std::to_string(req.column_segments), "1 to 65536");
  const AtmosphereSpec& spec = req.atmosphere;
  // The built-in ozone table ends where its laboratory data end (230-1060 nm) while the derivation
  // reaches 1690 nm: beyond the table the ozone columns are n/a (NaN) and tau total leaves ozone
  // out; the model of everything else is built without ozone, the ozone on the wavelengths it covers.
  const OzoneCoverage ozone = ozone_coverage(spec, grid);
  AtmosphereSpec without_ozone = spec;
  if (!ozone.missing_nm.empty()) without_ozone.ozone.enabled = false;
  const AtmosphereModel model(without_ozone, grid);

  CoefficientReport r;
  r.skyspec_version = version_string();
  r.origin = req.origin;
  r.wavelengths_nm = grid.nanometres();
  r.latitude_deg = req.latitude_deg;
  r.rayleigh_derived = spec.rayleigh.source == RayleighSpec::Source::Derived;
  r.gas = spec.rayleigh.derivation.gas;
  r.formula = spec.rayleigh.derivation.formula;
  r.co2_ppv = spec.rayleigh.derivation.co2_ppv;
  r.composition = bodhaine_air_composition(r.co2_ppv);
  r.derivation = derive_rayleigh(grid.nanometres(), spec.rayleigh.derivation);
  const Medium& air = *model.medium("air");
  // The aerosol as the report shows it: zero coefficients when the scene has none.
  Medium aerosol;
  if (const Medium* m = model.medium("aerosol")) {
    aerosol = *m;
  } else {
    aerosol.profile = make_profile(spec.mie.profile, spec.mie.scale_height_m, spec.top_altitude_m);
    aerosol.scattering_per_m = aerosol.extinction_per_m = SpectrumD::Zero(grid.size());
  }
  r.profile_description = air.profile.describe();
  r.top_altitude_m = spec.top_altitude_m;
  r.mie_enabled = spec.mie.enabled;
  r.mie_scattering_at_reference_per_m = spec.mie.scattering_per_m;
  r.mie_reference_wavelength_nm = spec.mie.reference_wavelength_nm;
  r.mie_angstrom_exponent = spec.mie.angstrom_exponent;
  r.mie_extinction_to_scattering = spec.mie.extinction_to_scattering;
  r.mie_tabulated = !spec.mie.table_wavelengths_nm.empty();
  if (spec.mie.model == MieSpec::Model::Opac) {
    for (int c = 0; c < kAerosolComponentCount; ++c)
      if (spec.mie.opac.number_per_cm3[static_cast<size_t>(c)] > 0.0)
        r.mie_opac_components.emplace_back(aerosol_component_names()[static_cast<size_t>(c)],
                                           spec.mie.opac.number_per_cm3[static_cast<size_t>(c)]);
    r.mie_opac_relative_humidity_percent = spec.mie.opac.relative_humidity_percent;
  }
  r.mie_profile_description = aerosol.profile.describe();

  r.ozone_enabled = spec.ozone.enabled;
  std::optional<AtmosphereModel> ozone_model;  // on ozone.covered_nm
  std::vector<double> ozone_extinction_per_m(grid.size(), std::numeric_limits<double>::quiet_NaN());
  if (r.ozone_enabled && !ozone.covered_nm.empty()) {
    ozone_model.emplace(spec, WavelengthGrid::from_list(ozone.covered_nm));
  }
  const Medium* ozone_medium = ozone_model ? ozone_model->medium("ozone") : nullptr;
  if (ozone_medium) {
    for (size_t k = 0; k < ozone.covered_index.size(); ++k)
      ozone_extinction_per_m[ozone.covered_index[k]] = ozone_medium->extinction_per_m[static_cast<int>(k)];
    r.ozone_column_DU = spec.ozone.column_DU;
    r.ozone_peak_number_density_per_m3 = ozone_model->ozone_peak_number_density_per_m3();
    r.ozone_cross_section_m2 = scaled(ozone_extinction_per_m, 1.0 / r.ozone_peak_number_density_per_m3);
    r.ozone_profile_description = ozone_medium->profile.describe();
  } else if (r.ozone_enabled) {
    r.ozone_enabled = false;  // no requested wavelength has ozone data: reported in the notes
  }

  // The other media of the list (fog, ice, rain), as the renderer sees them.
  std::vector<const Medium*> others;
  for (const Medium& m : model.media())
    if (m.name != "air" && m.name != "aerosol" && m.name != "ozone" && m.enabled()) {
      others.push_back(&m);
      std::string where;
      if (m.region) {
        // The axis's foot, R a, seen from the reference point (0, 0, R): its distance along the
        // ground and its azimuth clockwise from north.
        const Vec3& a = m.region->axis;
        const double distance = model.planet_radius_m() * std::atan2(std::hypot(a.x(), a.y()), a.z());
        const double azimuth = std::fmod(std::atan2(a.x(), a.y()) * 180.0 / kPi + 360.0, 360.0);
        where = "only in a vertical cylinder " + format_number(m.region->radius_m) + " m in radius whose axis stands " +
                format_number(std::round(distance)) + " m from the reference point at azimuth " +
                format_number(std::round(azimuth * 10.0) / 10.0) +
                " degrees (the levels give it inside; its optical depth is the column inside)";
      }
      r.media.push_back({m.name, m.profile.describe(), where});
    }

  const double R = model.planet_radius_m(), Rt = model.top_radius_m();
  for (double z : req.altitudes_m) {
    if (!std::isfinite(z) || z < 0.0 || z >= spec.top_altitude_m)
      throw InputError("altitudes_m", format_number(z),
                       "altitudes from 0 m up to (not including) the top of the atmosphere, " +
                           format_number(spec.top_altitude_m) + " m");
    ReportLevel level;
    level.altitude_m = z;
    const double rho_r = std::exp(air.profile.log_relative(z));
    const double rho_m = std::exp(aerosol.profile.log_relative(z));
    const double column_r_m = column_to_top_m(air.profile, R, Rt, R + z, 1.0, req.column_segments);
    const double column_m_m = column_to_top_m(aerosol.profile, R, Rt, R + z, 1.0, req.column_segments);
    level.rayleigh_scattering_per_m = scaled(air.scattering_per_m, rho_r);
    level.rayleigh_optical_depth = scaled(air.extinction_per_m, column_r_m);
    level.mie_scattering_per_m = scaled(aerosol.scattering_per_m, rho_m);
    level.mie_extinction_per_m = scaled(aerosol.extinction_per_m, rho_m);
    level.mie_optical_depth = scaled(aerosol.extinction_per_m, column_m_m);
    if (r.ozone_enabled) {
      const DensityProfile& profile = ozone_medium->profile;
      const double rho_o = profile.relative(z);
      const double column_o_m = column_to_top_m(profile, R, Rt, R + z, 1.0, req.column_segments);
      level.ozone_absorption_per_m = scaled(ozone_extinction_per_m, rho_o);
      level.ozone_optical_depth = scaled(ozone_extinction_per_m, column_o_m);
    } else {
      level.ozone_absorption_per_m.assign(r.wavelengths_nm.size(), 0.0);
      level.ozone_optical_depth.assign(r.wavelengths_nm.size(), 0.0);
    }
    for (const Medium* m : others) {
      const double rho = m->profile.relative(z);
      const double column_m = column_to_top_m(m->profile, R, Rt, R + z, 1.0, req.column_segments);
      level.media.push_back({m->name, scaled(m->scattering_per_m, rho), scaled(m->extinction_per_m, rho),
                             scaled(m->extinction_per_m, column_m)});
    }
    level.total_optical_depth.resize(level.rayleigh_optical_depth.size());
    for (size_t i = 0; i < level.total_optical_depth.size(); ++i) {
      level.total_optical_depth[i] = level.rayleigh_optical_depth[i] + level.mie_optical_depth[i] +
                                     (std::isnan(level.ozone_optical_depth[i]) ? 0.0 : level.ozone_optical_depth[i]);
      for (const ReportMediumLevel& m : level.media) level.total_optical_depth[i] += m.optical_depth[i];
    }

    std::ostringstream origin;
    if (!r.rayleigh_derived) {
      origin << "not used: the coefficients are typed in (atmosphere.rayleigh.source = \"fixed\"), scaled by the "
             << r.profile_description << " profile (rho = " << format_number(rho_r) << ")";
    } else {
      level.rayleigh_number_density_per_m3 = model.rayleigh_number_density_per_m3() * rho_r;
      switch (spec.rayleigh.profile) {
        case ProfileKind::UsStandard1976: {
          const AtmosphereState s = us_standard_atmosphere_1976(z);
          level.temperature_K = s.temperature_K;
          level.pressure_Pa = s.pressure_Pa;
          origin << "U.S. Standard Atmosphere 1976 at " << format_number(z)
                 << " m: T = " << fmt("%.2f", s.temperature_K) << " K, P = " << fmt("%.6g", s.pressure_Pa)
                 << " Pa, N = P / (k T)";
          break;
        }
        case ProfileKind::Exponential:
          origin << "N(0) exp(-z / H), H = " << format_number(spec.rayleigh.scale_height_m) << " m; "
                 << model.rayleigh_number_density_origin();
          break;
        case ProfileKind::Constant:
          origin << "constant with altitude; " << model.rayleigh_number_density_origin();
          break;
      }
    }
    level.number_density_origin = origin.str();
    r.levels.push_back(std::move(level));
  }

  if (req.conditions) {
    const AirConditions& c = *req.conditions;
    if (!std::isfinite(c.pressure_Pa) || c.pressure_Pa <= 0.0 || c.pressure_Pa > 1e8)
      throw InputError("conditions.pressure_Pa", format_number(c.pressure_Pa), "a pressure above 0 and up to 1e8 Pa");
    if (!std::isfinite(c.temperature_K) || c.temperature_K <= 0.0 || c.temperature_K > 1e4)
      throw InputError("conditions.temperature_K", format_number(c.temperature_K),
                       "a temperature above 0 and up to 10000 K");
    ReportConditions rc;
    rc.air = c;
    rc.number_density_per_m3 = c.pressure_Pa / (constants::kBoltzmann_J_per_K * c.temperature_K);
    rc.density_ratio = rc.number_density_per_m3 / constants::kStandardNumberDensity_per_m3;
    rc.pressure_altitude_m = standard_atmosphere_pressure_altitude_m(c.pressure_Pa);
    rc.column_gravity_m_per_s2 =
        gravity_m_per_s2(req.latitude_deg, mass_weighted_column_altitude_m(rc.pressure_altitude_m));
    const double molar_mass_kg_per_mol = mean_molecular_weight_air_g_per_mol(r.co2_ppv) * kKilogramsPerGram;
    rc.column_molecules_per_m2 =
        c.pressure_Pa * constants::kAvogadro_per_mol / (molar_mass_kg_per_mol * rc.column_gravity_m_per_s2);
    for (const auto& step : r.derivation) {
      rc.refractivity.push_back(step.refractivity * rc.density_ratio);
      rc.rayleigh_scattering_per_m.push_back(step.cross_section_m2 * rc.number_density_per_m3);
      rc.rayleigh_optical_depth_above.push_back(step.cross_section_m2 * rc.column_molecules_per_m2);
    }
    r.conditions = rc;
  }

  if (!ozone.missing_nm.empty()) {
    std::string listed;
    for (double nm : ozone.missing_nm) listed += (listed.empty() ? "" : ", ") + format_number(nm);
    r.notes.push_back("Ozone: the built-in cross-sections (laboratory data at 233 K) cover " + ozone.table_range +
                      "; at " + listed +
                      " nm the ozone columns are n/a and tau total is that of air molecules "
                      "and aerosols (ozone absorbs little there: about 1e-28 m^2 per molecule at 1000-1060 nm).");
  }
  if (!spec.ozone.enabled)
    r.notes.push_back(
        "Ozone: this atmosphere has no ozone (atmosphere.ozone.enabled = false), so the report has "
        "no ozone columns; the optical depths are those of air molecules and aerosols.");
  if (!r.rayleigh_derived)
    r.notes.push_back(
        "The Rayleigh coefficients of this atmosphere are typed in (atmosphere.rayleigh.source = "
        "\"fixed\"): the renderer uses them, not the derivation; the derivation is shown for "
        "comparison with the same refractive index formula and CO2.");
  r.formulas = report_formulas(r);
  r.references = published_comparisons();
  return r;
}

ReportFormat parse_report_format(const std::string& name, const std::string& setting) {
  if (name == "md" || name == "markdown") return ReportFormat::Markdown;
  if (name == "csv") return ReportFormat::Csv;
  if (name == "json") return ReportFormat::Json;
  if (name == "html") return ReportFormat::Html;
  throw InputError(setting, name, "one of: md, csv, json, html");
}

std::string to_string(ReportFormat f) {
  switch (f) {
    case ReportFormat::Markdown:
      return "md";
    case ReportFormat::Csv:
      return "csv";
    case ReportFormat::Json:
      return "json";
    case ReportFormat::Html:
      return "html";
  }
  return "md";
}

std::string format_report(const CoefficientReport& report, ReportFormat format) {
  switch (format) {
    case ReportFormat::Markdown:
      return report_to_markdown(report);
    case ReportFormat::Csv:
      return report_to_csv(report);
    case ReportFormat::Json:
      return report_to_json(report);
    case ReportFormat::Html:
      return report_to_html(report);
  }
  return report_to_markdown(report);
}

DerivationColumns derivation_columns(const CoefficientReport& r) {
  DerivationColumns c;
  for (const RayleighDerivationStep& s : r.derivation) {
    c.refractivity_ref.push_back(s.refractivity_ref);
    c.refractivity.push_back(s.refractivity);
    c.king_factor_air.push_back(s.king_factor);
    c.king_factor_n2.push_back(s.king_n2);
    c.king_factor_o2.push_back(s.king_o2);
    c.cross_section_m2.push_back(s.cross_section_m2);
  }
  return c;
}

}  // namespace skyspec
