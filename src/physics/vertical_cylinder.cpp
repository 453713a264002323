#include "skyspec/vertical_cylinder.hpp"

#include <cmath>
#include <limits>
#include <utility>

namespace skyspec {

bool VerticalCylinder::crossing(const Vec3& o, const Vec3& d, double& t0_out, double& t1_out) const {
  // |o_perp + t d_perp|^2 = r^2, with the parts perpendicular to the axis; o_perp is a difference
  // of two vectors of the planet's radius but itself small near the axis, exact to ~1e-9 R.
  const Vec3 op = o - o.dot(axis) * axis, dp = d - d.dot(axis) * axis;
  const double a = dp.squaredNorm(), b = op.dot(dp), c = (op.norm() - radius_m) * (op.norm() + radius_m);
  const double inf = std::numeric_limits<double>::infinity();
  if (a < 1e-24) {  // along the axis
    if (c > 0.0 || o.dot(axis) <= 0.0) return false;
    t0_out = -inf;
    t1_out = inf;
    return true;
  }
  const double disc = b * b - a * c;
  if (!(disc > 0.0)) return false;
  // The cancellation-free roots of a t^2 + 2 b t + c = 0.
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  double t0 = q / a, t1 = q != 0.0 ? c / q : 0.0;
  if (t0 > t1) std::swap(t0, t1);
  if ((o + 0.5 * (t0 + t1) * d).dot(axis) <= 0.0) return false;  // the planet's far side
  t0_out = t0;
  t1_out = t1;
  return true;
}

}  // namespace skyspec
