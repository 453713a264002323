// The light a medium confined to a region (Medium::region: a rain shower) scatters after it has
// scattered it already, which the scattering-order tables leave out (they hold the field of the
// atmosphere without it: AtmosphereModel::with_regional_media_as_probes).
//
// The renderer's higher-order source of a scatterer s at a point x, towards the camera (view
// direction w), is J_s(x, w) = integral of p_s(angle between w_in and -w) L(x, w_in) dw_in over the
// light L arriving at x. The tables give it for the field without the region. Here L is taken
// instead as the renderer's own radiance at x, which holds the region: the sun's light it scatters
// once (with the chords of its shadow), the background's light it scatters once (the tables'
// source) and the background seen through it. One such pass is the "successive orders" step that
// adds the light scattered twice by the region's medium and dims the background's light inside it:
//
//   Delta J_s(x) = sum over cells c of W_c,s L(x, w_in,c) - J_s,tables(x, w),
//
// on cells of scattering angle about -w (finer where rain's phase function has its bows) and of
// azimuth about it, W_c,s the integral of p_s over cell c (exact to the phase function's own
// sampling) and L at the cell's centre, for every scatterer s (the air inside the shower scatters
// its light too, and so does the air about it, which sees it). It is computed for the directions in
// which one camera sees the grid's points (w = the direction from the camera to x), on a grid over
// the region and the air about it: points on a square of side 4 r (Grid::reach) about the
// cylinder's axis at heights that split its vertical column into equal parts, interpolated
// trilinearly; added to the tables' source at the integrator's nodes in the square below the
// column's top (SingleScattering, ScatteringSources::regional). A second pass marches L with the first pass's
// Delta J, which it needs at each node towards the grid point the ray started from: the first pass
// keeps Delta J for every direction of its cells about -w (at each cell's centre, with the poles;
// the weights W_c,s for an outgoing direction d are the integrals of p_s over the cells about
// their angles with d, on 8 x 8 sub-cells, scaled to the integral of p_s over the sphere),
// interpolated bilinearly in the angle from -w and the azimuth about it at each of the 8 grid
// points about the node: the light scattered three times. Later passes do the same; the last keeps
// the camera's direction only. More orders are left out (docs/bows-and-halos.md measures what
// remains against the Monte Carlo), and so is the polarisation of Delta J (its intensity only).
//
// The ground near the region is lit by the region's light too, which the tables' irradiance of the
// ground leaves out: each pass also integrates its light over the sky of the grid's points on the
// ground (8 rows in the cosine of the zenith angle times 16 azimuths, midpoint
// rule), Delta E = E - E_tables, which the next pass and the render add to the ground's light
// there (SingleScattering's ground reflection, ScatteringSources::regional).
#pragma once

#include <vector>

#include "transport/single_scattering.hpp"

namespace skyspec {

class RegionalSecondOrder : public RegionalSource {
 public:
  struct Grid {
    int across = 7;   ///< points along each side of the square about the cylinder
    int heights = 7;  ///< heights, at equal shares of the column (the first at the ground)
    int phi = 16;     ///< azimuth cells about the view direction
    int passes = 3;   ///< 1: the light scattered twice by the region's medium; 2: three times; ...
    /// Half the side of the grid's square about the axis, in the cylinder's radii: the air about
    /// the region is lit by its light too.
    double reach = 2.0;
  };
  /// For renders from `camera` (a point in the atmosphere) with the sun along `sun` (unit), whose
  /// sources `sources` (the tables; no regional source) the integrator evaluates. Built over
  /// `threads` threads.
  RegionalSecondOrder(const SingleScattering& integrator, const ScatteringSources& sources, const Vec3& camera,
                      const Vec3& sun, Grid grid, int threads);
  RegionalSecondOrder(const SingleScattering& integrator, const ScatteringSources& sources, const Vec3& camera,
                      const Vec3& sun, int threads)
      : RegionalSecondOrder(integrator, sources, camera, sun, Grid{}, threads) {}

  /// Adds every scatterer's Delta J at x, inside a region, towards the camera (after the
  /// constructor; while it builds a later pass, towards `toward`): every scatterer's, since the
  /// air there scatters the region's light too. False outside every region.
  bool add(const Vec3& x, const Vec3& toward, float* const* out) const override;
  /// Adds Delta E at a ground point within 2 r of a region's axis: the light of the sky on the
  /// ground as the last pass sees it (the region's light included) less the tables' (bilinearly
  /// between the ground grid's points). False farther away.
  bool add_ground(const Vec3& ground_point, float* irradiance) const override;

  /// The edges of the cells of scattering angle, degrees (0 to 180).
  static const std::vector<double>& angle_edges_deg();

 private:
  /// A grid point's axes: w from the camera to it, a and b across w (the cells' azimuth).
  struct Frame {
    Vec3 w, a, b;
  };
  struct Region {
    int medium = -1;  ///< its index in AtmosphereModel::media()
    VerticalCylinder cylinder;
    Vec3 e1, e2;  ///< across the axis
    std::vector<double> heights_m;
    std::vector<Frame> frames;  // per point
    /// Delta J: [point][scatterer][wavelength] towards the camera (the last pass), or, while a
    /// later pass is built, [point][direction][scatterer][wavelength] (direction_index).
    std::vector<float> values;
    /// Delta E on the ground grid: [(iy * ground_across + ix) * n + wavelength].
    std::vector<float> ground;
  };
  Vec3 grid_point(const Region& region, int p) const;
  /// Ground grid point g (1 m above the ground), on the grid's square.
  Vec3 ground_point(const Region& region, int g) const;
  double half_side_m(const Region& region) const { return grid_.reach * region.cylinder.radius_m; }
  /// The directions a pass keeps Delta J for, in a point's frame: rows of angle from -w (row 0:
  /// -w itself; rows 1..cells: the cells' centres; the last: w) times the cells' azimuths (one
  /// at either pole).
  size_t direction_index(int row, int k) const;
  int direction_count() const;
  Grid grid_;
  int n_ = 0;
  int scatterers_ = 0;
  size_t values_per_point_ = 0;
  double planet_radius_m_ = 0.0;
  std::vector<double> row_angles_rad_;  ///< the rows' angles from -w
  bool directional_ = false;            ///< values hold every direction (while building a pass)
  std::vector<Region> regions_;
};

}  // namespace skyspec
