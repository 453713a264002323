// The quadrature rules of the integrators, in one place: the log-mean rule for integrands that are
// exponential in the path length between nodes, and the Richardson step that combines a rule on
// N pieces with the same rule on N/2 pieces.
//
// On a piece of length dt where f(t) = a exp(-(t / dt) x) runs from a to b = a exp(-x), the exact
// integral is dt (a - b) / x: the log-mean of a and b times dt. It is exact for an exponential
// density along a radial path and second order in dt otherwise, so the error of the composite
// rule is c dt^2 + O(dt^4); (4 I(dt) - I(2 dt)) / 3 cancels the c dt^2 term (Richardson 1911).
#pragma once

#include <algorithm>

#include <Eigen/Core>

namespace skyspec {

/// Log-mean of two positive values a, b given x = ln a - ln b: (a - b) / x, the exact integral
/// mean of an exponential through both (a when x -> 0). Used to integrate log-linear pieces.
inline double log_mean(double a, double b, double x) {
  if (x > -1e-3 && x < 1e-3) return b * (1.0 + x * (0.5 + x * (1.0 / 6.0 + x / 24.0)));
  return (a - b) / x;
}

/// log_mean without a branch, for loops over many values that the compiler should vectorise:
/// both forms are computed and mixed with a weight w of 0 or 1 (the division by x + w is safe
/// either way). `series_below` is the |x| under which the series is used (1e-3 in double
/// precision, 1e-2 in single).
template <typename T>
inline T log_mean_branchless(T a, T b, T x, T series_below) {
  const T w = (x < series_below && x > -series_below) ? T(1) : T(0);
  const T series = b * (T(1) + x * (T(0.5) + x * (T(1) / T(6) + x * (T(1) / T(24)))));
  const T exact = (a - b) / (x + w);
  return exact + w * (series - exact);
}

/// Richardson extrapolation of a second-order rule: fine on pieces dt, coarse on pieces 2 dt;
/// (4 fine - coarse) / 3, clamped at 0 (the integrands are non-negative; a coarse pair far off
/// would otherwise give a negative value).
inline double richardson(double fine, double coarse) { return std::max(0.0, (4.0 * fine - coarse) / 3.0); }

/// The same per wavelength, in single precision.
template <typename Fine, typename Coarse>
inline auto richardson(const Eigen::ArrayBase<Fine>& fine, const Eigen::ArrayBase<Coarse>& coarse) {
  return ((4.0f * fine - coarse) * (1.0f / 3.0f)).max(0.0f);
}

}  // namespace skyspec
