// Exposure: the factor that takes an image's scene-linear values to the display pipeline's input.
//
// After exposure, scene-linear 1.0 is what the "Un-tone-mapped" view shows as the display's white
// and what the ACES output transforms treat as scene value 1.0 (mid-grey is 0.18). Three ways to
// choose it:
//   - manual: scale = 2^EV (EV = 0 passes the values through; for spectral renders they are in
//     cd m^-2, so EV = 0 makes 1 cd m^-2 white);
//   - camera: a physical camera with ISO speed S, shutter time t and f-number N, through the
//     saturation-based sensitivity of ISO 12232:2006 as Lagarde & de Rousiers 2014 ("Moving
//     Frostbite to physically based rendering", SIGGRAPH 2014 course notes) write it:
//       EV100 = log2(N^2 / t * 100 / S),   L_max = 78 / (S q) * N^2 / t = 1.2 * 2^EV100 cd m^-2
//     (q = 0.65 lens and vignetting attenuation), and the luminance L_max that just saturates the
//     sensor is mapped to 1: scale = 1 / L_max. Meaningful for spectral renders (cd m^-2);
//   - automatic: the log-average ("key") luminance of the image is mapped to 0.18 (Reinhard et al.
//     2002, "Photographic tone reproduction for digital images", eq. 1 with key a = 0.18), metered
//     on a grid of at most 64 x 64 of the image's pixels, over the pixels no darker than 1/100 of
//     their 90th percentile (so that dark ground and the night side do not count).
// Luminance is Y = 0.2126 R + 0.7152 G + 0.0722 B of linear Rec.709 (ITU-R BT.709 / sRGB).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "skyspec/display.hpp"

namespace skyspec {

/// The chosen exposure: its scale, log2(scale), and one sentence saying how it was chosen.
struct ResolvedExposure {
  ExposureSettings::Mode mode = ExposureSettings::Mode::Automatic;
  double scale = 1.0;
  double ev = 0.0;
  std::string description;
};

constexpr double kAutoExposureKey = 0.18;
constexpr int kMeteringGridMax = 64;

/// EV100 = log2(N^2 / t * 100 / S). Throws InputError(display.exposure.f_number / shutter_s / iso, ...)
/// for a non-positive or non-finite value.
double camera_ev100(double f_number, double shutter_s, double iso);
/// 1 / (1.2 * 2^EV100): the scale that maps the saturating luminance to 1.
double camera_exposure_scale(double f_number, double shutter_s, double iso);

/// Luminance of a linear Rec.709 triple: Y = these weights . (R, G, B) (ITU-R BT.709).
inline constexpr double kRec709LuminanceWeights[3] = {0.2126, 0.7152, 0.0722};
inline double rec709_luminance(const float* rgb) {
  return kRec709LuminanceWeights[0] * rgb[0] + kRec709LuminanceWeights[1] * rgb[1] +
         kRec709LuminanceWeights[2] * rgb[2];
}

/// The metered pixels (x, y) of a width x height image: every k-th column and row, k =
/// ceil(max(width, height) / 64), starting at k / 2 (all pixels when both sides are <= 64).
std::vector<std::pair<int, int>> metering_pixels(int width, int height);

/// The automatic rule on a set of luminances: 0.18 / exp(mean log Y) over the values within a
/// factor 100 of the 90th percentile; 1 when no value is positive.
double key_exposure_scale(const std::vector<double>& luminance);

/// The automatic exposure of a linear Rec.709 image in memory ([y][x][c]), metered on
/// metering_pixels(width, height).
double metered_exposure_scale(const std::vector<float>& linear_rgb, int width, int height);

/// Resolves the settings; for Automatic, metered_scale is the metered value (callers meter the
/// image they have: an image in memory, or a renderer's directions before rendering).
ResolvedExposure resolve_exposure(const ExposureSettings& settings, double metered_scale);

}  // namespace skyspec
