// Planet-scale geometry: rays, sphere intersections, and the planet's shadow.
//
// World space is planet-centred, in metres, in double precision: at a radius of 6.4e6 m a float
// resolves only ~0.5 m, and the quantities that decide whether a ray grazes the ground
// (|o|^2 - r^2, the discriminant) cancel catastrophically. The formulations below avoid
// subtracting nearly equal large numbers.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>

#include "skyspec/vec3.hpp"

namespace skyspec {

/// Where a ray o + t d (|d| = 1) meets a sphere of radius r centred at the origin.
struct SphereHit {
  bool hit = false;       ///< false if the ray's line misses the sphere
  double t_near_m = 0.0;  ///< smaller root (may be negative: behind the origin)
  double t_far_m = 0.0;   ///< larger root
};

/// Intersect the line o + t d with the sphere |p| = radius_m. d must be a unit vector.
/// The discriminant is formed as (r - |o_perp|)(r + |o_perp|), with o_perp the part of o
/// perpendicular to d, and the roots with the cancellation-free quadratic formula.
SphereHit intersect_sphere(const Vec3& origin_m, const Vec3& dir, double radius_m);

/// Distance along the ray o + t d (|d| = 1) to where it enters the ball |p| <= radius_m: t_near
/// where the sphere is ahead; 0 for an origin inside, and for an origin on the sphere (a camera at
/// height 0: |o| = R to the last bit) that points below the horizontal, which enters at once
/// (intersect_sphere's t_near is then 0 or a rounding error either side of it); +infinity where
/// the ray never enters.
double sphere_entry_distance(const Vec3& origin_m, const Vec3& dir, double radius_m);

/// Parameter interval [t0, t1] along a ray, in metres.
struct Interval {
  double t0_m = 0.0, t1_m = 0.0;
  double length_m() const { return t1_m - t0_m; }
};

/// Up to two intervals (the lit parts of a ray segment).
struct IntervalSet {
  std::array<Interval, 2> parts{};
  int count = 0;
};

/// Parts of the segment [t0, t1] of the ray o + t d that receive direct sunlight, i.e. lie outside
/// the planet's shadow: the half-cylinder of radius planet_radius_m behind the planet (points p with
/// p.s < 0 and |p - (p.s) s| < R, for sun direction s). A point lies in this shadow exactly when
/// the ray from it towards the sun hits the planet, so the boundary is found in closed form instead
/// of by marching light rays.
IntervalSet lit_intervals(const Vec3& origin_m, const Vec3& dir, double t0_m, double t1_m, const Vec3& sun_dir,
                          double planet_radius_m);

/// Unit vector in the east-north-up frame for an azimuth and an elevation in degrees.
Vec3 direction_from_angles(double azimuth_deg, double elevation_deg);

/// Cosine of the zenith angle of direction dir at point p (p need not be normalised).
inline double cos_zenith(const Vec3& p, const Vec3& dir) { return p.dot(dir) / p.norm(); }

}  // namespace skyspec
