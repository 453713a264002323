#include "skyspec/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "skyspec/units.hpp"

namespace skyspec {

Vec3 direction_from_angles(double azimuth_deg, double elevation_deg) {
  const double az = degrees_to_radians(azimuth_deg), el = degrees_to_radians(elevation_deg);
  return Vec3(std::cos(el) * std::sin(az), std::cos(el) * std::cos(az), std::sin(el));
}

SphereHit intersect_sphere(const Vec3& origin_m, const Vec3& dir, double radius_m) {
  // |o + t d|^2 = r^2  <=>  t^2 + 2 b t + c = 0, b = o.d, c = |o|^2 - r^2.
  const double b = origin_m.dot(dir);
  const Vec3 o_perp = origin_m - b * dir;
  const double d_perp = o_perp.norm();
  // Discriminant b^2 - c = r^2 - |o_perp|^2, factored to avoid cancellation near tangency.
  const double disc = (radius_m - d_perp) * (radius_m + d_perp);
  if (disc < 0.0) return {};
  const double sqrt_disc = std::sqrt(disc);
  // c = (|o| - r)(|o| + r) is accurate for origins close to the sphere.
  const double o_norm = origin_m.norm();
  const double c = (o_norm - radius_m) * (o_norm + radius_m);
  // q = -(b + sign(b) sqrt(disc)); roots are q and c / q (Numerical Recipes 5.6).
  const double q = b > 0.0 ? -(b + sqrt_disc) : -(b - sqrt_disc);
  SphereHit h;
  h.hit = true;
  if (q == 0.0) {  // origin on the sphere and the ray tangent to it
    h.t_near_m = h.t_far_m = 0.0;
    return h;
  }
  double t0 = q, t1 = c / q;
  if (t0 > t1) std::swap(t0, t1);
  h.t_near_m = t0;
  h.t_far_m = t1;
  return h;
}

double sphere_entry_distance(const Vec3& origin_m, const Vec3& dir, double radius_m) {
  if (origin_m.norm() < radius_m) return 0.0;
  const SphereHit h = intersect_sphere(origin_m, dir, radius_m);
  if (!h.hit) return std::numeric_limits<double>::infinity();
  if (h.t_near_m > 0.0) return h.t_near_m;
  // t_near <= 0: the origin is on the sphere, to rounding (outside it, both roots share a sign).
  if (h.t_far_m > 0.0 && origin_m.dot(dir) < 0.0) return 0.0;
  return std::numeric_limits<double>::infinity();
}

IntervalSet lit_intervals(const Vec3& origin_m, const Vec3& dir, double t0_m, double t1_m, const Vec3& sun_dir,
                          double planet_radius_m) {
  IntervalSet out;
  if (!(t1_m > t0_m)) return out;
  // Shadow cylinder: |p_perp(t)|^2 < R^2 with p_perp = o_perp + t d_perp (components normal to s).
  const Vec3 o_perp = origin_m - origin_m.dot(sun_dir) * sun_dir;
  const Vec3 d_perp = dir - dir.dot(sun_dir) * sun_dir;
  const double a = d_perp.squaredNorm();
  double cyl0, cyl1;  // t-range inside the infinite cylinder
  if (a < 1e-18) {
    // Ray parallel to the sun direction: inside the cylinder for all t or for none.
    if (o_perp.norm() >= planet_radius_m) {
      out.parts[0] = {t0_m, t1_m};
      out.count = 1;
      return out;
    }
    cyl0 = -INFINITY;
    cyl1 = INFINITY;
  } else {
    const double b = o_perp.dot(d_perp) / a;
    const Vec3 closest = o_perp - b * d_perp;  // perpendicular point nearest the axis
    const double dist = closest.norm();
    const double disc = (planet_radius_m - dist) * (planet_radius_m + dist) / a;
    if (disc <= 0.0) {
      out.parts[0] = {t0_m, t1_m};
      out.count = 1;
      return out;
    }
    const double half = std::sqrt(disc);
    cyl0 = -b - half;
    cyl1 = -b + half;
  }
  // Half-space behind the planet: o.s + t d.s < 0.
  const double os = origin_m.dot(sun_dir), ds = dir.dot(sun_dir);
  double sh0 = cyl0, sh1 = cyl1;
  if (ds > 0.0) {
    sh1 = std::min(sh1, -os / ds);
  } else if (ds < 0.0) {
    sh0 = std::max(sh0, -os / ds);
  } else if (os >= 0.0) {
    sh1 = sh0;  // never behind the planet
  }
  // Lit = [t0, t1] minus [sh0, sh1].
  if (!(sh1 > sh0) || sh1 <= t0_m || sh0 >= t1_m) {
    out.parts[0] = {t0_m, t1_m};
    out.count = 1;
    return out;
  }
  if (sh0 > t0_m) out.parts[out.count++] = {t0_m, sh0};
  if (sh1 < t1_m) out.parts[out.count++] = {sh1, t1_m};
  return out;
}

}  // namespace skyspec
