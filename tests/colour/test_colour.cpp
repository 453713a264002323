#include <boost/test/unit_test.hpp>

#include <cmath>
#include <vector>

#include "check_helpers.hpp"
#include "skyspec/colour.hpp"
#include "skyspec/error.hpp"
#include "skyspec/spectrum.hpp"

BOOST_AUTO_TEST_SUITE(test_colour)

using namespace skyspec;
using test::relative;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// A smooth, positive test spectrum (arbitrary units).
double smooth_spectrum(double lambda_nm) { return 1.0 + 0.5 * std::sin(2.0 * kPi * (lambda_nm - 360.0) / 200.0); }

/// The spectrum sampled on a grid.
SpectrumD sample(const WavelengthGrid& grid, double (*f)(double)) {
  SpectrumD s(grid.size());
  for (int i = 0; i < grid.size(); ++i) s[i] = f(grid.nm(i));
  return s;
}

/// Linear interpolation of (xs, ys) at x; zero outside [xs.front(), xs.back()].
double interpolate(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  if (x < xs.front() || x > xs.back()) return 0.0;
  for (size_t i = 1; i < xs.size(); ++i)
    if (x <= xs[i]) return ys[i - 1] + (ys[i] - ys[i - 1]) * (x - xs[i - 1]) / (xs[i] - xs[i - 1]);
  return ys.back();
}

const std::vector<double>& cmf_column(const CmfTable& t, int c) { return c == 0 ? t.x : c == 1 ? t.y : t.z; }

/// Relative difference |a - b| / |b|.

}  // namespace

// ------------------------------------------------------------------------------------------------
BOOST_AUTO_TEST_SUITE(cmf_table)

BOOST_AUTO_TEST_CASE(table_has_the_cie_1931_rows) {
  const CmfTable& t = cie1931_2deg();
  BOOST_TEST(t.nm.size() == 95u);
  BOOST_TEST(t.nm.front() == 360.0);
  BOOST_TEST(t.nm.back() == 830.0);
  for (size_t i = 1; i < t.nm.size(); ++i) BOOST_TEST(t.nm[i] - t.nm[i - 1] == 5.0);
  // Landmarks of CIE 015:2004 table T.4: y-bar(555) = 1, x-bar peaks at 600 nm (1.0622),
  // z-bar at 445 nm (1.7826).
  const auto at = [&](double nm) { return static_cast<size_t>((nm - 360.0) / 5.0); };
  BOOST_TEST(t.y[at(555)] == 1.0);
  BOOST_TEST(t.x[at(600)] == 1.0622);
  BOOST_TEST(t.z[at(445)] == 1.7826);
}

// Sum of y-bar over the 5 nm table: 21.3714 (x 5 nm = 106.857). pbrt-v4's CIE_Y_integral,
// 106.856895, is the sum over the 1 nm CIE table: the independent figure agrees to ~1e-6.
BOOST_AUTO_TEST_CASE(y_bar_sum_matches_published_integral) {
  const CmfTable& t = cie1931_2deg();
  double sum_y = 0.0;
  for (double v : t.y) sum_y += v;
  BOOST_TEST(std::abs(sum_y - 21.37141) < 1e-5);
  BOOST_TEST(relative(5.0 * sum_y, 106.856895) < 1e-5);
}

// The 1931 observer is normalised so that an equal-energy spectrum has equal X, Y, Z. The
// tabulated functions meet this to 3.4e-4 (z-bar is the largest: 106.892 against 106.857 for
// y-bar, the same excess as in the 1 nm table), so the tolerance is 5e-4, not 1e-4.
BOOST_AUTO_TEST_CASE(x_y_z_integrals_are_equal) {
  const WavelengthGrid grid = WavelengthGrid::uniform(360, 830, 5);
  const SpectrumD ones = SpectrumD::Ones(grid.size());
  const Eigen::Vector3d xyz = SpectrumToXyz(grid)(ones);
  BOOST_TEST(relative(xyz.y(), 106.856895) < 1e-5);
  BOOST_TEST(relative(xyz.x(), xyz.y()) < 5e-4);
  BOOST_TEST(relative(xyz.z(), xyz.y()) < 5e-4);
}

BOOST_AUTO_TEST_SUITE_END()

// ------------------------------------------------------------------------------------------------
BOOST_AUTO_TEST_SUITE(spectrum_to_xyz)

BOOST_AUTO_TEST_CASE(equal_energy_spectrum_is_white) {
  {
    const WavelengthGrid grid = WavelengthGrid::uniform(360, 830, 5);
    const SpectrumD ones = SpectrumD::Ones(grid.size());
    const Eigen::Vector2d xy = xy_chromaticity(SpectrumToXyz(grid)(ones));
    BOOST_TEST(std::abs(xy.x() - 1.0 / 3.0) < 1e-4);
    BOOST_TEST(std::abs(xy.y() - 1.0 / 3.0) < 1e-4);
  }
  {
    const WavelengthGrid grid = WavelengthGrid::uniform(380, 780, 10);
    const SpectrumD ones = SpectrumD::Ones(grid.size());
    const Eigen::Vector2d xy = xy_chromaticity(SpectrumToXyz(grid)(ones));
    BOOST_TEST(std::abs(xy.x() - 1.0 / 3.0) < 2e-3);
    BOOST_TEST(std::abs(xy.y() - 1.0 / 3.0) < 2e-3);
  }
}

// On a grid made of table points (here every other one) the exact integral is, per 5 nm table
// interval [a, b] where spectrum f and CMF g are both linear,
//   integral f g = (b - a) / 6 (2 f_a g_a + f_a g_b + f_b g_a + 2 f_b g_b),
// with f at the odd table points interpolated from the grid. Computed here independently.
BOOST_AUTO_TEST_CASE(subset_grid_matches_closed_form_on_the_table) {
  const CmfTable& t = cie1931_2deg();
  const WavelengthGrid grid = WavelengthGrid::uniform(400, 700, 10);
  const SpectrumD s = sample(grid, smooth_spectrum);
  const std::vector<double> s_values(s.data(), s.data() + s.size());
  const Eigen::Vector3d xyz = SpectrumToXyz(grid)(s);
  for (int c = 0; c < 3; ++c) {
    const std::vector<double>& g = cmf_column(t, c);
    double expected = 0.0;
    for (size_t i = 1; i < t.nm.size(); ++i) {
      const double a = t.nm[i - 1], b = t.nm[i];
      if (a < 400 || b > 700) continue;
      const double fa = interpolate(grid.nanometres(), s_values, a);
      const double fb = interpolate(grid.nanometres(), s_values, b);
      expected += (b - a) / 6.0 * (2 * fa * g[i - 1] + fa * g[i] + fb * g[i - 1] + 2 * fb * g[i]);
    }
    BOOST_TEST(relative(xyz[c], expected) < 1e-12);
  }
}

// A grid that is the table's own points: the exact integral equals the trapezoid sum of
// spectrum x CMF over the table plus, per interval, -(b - a) / 6 (f_b - f_a)(g_b - g_a) (the
// trapezoid rule's error for a product of two linear functions). With the correction the two agree
// to rounding; without it to 1e-3 for this smooth spectrum (the CMFs change by up to 0.3 per 5 nm).
BOOST_AUTO_TEST_CASE(table_grid_matches_trapezoid_integration) {
  const CmfTable& t = cie1931_2deg();
  const WavelengthGrid grid = WavelengthGrid::uniform(400, 700, 5);
  const SpectrumD s = sample(grid, smooth_spectrum);
  const Eigen::Vector3d xyz = SpectrumToXyz(grid)(s);
  for (int c = 0; c < 3; ++c) {
    const std::vector<double>& g = cmf_column(t, c);
    double trapezoid = 0.0, correction = 0.0;
    for (size_t i = 1; i < t.nm.size(); ++i) {
      const double a = t.nm[i - 1], b = t.nm[i];
      if (a < 400 || b > 700) continue;
      const double fa = smooth_spectrum(a), fb = smooth_spectrum(b);
      trapezoid += (b - a) / 2.0 * (fa * g[i - 1] + fb * g[i]);
      correction -= (b - a) / 6.0 * (fb - fa) * (g[i] - g[i - 1]);
    }
    BOOST_TEST(relative(xyz[c], trapezoid) < 1e-3);
    BOOST_TEST(relative(xyz[c], trapezoid + correction) < 1e-12);
  }
}

// Off-table grid points: compare with brute-force midpoint integration of the product of the two
// piecewise-linear functions on a 0.005 nm mesh.
BOOST_AUTO_TEST_CASE(irregular_grid_matches_brute_force_integration) {
  const CmfTable& t = cie1931_2deg();
  const WavelengthGrid grid = WavelengthGrid::from_list(
      {361.3, 377.8, 402.5, 431.0, 455.55, 498.2, 530.0, 561.7, 604.4, 650.1, 702.9, 755.0, 801.25, 829.9});
  const SpectrumD s = sample(grid, smooth_spectrum);
  const std::vector<double> s_values(s.data(), s.data() + s.size());
  const Eigen::Vector3d xyz = SpectrumToXyz(grid)(s);
  constexpr double kStep_nm = 0.005;
  Eigen::Vector3d brute = Eigen::Vector3d::Zero();
  for (double lambda = grid.min_nm() + kStep_nm / 2; lambda < grid.max_nm(); lambda += kStep_nm) {
    const double f = interpolate(grid.nanometres(), s_values, lambda);
    for (int c = 0; c < 3; ++c) brute[c] += kStep_nm * f * interpolate(t.nm, cmf_column(t, c), lambda);
  }
  for (int c = 0; c < 3; ++c) BOOST_TEST(relative(xyz[c], brute[c]) < 1e-6);
}

// A narrow triangle (+-1 nm) at 555 nm has nearly the chromaticity of the 555 nm table row,
// (x, y) = (0.5120501, 1) / (0.5120501 + 1 + 0.005749999) = (0.33736, 0.65885).
BOOST_AUTO_TEST_CASE(narrow_line_lies_on_the_spectral_locus) {
  const CmfTable& t = cie1931_2deg();
  const size_t row = (555 - 360) / 5;
  const Eigen::Vector2d locus = xy_chromaticity(Eigen::Vector3d(t.x[row], t.y[row], t.z[row]));
  BOOST_TEST(std::abs(locus.x() - 0.33736) < 1e-5);
  BOOST_TEST(std::abs(locus.y() - 0.65885) < 1e-5);

  const WavelengthGrid grid = WavelengthGrid::from_list({554, 555, 556});
  SpectrumD line(3);
  line << 0.0, 1.0, 0.0;
  const Eigen::Vector2d xy = xy_chromaticity(SpectrumToXyz(grid)(line));
  BOOST_TEST(std::abs(xy.x() - locus.x()) < 5e-4);
  BOOST_TEST(std::abs(xy.y() - locus.y()) < 5e-4);
}

BOOST_AUTO_TEST_CASE(scale_and_float_spectra) {
  const WavelengthGrid grid = WavelengthGrid::uniform(380, 780, 10);
  const SpectrumD s = sample(grid, smooth_spectrum);
  const Spectrum s_float = s.cast<float>();
  const SpectrumToXyz unit(grid), luminous(grid, 683.0);
  BOOST_TEST(relative(luminous(s).y(), 683.0 * unit(s).y()) < 1e-12);
  BOOST_TEST(relative(unit(s_float).y(), unit(s).y()) < 1e-6);
  BOOST_TEST(unit.weights().cols() == grid.size());
  BOOST_CHECK_THROW(unit(SpectrumD(SpectrumD::Ones(3))), Error);
}

BOOST_AUTO_TEST_CASE(grids_that_cannot_be_integrated_are_rejected) {
  const auto setting_is_spectrum = [](const InputError& e) { return e.setting() == "spectrum"; };
  BOOST_CHECK_EXCEPTION((void)SpectrumToXyz(WavelengthGrid::from_list({550})), InputError, setting_is_spectrum);
  BOOST_CHECK_NO_THROW((void)SpectrumToXyz(WavelengthGrid::uniform(360, 830, 10)));
}

// Beyond the CMF table (360-830 nm) the CMFs count as zero: a grid reaching into the ultraviolet or
// infrared gives the colour of its overlap, and one entirely outside it has none.
BOOST_AUTO_TEST_CASE(colour_comes_from_the_overlap_with_the_cmfs) {
  const WavelengthGrid visible = WavelengthGrid::uniform(360, 830, 10);
  const WavelengthGrid wide = WavelengthGrid::uniform(280, 1060, 10);
  const SpectrumToXyz to_visible(visible), to_wide(wide);
  SpectrumD on_visible(visible.size()), on_wide(wide.size());
  for (int i = 0; i < visible.size(); ++i) on_visible[i] = smooth_spectrum(visible.nm(i));
  for (int i = 0; i < wide.size(); ++i) on_wide[i] = smooth_spectrum(wide.nm(i));
  const Eigen::Vector3d a = to_visible(on_visible), b = to_wide(on_wide);
  // The same samples inside 360-830 nm; the hats of 360 and 830 nm reach 10 nm beyond, where the
  // CMFs are zero, so the two agree to the table's end values (1e-4 of the peak).
  for (int c = 0; c < 3; ++c) BOOST_TEST(std::abs(b[c] / a[c] - 1.0) < 1e-4, "component " << c);
  // Ultraviolet only: no colour.
  const WavelengthGrid uv = WavelengthGrid::uniform(280, 350, 10);
  BOOST_TEST(SpectrumToXyz(uv).weights().cwiseAbs().maxCoeff() == 0.0);
}

BOOST_AUTO_TEST_SUITE_END()

// ------------------------------------------------------------------------------------------------
BOOST_AUTO_TEST_SUITE(rec709)

// The matrix derived from the primaries and white xy (0.3127, 0.3290), as published to 10 digits
// (e.g. the "sRGB" article's higher-precision matrix; colour-science's sRGB colourspace).
BOOST_AUTO_TEST_CASE(matrix_matches_published_derivation) {
  const Eigen::Matrix3d m = xyz_to_linear_rec709();
  const double expected[3][3] = {{3.2409699419, -1.5373831776, -0.4986107603},
                                 {-0.9692436363, 1.8759675015, 0.0415550574},
                                 {0.0556300797, -0.2039769589, 1.0569715142}};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) BOOST_TEST(std::abs(m(r, c) - expected[r][c]) < 1e-9);
}

// IEC 61966-2-1 prints the matrix to 4 decimals (3.2406, -1.5372, -0.4986, ...), computed from the
// white rounded to XYZ (0.9505, 1, 1.0890); the exact derivation differs from it by up to 3.7e-4
// (the first element: 3.24097 against 3.2406), so these printed figures are checked to 5e-4.
BOOST_AUTO_TEST_CASE(matrix_matches_iec_61966_2_1_to_printed_precision) {
  const Eigen::Matrix3d m = xyz_to_linear_rec709();
  const double iec[3][3] = {{3.2406, -1.5372, -0.4986}, {-0.9689, 1.8758, 0.0415}, {0.0557, -0.2040, 1.0570}};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) BOOST_TEST(std::abs(m(r, c) - iec[r][c]) < 5e-4);
  // ITU-R BT.709 luminance coefficients: the Y row of RGB -> XYZ.
  const Eigen::Matrix3d to_xyz = linear_rec709_to_xyz();
  BOOST_TEST(std::abs(to_xyz(1, 0) - 0.2126) < 1e-4);
  BOOST_TEST(std::abs(to_xyz(1, 1) - 0.7152) < 1e-4);
  BOOST_TEST(std::abs(to_xyz(1, 2) - 0.0722) < 1e-4);
}

BOOST_AUTO_TEST_CASE(matrices_are_inverse_and_reproduce_the_primaries) {
  const Eigen::Matrix3d to_xyz = linear_rec709_to_xyz();
  BOOST_TEST((to_xyz * xyz_to_linear_rec709() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-12);
  const Chromaticities c = rec709_chromaticities();
  const double* primaries[3] = {c.red, c.green, c.blue};
  for (int p = 0; p < 3; ++p) {
    const Eigen::Vector2d xy = xy_chromaticity(to_xyz.col(p));
    BOOST_TEST(std::abs(xy.x() - primaries[p][0]) < 1e-12);
    BOOST_TEST(std::abs(xy.y() - primaries[p][1]) < 1e-12);
  }
  BOOST_TEST(c.white[0] == 0.3127);
  BOOST_TEST(c.white[1] == 0.3290);
}

// White at the standard's chromaticity maps to RGB = (1, 1, 1) exactly. The commonly quoted D65
// XYZ (0.95047, 1, 1.08883) is D65 integrated with the 1931 observer, xy (0.31271, 0.32902): its
// RGB are equal to 4e-4 (1.00016, 0.99998, 0.99976), hence that tolerance.
BOOST_AUTO_TEST_CASE(d65_white_maps_to_equal_rgb) {
  const Eigen::Matrix3d m = xyz_to_linear_rec709();
  const Eigen::Vector3d standard_white(0.3127 / 0.3290, 1.0, (1.0 - 0.3127 - 0.3290) / 0.3290);
  BOOST_TEST(((m * standard_white).array() - 1.0).abs().maxCoeff() < 1e-12);
  const Eigen::Vector3d rgb = m * Eigen::Vector3d(0.95047, 1.0, 1.08883);
  BOOST_TEST(rgb.maxCoeff() - rgb.minCoeff() < 5e-4);
  BOOST_TEST(std::abs(rgb.y() - 1.0) < 1e-4);
}

BOOST_AUTO_TEST_SUITE_END()

// ------------------------------------------------------------------------------------------------
BOOST_AUTO_TEST_SUITE(transfer_and_chromaticity)

BOOST_AUTO_TEST_CASE(srgb_encode_known_values) {
  BOOST_TEST(srgb_encode(0.0) == 0.0);
  BOOST_TEST(srgb_encode(1.0) == 1.0);
  BOOST_TEST(srgb_encode(-0.5) == 0.0);
  BOOST_TEST(srgb_encode(7.0) == 1.0);
  BOOST_TEST(srgb_encode(std::nan("")) == 0.0);
  // Linear segment below the break point, 12.92 L.
  BOOST_TEST(std::abs(srgb_encode(0.001) - 0.01292) < 1e-12);
  // At the break point 0.0031308 both pieces give 0.04045 (to 3e-8: the standard's rounding).
  BOOST_TEST(std::abs(srgb_encode(0.0031308) - 0.0404500) < 1e-6);
  // Continuous there: a step of 1e-7 in L moves V by about 12.9e-7 on either side.
  BOOST_TEST(std::abs(srgb_encode(0.0031309) - srgb_encode(0.0031308)) < 1.5e-6);
  // 18 % grey: 1.055 * 0.18^(1/2.4) - 0.055 = 0.461356.
  BOOST_TEST(std::abs(srgb_encode(0.18) - 0.4613561) < 1e-7);
  BOOST_TEST(std::abs(srgb_encode(0.5) - 0.7353570) < 1e-7);
}

BOOST_AUTO_TEST_CASE(chromaticity_of_xyz) {
  const Eigen::Vector2d xy = xy_chromaticity(Eigen::Vector3d(1.0, 2.0, 1.0));
  BOOST_TEST(xy.x() == 0.25);
  BOOST_TEST(xy.y() == 0.5);
  BOOST_TEST(xy_chromaticity(Eigen::Vector3d::Zero()).norm() == 0.0);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE_END()  // test_colour
