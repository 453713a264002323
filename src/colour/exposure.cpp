// Exposure rules: manual EV, ISO 12232 saturation-based camera exposure, metered key value.
#include "colour/exposure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "base/text_format.hpp"
#include "skyspec/error.hpp"

namespace skyspec {
namespace {

void require_positive(double v, const char* flag, const char* what) {
  if (!std::isfinite(v) || v <= 0.0) throw InputError(flag, format_number(v), what);
}

std::string printf_string(const char* format, double a, double b = 0, double c = 0, double d = 0, double e = 0) {
  char text[256];
  std::snprintf(text, sizeof text, format, a, b, c, d, e);
  return text;
}

}  // namespace

double camera_ev100(double f_number, double shutter_s, double iso) {
  require_positive(f_number, display_setting::kFNumber, "a positive f-number, e.g. 8");
  require_positive(shutter_s, display_setting::kShutter, "a positive time in seconds, e.g. 1/250 or 0.004");
  require_positive(iso, display_setting::kIso, "a positive ISO speed, e.g. 100");
  return std::log2(f_number * f_number / shutter_s * 100.0 / iso);
}

double camera_exposure_scale(double f_number, double shutter_s, double iso) {
  // L_max = 78 / (S q) * N^2 / t with q = 0.65: 78 / (100 * 0.65) = 1.2 at S = 100.
  return 1.0 / (1.2 * std::exp2(camera_ev100(f_number, shutter_s, iso)));
}

std::vector<std::pair<int, int>> metering_pixels(int width, int height) {
  std::vector<std::pair<int, int>> pixels;
  if (width <= 0 || height <= 0) return pixels;
  const int longest = std::max(width, height);
  const int step = (longest + kMeteringGridMax - 1) / kMeteringGridMax;
  for (int y = step / 2; y < height; y += step)
    for (int x = step / 2; x < width; x += step) pixels.emplace_back(x, y);
  return pixels;
}

double key_exposure_scale(const std::vector<double>& luminance) {
  std::vector<double> positive;
  positive.reserve(luminance.size());
  for (double v : luminance)
    if (v > 0.0 && std::isfinite(v)) positive.push_back(v);
  if (positive.empty()) return 1.0;
  // Only values within a factor 100 of the 90th percentile count, so that dark ground or the
  // night side does not drag the exposure of the sky up.
  std::vector<double> sorted = positive;
  const size_t k = sorted.size() * 9 / 10;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(k), sorted.end());
  const double floor = 0.01 * sorted[k];
  double sum_log = 0.0;
  size_t count = 0;
  for (double v : positive)
    if (v >= floor) {
      sum_log += std::log(v);
      ++count;
    }
  return kAutoExposureKey / std::exp(sum_log / static_cast<double>(count));
}

double metered_exposure_scale(const std::vector<float>& linear_rgb, int width, int height) {
  std::vector<double> luminance;
  for (const auto& [x, y] : metering_pixels(width, height)) {
    const size_t i = (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 3;
    if (i + 2 < linear_rgb.size()) luminance.push_back(rec709_luminance(&linear_rgb[i]));
  }
  return key_exposure_scale(luminance);
}

ResolvedExposure resolve_exposure(const ExposureSettings& s, double metered_scale) {
  ResolvedExposure r;
  r.mode = s.mode;
  switch (s.mode) {
    case ExposureSettings::Mode::Manual:
      if (!std::isfinite(s.ev) || std::abs(s.ev) > 200.0)
        throw InputError(display_setting::kExposureEv, format_number(s.ev), "an exposure in EV from -200 to 200");
      r.scale = std::exp2(s.ev);
      r.description = printf_string("manual: scale = 2^EV = %.6g (EV %.4g)", r.scale, s.ev);
      break;
    case ExposureSettings::Mode::Camera: {
      const double ev100 = camera_ev100(s.f_number, s.shutter_s, s.iso);
      r.scale = camera_exposure_scale(s.f_number, s.shutter_s, s.iso);
      r.description = printf_string(
          "camera: f/%.4g, %.6g s, ISO %.6g: EV100 = %.4f, saturation luminance 1.2 * 2^EV100 = %.6g cd/m^2 -> 1",
          s.f_number, s.shutter_s, s.iso, ev100, 1.0 / r.scale);
      break;
    }
    case ExposureSettings::Mode::Automatic:
      if (!std::isfinite(metered_scale) || metered_scale <= 0.0)
        throw Error("internal error: the metered exposure is not a positive number");
      r.scale = metered_scale;
      r.description =
          printf_string("automatic: log-average luminance of the metered pixels -> 0.18, scale = %.6g (EV %.4g)",
                        r.scale, std::log2(r.scale));
      break;
  }
  r.ev = std::log2(r.scale);
  return r;
}

}  // namespace skyspec
