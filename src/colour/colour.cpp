// Colour science: the CIE 1931 observer table, exact spectrum -> XYZ weights, Rec.709 / sRGB.
#include "skyspec/colour.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <locale>
#include <string>
#include <string_view>

#include "base/csv_table.hpp"
#include "base/embedded_data.hpp"
#include "skyspec/error.hpp"

namespace skyspec {
namespace {

// ---------------------------------------------------------------------------------------------
// The CMF table (data/cie/cie1931_2deg_5nm.csv, compiled into the library).
// ---------------------------------------------------------------------------------------------

constexpr std::string_view kCie1931File = "cie/cie1931_2deg_5nm.csv";

/// Splits "a,b,c,d" into its fields.
/// Parses the "nm,x,y,z" table (format: csv_table.hpp). Wavelengths must increase strictly.
CmfTable parse_cmf_csv(std::string_view file_name, std::string_view text) {
  CmfTable table;
  for (const CsvRow& row : parse_csv(file_name, text, {"nm", "x", "y", "z"})) {
    const double nm = csv_number(file_name, row, 0);
    if (!table.nm.empty() && nm <= table.nm.back())
      throw Error(std::string(file_name) + ":" + std::to_string(row.line_number) + ": wavelengths must increase");
    table.nm.push_back(nm);
    table.x.push_back(csv_number(file_name, row, 1));
    table.y.push_back(csv_number(file_name, row, 2));
    table.z.push_back(csv_number(file_name, row, 3));
  }
  if (table.nm.size() < 2) throw Error(std::string(file_name) + ": fewer than 2 rows of data");
  return table;
}

/// The CMFs at lambda_nm by linear interpolation of the table (zero outside it).
Eigen::Vector3d cmf_at(const CmfTable& t, double lambda_nm) {
  if (lambda_nm < t.nm.front() || lambda_nm > t.nm.back()) return Eigen::Vector3d::Zero();
  // First table point strictly greater than lambda, so the bracket is [i - 1, i].
  auto upper = std::upper_bound(t.nm.begin(), t.nm.end(), lambda_nm);
  size_t i = static_cast<size_t>(upper - t.nm.begin());
  if (i == t.nm.size()) i = t.nm.size() - 1;  // lambda == last point
  const size_t j = i - 1;
  const double f = (lambda_nm - t.nm[j]) / (t.nm[i] - t.nm[j]);
  return {t.x[j] + f * (t.x[i] - t.x[j]), t.y[j] + f * (t.y[i] - t.y[j]), t.z[j] + f * (t.z[i] - t.z[j])};
}

// ---------------------------------------------------------------------------------------------
// Rec.709 primaries (ITU-R BT.709-6 item 1.3; the same as sRGB, IEC 61966-2-1) and D65 white.
// ---------------------------------------------------------------------------------------------

constexpr double kRed[2] = {0.64, 0.33}, kGreen[2] = {0.30, 0.60}, kBlue[2] = {0.15, 0.06};
constexpr double kD65[2] = {0.3127, 0.3290};

/// XYZ of chromaticity (x, y) scaled to Y = 1: (x / y, 1, (1 - x - y) / y).
Eigen::Vector3d xyz_with_unit_luminance(const double xy[2]) {
  return {xy[0] / xy[1], 1.0, (1.0 - xy[0] - xy[1]) / xy[1]};
}

}  // namespace

// ---------------------------------------------------------------------------------------------

const CmfTable& cie1931_2deg() {
  static const CmfTable table = parse_cmf_csv(kCie1931File, embedded_file(kCie1931File));
  return table;
}

// The spectrum is L(lambda) = sum_i L_i phi_i(lambda), phi_i the "hat" function that is 1 at grid
// point i, 0 at the other grid points, linear between them and 0 outside [lambda_0, lambda_n-1].
// Hence X = sum_i L_i W_x,i with W_x,i = scale * integral phi_i(lambda) x-bar(lambda) dlambda, and
// likewise for Y and Z. Splitting each grid interval at the table points inside it gives pieces
// on which both phi_i and the interpolated CMF are linear, so their product is a quadratic and
// Simpson's rule, (b - a) / 6 * (f(a) + 4 f(m) + f(b)), integrates it exactly.
SpectrumToXyz::SpectrumToXyz(const WavelengthGrid& grid, double scale) {
  const CmfTable& cmf = cie1931_2deg();
  if (grid.size() < 2)
    throw InputError("spectrum", grid.describe(),
                     "at least 2 wavelengths to integrate against the CIE colour-matching functions");
  // Wavelengths outside the table (360-830 nm) see colour-matching functions of zero (cmf_at):
  // the colour of a spectrum reaching into the ultraviolet or infrared is that of its overlap with
  // the table, and a grid entirely outside it has no colour (X = Y = Z = 0).
  const int n = grid.size();
  w_ = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, n);
  for (int k = 0; k + 1 < n; ++k) {
    const double lo_nm = grid.nm(k), hi_nm = grid.nm(k + 1);
    // Breakpoints of this grid interval: its ends and every table point strictly inside.
    std::vector<double> cuts{lo_nm};
    for (double t : cmf.nm)
      if (t > lo_nm && t < hi_nm) cuts.push_back(t);
    cuts.push_back(hi_nm);

    const auto hat_hi = [&](double lambda_nm) { return (lambda_nm - lo_nm) / (hi_nm - lo_nm); };
    for (size_t p = 0; p + 1 < cuts.size(); ++p) {
      const double a = cuts[p], b = cuts[p + 1], m = 0.5 * (a + b);
      const double simpson[3] = {(b - a) / 6.0, 4.0 * (b - a) / 6.0, (b - a) / 6.0};
      const double at[3] = {a, m, b};
      for (int q = 0; q < 3; ++q) {
        const Eigen::Vector3d cmf_value = cmf_at(cmf, at[q]);
        const double phi_hi = hat_hi(at[q]), phi_lo = 1.0 - phi_hi;
        w_.col(k) += simpson[q] * phi_lo * cmf_value;
        w_.col(k + 1) += simpson[q] * phi_hi * cmf_value;
      }
    }
  }
  w_ *= scale;
}

namespace {
/// W s for a spectrum of either precision, accumulated in double without a temporary.
template <typename SpectrumArray>
Eigen::Vector3d apply_weights(const Eigen::Matrix<double, 3, Eigen::Dynamic>& w, const SpectrumArray& s) {
  if (s.size() != w.cols())
    throw Error("SpectrumToXyz: spectrum has " + std::to_string(s.size()) + " values, grid has " +
                std::to_string(w.cols()));
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < s.size(); ++i) xyz += w.col(i) * static_cast<double>(s[i]);
  return xyz;
}
}  // namespace

Eigen::Vector3d SpectrumToXyz::operator()(const SpectrumD& s) const { return apply_weights(w_, s); }
Eigen::Vector3d SpectrumToXyz::operator()(const Spectrum& s) const { return apply_weights(w_, s); }

// RGB -> XYZ from primaries and white (e.g. SMPTE RP 177-1993, section 3.3): the columns of
// P = [XYZ_r XYZ_g XYZ_b] hold each primary's XYZ at unit luminance; the per-primary luminances
// S solve P S = XYZ_white (white at Y = 1), so that RGB = (1, 1, 1) is white; M = P diag(S).
Eigen::Matrix3d linear_rec709_to_xyz() {
  Eigen::Matrix3d primaries;
  primaries.col(0) = xyz_with_unit_luminance(kRed);
  primaries.col(1) = xyz_with_unit_luminance(kGreen);
  primaries.col(2) = xyz_with_unit_luminance(kBlue);
  const Eigen::Vector3d white = xyz_with_unit_luminance(kD65);
  const Eigen::Vector3d luminance = primaries.partialPivLu().solve(white);
  return primaries * luminance.asDiagonal();
}

Eigen::Matrix3d xyz_to_linear_rec709() { return linear_rec709_to_xyz().inverse(); }

Chromaticities rec709_chromaticities() {
  return Chromaticities{{kRed[0], kRed[1]}, {kGreen[0], kGreen[1]}, {kBlue[0], kBlue[1]}, {kD65[0], kD65[1]}};
}

// IEC 61966-2-1:1999 section 4.1 (encoding): V = 12.92 L for L <= 0.0031308, otherwise
// V = 1.055 L^(1 / 2.4) - 0.055. Inputs are clamped to [0, 1]; NaN encodes as 0.
double srgb_encode(double linear) {
  if (!(linear > 0.0)) return 0.0;
  if (linear >= 1.0) return 1.0;
  if (linear <= 0.0031308) return 12.92 * linear;
  return 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

// x = X / (X + Y + Z), y = Y / (X + Y + Z).
Eigen::Vector2d xy_chromaticity(const Eigen::Vector3d& xyz) {
  const double sum = xyz.sum();
  if (sum == 0.0) return Eigen::Vector2d::Zero();
  return {xyz.x() / sum, xyz.y() / sum};
}

}  // namespace skyspec
