// Vertical profiles of the number density of a scattering species, relative to its value at
// altitude 0 (sea level): rho(z) = N(z) / N(0). The volume coefficient of the species at
// altitude z is beta(lambda, z) = beta(lambda, 0) rho(z).
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace skyspec {

class DensityProfile {
 public:
  enum class Kind { Exponential, UsStandard1976, Constant, Tent, Layer };

  /// rho(z) = exp(-z / H).
  static DensityProfile exponential(double scale_height_m);
  /// rho(z) = N_1976(z) / N_1976(0) from the U.S. Standard Atmosphere 1976 (T and P from the
  /// standard's layers, N = P / kT), tabulated at 10 m with log-linear interpolation up to top_m.
  static DensityProfile us_standard_1976(double top_m);
  /// rho(z) = 1: a homogeneous layer (closed-form tests, teaching).
  static DensityProfile constant();
  /// A layer: 0 below bottom_m, rising linearly to 1 at peak_m, falling linearly to 0 at top_m
  /// (the ozone layer model of Bruneton 2017's reference implementation).
  static DensityProfile tent(double bottom_m, double peak_m, double top_m);
  /// A cloud layer whose density is positive everywhere: rho(z) = 1 from base_m to top_m, falling
  /// as exp(-(base_m - z) / edge_m) below the base and exp(-(z - top_m) / edge_m) above the top.
  /// ln rho is piecewise linear in z, so the log-mean rule is exact between its two kinks
  /// (breakpoints_m), where integrators split their rays.
  static DensityProfile layer(double base_m, double top_m, double edge_m);

  Kind kind() const { return kind_; }
  double scale_height_m() const { return scale_height_m_; }  ///< exponential only
  std::string describe() const;

  /// ln rho(z): the integrator works with logarithms (an exponential profile is linear in them).
  /// -infinity where the density is zero (tent profile outside its layer).
  double log_relative(double altitude_m) const;
  /// rho(z).
  double relative(double altitude_m) const;
  /// True when rho > 0 everywhere, so that integrals may use the log-mean rule; false for the
  /// tent, which is integrated with the trapezoid rule.
  bool positive_everywhere() const { return kind_ != Kind::Tent; }
  /// Integral of rho over all altitudes, m (tent only: its thickness-weighted area).
  double tent_area_m() const { return 0.5 * (top_m_ - bottom_m_); }
  /// Integral of rho from the ground (altitude 0) up, m (layer only):
  /// edge (1 - exp(-base / edge)) + (top - base) + edge.
  double layer_column_m() const;
  /// Altitudes where ln rho has a kink that column integrals should not step across (layer: its
  /// base and top); empty for the other profiles.
  std::vector<double> breakpoints_m() const;

 private:
  Kind kind_ = Kind::Constant;
  double scale_height_m_ = 0.0;
  // US 1976: ln rho at altitudes step_m_ apart from 0 (values below 0 are extrapolated linearly).
  std::shared_ptr<const std::vector<double>> log_table_;
  double step_m_ = 10.0;
  double bottom_m_ = 0.0, peak_m_ = 0.0, top_m_ = 0.0;  // tent; layer: bottom_m_ is its base
  double edge_m_ = 0.0;                                 // layer
};

}  // namespace skyspec
