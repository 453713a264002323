// The sky seen from one point, tabulated over view directions.
//
// For a camera at a fixed point and a sun at infinity the radiance depends on the view direction
// only, and the scene is mirror-symmetric about the vertical plane through the sun: two angles
// describe every ray, the view zenith angle theta and the azimuth phi from the sun's azimuth, in
// [0, pi]. A render asks for hundreds of thousands of directions; a table of a few thousand
// marched rays, interpolated, gives the same image at a fraction of the cost (Hillaire 2020 does
// this for real time; here it is held to the accuracy of the per-pixel march).
//
// What is tabulated are the phase-free parts of the radiance (RadianceParts in
// single_scattering.hpp), which are smooth in direction; the phase functions, sharply peaked
// around the sun for aerosols, are applied exactly per pixel. Rows crowd where the sky changes
// fastest, near the horizon (sky_view_table.cpp, zenith_of), and the horizon is
// a boundary of the table: directions above it are interpolated only from rays above it, and
// directions below it (the ground, or the air in front of it) only from rays below it, so the
// step in radiance at the horizon is not smeared.
//
// It applies to cameras inside the atmosphere and above the ground, without a regional medium (see
// applicable()).
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "base/zeroed_floats.hpp"
#include "skyspec/geometry.hpp"
#include "transport/single_scattering.hpp"

namespace skyspec {

struct SkyViewResolution {
  int sky_rows = 128;       ///< view zenith samples from the horizon to the zenith
  int ground_rows = 48;     ///< view zenith samples from the horizon to the nadir
  int azimuths = 64;        ///< azimuth samples from towards the sun (0) to away from it (pi)
  bool ground_side = true;  ///< tabulate below the horizon too (false: an image of the sky alone)
  /// The higher orders' light (what the higher-order source adds to the phase-free part, and their
  /// polarisation) on a coarser table of this many sky rows and azimuths (ground rows half the sky
  /// rows), interpolated to this table's entries; 0: on this table's own.
  int higher_sky_rows = 0, higher_azimuths = 0;
};

class SkyViewTable {
 public:
  /// Whether a table represents the sky seen from origin_m: inside the atmosphere, above ground,
  /// in an atmosphere whose media are everywhere (a regional medium's sharp walls would be blurred
  /// by the table's interpolation, and its rays are not alike in azimuth: every pixel is marched).
  static bool applicable(const AtmosphereModel& atm, const Vec3& origin_m);

  /// Marches every table ray with `integrator` (sources as for a pixel, without terrain) from
  /// origin_m, for the sun in direction sun_dir (unit), on `threads` threads. The rays are marched
  /// in the table's own frame, the camera on the z axis and the sun in the x-z plane
  /// (own_frame_sun), so the entries depend on the camera's radius and the sun's zenith angle
  /// there only, not on the number of threads: reoriented() serves every camera at that radius
  /// with the sun at that zenith angle.
  SkyViewTable(const SingleScattering& integrator, const ScatteringSources& sources, const Vec3& origin_m,
               const Vec3& sun_dir, SkyViewResolution resolution, int threads);

  /// The sun's direction in the table's own frame for a camera at origin_m: (sin z, 0, cos z), z
  /// the sun's zenith angle there.
  static Vec3 own_frame_sun(const Vec3& origin_m, const Vec3& sun_dir);
  /// This table for a camera at origin_m with the sun along sun_dir: the same entries (shared, not
  /// copied), looked up in that camera's frame. Throws Error unless the camera's radius and own_frame_sun
  /// are exactly this table's (the same entries would be marched).
  SkyViewTable reoriented(const Vec3& origin_m, const Vec3& sun_dir) const;

  /// The phase-free parts of the radiance along the unit direction dir, per unit solar irradiance,
  /// interpolated (cubic across rows, linear in azimuth) on the side of the horizon dir is on.
  /// False (and `out` untouched) for a direction below the horizon when that side was not built.
  bool lookup(const Vec3& dir, RadianceParts& out) const;
  /// lookup() for count unit directions at once, their angles computed together (a loop that
  /// vectorises): direction k's parts go to out + parts() n k (each scattering medium's, then the
  /// phase-free part, n floats each, n the wavelengths), found[k] is lookup()'s answer. The same
  /// values as lookup().
  void lookup_many(int count, const Vec3* dirs, float* out, bool* found) const;
  /// lookup() and, for a table built with ScatteringSources::polarisation, the higher orders'
  /// polarised_q and polarised_u too (in the direction's polarisation_frame; the table holds the
  /// side of the sun's vertical plane towards +across, and U changes sign on the other). False for
  /// a table without polarisation.
  bool lookup_polarised(const Vec3& dir, RadianceParts& out) const;
  bool polarised() const { return polarised_; }
  /// Parts per direction: one per scattering medium and the phase-free part.
  int parts() const { return parts_; }
  /// The zenith angle of the horizon seen from the table's point (> pi/2 above the ground).
  double horizon_zenith_rad() const { return horizon_zenith_rad_; }

  /// The direction of table row `row` (of the sky side, or of the ground side) and azimuth
  /// column `column`, for tests.
  Vec3 direction(bool sky_side, int row, int column) const;

  const SkyViewResolution& resolution() const { return res_; }
  /// The bytes its entries take.
  size_t bytes() const;

 private:
  // Row placement coordinate in [0, 1] of a zenith angle on one side of the horizon, its inverse,
  // the variable rows are interpolated in, and the distance to the ground (sky_view_table.cpp).
  double placement_of(bool sky_side, double theta) const;
  double zenith_of(bool sky_side, double u) const;
  double first_row_zenith(bool sky_side, int rows) const;
  double key_of(bool sky_side, double theta) const;
  double ground_distance(double theta) const;
  // The view zenith angle and the azimuth from the sun (in [0, pi]) of a unit direction by the
  // polynomial atan2; theta again by libm's where it is within 1e-6 rad of the horizon; the
  // table's interpolation at (theta, phi) (false where it has no side for theta).
  void angles_of(const Vec3& dir, double& theta, double& phi) const;
  double refined_zenith(const Vec3& dir, double theta) const;
  // The rows and columns around (theta, phi) and their weights (interpolate's; false where the
  // table has no side for theta).
  struct Weights {
    bool sky_side = true;
    int first_row = 0, n_rows = 0, c0 = 0;
    double row_w[4] = {0, 0, 0, 0};
    float w0 = 0, w1 = 0;
  };
  bool weights(double theta, double phi, Weights& w) const;
  // Whether a and b mix the same rows with the same weights at the same column pair.
  static bool same_rows(const Weights& a, const Weights& b);
  // The entry of w's first row at column c0 (on w's side of the horizon).
  const float* first_entry(const Weights& w) const;
  // The radiance's parts at those weights, into parts[0 .. parts() - 1] or into out.
  void mix(const Weights& w, float* const* parts) const;
  void mix(const Weights& w, RadianceParts& out) const;

  // The look-ups' frame for a camera at origin_m with the sun along sun_dir.
  void set_frame(const Vec3& origin_m, const Vec3& sun_dir);
  // The higher orders' light from a coarse table of it alone (SkyViewResolution::higher_sky_rows).
  void add_coarse_higher_orders(const SkyViewTable& higher, int threads);

  SkyViewResolution res_;
  int n_ = 0;                      // wavelengths
  int parts_ = 0;                  // per direction: one per scattering medium, and the phase-free part
  Vec3 up_, toward_sun_, across_;  // local frame: zenith, sun's azimuth, perpendicular
  Vec3 own_sun_;                   // own_frame_sun of the marched rays
  double horizon_zenith_rad_ = 0.0;
  double r_m_ = 0.0, R_m_ = 0.0, rho_m_ = 0.0;  // camera and planet radii, distance to the horizon
  std::vector<double> sky_theta_, ground_theta_, sky_key_, ground_key_;  // per row: zenith angle, key
  std::vector<double> sky_inv_den_, ground_inv_den_;  // per row pair: its rows' Lagrange denominators (4 each)
  bool polarised_ = false;
  // The entries, written while the constructor marches the rays and shared by reoriented() copies.
  struct Entries {
    // [side][row][column][part][lambda], part = each scattering medium's, then phase_free. Zeroed
    // by the system as the table's rays fill them (ZeroedFloats), not on the calling thread first.
    ZeroedFloats sky, ground;
    // With polarisation: [side][row][column][Q, U][lambda].
    ZeroedFloats polarised_sky, polarised_ground;
  };
  std::shared_ptr<Entries> entries_ = std::make_shared<Entries>();
};

}  // namespace skyspec
