// Colour science: CIE colour-matching functions, spectrum -> XYZ, XYZ -> linear Rec.709, sRGB.
//
// Spectra are integrated against the CIE 1931 2-degree observer exactly for the chosen wavelength
// grid: the sampled spectrum is taken as the piecewise-linear interpolant of its samples on
// [lambda_min, lambda_max] (zero outside), the CMFs as the piecewise-linear interpolant of their
// 5 nm table, and the integral of the product is evaluated in closed form. The result is a fixed
// 3 x n weight matrix, so XYZ = W L is one small matrix-vector product per pixel.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "skyspec/spectrum.hpp"

namespace skyspec {

/// A colour-matching-function table: wavelengths (nm) and x-bar, y-bar, z-bar values.
struct CmfTable {
  std::vector<double> nm, x, y, z;
};
/// CIE 1931 2-degree standard observer, 360-830 nm at 5 nm (data/cie/, see data/README.md).
const CmfTable& cie1931_2deg();

/// Linear map from a spectrum on a grid to CIE XYZ.
class SpectrumToXyz {
 public:
  /// scale multiplies the integral: with scale = 683 lm/W and spectral radiance in
  /// W m^-2 sr^-1 nm^-1, Y is luminance in cd m^-2. Throws InputError("spectrum", ...) when the grid
  /// has fewer than 2 samples. Outside the CMF table (360-830 nm) the CMFs count as zero: a grid
  /// reaching into the ultraviolet or infrared gets the colour of its overlap with the table.
  explicit SpectrumToXyz(const WavelengthGrid& grid, double scale = 1.0);
  /// W (3 x n): XYZ = W * spectrum.
  const Eigen::Matrix<double, 3, Eigen::Dynamic>& weights() const { return w_; }
  Eigen::Vector3d operator()(const Spectrum& s) const;
  Eigen::Vector3d operator()(const SpectrumD& s) const;

 private:
  Eigen::Matrix<double, 3, Eigen::Dynamic> w_;
};

/// XYZ -> linear Rec.709 / sRGB primaries with D65 white (IEC 61966-2-1 matrix derived from the
/// primaries' chromaticities, so that D65 XYZ (0.95047, 1, 1.08883) maps to equal RGB).
Eigen::Matrix3d xyz_to_linear_rec709();
Eigen::Matrix3d linear_rec709_to_xyz();

/// Rec.709 primaries and D65 white as CIE xy chromaticities: red, green, blue, white.
struct Chromaticities {
  double red[2], green[2], blue[2], white[2];
};
Chromaticities rec709_chromaticities();

/// The sRGB transfer function (IEC 61966-2-1) applied to a linear value in [0, 1] (clamped).
double srgb_encode(double linear);

/// Chromaticity (x, y) of an XYZ triple; (0, 0) for black.
Eigen::Vector2d xy_chromaticity(const Eigen::Vector3d& xyz);

}  // namespace skyspec
