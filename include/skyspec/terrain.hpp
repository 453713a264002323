// Terrain: a height field on the planet's sphere that hides what lies behind it, casts shadows
// into the air and reflects light (issue 38).
//
// Where the heights are. The terrain is sampled on a regular grid of the gnomonic (central)
// projection about the scene's reference point (the point of the sphere under the camera, world
// position (0, 0, R); x east, y north, z up there): a world point P has map coordinates
//
//   (east, north) = R (P_x / P_z, P_y / P_z),
//
// the point of the tangent plane at the reference point on the line from the planet's centre
// through P. The surface above map point q is the point at radius R + h(q) on that line, with h
// interpolated bilinearly between the grid's samples; outside the grid h = 0 (the sphere). Two
// properties make the projection the right one: a straight ray in space projects onto a straight
// line of the map (its points and the centre lie in one plane, and the projection maps great
// circles to straight lines), and along it the map coordinates are ratios of linear functions of
// the ray's parameter, so where the ray crosses a grid line has a closed form. Its scale grows as
// 1 / cos^2 of the angle from the reference point: 1.0002 at 100 km, 1.006 at 500 km (heights
// are interpolated in the map, so a DEM resampled onto it keeps its shape to that factor).
//
// Finding the surface. A maximum-height quadtree (the max mip-map of the cells' corner heights,
// level k holding the maximum over 2^k x 2^k cells) is walked front to back along a ray: a block
// whose maximum lies below the ray's lowest altitude over the block is skipped whole (the altitude
// |P| - R along a straight ray is convex, so its minimum over a stretch is at the stretch's end or
// at the ray's lowest point), so visibility costs a number of steps that grows with the logarithm
// of the grid's size where the ray passes high. In a cell the bilinear surface is found by sampling
// the height above the surface at four points and bisecting the first sign change to 1e-4 m;
// a ray that grazes a cell's surface between two samples without crossing it at a sample
// is taken as missing it (the error is at most the surface's curvature over a quarter cell).
//
// Sunlit parts of a view ray. Along a view ray the sun's visibility is probed at points whose
// spacing comes from a Lipschitz bound: if the ray towards the sun from p clears the quadtree's
// blocks by c metres, or runs d metres deep inside the terrain, every point within
// c / (1 + L) (or d / (1 + L)) of p has the same visibility, L the surface's largest slope (times
// the projection's scale; within a cell's highest corner c is the least of four sampled heights
// above the cell's surface, halved: an estimate, not a bound). The steps are at most kMaxSunStep cells and at least a
// quarter of a cell; each change of visibility between two probes is bisected to 1e-3 m. A shadow (or a gap of light)
// shorter than a quarter of a cell along the view ray can be missed.
#pragma once

#include <cstdint>
#include <vector>

#include "skyspec/geometry.hpp"
#include "skyspec/spectrum.hpp"
#include "skyspec/vec3.hpp"

namespace skyspec {

/// Heights above the sphere (metres) on a regular grid of the map (see above).
struct HeightGrid {
  int columns = 0, rows = 0;             ///< samples west to east, south to north (each >= 2)
  double spacing_m = 0.0;                ///< between neighbouring samples, in the map
  double east0_m = 0.0, north0_m = 0.0;  ///< map coordinates of sample (0, 0), the south-west corner
  std::vector<float> height_m;           ///< row-major, row 0 southmost: height_m[row * columns + column]
  float at(int column, int row) const {
    return height_m[static_cast<size_t>(row) * static_cast<size_t>(columns) + static_cast<size_t>(column)];
  }
  double east_m(int column) const { return east0_m + spacing_m * column; }
  double north_m(int row) const { return north0_m + spacing_m * row; }
};

/// What the terrain's surface reflects (Lambertian): its own albedo per wavelength of the render's
/// grid (empty: the ground's, AtmosphereModel::ground_albedo), times a factor in [0, 1] given at
/// each sample of the height grid (empty: 1) and interpolated bilinearly between samples (an
/// albedo map). Beyond the grid the ground is the sphere, with the ground's albedo.
struct TerrainAlbedo {
  SpectrumD spectrum;
  std::vector<float> map;  ///< row-major like HeightGrid::height_m
};

/// A height field on a planet of radius planet_radius_m, with its quadtree.
class Terrain {
 public:
  /// Throws Error when the grid is malformed (sizes, a non-finite or negative height, a spacing
  /// that is not positive, or a grid reaching more than 30 degrees from the reference point), or
  /// the albedo is (a value outside [0, 1], a map of another size than the grid).
  Terrain(HeightGrid grid, double planet_radius_m, TerrainAlbedo albedo = {});

  const HeightGrid& grid() const { return grid_; }
  double planet_radius_m() const { return R_; }
  double max_height_m() const { return levels_.back().max.front(); }
  /// The largest slope of the bilinear surface, dh / d(map distance).
  double max_slope() const { return slope_; }

  /// Map coordinates of a world point (P_z > 0).
  double east_of(const Vec3& p) const { return R_ * p.x() / p.z(); }
  double north_of(const Vec3& p) const { return R_ * p.y() / p.z(); }
  /// h at map coordinates (0 outside the grid).
  double height_at(double east_m, double north_m) const;
  /// The surface's height under a world point, and the point's altitude above it (negative inside).
  double height_under(const Vec3& p) const;
  double clearance(const Vec3& p) const { return p.norm() - R_ - height_under(p); }
  /// The surface's outward unit normal at the surface point under p.
  Vec3 normal_under(const Vec3& p) const;
  /// Whether p lies over the grid (its map coordinates within the grid's rectangle): the ground
  /// there is the terrain's surface, with the terrain's albedo, wherever a ray meets it (also
  /// where the grid's height is 0 and a ray ends on the sphere).
  bool covers(const Vec3& p) const;
  /// The terrain's own spectral albedo (empty: the ground's), whether it has one or an albedo map
  /// (else its surface reflects as the ground does), and the map's factor under p (1 without a map
  /// or beyond the grid).
  const SpectrumD& own_albedo() const { return albedo_.spectrum; }
  bool has_albedo_map() const { return !albedo_.map.empty(); }
  bool has_own_albedo() const { return albedo_.spectrum.size() > 0 || !albedo_.map.empty(); }
  double albedo_factor_under(const Vec3& p) const;

  /// The first t in [t0, t1] where the ray o + t d (|d| = 1) meets the surface, or +infinity.
  double intersect(const Vec3& o, const Vec3& d, double t0, double t1) const;
  /// Whether the surface hides a sun in direction s (unit) from p.
  bool shadowed(const Vec3& p, const Vec3& s) const;
  /// The skyline above a ray o + t d that meets the surface at t_hit: the ray is tilted upwards
  /// (towards the local zenith at o, in the vertical plane of d), the tilt doubled from a
  /// milliradian until the ray clears the surface and then bisected kSkylineSteps times (to 1/64 of
  /// itself); the returned point is where the steepest tilt that still meets the surface meets it
  /// (o + t_hit d if none does). Assumes that a ray tilted less meets the surface too (one skyline
  /// above the hit).
  Vec3 skyline_above(const Vec3& o, const Vec3& d, double t_hit) const;
  static constexpr int kSkylineSteps = 6;
  /// Appends to out the parts of [t0, t1] on the ray o + t d from which a sun in direction s is
  /// not hidden by the surface (the planet's own shadow is not considered), in order.
  void sunlit_parts(const Vec3& o, const Vec3& d, double t0, double t1, const Vec3& s,
                    std::vector<Interval>& out) const;
  /// The stretch of [t0, t1] on the ray o + t d where the terrain can matter: the ray meets a box
  /// that holds the terrain, or the box swept away from the sun (the points whose ray towards the
  /// sun meets it). False when there is none; elsewhere the terrain neither hides nor shadows.
  bool affected_stretch(const Vec3& o, const Vec3& d, double t0, double t1, const Vec3& s, Interval& out) const;

  /// The longest step between two probes of the sun's visibility, in cells.
  static constexpr double kMaxSunStep = 64.0;

 private:
  struct Level {
    int width = 0, height = 0;  // blocks
    std::vector<float> max;     // per block
  };
  struct RayQuery;
  HeightGrid grid_;
  double R_;
  TerrainAlbedo albedo_;
  std::vector<Level> levels_;  // levels_[0]: one block per cell
  double slope_ = 0.0;
  double lipschitz_ = 1.0;   // 1 + slope x the projection's largest scale: c / lipschitz_ is a safe step
  float border_max_ = 0.0f;  // the highest sample on the grid's edge
  Vec3 box_lo_, box_hi_;     // a world box holding the terrain
  double cell_height(int cell_x, int cell_y, double fx, double fy) const;
  /// values (one per grid sample) interpolated bilinearly at map coordinates; `outside` beyond the grid.
  double on_grid(const std::vector<float>& values, double east_m, double north_m, double outside) const;
  bool clip_to_rect(const RayQuery& q, double e0, double e1, double n0, double n1, double& t0, double& t1) const;
  bool visit(int level, int bx, int by, double t0, double t1, RayQuery& q) const;
  bool leaf(int cx, int cy, double t0, double t1, RayQuery& q) const;
  /// Walks the ray over [t0, t1]; true (and q's hit) at the first crossing of the surface.
  bool trace(RayQuery& q, double t0, double t1) const;
  /// The sun's visibility from p and how far p can move keeping it (metres).
  bool probe_sun(const Vec3& p, const Vec3& s, double& safe_m) const;
  /// sunlit_parts without its memory of the last call.
  void probe_sunlit_parts(const Vec3& o, const Vec3& d, double t0, double t1, const Vec3& s,
                          std::vector<Interval>& out) const;
  std::uint64_t serial_;  // tells terrains apart in sunlit_parts' memory (next_serial)
  static std::uint64_t next_serial();
};

/// A synthetic mountain ridge (terrain.model = "ridge"): a straight crest at distance_m from the
/// reference point in the direction azimuth_deg (clockwise from north), running across that
/// direction over length_m, its cross-section h = H cos^2(pi x / (2 w)) for |x| < w (x measured
/// from the crest along azimuth_deg, w = half_width_m), and along the crest
/// H = height_m (1 - notch_depth (1 - cos(2 pi y / notch_spacing_m)) / 2): notches every
/// notch_spacing_m (none when 0) that let the sun through as light shafts. Near its ends (the
/// last half_width_m) the crest falls to 0 as cos^2 too.
struct RidgeSpec {
  double height_m = 1500.0;
  double distance_m = 20000.0;
  double azimuth_deg = 270.0;
  double half_width_m = 3000.0;
  double length_m = 80000.0;
  double notch_spacing_m = 0.0;
  double notch_depth = 0.6;
};
/// The ridge's heights on a grid of spacing_m covering it.
HeightGrid ridge_heights(const RidgeSpec& ridge, double spacing_m);
/// The ridge's analytic height at map coordinates.
double ridge_height_at(const RidgeSpec& ridge, double east_m, double north_m);

}  // namespace skyspec
