// Ozone: absorption cross-section table, Dobson units, tent profile; see ozone.hpp.
#include "physics/ozone.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>
#include <vector>

#include "base/csv_table.hpp"
#include "base/embedded_data.hpp"
#include "base/text_format.hpp"
#include "skyspec/error.hpp"
#include "skyspec/units.hpp"

namespace skyspec {
namespace {

constexpr double kMaxColumn_DU = 1000.0;
constexpr double kMaxAltitude_m = 100e3;

struct OzoneBin {
  double lower_nm, upper_nm, cross_section_m2;
  std::string_view file;
  int line_number;
};

void append_bins(std::string_view file, std::vector<OzoneBin>& bins) {
  for (const CsvRow& row : parse_csv(file, embedded_file(file), {"lower_nm", "upper_nm", "cross_section_m2"}))
    bins.push_back(
        {csv_number(file, row, 0), csv_number(file, row, 1), csv_number(file, row, 2), file, row.line_number});
}

// The files' bins in wavelength order, one table: Bogumil's ultraviolet, Serdyuchenko's 360-840 nm,
// Bogumil's near infrared.
TabulatedSpectrum load_ozone_table() {
  std::vector<OzoneBin> bins;
  for (std::string_view file : ozone_cross_section_files()) append_bins(file, bins);
  std::stable_sort(bins.begin(), bins.end(),
                   [](const OzoneBin& a, const OzoneBin& b) { return a.lower_nm < b.lower_nm; });
  std::vector<double> edges_nm{bins.front().lower_nm}, cross_section_m2;
  for (const OzoneBin& bin : bins) {
    // Bins must be contiguous: each lower edge is the previous upper edge.
    if (bin.lower_nm != edges_nm.back())
      throw Error(std::string(bin.file) + ":" + std::to_string(bin.line_number) +
                  ": bins must be contiguous (lower_nm must equal the previous upper_nm, " +
                  format_number(edges_nm.back()) + ")");
    edges_nm.push_back(bin.upper_nm);
    cross_section_m2.push_back(bin.cross_section_m2);
  }
  return TabulatedSpectrum::bin_averages(
      "the ozone cross-section table (233 K: Bogumil et al. 2003 below 360 nm and above 840 nm, "
      "Serdyuchenko et al. 2014 between)",
      std::move(edges_nm), std::move(cross_section_m2));
}

void check_column(double column_DU, const std::string& setting) {
  if (!(column_DU >= 0.0 && column_DU <= kMaxColumn_DU))
    throw InputError(setting, format_number(column_DU),
                     "an ozone column in Dobson units from 0 to 1000 (observed: about 100-600, typically 300)");
}

}  // namespace

const std::vector<std::string_view>& ozone_cross_section_files() {
  static const std::vector<std::string_view> files{"ozone/bogumil2003_233K.csv",
                                                   "ozone/serdyuchenko2014_233K_10nm.csv"};
  return files;
}

const TabulatedSpectrum& ozone_cross_section_table() {
  static const TabulatedSpectrum table = load_ozone_table();
  return table;
}

SpectrumD ozone_cross_section_on_grid(const WavelengthGrid& grid, const std::string& setting) {
  return ozone_cross_section_table().mean_on_grid(grid, setting);
}

double dobson_units_to_per_m2(double column_DU, const std::string& setting) {
  check_column(column_DU, setting);
  return column_DU * constants::kDobsonUnit_per_m2;
}

double per_m2_to_dobson_units(double column_per_m2) { return column_per_m2 / constants::kDobsonUnit_per_m2; }

SpectrumD ozone_vertical_optical_depth_on_grid(const WavelengthGrid& grid, double column_DU,
                                               const std::string& setting) {
  const double column_per_m2 = dobson_units_to_per_m2(column_DU);
  return ozone_cross_section_on_grid(grid, setting) * column_per_m2;
}

// ---------------------------------------------------------------------------------------------

OzoneTentProfile OzoneTentProfile::bruneton2017(double column_DU, const std::string& setting) {
  return OzoneTentProfile(column_DU, 10e3, 25e3, 40e3, setting);
}

OzoneTentProfile::OzoneTentProfile(double column_DU, double bottom_m, double peak_m, double top_m,
                                   const std::string& column_setting)
    : column_DU_(column_DU), bottom_m_(bottom_m), peak_m_(peak_m), top_m_(top_m) {
  check_column(column_DU, column_setting);
  if (!(bottom_m >= 0.0 && bottom_m < kMaxAltitude_m))
    throw InputError("ozone.bottom_altitude_m", format_number(bottom_m), "an altitude from 0 to 100000 m");
  if (!(peak_m > bottom_m && peak_m < kMaxAltitude_m))
    throw InputError(
        "ozone.peak_altitude_m", format_number(peak_m),
        "an altitude above ozone.bottom_altitude_m (" + format_number(bottom_m) + " m) and below 100000 m");
  if (!(top_m > peak_m && top_m <= kMaxAltitude_m))
    throw InputError("ozone.top_altitude_m", format_number(top_m),
                     "an altitude above ozone.peak_altitude_m (" + format_number(peak_m) + " m), at most 100000 m");
  column_per_m2_ = column_DU * constants::kDobsonUnit_per_m2;
  // The tent is a triangle of base (top - bottom) and height n_peak: N = n_peak (top - bottom) / 2.
  peak_per_m3_ = column_per_m2_ / (0.5 * (top_m - bottom_m));
}

double OzoneTentProfile::number_density_per_m3(double z_m) const {
  if (z_m <= bottom_m_ || z_m >= top_m_) return 0.0;
  if (z_m <= peak_m_) return peak_per_m3_ * (z_m - bottom_m_) / (peak_m_ - bottom_m_);
  return peak_per_m3_ * (top_m_ - z_m) / (top_m_ - peak_m_);
}

double OzoneTentProfile::cumulative_per_m2(double z_m) const {
  // Area of the triangle's part below z: a quadratic on each flank.
  if (z_m <= bottom_m_) return 0.0;
  if (z_m >= top_m_) return column_per_m2_;
  if (z_m <= peak_m_) {
    const double rise_m = z_m - bottom_m_;
    return 0.5 * peak_per_m3_ * rise_m * rise_m / (peak_m_ - bottom_m_);
  }
  const double remaining_m = top_m_ - z_m;
  return column_per_m2_ - 0.5 * peak_per_m3_ * remaining_m * remaining_m / (top_m_ - peak_m_);
}

double OzoneTentProfile::column_between_per_m2(double z0_m, double z1_m) const {
  return cumulative_per_m2(z1_m) - cumulative_per_m2(z0_m);
}

}  // namespace skyspec
