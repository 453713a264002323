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
// its light too). It is computed for the directions in which one camera sees the region (w = the
// direction from the camera to x), on a grid over the region: points on a square of side 2 r across
// the cylinder at heights that split its vertical column into equal parts, interpolated
// trilinearly; added to the tables' source at the integrator's nodes inside the region
// (SingleScattering, ScatteringSources::regional). A second pass marches L with the first pass's
// Delta J, taken at each point as the camera direction's for every direction: the light scattered
// three times, approximately; more is left out (docs/bows-and-halos.md measures what remains
// against the Monte Carlo), and so is the polarisation of Delta J (its intensity only).
#pragma once

#include <vector>

#include "transport/single_scattering.hpp"

namespace skyspec {

class RegionalSecondOrder : public RegionalSource {
 public:
  struct Grid {
    int across = 7;   ///< points along each side of the square over the cylinder
    int heights = 7;  ///< heights, at equal shares of the column (the first at the ground)
    int phi = 16;     ///< azimuth cells about the view direction
    int passes = 2;   ///< 1: the light scattered twice by the region's medium; 2: three times too
  };
  /// For renders from `camera` (a point in the atmosphere) with the sun along `sun` (unit), whose
  /// sources `sources` (the tables; no regional source) the integrator evaluates. Built over
  /// `threads` threads.
  RegionalSecondOrder(const SingleScattering& integrator, const ScatteringSources& sources, const Vec3& camera,
                      const Vec3& sun, Grid grid, int threads);
  RegionalSecondOrder(const SingleScattering& integrator, const ScatteringSources& sources, const Vec3& camera,
                      const Vec3& sun, int threads)
      : RegionalSecondOrder(integrator, sources, camera, sun, Grid{}, threads) {}

  /// Adds scatterer s's Delta J at x, inside a region: every scatterer's, since the air there
  /// scatters the region's light too. False outside every region.
  bool add(int scatterer, const Vec3& x, float* out) const override;

  /// The edges of the cells of scattering angle, degrees (0 to 180).
  static const std::vector<double>& angle_edges_deg();

 private:
  struct Region {
    int medium = -1;  ///< its index in AtmosphereModel::media()
    VerticalCylinder cylinder;
    Vec3 e1, e2;  ///< across the axis
    std::vector<double> heights_m;
    std::vector<float> values;  // [point][scatterer][wavelength], point = (iz * across + iy) * across + ix
  };
  Vec3 grid_point(const Region& region, int p) const;
  Grid grid_;
  int n_ = 0;
  size_t values_per_point_ = 0;
  double planet_radius_m_ = 0.0;
  std::vector<Region> regions_;
};

}  // namespace skyspec
