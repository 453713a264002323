// RGB-fast vs spectral: how far the classic three-wavelength RGB sky is from the spectral one.
//
// The RGB-fast path (the seed tutorial, Nishita et al. 1993 and most real-time sky code) computes
// radiance at 680, 550 and 440 nm and reads the three numbers as linear RGB. The spectral path
// integrates the whole spectrum against the CIE 1931 colour-matching functions. To compare them
// colorimetrically both must be put on a common white and exposure; the rules (also printed in
// every report, see comparison_rules()):
//
//   1. Common white and luminance scale: the extraterrestrial sun. Each image is divided by the
//      luminance of its own sun, computed through the same conversion as its pixels (R, G, B of
//      the sun's spectral irradiance: for the spectral path via XYZ, for the RGB-fast path its
//      680/550/440 nm values), and chromatically adapted (Bradford) from the sun's colour to D65.
//      The RGB-fast path treats sunlight as RGB white, so after this both images describe the sky
//      as lit by a sun of D65 colour and unit luminance: the spectral path's spectral shape of the
//      sun is kept, its overall colour cast (e.g. equal-energy vs D65 for a flat sun) is not
//      counted as an error.
//   2. Common exposure: both images are multiplied by the automatic exposure of the reference
//      (spectral) image (exposure.hpp: its log-average luminance over the compared pixels -> 0.18),
//      and CIELAB uses the D65 white at luminance 1 after that: L* = 100 is the display white of
//      the un-tone-mapped view; brighter pixels (near the sun) have L* > 100.
//   3. Compared pixels: view direction at or above the horizon, inside the image. Regions, in this
//      order (a pixel belongs to the first that matches): near the sun (angular distance to the
//      sun's centre below near_sun_deg), horizon band (elevation below horizon_deg), zenith
//      (zenith angle below zenith_deg), the rest.
//   4. Per pixel: CIEDE2000 (ciede2000.hpp, k_L = k_C = k_H = 1) and the relative luminance error
//      (Y_test - Y_reference) / Y_reference (pixels with Y_reference > 0).
//   5. Statistics: mean, median and 95th percentile (linear interpolation between order
//      statistics), maximum, and the share of pixels with Delta E_00 above 1, 2 and 5.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "skyspec/render.hpp"
#include "skyspec/scene.hpp"

namespace skyspec {

enum class SkyRegion : uint8_t { NearSun = 0, Horizon = 1, Zenith = 2, Rest = 3 };
constexpr uint8_t kNotCompared = 255;
/// "near the sun", "horizon band", "zenith", "the rest".
std::string to_string(SkyRegion region);
/// "near_sun", "horizon", "zenith", "rest" (JSON keys).
std::string region_key(SkyRegion region);

struct RegionSettings {
  double near_sun_deg = 10.0;
  double horizon_deg = 10.0;
  double zenith_deg = 20.0;
};

/// The view direction of every pixel (the scene's camera), relative to the horizon and the sun.
struct PixelGeometry {
  int width = 0, height = 0;
  std::vector<float> elevation_deg, sun_angle_deg;
  std::vector<uint8_t> region;  ///< SkyRegion, or kNotCompared (below the horizon, outside the image)
};
PixelGeometry pixel_geometry(const Scene& scene, const RegionSettings& regions = {});

/// An image to compare: skyspec's R, G, B and its sun.
struct SkyImage {
  int width = 0, height = 0;
  std::vector<float> rgb;                             ///< linear Rec.709 as skyspec writes it ([y][x][c])
  Eigen::Vector3d sun_rgb = Eigen::Vector3d::Ones();  ///< the sun's irradiance through the same conversion
  std::string path;                                   ///< "spectral" or "rgb-fast"
  std::string label;  ///< for reports, e.g. "spectral (41 samples, 380-780 nm, 10 nm step)"
};

/// Renders a scene into memory (without its spectral channels).
SkyImage render_sky_image(const Scene& scene, const ProgressFn& progress = {});
/// Reads an EXR written by `skyspec render` (R, G, B and the skyspec:sunRGB, skyspec:renderPath
/// and skyspec:scene attributes); the scene it records is returned in *scene. IoError/InputError
/// naming the file when something is missing.
SkyImage read_sky_image(const std::filesystem::path& path, Scene* scene);

/// The RGB-fast twin of a scene: the same atmosphere, sun and camera on 440/550/680 nm with
/// render.path = "rgb-fast" (fixed Rayleigh coefficients must list those wavelengths).
Scene rgb_fast_twin(const Scene& scene);
/// The spectral twin: the same atmosphere, sun and camera on 380-780 nm in 10 nm steps with
/// render.path = "spectral". Fixed Rayleigh coefficients (the seed preset's typed-in three) are
/// extended over the grid with the lambda^-4 law fitted to them (least squares in log space); *note
/// says so with the fitted constant and how well it reproduces the typed-in values.
Scene spectral_twin(const Scene& scene, std::string* note = nullptr);

struct DeltaEStats {
  size_t pixels = 0;
  double mean = 0, median = 0, p95 = 0, max = 0;
  double share_above_1 = 0, share_above_2 = 0, share_above_5 = 0;
};
struct LuminanceErrorStats {
  size_t pixels = 0;
  double mean = 0;  ///< signed
  double median_abs = 0, p95_abs = 0, max_abs = 0;
};
struct RegionStats {
  DeltaEStats delta_e;
  LuminanceErrorStats luminance;
};

struct SkyComparison {
  int width = 0, height = 0;
  std::vector<float> delta_e;          ///< per pixel, 0 where not compared
  std::vector<float> luminance_error;  ///< per pixel, relative, 0 where not compared
  std::vector<uint8_t> region;         ///< SkyRegion or kNotCompared
  RegionStats all;
  std::array<RegionStats, 4> regions;  ///< indexed by SkyRegion
  double exposure_scale = 1.0;         ///< rule 2's factor on sun-relative luminance
  /// Both images after rules 1 and 2, as linear Rec.709 (display white = 1), for previews.
  std::vector<float> reference_rgb, test_rgb;
};

/// Compares test against reference (same size as the geometry). InputError if the sizes differ.
SkyComparison compare_skies(const SkyImage& reference, const SkyImage& test, const PixelGeometry& geometry);

/// Statistics of per-pixel values (percentiles by linear interpolation between order statistics).
DeltaEStats delta_e_stats(std::vector<double> values);

/// The rules above as Markdown bullet points, with the region limits filled in.
std::string comparison_rules(const RegionSettings& regions);

/// One sun elevation of a sweep.
struct SweepPoint {
  double sun_elevation_deg = 0;
  RegionStats all;
  std::array<RegionStats, 4> regions;
};

}  // namespace skyspec
