// A vertical cylinder over a disc of the ground: where a medium confined to a region is
// (Medium::region: a rain shower).
#pragma once

#include "skyspec/vec3.hpp"

namespace skyspec {

/// The air above a disc of the ground: the points within radius_m of the line through the
/// planet's centre along `axis` (unit; the local vertical at the disc's centre), on the axis's side
/// of the planet. A rain shower is one (Medium::region). Its walls are parallel to the axis, so at
/// altitude h its edge lies radius_m from the axis however high, where a cone from the planet's
/// centre would have widened by h / R (0.16 % at 10 km).
struct VerticalCylinder {
  Vec3 axis = Vec3(0, 0, 1);
  double radius_m = 0.0;
  /// Whether p is inside (or on the wall).
  bool contains(const Vec3& p) const {
    const double along = p.dot(axis);
    return along > 0.0 && (p - along * axis).squaredNorm() <= radius_m * radius_m;
  }
  /// Where the line o + t d (|d| = 1) runs inside: [t0, t1] (t0 = -infinity and t1 = +infinity for a
  /// line along the axis inside the walls). False when it never does.
  bool crossing(const Vec3& o, const Vec3& d, double& t0, double& t1) const;
};

}  // namespace skyspec
