#include "skyspec/terrain.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "skyspec/error.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
// Rays are followed only where they run within this angle of the reference point (P_z above
// R cos of it): the map's coordinates stay finite and monotonic along them there.
constexpr double kMaxAngleDeg = 40.0;
constexpr double kMaxGridAngleDeg = 30.0;
}  // namespace

// A ray o + t d and what the walk learns about it.
struct Terrain::RayQuery {
  Vec3 o, d;
  double R = 0.0;
  double t_low = 0.0;       // where the ray is lowest: |o + t d| is convex in t
  double t_hit = kInf;      // the first crossing found
  double clearance = kInf;  // the least margin by which skipped blocks lie below the ray
  RayQuery(const Vec3& origin, const Vec3& dir, double radius)
      : o(origin), d(dir), R(radius), t_low(-origin.dot(dir)) {}
  double w(double t) const { return o.z() + t * d.z(); }
  double east(double t) const { return R * (o.x() + t * d.x()) / w(t); }
  double north(double t) const { return R * (o.y() + t * d.y()) / w(t); }
  double altitude(double t) const { return (o + t * d).norm() - R; }
  double lowest_altitude(double t0, double t1) const { return altitude(std::clamp(t_low, t0, t1)); }
  // The t at which east(t) = e (a line of the map); the denominator is zero only where east(t)
  // does not change along the ray.
  double t_at_east(double e) const { return (e * o.z() - R * o.x()) / (R * d.x() - e * d.z()); }
  double t_at_north(double n) const { return (n * o.z() - R * o.y()) / (R * d.y() - n * d.z()); }
};

Terrain::Terrain(HeightGrid grid, double planet_radius_m, TerrainAlbedo albedo)
    : grid_(std::move(grid)), R_(planet_radius_m), albedo_(std::move(albedo)), serial_(next_serial()) {
  const HeightGrid& g = grid_;
  if (g.columns < 2 || g.rows < 2)
    throw Error("terrain: a height grid needs at least 2 x 2 samples, not " + std::to_string(g.columns) + " x " +
                std::to_string(g.rows));
  if (g.height_m.size() != static_cast<size_t>(g.columns) * static_cast<size_t>(g.rows))
    throw Error("terrain: " + std::to_string(g.height_m.size()) + " heights for a grid of " +
                std::to_string(g.columns) + " x " + std::to_string(g.rows));
  if (!(g.spacing_m > 0.0) || !std::isfinite(g.spacing_m))
    throw Error("terrain: the grid spacing must be positive, not " + std::to_string(g.spacing_m));
  for (float h : g.height_m)
    if (!std::isfinite(h) || h < 0.0f)
      throw Error("terrain: heights must be finite and not negative (the sphere is height 0), found " +
                  std::to_string(h));
  for (double a : albedo_.spectrum)
    if (!(a >= 0.0 && a <= 1.0)) throw Error("terrain: an albedo must lie in [0, 1], not " + std::to_string(a));
  if (!albedo_.map.empty() && albedo_.map.size() != g.height_m.size())
    throw Error("terrain: an albedo map of " + std::to_string(albedo_.map.size()) + " samples for a grid of " +
                std::to_string(g.height_m.size()));
  for (float a : albedo_.map)
    if (!(a >= 0.0f && a <= 1.0f))
      throw Error("terrain: an albedo map's factor must lie in [0, 1], not " + std::to_string(a));
  const double e1 = g.east_m(g.columns - 1), n1 = g.north_m(g.rows - 1);
  const double reach = std::max(
      {std::hypot(g.east0_m, g.north0_m), std::hypot(e1, g.north0_m), std::hypot(g.east0_m, n1), std::hypot(e1, n1)});
  if (!(std::atan(reach / R_) <= degrees_to_radians(kMaxGridAngleDeg)))
    throw Error("terrain: the grid reaches " + std::to_string(reach / 1000.0) +
                " km (in the map) from the reference point; at most " + std::to_string(kMaxGridAngleDeg) +
                " degrees of the planet are supported");

  // Level 0: each cell's highest corner (a bilinear surface is highest at a corner); then 2 x 2
  // blocks of the level below, up to one block.
  Level base;
  base.width = g.columns - 1;
  base.height = g.rows - 1;
  base.max.resize(static_cast<size_t>(base.width) * static_cast<size_t>(base.height));
  for (int y = 0; y < base.height; ++y)
    for (int x = 0; x < base.width; ++x) {
      const float a = g.at(x, y), b = g.at(x + 1, y), c = g.at(x, y + 1), e = g.at(x + 1, y + 1);
      base.max[static_cast<size_t>(y) * base.width + x] = std::max({a, b, c, e});
      // The bilinear surface's steepest slope in the cell is at an edge: its gradient there is
      // (difference along the edge, largest difference across) / spacing.
      const double sx = std::max(std::abs(b - a), std::abs(e - c)), sy = std::max(std::abs(c - a), std::abs(e - b));
      slope_ = std::max(slope_, std::hypot(sx, sy) / g.spacing_m);
    }
  levels_.push_back(std::move(base));
  while (levels_.back().width > 1 || levels_.back().height > 1) {
    const Level& below = levels_.back();
    Level up;
    up.width = (below.width + 1) / 2;
    up.height = (below.height + 1) / 2;
    up.max.assign(static_cast<size_t>(up.width) * static_cast<size_t>(up.height), 0.0f);
    for (int y = 0; y < below.height; ++y)
      for (int x = 0; x < below.width; ++x) {
        float& m = up.max[static_cast<size_t>(y / 2) * up.width + x / 2];
        m = std::max(m, below.max[static_cast<size_t>(y) * below.width + x]);
      }
    levels_.push_back(std::move(up));
  }
  for (int x = 0; x < g.columns; ++x) border_max_ = std::max({border_max_, g.at(x, 0), g.at(x, g.rows - 1)});
  for (int y = 0; y < g.rows; ++y) border_max_ = std::max({border_max_, g.at(0, y), g.at(g.columns - 1, y)});
  // A shift of a world point by delta moves its map point by at most delta times the projection's
  // scale, 1 / cos^2 of the angle from the reference point (with room for the altitude).
  const double cos_max = std::cos(std::atan((reach + kMaxSunStep * g.spacing_m) / R_));
  lipschitz_ = 1.0 + slope_ * 1.01 / (cos_max * cos_max);

  // A world box holding the terrain: its edges at heights 0 and max, sampled densely (x and y
  // are extreme on the edges, z lowest at a corner at height 0), with a metre to spare.
  box_lo_ = Vec3::Constant(kInf);
  box_hi_ = Vec3::Constant(-kInf);
  const double top = max_height_m();
  auto include = [&](double e, double n) {
    const Vec3 dir = Vec3(e, n, R_).normalized();
    for (double h : {0.0, top}) {
      const Vec3 p = (R_ + h) * dir;
      box_lo_ = box_lo_.cwiseMin(p);
      box_hi_ = box_hi_.cwiseMax(p);
    }
  };
  constexpr int kEdgeSamples = 256;
  for (int k = 0; k <= kEdgeSamples; ++k) {
    const double f = static_cast<double>(k) / kEdgeSamples;
    include(g.east0_m + f * (e1 - g.east0_m), g.north0_m);
    include(g.east0_m + f * (e1 - g.east0_m), n1);
    include(g.east0_m, g.north0_m + f * (n1 - g.north0_m));
    include(e1, g.north0_m + f * (n1 - g.north0_m));
  }
  box_hi_.z() = R_ + top;  // the top of the terrain's cap, wherever it is
  box_lo_ -= Vec3::Constant(1.0);
  box_hi_ += Vec3::Constant(1.0);
}

double Terrain::cell_height(int cx, int cy, double fx, double fy) const {
  const double a = grid_.at(cx, cy), b = grid_.at(cx + 1, cy), c = grid_.at(cx, cy + 1), e = grid_.at(cx + 1, cy + 1);
  return (1.0 - fy) * ((1.0 - fx) * a + fx * b) + fy * ((1.0 - fx) * c + fx * e);
}

double Terrain::on_grid(const std::vector<float>& values, double east_m, double north_m, double outside) const {
  const double x = (east_m - grid_.east0_m) / grid_.spacing_m, y = (north_m - grid_.north0_m) / grid_.spacing_m;
  if (!(x >= 0.0 && y >= 0.0 && x <= grid_.columns - 1 && y <= grid_.rows - 1)) return outside;
  const int cx = std::min(static_cast<int>(x), grid_.columns - 2), cy = std::min(static_cast<int>(y), grid_.rows - 2);
  const double fx = x - cx, fy = y - cy;
  const auto at = [&](int c, int r) {
    return static_cast<double>(values[static_cast<size_t>(r) * static_cast<size_t>(grid_.columns) + c]);
  };
  return (1.0 - fy) * ((1.0 - fx) * at(cx, cy) + fx * at(cx + 1, cy)) +
         fy * ((1.0 - fx) * at(cx, cy + 1) + fx * at(cx + 1, cy + 1));
}

double Terrain::height_at(double east_m, double north_m) const { return on_grid(grid_.height_m, east_m, north_m, 0.0); }

double Terrain::height_under(const Vec3& p) const {
  if (!(p.z() > 0.0)) return 0.0;
  return height_at(east_of(p), north_of(p));
}

bool Terrain::covers(const Vec3& p) const {
  if (!(p.z() > 0.0)) return false;
  const double x = (east_of(p) - grid_.east0_m) / grid_.spacing_m, y = (north_of(p) - grid_.north0_m) / grid_.spacing_m;
  return x >= 0.0 && y >= 0.0 && x <= grid_.columns - 1 && y <= grid_.rows - 1;
}

double Terrain::albedo_factor_under(const Vec3& p) const {
  if (albedo_.map.empty() || !(p.z() > 0.0)) return 1.0;
  return on_grid(albedo_.map, east_of(p), north_of(p), 1.0);
}

Vec3 Terrain::normal_under(const Vec3& p) const {
  const double e = east_of(p), n = north_of(p), eps = 0.01 * grid_.spacing_m;
  auto surface = [&](double de, double dn) {
    return Vec3((R_ + height_at(e + de, n + dn)) * Vec3(e + de, n + dn, R_).normalized());
  };
  const Vec3 te = surface(eps, 0) - surface(-eps, 0), tn = surface(0, eps) - surface(0, -eps);
  return te.cross(tn).normalized();
}

bool Terrain::clip_to_rect(const RayQuery& q, double e0, double e1, double n0, double n1, double& t0,
                           double& t1) const {
  // Along the ray the map coordinates are monotonic (where P_z > 0), so each slab is one stretch.
  auto clip = [&](double a, double b, auto&& coord, auto&& t_at) {
    const double c0 = coord(t0), c1 = coord(t1);
    if (std::max(c0, c1) < a || std::min(c0, c1) > b) return false;
    const double lo = std::min(t0, t1), hi = std::max(t0, t1);
    if (c0 <= c1) {
      if (c0 < a) t0 = std::clamp(t_at(a), lo, hi);
      if (c1 > b) t1 = std::clamp(t_at(b), lo, hi);
    } else {
      if (c0 > b) t0 = std::clamp(t_at(b), lo, hi);
      if (c1 < a) t1 = std::clamp(t_at(a), lo, hi);
    }
    return t0 <= t1;
  };
  return clip(
             e0, e1, [&](double t) { return q.east(t); }, [&](double e) { return q.t_at_east(e); }) &&
         clip(
             n0, n1, [&](double t) { return q.north(t); }, [&](double n) { return q.t_at_north(n); });
}

bool Terrain::leaf(int cx, int cy, double t0, double t1, RayQuery& q) const {
  const double e0 = grid_.east_m(cx), n0 = grid_.north_m(cy), inv = 1.0 / grid_.spacing_m;
  auto above = [&](double t) {
    const double fx = std::clamp((q.east(t) - e0) * inv, 0.0, 1.0), fy = std::clamp((q.north(t) - n0) * inv, 0.0, 1.0);
    return q.altitude(t) - cell_height(cx, cy, fx, fy);
  };
  constexpr int kSamples = 4;
  double prev_t = t0, least = above(t0);
  if (least <= 0.0) {
    q.t_hit = t0;
    return true;
  }
  for (int k = 1; k <= kSamples; ++k) {
    const double t = t0 + (t1 - t0) * k / kSamples, f = above(t);
    if (f <= 0.0) {
      double a = prev_t, b = t;  // above at a, inside at b
      for (int i = 0; i < 60 && b - a > 1e-4; ++i) {
        const double m = 0.5 * (a + b);
        (above(m) > 0.0 ? a : b) = m;
      }
      q.t_hit = b;
      return true;
    }
    least = std::min(least, f);
    prev_t = t;
  }
  // The sampled margin, halved for what may dip between samples.
  q.clearance = std::min(q.clearance, 0.5 * least);
  return false;
}

bool Terrain::visit(int level, int bx, int by, double t0, double t1, RayQuery& q) const {
  const Level& l = levels_[static_cast<size_t>(level)];
  const double top = l.max[static_cast<size_t>(by) * l.width + bx];
  const double lowest = q.lowest_altitude(t0, t1);
  if (lowest > top) {
    q.clearance = std::min(q.clearance, lowest - top);
    return false;
  }
  if (level == 0) return leaf(bx, by, t0, t1, q);
  // The four children, in the order the ray meets them: cut [t0, t1] where it crosses the
  // block's middle lines.
  const int half = 1 << (level - 1);
  const double e_mid = grid_.east_m(2 * bx * half + half), n_mid = grid_.north_m(2 * by * half + half);
  double cuts[4] = {t0, t1, t1, t1};
  int n = 1;
  for (double c : {q.t_at_east(e_mid), q.t_at_north(n_mid)})
    if (c > t0 && c < t1) cuts[n++] = c;
  cuts[n] = t1;
  if (n == 3 && cuts[1] > cuts[2]) std::swap(cuts[1], cuts[2]);
  const Level& below = levels_[static_cast<size_t>(level) - 1];
  for (int i = 0; i < n; ++i) {
    const double a = cuts[i], b = cuts[i + 1];
    if (!(b > a)) continue;
    const double m = 0.5 * (a + b);
    const int cx = 2 * bx + (q.east(m) >= e_mid ? 1 : 0), cy = 2 * by + (q.north(m) >= n_mid ? 1 : 0);
    if (cx >= below.width || cy >= below.height) continue;  // past the grid's edge (rounding)
    if (visit(level - 1, cx, cy, a, b, q)) return true;
  }
  return false;
}

bool Terrain::trace(RayQuery& q, double t0, double t1) const {
  // Where the ray runs near enough the reference point for the map.
  const double w_min = R_ * std::cos(degrees_to_radians(kMaxAngleDeg));
  if (q.d.z() > 0.0)
    t0 = std::max(t0, (w_min - q.o.z()) / q.d.z());
  else if (q.d.z() < 0.0)
    t1 = std::min(t1, (w_min - q.o.z()) / q.d.z());
  else if (q.o.z() < w_min)
    return false;
  if (!(t1 > t0)) return false;
  if (!clip_to_rect(q, grid_.east0_m, grid_.east_m(grid_.columns - 1), grid_.north0_m, grid_.north_m(grid_.rows - 1),
                    t0, t1))
    return false;
  return visit(static_cast<int>(levels_.size()) - 1, 0, 0, t0, t1, q);
}

double Terrain::intersect(const Vec3& o, const Vec3& d, double t0, double t1) const {
  RayQuery q(o, d, R_);
  return trace(q, t0, t1) ? q.t_hit : kInf;
}

namespace {
// Far enough for a ray towards the sun to leave any terrain the map holds.
constexpr double kSunRayLength_m = 4.0e6;
}  // namespace

bool Terrain::shadowed(const Vec3& p, const Vec3& s) const {
  RayQuery q(p, s, R_);
  return trace(q, 0.0, kSunRayLength_m);
}

std::uint64_t Terrain::next_serial() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}

Vec3 Terrain::skyline_above(const Vec3& o, const Vec3& d, double t_hit) const {
  const Vec3 up = o.normalized();
  Vec3 e = up - up.dot(d) * d;  // upwards, perpendicular to d
  if (e.norm() < 1e-9) e = std::abs(d.x()) < 0.9 ? Vec3(1.0, 0.0, 0.0).cross(d) : Vec3(0.0, 1.0, 0.0).cross(d);
  e = e.normalized();
  Vec3 best = o + t_hit * d;
  const auto meets = [&](double tilt) {
    const Vec3 dm = std::cos(tilt) * d + std::sin(tilt) * e;
    const double t = intersect(o, dm, 0.0, kSunRayLength_m);
    if (t < kInf) best = o + t * dm;
    return t < kInf;
  };
  // The tilt doubled from a milliradian until the ray clears the surface (straight up counts as
  // clear), then bisected.
  double lo = 0.0, hi = 1e-3;
  while (hi < 0.5 * kPi && meets(hi)) {
    lo = hi;
    hi = std::min(2.0 * hi, 0.5 * kPi);
  }
  for (int k = 0; k < kSkylineSteps; ++k) {
    const double mid = 0.5 * (lo + hi);
    if (meets(mid))
      lo = mid;
    else
      hi = mid;
  }
  return best;
}

bool Terrain::probe_sun(const Vec3& p, const Vec3& s, double& safe_m) const {
  const double spacing = grid_.spacing_m, longest = kMaxSunStep * spacing / 1.01;
  RayQuery q(p, s, R_);
  if (trace(q, 0.0, kSunRayLength_m)) {
    // How deep the ray runs inside: its depth sampled every half cell after the crossing.
    double depth = 0.0;
    for (int k = 1; k <= 64; ++k) {
      const Vec3 x = p + (q.t_hit + 0.5 * spacing * k) * s;
      const double below = height_under(x) - (x.norm() - R_);
      if (below <= 0.0) break;
      depth = std::max(depth, below);
    }
    safe_m = std::min(longest, depth / lipschitz_);
    return true;
  }
  // Lit: the margin over the blocks the walk skipped, and over the grid's border for a ray that
  // a shift could bring into the grid (the stretches within kMaxSunStep cells outside it).
  double margin = q.clearance;
  const double pad = kMaxSunStep * spacing;
  double d0 = 0.0, d1 = kSunRayLength_m;
  const double e0 = grid_.east0_m, e1 = grid_.east_m(grid_.columns - 1);
  const double n0 = grid_.north0_m, n1 = grid_.north_m(grid_.rows - 1);
  const double w_min = R_ * std::cos(degrees_to_radians(kMaxAngleDeg));
  if (s.z() < 0.0) d1 = std::min(d1, (w_min - p.z()) / s.z());
  if (d1 > d0 && clip_to_rect(q, e0 - pad, e1 + pad, n0 - pad, n1 + pad, d0, d1)) {
    double g0 = d0, g1 = d1;
    if (clip_to_rect(q, e0, e1, n0, n1, g0, g1)) {
      if (g0 > d0) margin = std::min(margin, q.lowest_altitude(d0, g0) - border_max_);
      if (d1 > g1) margin = std::min(margin, q.lowest_altitude(g1, d1) - border_max_);
    } else {
      margin = std::min(margin, q.lowest_altitude(d0, d1) - border_max_);
    }
  }
  safe_m = std::clamp(margin / lipschitz_, 0.0, longest);
  return false;
}

void Terrain::sunlit_parts(const Vec3& o, const Vec3& d, double t0, double t1, const Vec3& s,
                           std::vector<Interval>& out) const {
  if (!(t1 > t0)) return;
  // The last answer on this thread, for the same terrain and the same arguments exactly: the
  // renderer asks whether a ray is shadowed and then the integrator asks again along the same ray.
  struct Last {
    std::uint64_t serial = 0;
    Vec3 o, d, s;
    double t0 = 0.0, t1 = 0.0;
    std::vector<Interval> parts;
  };
  thread_local Last last;
  if (last.serial == serial_ && last.t0 == t0 && last.t1 == t1 && last.o == o && last.d == d && last.s == s) {
    out.insert(out.end(), last.parts.begin(), last.parts.end());
    return;
  }
  const size_t first = out.size();
  probe_sunlit_parts(o, d, t0, t1, s, out);
  last.serial = serial_;
  last.o = o;
  last.d = d;
  last.s = s;
  last.t0 = t0;
  last.t1 = t1;
  last.parts.assign(out.begin() + static_cast<std::ptrdiff_t>(first), out.end());
}

void Terrain::probe_sunlit_parts(const Vec3& o, const Vec3& d, double t0, double t1, const Vec3& s,
                                 std::vector<Interval>& out) const {
  const double shortest = 0.25 * grid_.spacing_m;
  double safe = 0.0;
  double t = t0;
  bool lit = !probe_sun(o + t * d, s, safe);
  double start = t0;
  while (t < t1) {
    const double next = std::min(t1, t + std::max(safe, shortest));
    double next_safe = 0.0;
    const bool next_lit = !probe_sun(o + next * d, s, next_safe);
    if (next_lit != lit) {
      double a = t, b = next;  // visibility `lit` at a, the other at b
      for (int i = 0; i < 60 && b - a > 1e-3; ++i) {
        const double m = 0.5 * (a + b);
        (shadowed(o + m * d, s) != lit ? a : b) = m;
      }
      const double edge = 0.5 * (a + b);
      if (lit)
        out.push_back({start, edge});
      else
        start = edge;
      lit = next_lit;
    }
    t = next;
    safe = next_safe;
  }
  if (lit && t1 > start) out.push_back({start, t1});
}

namespace {
// The convex polygon of (t, lambda) with a t + b lambda + c >= 0 kept (Sutherland-Hodgman).
struct Point2 {
  double t, l;
};
void clip_polygon(std::vector<Point2>& poly, double a, double b, double c, std::vector<Point2>& scratch) {
  scratch.clear();
  const size_t n = poly.size();
  for (size_t i = 0; i < n; ++i) {
    const Point2 p = poly[i], q = poly[(i + 1) % n];
    const double fp = a * p.t + b * p.l + c, fq = a * q.t + b * q.l + c;
    if (fp >= 0.0) scratch.push_back(p);
    if ((fp >= 0.0) != (fq >= 0.0)) {
      const double f = fp / (fp - fq);
      scratch.push_back({p.t + f * (q.t - p.t), p.l + f * (q.l - p.l)});
    }
  }
  poly.swap(scratch);
}
}  // namespace

bool Terrain::affected_stretch(const Vec3& o, const Vec3& d, double t0, double t1, const Vec3& s, Interval& out) const {
  if (!(t1 > t0)) return false;
  // Points o + t d + lambda s (lambda >= 0) inside the box: the ray meets the box (lambda = 0) or
  // the point's ray towards the sun does.
  constexpr double kLambda = 2.0 * kSunRayLength_m;
  thread_local std::vector<Point2> poly, scratch;
  poly = {{t0, 0.0}, {t1, 0.0}, {t1, kLambda}, {t0, kLambda}};
  for (int i = 0; i < 3 && !poly.empty(); ++i) {
    clip_polygon(poly, d[i], s[i], o[i] - box_lo_[i], scratch);  // o + t d + l s >= lo
    if (poly.empty()) break;
    clip_polygon(poly, -d[i], -s[i], box_hi_[i] - o[i], scratch);  // ... <= hi
  }
  if (poly.empty()) return false;
  out.t0_m = kInf;
  out.t1_m = -kInf;
  for (const Point2& p : poly) {
    out.t0_m = std::min(out.t0_m, p.t);
    out.t1_m = std::max(out.t1_m, p.t);
  }
  out.t0_m = std::max(out.t0_m, t0);
  out.t1_m = std::min(out.t1_m, t1);
  return out.t1_m >= out.t0_m;
}

double ridge_height_at(const RidgeSpec& r, double east_m, double north_m) {
  const double a = degrees_to_radians(r.azimuth_deg);
  const double x = east_m * std::sin(a) + north_m * std::cos(a) - r.distance_m;  // across the crest
  const double y = -east_m * std::cos(a) + north_m * std::sin(a);                // along it
  const double w = r.half_width_m, half_length = 0.5 * r.length_m;
  if (std::abs(x) >= w || std::abs(y) >= half_length) return 0.0;
  const double across = std::cos(kPi * x / (2.0 * w));
  double crest = r.height_m;
  if (r.notch_spacing_m > 0.0) crest *= 1.0 - r.notch_depth * 0.5 * (1.0 - std::cos(2.0 * kPi * y / r.notch_spacing_m));
  const double end = std::abs(y) - (half_length - w);
  if (end > 0.0) crest *= std::pow(std::cos(kPi * end / (2.0 * w)), 2);
  return crest * across * across;
}

HeightGrid ridge_heights(const RidgeSpec& r, double spacing_m) {
  if (!(r.length_m > 2.0 * r.half_width_m))
    throw Error("terrain: the ridge's length (" + std::to_string(r.length_m) +
                " m) must exceed twice its half width (" + std::to_string(r.half_width_m) + " m)");
  // The map rectangle that holds the ridge's rotated footprint, a cell to spare.
  const double a = degrees_to_radians(r.azimuth_deg);
  const Vec3 across(std::sin(a), std::cos(a), 0.0), along(-std::cos(a), std::sin(a), 0.0);
  double e_lo = kInf, e_hi = -kInf, n_lo = kInf, n_hi = -kInf;
  for (double x : {r.distance_m - r.half_width_m, r.distance_m + r.half_width_m})
    for (double y : {-0.5 * r.length_m, 0.5 * r.length_m}) {
      const Vec3 p = x * across + y * along;
      e_lo = std::min(e_lo, p.x());
      e_hi = std::max(e_hi, p.x());
      n_lo = std::min(n_lo, p.y());
      n_hi = std::max(n_hi, p.y());
    }
  HeightGrid g;
  g.spacing_m = spacing_m;
  g.east0_m = std::floor(e_lo / spacing_m - 1.0) * spacing_m;
  g.north0_m = std::floor(n_lo / spacing_m - 1.0) * spacing_m;
  g.columns = static_cast<int>(std::ceil((e_hi - g.east0_m) / spacing_m)) + 2;
  g.rows = static_cast<int>(std::ceil((n_hi - g.north0_m) / spacing_m)) + 2;
  const double cells = static_cast<double>(g.columns) * g.rows;
  if (cells > 1.0e8)
    throw Error("terrain: the ridge needs " + std::to_string(g.columns) + " x " + std::to_string(g.rows) +
                " samples at a spacing of " + std::to_string(spacing_m) + " m (at most 1e8)");
  g.height_m.resize(static_cast<size_t>(cells));
  for (int y = 0; y < g.rows; ++y)
    for (int x = 0; x < g.columns; ++x)
      g.height_m[static_cast<size_t>(y) * g.columns + x] =
          static_cast<float>(ridge_height_at(r, g.east_m(x), g.north_m(y)));
  return g;
}

}  // namespace skyspec
