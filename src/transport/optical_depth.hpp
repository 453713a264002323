// Column densities and the precomputed table of them towards the sun.
//
// The optical depth between two points is tau(lambda) = sum_species beta_ext,s(lambda) C_s, with
// C_s = integral rho_s(z(t)) dt the species' column of relative density (metres of
// altitude-0-equivalent gas). C_s does not depend on wavelength, so one table of a few scalars
// per (altitude, sun zenith cosine) replaces every light-ray march of the seed tutorial
// (Nishita et al. 1993 tabulate the same quantity; Bruneton & Neyret 2008 tabulate its exp).
#pragma once

#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include "skyspec/atmosphere.hpp"
#include "skyspec/geometry.hpp"
#include "transport/quadrature.hpp"

namespace skyspec {

/// Columns of relative density, one per medium of AtmosphereModel::media() (in its order); the
/// entries past the atmosphere's media are zero.
using Columns = std::array<double, kMaxMedia>;

/// Distance from radius r along zenith cosine mu to the sphere of radius top_r (r <= top_r).
/// Inline and written with selects, so that loops over many points vectorise.
inline double distance_to_top_m(double r_m, double mu, double top_r_m) {
  // Root of t^2 + 2 r mu t + (r^2 - R_t^2) = 0 that is >= 0; discriminant r^2 (mu^2 - 1) + R_t^2
  // written as (R_t - r)(R_t + r) + r^2 mu^2 to keep precision near the top.
  const double disc = (top_r_m - r_m) * (top_r_m + r_m) + r_m * r_m * mu * mu;
  const double root = -r_m * mu + std::sqrt(disc > 0.0 ? disc : 0.0);
  return root > 0.0 ? root : 0.0;
}

/// Column of relative density from radius r, zenith cosine mu, to the top of the atmosphere, by
/// the exponential (log-mean) rule with Richardson extrapolation on `segments` pieces (split at
/// the ray's lowest point when it descends first). Rays that hit the planet are not handled:
/// callers check the horizon.
double column_to_top_m(const DensityProfile& profile, double planet_radius_m, double top_radius_m, double r_m,
                       double mu, int segments);

/// Columns for all media from (r, mu) to the top: the table's reference computation.
Columns columns_to_top_m(const AtmosphereModel& atm, double r_m, double mu, int segments);

/// Precomputed columns to the top of the atmosphere over (r, mu), parameterised as in Bruneton &
/// Neyret 2008 / Bruneton 2017 (x_r = sqrt(r^2 - R^2) / sqrt(R_t^2 - R^2), x_mu by distance to the
/// top between its minimum and its value at the horizon), so resolution concentrates at the
/// ground and at the horizon. Only directions that clear the planet are stored.
class SunColumnTable {
 public:
  struct Resolution {
    int n_r = 128;       ///< samples in altitude
    int n_mu = 256;      ///< samples in zenith cosine (horizon to zenith)
    int segments = 128;  ///< integration pieces per table entry
  };
  /// The sun zenith cosines the table is to serve: entries are computed only where a look-up with
  /// mu in [lo, hi] interpolates (the same grid and values as the whole table there). A look-up
  /// outside the band is computed directly (columns_to_top_m), so it is slower, never wrong.
  struct MuBand {
    double lo = -1.0, hi = 1.0;
    /// A camera's band (band_seen_from) is narrower at low altitudes: where camera_radius_m > 0,
    /// the band at radius r is the sun's zenith angle at the camera, sun_zenith_rad, widened by
    /// acos(R / camera_radius_m) + acos(R / r) (within [lo, hi]).
    double camera_radius_m = 0.0;
    double sun_zenith_rad = 0.0;
  };
  SunColumnTable(const AtmosphereModel& atm, Resolution res, MuBand band);
  SunColumnTable(const AtmosphereModel& atm, Resolution res) : SunColumnTable(atm, res, MuBand{-1.0, 1.0}) {}
  SunColumnTable(const AtmosphereModel& atm) : SunColumnTable(atm, Resolution{}) {}
  /// The table these arguments build, built once per process while it is among the last few asked
  /// for (thread-safe): frames of one atmosphere, such as the viewer's as the sun moves, share one.
  /// It depends on the radii, the media's density profiles, the resolution and the band only.
  /// Tables of more than kSharedBytes are built for the caller alone.
  static std::shared_ptr<const SunColumnTable> shared(const AtmosphereModel& atm, Resolution res, MuBand band);
  static constexpr size_t kSharedBytes = size_t{64} << 20;

  /// The local sun zenith cosines met in the part of the atmosphere seen from origin_m with the
  /// sun in direction sun_dir (unit). A point p at radius r seen from o is at most
  /// acos(R / |o|) + acos(R / r) away from it in angle at the planet's centre (the two tangents
  /// to the ground), and the sun's zenith angle at p differs from its angle at o by at most that:
  /// so the band is narrowest near the ground, widest (r = R_t) at the top. From inside the
  /// planet or from far away this is (nearly) every angle.
  static MuBand band_seen_from(const AtmosphereModel& atm, const Vec3& origin_m, const Vec3& sun_dir);

  /// Columns from radius r towards zenith cosine mu; r is clamped to [R, R_t] and mu to the
  /// horizon cosine, so callers must have established that the point is lit.
  Columns lookup(double r_m, double mu) const;
  /// lookup() at count points (r_m[k], mu[k]), the same values: the table coordinates of all
  /// points are computed first in a loop the compiler vectorises (the square roots and divisions
  /// of several points at once), then interpolated.
  void lookup_many(int count, const double* r_m, const double* mu, Columns* out) const;
  const Resolution& resolution() const { return res_; }
  /// Entries computed (all n_r * n_mu without a band).
  long computed_entries() const;

 private:
  // Where (r_m, mu) falls in the table: r clamped, x_mu, and the fractional indices fr, fm.
  struct Place {
    double r, x_mu, fr, fm;
  };
  Place place(double r_m, double mu) const;
  Columns interpolate(const Place& p) const;
  Columns direct(double r, double x_mu) const;
  /// The columns from (r, mu) to the top, integrated (columns_to_top_m).
  Columns integrate(double r, double mu) const;
  std::vector<DensityProfile> profiles_;  // the atmosphere's media's, in its order
  int media_;                             // columns per entry: the atmosphere's media
  double R_, Rt_, H_;
  Resolution res_;
  std::vector<Columns> data_;     // [i_r * n_mu + i_mu]
  std::vector<int> first_, end_;  // per altitude row: the computed i_mu are [first, end)
};

}  // namespace skyspec
