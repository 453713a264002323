// atan2 for the per-pixel hot path: a polynomial, cheaper than libm's correctly rounded one.
//
// Octant reduction to a = min(|x|, |y|) / max(|x|, |y|) in [0, 1], then atan(a) by an odd
// polynomial of degree 19 fitted to atan on [0, 1] for the smallest largest error (Lawson's
// iteratively reweighted least squares on 6000 Chebyshev nodes). Its largest
// error is 8.9e-10 rad (tests/base/test_fast_atan2.cpp checks 1e-9 over all quadrants): two hundred
// times finer than anything the sky-view table resolves (its finest row spacing is about 1e-4
// rad), and far coarser than libm's, so it is used only where angles index a table.
#pragma once

#include <cmath>

#include "skyspec/units.hpp"

namespace skyspec::detail {

inline double atan_unit(double a) {  // atan(a) for a in [0, 1]
  const double a2 = a * a;
  double p = -0.001509301664000276;
  p = p * a2 + 0.0095673335430355722;
  p = p * a2 - 0.028490763536065923;
  p = p * a2 + 0.055028088310375076;
  p = p * a2 - 0.082137609358935854;
  p = p * a2 + 0.10878009656412686;
  p = p * a2 - 0.14247222621895667;
  p = p * a2 + 0.19996436807012852;
  p = p * a2 - 0.333331803766449;
  p = p * a2 + 0.99999998056029582;
  return p * a;
}

/// atan2(y, x) in [-pi, pi] to within 1e-9 rad; 0 for (0, 0) as std::atan2 (signed zeros aside).
/// Selects only, no branches, so that loops over many angles vectorise.
inline double fast_atan2(double y, double x) {
  constexpr double kHalfPi = 0.5 * kPi;
  const double ax = std::abs(x), ay = std::abs(y);
  const double hi = ax > ay ? ax : ay, lo = ax > ay ? ay : ax;
  double t = atan_unit(lo / (hi > 0.0 ? hi : 1.0));  // (0, 0): 0
  t = ay > ax ? kHalfPi - t : t;                     // |y| > |x|: atan(|y|/|x|) = pi/2 - atan(|x|/|y|)
  t = x < 0.0 ? kPi - t : t;
  return y < 0.0 ? -t : t;
}

}  // namespace skyspec::detail
