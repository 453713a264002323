// Published Rayleigh-scattering figures, parsed once from the CSV tables embedded from
// data/reference/ (provenance in data/README.md and in each file's comment lines).
#include "report/published_references.hpp"

#include <cmath>
#include <sstream>
#include <string>
#include <string_view>

#include "base/embedded_data.hpp"
#include "base/text_format.hpp"
#include "skyspec/error.hpp"
#include "skyspec/units.hpp"

namespace skyspec {
namespace {

constexpr double kSquareMetresPerSquareCentimetre = 1.0e-4;
constexpr double kFractionPerPercent = 0.01;

/// The data rows of an embedded CSV file: '#' lines skipped, the header line skipped, every other
/// line split at commas. Malformed files are a build defect, reported as skyspec::Error.
std::vector<std::vector<std::string>> csv_rows(const std::string& name) {
  const std::string_view text = embedded_file(name);
  std::vector<std::vector<std::string>> rows;
  std::istringstream in{std::string(text)};
  std::string line;
  bool header_seen = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    if (!header_seen) {
      header_seen = true;
      continue;
    }
    std::vector<std::string> fields;
    std::istringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) fields.push_back(cell);
    rows.push_back(fields);
  }
  if (rows.empty()) throw Error("embedded table " + name + " has no rows");
  return rows;
}

double number(const std::string& cell, const std::string& name) {
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(cell, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != cell.size() || !std::isfinite(v)) throw Error("embedded table " + name + ": bad number \"" + cell + "\"");
  return v;
}

std::vector<PublishedValue> two_column_table(const std::string& name, double wavelength_scale, double value_scale) {
  std::vector<PublishedValue> table;
  for (const auto& row : csv_rows(name)) {
    if (row.size() != 2) throw Error("embedded table " + name + ": expected 2 columns");
    table.push_back({number(row[0], name) * wavelength_scale, number(row[1], name) * value_scale});
  }
  return table;
}

struct FitBranch {
  double min_um, max_um, a_cm2, b, c, d;
};

const std::vector<FitBranch>& bucholtz_fit() {
  static const std::vector<FitBranch> branches = [] {
    const std::string name = "reference/bucholtz1995_cross_section_fit.csv";
    std::vector<FitBranch> b;
    for (const auto& row : csv_rows(name)) {
      if (row.size() != 6) throw Error("embedded table " + name + ": expected 6 columns");
      b.push_back({number(row[0], name), number(row[1], name), number(row[2], name), number(row[3], name),
                   number(row[4], name), number(row[5], name)});
    }
    return b;
  }();
  return branches;
}

}  // namespace

const Bodhaine1999Fit& bodhaine1999_fit() {
  static const Bodhaine1999Fit fit = [] {
    const std::string name = "reference/bodhaine1999_fit.csv";
    const auto rows = csv_rows(name);
    if (rows.size() != 1 || rows[0].size() != 6)
      throw Error("embedded table " + name + ": expected 1 row of 6 columns");
    const auto& r = rows[0];
    return Bodhaine1999Fit{number(r[0], name), number(r[1], name), number(r[2], name),
                           number(r[3], name), number(r[4], name), number(r[5], name)};
  }();
  return fit;
}

// Bodhaine et al. 1999 eq. (29): sigma = 1e-28 cm^2 (a + b/l^2 + c l^2) / (1 + d/l^2 + e l^2), l in um.
double bodhaine1999_fit_ratio(double lambda_nm) {
  const Bodhaine1999Fit& f = bodhaine1999_fit();
  const double l2 = std::pow(lambda_nm / kNanometresPerMicrometre, 2.0);
  return (f.a + f.b / l2 + f.c * l2) / (1.0 + f.d / l2 + f.e * l2);
}
double bodhaine1999_cross_section_fit_m2(double lambda_nm) {
  constexpr double kFitUnit_cm2 = 1e-28;
  return bodhaine1999_fit_ratio(lambda_nm) * kFitUnit_cm2 * kSquareMetresPerSquareCentimetre;
}
// Eq. (30): tau = tau_scale (the same ratio).
double bodhaine1999_optical_depth_fit(double lambda_nm) {
  return bodhaine1999_fit().tau_scale * bodhaine1999_fit_ratio(lambda_nm);
}

const std::vector<PublishedValue>& bodhaine1999_table3_optical_depth() {
  static const auto table = two_column_table("reference/bodhaine1999_table3_optical_depth.csv", 1.0, 1.0);
  return table;
}

const Bodhaine1999TextValues& bodhaine1999_text_values() {
  static const Bodhaine1999TextValues values = [] {
    const std::string name = "reference/bodhaine1999_text_values.csv";
    Bodhaine1999TextValues v{0.0, 0.0, 0.0};
    for (const auto& row : csv_rows(name)) {
      if (row.size() != 4) throw Error("embedded table " + name + ": expected 4 columns");
      const double value = number(row[2], name);
      if (row[0] == "cross_section" && row[3] == "cm^2")
        v.cross_section_550nm_m2 = value * kSquareMetresPerSquareCentimetre;
      else if (row[0] == "king_factor_air")
        v.king_factor_air_550nm = value;
      else if (row[0] == "optical_depth")
        v.optical_depth_550nm = value;
      else
        throw Error("embedded table " + name + ": unknown quantity " + row[0]);
    }
    if (v.cross_section_550nm_m2 <= 0.0 || v.king_factor_air_550nm <= 0.0 || v.optical_depth_550nm <= 0.0)
      throw Error("embedded table " + name + ": a quantity is missing");
    return v;
  }();
  return values;
}

const std::vector<PublishedValue>& bucholtz1995_depolarization() {
  static const auto table =
      two_column_table("reference/bucholtz1995_depolarization.csv", kNanometresPerMicrometre, kFractionPerPercent);
  return table;
}

// King 1923: F = (6 + 3 rho) / (6 - 7 rho).
double king_factor_from_depolarization(double rho) { return (6.0 + 3.0 * rho) / (6.0 - 7.0 * rho); }

// Bucholtz 1995: sigma = A lambda^-(B + C lambda + D / lambda), lambda in um, sigma in cm^2.
double bucholtz1995_cross_section_fit_m2(double lambda_nm) {
  const auto& branches = bucholtz_fit();
  const double lambda_um = lambda_nm / kNanometresPerMicrometre;
  if (!std::isfinite(lambda_um) || lambda_um < branches.front().min_um || lambda_um > branches.back().max_um)
    throw InputError("wavelength_nm", format_number(lambda_nm),
                     "200 to 1690 nm (Bucholtz's fit, used up to the range of the refractive index of air)");
  const FitBranch* use = &branches.back();
  for (const auto& b : branches)
    if (lambda_um <= b.max_um) {
      use = &b;
      break;
    }
  const double exponent = use->b + use->c * lambda_um + use->d / lambda_um;
  return use->a_cm2 * std::pow(lambda_um, -exponent) * kSquareMetresPerSquareCentimetre;
}

double bucholtz1995_fit_branch_nm() { return bucholtz_fit().front().max_um * kNanometresPerMicrometre; }

}  // namespace skyspec
