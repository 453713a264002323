// The gases' absorption bands: Bird & Riordan's band model and its exponential sums; see gas_bands.hpp.
#include "physics/gas_bands.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <string_view>

#include "base/csv_table.hpp"
#include "base/embedded_data.hpp"
#include "skyspec/error.hpp"

namespace skyspec {
namespace {

constexpr std::string_view kBandsFile = "gases/bird_riordan1986_bands.csv";
constexpr std::string_view kSumsFile = "gases/exponential_sums.csv";

struct BandModelConstants {
  double c1, c2;
};
// Eqs. 2-8 and 2-11 of Bird & Riordan (1986), the constants as their report prints them.
BandModelConstants constants_of(GasBand gas) {
  return gas == GasBand::WaterVapour ? BandModelConstants{0.2385, 20.07} : BandModelConstants{1.41, 118.93};
}
size_t index_of(GasBand gas) { return gas == GasBand::WaterVapour ? 0 : 1; }

struct BandTable {
  std::vector<double> nm;
  std::array<std::vector<double>, 2> a;  // per GasBand
};

const BandTable& band_table() {
  static const BandTable table = [] {
    BandTable t;
    for (const CsvRow& row :
         parse_csv(kBandsFile, embedded_file(kBandsFile), {"nm", "water_vapour_per_cm", "mixed_gases_per_air_mass"})) {
      const double nm = csv_number(kBandsFile, row, 0);
      if (!t.nm.empty() && !(nm > t.nm.back()))
        throw Error(std::string(kBandsFile) + ":" + std::to_string(row.line_number) + ": wavelengths must increase");
      t.nm.push_back(nm);
      for (size_t g = 0; g < 2; ++g) {
        const double a = csv_number(kBandsFile, row, g + 1);
        if (a < 0.0)
          throw Error(std::string(kBandsFile) + ":" + std::to_string(row.line_number) + ": negative coefficient");
        t.a[g].push_back(a);
      }
    }
    return t;
  }();
  return table;
}

const std::array<std::vector<ExponentialTerm>, 2>& sums() {
  static const std::array<std::vector<ExponentialTerm>, 2> s = [] {
    std::array<std::vector<ExponentialTerm>, 2> out;
    for (const CsvRow& row : parse_csv(kSumsFile, embedded_file(kSumsFile), {"gas", "term", "k", "weight"})) {
      const std::string& gas = row.fields[0];
      const size_t g = gas == "water_vapour" ? 0 : gas == "mixed_gases" ? 1 : 2;
      if (g == 2) throw Error(std::string(kSumsFile) + ":" + std::to_string(row.line_number) + ": unknown gas " + gas);
      out[g].push_back({csv_number(kSumsFile, row, 2), csv_number(kSumsFile, row, 3)});
    }
    for (auto& terms : out) {
      double total = 0.0;
      for (const ExponentialTerm& t : terms) total += t.weight;
      if (terms.empty() || terms.size() != out[0].size() || !(std::abs(total - 1.0) < 1e-6))
        throw Error(std::string(kSumsFile) + ": each gas needs the same number of terms, weights summing to 1");
      std::sort(terms.begin(), terms.end(),
                [](const ExponentialTerm& x, const ExponentialTerm& y) { return x.k < y.k; });
    }
    return out;
  }();
  return s;
}

// The band optical depth -ln T of eq. (1) at x.
double band_optical_depth(GasBand gas, double x) {
  const BandModelConstants c = constants_of(gas);
  return c.c1 * x / std::pow(1.0 + c.c2 * x, 0.45);
}

}  // namespace

double band_transmittance(GasBand gas, double x) { return std::exp(-band_optical_depth(gas, x)); }

const std::vector<ExponentialTerm>& exponential_sum(GasBand gas) { return sums()[index_of(gas)]; }

int exponential_term_count() { return static_cast<int>(sums()[0].size()); }

const std::vector<double>& band_model_wavelengths_nm() { return band_table().nm; }

double band_coefficient(GasBand gas, double lambda_nm) {
  const BandTable& t = band_table();
  if (!(lambda_nm >= t.nm.front() && lambda_nm <= t.nm.back())) return 0.0;
  const auto hi = std::lower_bound(t.nm.begin(), t.nm.end(), lambda_nm);
  const size_t j = static_cast<size_t>(hi - t.nm.begin());
  const std::vector<double>& a = t.a[index_of(gas)];
  if (j == 0 || *hi == lambda_nm) return a[j];
  const double f = (lambda_nm - t.nm[j - 1]) / (t.nm[j] - t.nm[j - 1]);
  return a[j - 1] + f * (a[j] - a[j - 1]);
}

GasTermCoefficients gas_term_coefficients(int term, double lambda_nm, double water_vapour_cm,
                                          double relative_surface_pressure) {
  if (term < 0 || term >= exponential_term_count())
    throw Error("gas_term_coefficients: term " + std::to_string(term) + " of " +
                std::to_string(exponential_term_count()));
  const double a_w = band_coefficient(GasBand::WaterVapour, lambda_nm) * (water_vapour_cm > 0.0 ? 1.0 : 0.0);
  const double a_u = band_coefficient(GasBand::MixedGases, lambda_nm) * (relative_surface_pressure > 0.0 ? 1.0 : 0.0);
  GasTermCoefficients c;
  if (a_w == 0.0 && a_u == 0.0) return c;
  c.absorbs = true;
  // The reference path's absorber amounts and each gas's band optical depth on it.
  const double u_w = water_vapour_cm * kGasReferenceAirMasses, u_u = relative_surface_pressure * kGasReferenceAirMasses;
  const double tau_w = band_optical_depth(GasBand::WaterVapour, a_w * u_w);
  const double tau_u = band_optical_depth(GasBand::MixedGases, a_u * u_u);
  const bool water_leads = tau_w >= tau_u;
  const GasBand lead = water_leads ? GasBand::WaterVapour : GasBand::MixedGases;
  const ExponentialTerm& t = exponential_sum(lead)[static_cast<size_t>(term)];
  c.weight = t.weight;
  // The leading gas: eq. (2)'s term; the other: Beer-Lambert matched to eq. (1) on the reference path.
  if (water_leads) {
    c.water_vapour_per_cm = t.k * a_w;
    c.mixed_gases_per_air_mass = u_u > 0.0 ? tau_u / u_u : 0.0;
  } else {
    c.mixed_gases_per_air_mass = t.k * a_u;
    c.water_vapour_per_cm = u_w > 0.0 ? tau_w / u_w : 0.0;
  }
  return c;
}

}  // namespace skyspec
