// Light scattered more than once: scattering orders accumulated into precomputed tables.
//
// Method (in the spirit of Bruneton & Neyret 2008, with the 2-D source tables of Hillaire 2020):
// for every order k >= 2 the in-scattering source J_k at a point is tabulated over altitude and
// sun zenith cosine (the sky is symmetric about the axis through the planet's centre along the
// sun direction, so those two numbers fix it), per wavelength, per unit solar irradiance:
//
//   J_k(r, mu_s) = 1 / (4 pi) integral over the sphere of L_{k-1}(x, omega) d omega,
//   G_k(mu_s)    = integral over the sky hemisphere of L_{k-1}(ground, omega) cos(theta) d omega,
//
// where L_1 is single scattering plus the direct sun reflected by the ground, and L_{k-1} for
// k > 2 is the radiance produced by J_{k-1} along each ray (plus the ground's reflection of
// G_{k-1}). The single approximation: light scattered a second or later time is scattered
// isotropically (J is the mean radiance, not weighted by the phase function). Everything else,
// extinction, shadow, ground, curvature, is as for single scattering. The directional integrals
// use Gauss-Legendre quadrature in the zenith cosine, split at the horizon, and the midpoint rule
// in azimuth over the half space (the field is symmetric about the sun's vertical plane).
// The tables depend on the atmosphere and the grid only, not on the sun's spectrum.
#pragma once

#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "transport/single_scattering.hpp"

namespace skyspec {

struct MultipleScatteringSettings {
  int orders = 4;              ///< highest scattering order counted (1: single scattering only)
  int altitude_samples = 24;   ///< table rows, denser near the ground (x = sqrt(h / h_top))
  int sun_samples = 48;        ///< table columns over mu_s in [-1, 1], denser near the horizon
  int sky_zenith_nodes = 12;   ///< Gauss-Legendre nodes above the horizon
  int ground_zenith_nodes = 6; ///< Gauss-Legendre nodes below the horizon
  int azimuth_nodes = 8;       ///< midpoint nodes over [0, pi]
  int view_segments = 24;      ///< quadrature segments of each ray while building the tables
};

/// One scattering order (or a sum of orders): J over (r, mu_s) and G over mu_s, per wavelength.
class SourceTable : public InScatteringSource {
 public:
  SourceTable(double planet_radius_m, double top_radius_m, int n_altitude, int n_sun, int n_wavelengths);
  void source(double r_m, double mu_sun, float* out) const override;
  void ground_irradiance(double mu_sun, float* out) const override;

  /// Geometry of the table's samples.
  double altitude_m(int i_altitude) const;
  double mu_sun(int i_sun) const;
  int altitude_count() const { return n_h_; }
  int sun_count() const { return n_mu_; }
  float* j_at(int i_altitude, int i_sun) { return &j_[index(i_altitude, i_sun)]; }
  const float* j_at(int i_altitude, int i_sun) const { return &j_[index(i_altitude, i_sun)]; }
  float* g_at(int i_sun) { return &g_[static_cast<size_t>(i_sun) * n_l_]; }
  const float* g_at(int i_sun) const { return &g_[static_cast<size_t>(i_sun) * n_l_]; }
  /// this += other (same shape).
  void add(const SourceTable& other);
  /// Exact binary form (for the disk cache): shape, then J and G as raw floats.
  void write(std::ostream& out) const;
  /// Reads what write() wrote; false (and the table untouched) if the stream is short or the shape
  /// differs from this table's.
  bool read(std::istream& in);
  /// Mean of J over the table and the wavelengths (for diagnostics and tests).
  double mean_source() const;

 private:
  size_t index(int ih, int imu) const { return (static_cast<size_t>(ih) * n_mu_ + imu) * n_l_; }
  double R_, Rt_;
  int n_h_, n_mu_, n_l_;
  std::vector<float> j_, g_;
};

/// Orders 2..K computed one from the other; source() and ground_irradiance() return their sum.
class ScatteringOrders : public InScatteringSource {
 public:
  /// The integrator provides the atmosphere, the sun columns and the single-scattering term.
  ScatteringOrders(const SingleScattering& integrator, const MultipleScatteringSettings& settings);
  void source(double r_m, double mu_sun, float* out) const override { sum_->source(r_m, mu_sun, out); }
  void ground_irradiance(double mu_sun, float* out) const override { sum_->ground_irradiance(mu_sun, out); }

  int highest_order() const { return settings_.orders; }
  /// The table of order k, 2 <= k <= highest_order().
  const SourceTable& order(int k) const { return *orders_.at(static_cast<size_t>(k - 2)); }
  const SourceTable& sum() const { return *sum_; }
  double build_seconds() const { return build_seconds_; }

  /// Seconds the constructor would take for these settings, without building them: orders 2 of a
  /// 4 x 4 table (the same rays per entry as the real one) are built and timed, and the time is
  /// scaled by the entries (altitudes x sun angles) and the orders. Orders after the second cost
  /// about what the second does (a table look-up replaces the single-scattering sum at each step).
  static double estimate_build_seconds(const SingleScattering& integrator, const MultipleScatteringSettings& settings);

  /// Saves the tables to `path` atomically, tagged with `key` (the scene keys they depend on).
  /// Returns false (and leaves no file) if it cannot.
  bool save(const std::string& path, const std::string& key) const;
  /// Loads tables saved under exactly `key` for this atmosphere and settings; null if the file is
  /// missing, from another key or version, or damaged.
  static std::unique_ptr<ScatteringOrders> load(const std::string& path, const std::string& key,
                                                const AtmosphereModel& atm, const MultipleScatteringSettings& settings);

 private:
  explicit ScatteringOrders(const MultipleScatteringSettings& settings) : settings_(settings) {}
  MultipleScatteringSettings settings_;
  std::vector<std::unique_ptr<SourceTable>> orders_;
  std::unique_ptr<SourceTable> sum_;
  double build_seconds_ = 0.0;
};

/// Gauss-Legendre nodes and weights on [a, b].
void gauss_legendre(int n, double a, double b, std::vector<double>& nodes, std::vector<double>& weights);

}  // namespace skyspec
