// Single scattering along a view ray (Nishita et al. 1993; the seed tutorial's equation 4):
//
//   L(lambda) = E_sun(lambda) sum_s beta_sca,s(lambda) p_s(mu)
//               * integral_0^T rho_s(t) exp(-tau_view(0, t) - tau_sun(t)) dt
//
// over the part of the ray inside the atmosphere and outside the planet's shadow, with
// tau = sum_s beta_ext,s C_s. All wavelengths are carried together as one vector.
//
// Quadrature: the ray is cut at the shadow boundaries (closed form) and at its lowest point, and
// each piece into segments; on a segment, ln of the integrand rho_s exp(-tau) is taken as linear in
// t, which integrates exactly where the density is exponential and the optical depth linear
// (the log-mean rule). The rule is second order; pairs of segments give a coarse estimate of the
// same integral and Richardson extrapolation, (4 fine - coarse) / 3, removes the leading error
// term at the cost of one extra log-mean per pair (no extra exponentials). View-ray columns are
// accumulated with the log-mean rule; columns towards the sun come from the SunColumnTable.
#pragma once

#include "skyspec/geometry.hpp"
#include "skyspec/optical_depth.hpp"
#include "skyspec/spectrum.hpp"

namespace skyspec {

struct IntegratorSettings {
  int view_segments = 32;  ///< segments along each lit piece of a view ray, in total
};

/// Per-thread scratch memory (spectral arrays are allocated once and reused).
struct ScatteringWorkspace {
  explicit ScatteringWorkspace(int n_wavelengths);
  Spectrum tau_a, tau_b, tau_c, trans_a, trans_b, trans_c, f_a, f_b, x;
  Spectrum sum_rayleigh, sum_mie, coarse_rayleigh, coarse_mie;  // fine and coarse (paired) rules
};

/// How the sun's columns are obtained at a point; the table in production, closed forms in tests.
class SunColumns {
 public:
  virtual ~SunColumns() = default;
  virtual Columns at(double r_m, double mu_sun) const = 0;
};

class TableSunColumns : public SunColumns {
 public:
  explicit TableSunColumns(const SunColumnTable& t) : table_(t) {}
  Columns at(double r_m, double mu_sun) const override { return table_.lookup(r_m, mu_sun); }

 private:
  const SunColumnTable& table_;
};

class SingleScattering {
 public:
  /// The atmosphere and sun-column provider must outlive this object.
  SingleScattering(const AtmosphereModel& atm, const SunColumns& sun_columns, IntegratorSettings s);

  /// Radiance reaching origin_m from direction -dir... i.e. seen looking along dir (unit), for a
  /// sun in direction sun_dir (unit) with spectral irradiance sun_irradiance (per wavelength).
  /// Writes `out` (size = grid size). Rays that start below the ground give 0.
  void radiance(const Vec3& origin_m, const Vec3& dir, const Vec3& sun_dir,
                const Spectrum& sun_irradiance, ScatteringWorkspace& ws, Spectrum& out) const;

  const AtmosphereModel& atmosphere() const { return atm_; }

 private:
  const AtmosphereModel& atm_;
  const SunColumns& sun_;
  IntegratorSettings settings_;
  Spectrum ext_rayleigh_, ext_mie_, sca_rayleigh_, sca_mie_;  // float copies, per metre
};

}  // namespace skyspec
