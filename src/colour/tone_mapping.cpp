// Tone-mapping operators (Reinhard et al. 2002; Hable 2010; Narkowicz 2016).
#include "colour/tone_mapping.hpp"

#include <algorithm>
#include <cmath>

#include "colour/exposure.hpp"
#include "skyspec/error.hpp"

namespace skyspec {

const std::vector<std::string>& tone_operator_names() {
  static const std::vector<std::string> names = {"reinhard", "reinhard-extended", "reinhard-luminance",
                                                 "uncharted2-filmic", "aces-approx"};
  return names;
}

std::optional<ToneOperator> tone_operator_from_name(const std::string& name) {
  static const ToneOperator ops[] = {ToneOperator::Reinhard, ToneOperator::ReinhardExtended,
                                     ToneOperator::ReinhardLuminance, ToneOperator::Uncharted2Filmic,
                                     ToneOperator::AcesApprox};
  const auto& names = tone_operator_names();
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return ops[i];
  return std::nullopt;
}

std::string to_string(ToneOperator op) { return tone_operator_names()[static_cast<size_t>(op)]; }

// Reinhard et al. 2002, eq. 3.
double reinhard(double c) { return c / (1.0 + c); }

// Reinhard et al. 2002, eq. 4: L (1 + L / L_white^2) / (1 + L).
double reinhard_extended(double c, double white) { return c * (1.0 + c / (white * white)) / (1.0 + c); }

namespace {
// Hable's curve with his published constants: shoulder strength A, linear strength B, linear
// angle C, toe strength D, toe numerator E, toe denominator F.
double hable_curve(double x) {
  constexpr double A = 0.15, B = 0.50, C = 0.10, D = 0.20, E = 0.02, F = 0.30;
  return (x * (A * x + C * B) + D * E) / (x * (A * x + B) + D * F) - E / F;
}
}  // namespace

double uncharted2_filmic(double c) {
  constexpr double exposure_bias = 2.0, linear_white = 11.2;
  return hable_curve(exposure_bias * c) / hable_curve(linear_white);
}

double aces_approx_narkowicz(double c) {
  constexpr double a = 2.51, b = 0.03, cc = 2.43, d = 0.59, e = 0.14;
  const double x = 0.6 * c;
  return std::clamp(x * (a * x + b) / (x * (cc * x + d) + e), 0.0, 1.0);
}

double apply_tone_operator(ToneOperator op, std::vector<float>& rgb, std::optional<double> white) {
  for (float& v : rgb)
    if (!(v > 0.0f)) v = 0.0f;  // also NaN -> 0
  double w = 0.0;
  if (op == ToneOperator::ReinhardExtended || op == ToneOperator::ReinhardLuminance) {
    if (white) {
      if (!std::isfinite(*white) || *white <= 0.0)
        throw InputError(display_setting::kLookWhite, std::to_string(*white), "a positive scene-linear value");
      w = *white;
    } else {
      w = 1.0;
      for (size_t i = 0; i + 2 < rgb.size(); i += 3) w = std::max(w, rec709_luminance(&rgb[i]));
    }
  }
  const auto per_channel = [&rgb](auto f) {
    for (float& v : rgb) v = static_cast<float>(f(static_cast<double>(v)));
  };
  switch (op) {
    case ToneOperator::Reinhard:
      per_channel(reinhard);
      break;
    case ToneOperator::ReinhardExtended:
      per_channel([w](double c) { return reinhard_extended(c, w); });
      break;
    case ToneOperator::Uncharted2Filmic:
      per_channel(uncharted2_filmic);
      break;
    case ToneOperator::AcesApprox:
      per_channel(aces_approx_narkowicz);
      break;
    case ToneOperator::ReinhardLuminance:
      for (size_t i = 0; i + 2 < rgb.size(); i += 3) {
        const double y = rec709_luminance(&rgb[i]);
        if (y <= 0.0) continue;
        const double ratio = reinhard_extended(y, w) / y;
        for (int c = 0; c < 3; ++c)
          rgb[i + static_cast<size_t>(c)] = static_cast<float>(rgb[i + static_cast<size_t>(c)] * ratio);
      }
      break;
  }
  return w;
}

}  // namespace skyspec
