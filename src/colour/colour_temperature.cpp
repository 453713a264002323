// Correlated colour temperature from its definition; see colour_temperature.hpp.
#include "colour/colour_temperature.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "skyspec/colour.hpp"

namespace skyspec {
namespace {

/// Second radiation constant, m K (CIE 015:2004, ITS-90).
constexpr double kSecondRadiationConstant_m_K = 1.4388e-2;
/// The search range in reciprocal megakelvin ("mired"): 1000 K to 1e6 K.
constexpr double kMinMired = 1.0, kMaxMired = 1000.0;
constexpr int kCoarseSteps = 2000;
/// CIE 015: beyond |Duv| = 0.05 a correlated colour temperature is not meaningful.
constexpr double kMaxDuv = 0.05;

double distance_to_locus(const Eigen::Vector2d& uv, double mired) {
  return (planckian_uv_1960(1e6 / mired) - uv).norm();
}

}  // namespace

Eigen::Vector2d uv_1960(const Eigen::Vector3d& xyz) {
  const double d = xyz[0] + 15.0 * xyz[1] + 3.0 * xyz[2];
  return {4.0 * xyz[0] / d, 6.0 * xyz[1] / d};
}

// Planck's law up to a constant factor (it cancels in the chromaticity), summed at the table's
// 5 nm points as CIE 015 computes tristimulus values.
Eigen::Vector2d planckian_uv_1960(double temperature_K) {
  const CmfTable& cmf = cie1931_2deg();
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < cmf.nm.size(); ++i) {
    const double lambda_m = cmf.nm[i] * 1e-9;
    const double m = std::pow(lambda_m, -5.0) / std::expm1(kSecondRadiationConstant_m_K / (lambda_m * temperature_K));
    xyz += m * Eigen::Vector3d(cmf.x[i], cmf.y[i], cmf.z[i]);
  }
  return uv_1960(xyz);
}

std::optional<ColourTemperature> correlated_colour_temperature(const Eigen::Vector3d& xyz) {
  const double d = xyz[0] + 15.0 * xyz[1] + 3.0 * xyz[2];
  if (!(d > 0.0) || !std::isfinite(d) || !xyz.allFinite()) return std::nullopt;
  const Eigen::Vector2d uv = uv_1960(xyz);
  // Coarse scan in mired (the locus is evenly spread in reciprocal temperature), then golden
  // section on the bracket around the nearest scan point.
  const double step = (kMaxMired - kMinMired) / kCoarseSteps;
  int best = 0;
  double best_distance = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= kCoarseSteps; ++k) {
    const double dist = distance_to_locus(uv, kMinMired + k * step);
    if (dist < best_distance) best_distance = dist, best = k;
  }
  double lo = kMinMired + std::max(0, best - 1) * step, hi = kMinMired + std::min(kCoarseSteps, best + 1) * step;
  const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = hi - ratio * (hi - lo), b = lo + ratio * (hi - lo);
  double fa = distance_to_locus(uv, a), fb = distance_to_locus(uv, b);
  while (hi - lo > 1e-9) {
    if (fa < fb) {
      hi = b, b = a, fb = fa;
      a = hi - ratio * (hi - lo), fa = distance_to_locus(uv, a);
    } else {
      lo = a, a = b, fa = fb;
      b = lo + ratio * (hi - lo), fb = distance_to_locus(uv, b);
    }
  }
  const double mired = 0.5 * (lo + hi);
  const Eigen::Vector2d on_locus = planckian_uv_1960(1e6 / mired);
  // The sign: the vector to the nearest locus point is normal to the locus, which runs mostly
  // along u, so "above" (positive Duv) is the side of larger v.
  const double duv = std::copysign((uv - on_locus).norm(), uv[1] - on_locus[1]);
  if (std::abs(duv) > kMaxDuv) return std::nullopt;
  return ColourTemperature{1e6 / mired, duv};
}

}  // namespace skyspec
