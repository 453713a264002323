// Number size distributions of spherical particles: dN/dr, particles per unit radius, normalised
// to one particle (number_per_m3 gives the concentration where the distribution defines one).
//
//   lognormal       dN/dr = 1 / (sqrt(2 pi) r ln s) exp(-(ln r - ln r_m)^2 / (2 ln^2 s))
//                   r_m the median radius of the number distribution, s the geometric standard
//                   deviation (OPAC's "rmod" and "sigma": Hess, Koepke & Schult 1998, BAMS 79, 831, eq. 1)
//   modified gamma  dN/dr = A r^alpha exp(-B r^gamma), B = alpha / (gamma r_c^gamma), r_c the mode radius
//                   (Deirmendjian 1969, "Electromagnetic scattering on spherical polydispersions"; OPAC's
//                   clouds and fog)
//   Marshall-Palmer N(D) = N0 exp(-Lambda D), N0 = 8000 m^-3 mm^-1, Lambda = 4.1 R^-0.21 mm^-1 for a
//                   rain rate R in mm/h (Marshall & Palmer 1948, J. Meteorol. 5, 165); in radius
//                   dN/dr = 2 N0 exp(-2 Lambda r), N0 / Lambda drops per m^3
//
// Each distribution also gives the radius range that integrals over it need: where the moments
// r^0 .. r^3 of the distribution hold all but 1e-9 of their value (or the range a user gives,
// as OPAC's rmin / rmax).
#pragma once

#include <string>
#include <vector>

namespace skyspec {

/// A node of a quadrature over a size distribution: sum of weight f(radius_m) ~ integral f(r) dN/dr dr.
struct RadiusNode {
  double radius_m;
  double weight;  ///< the rule's weight times dN/dr at the node
};

class SizeDistribution {
 public:
  enum class Kind { Lognormal, ModifiedGamma, MarshallPalmer };

  static SizeDistribution lognormal(double median_radius_m, double geometric_standard_deviation);
  /// lognormal() cut to [r_m / s^spreads, r_m s^spreads] (and renormalised): drops or droplets of
  /// a median radius r_m and spread s without the far tails (rain and fog cut at 3 spreads).
  static SizeDistribution lognormal_within(double median_radius_m, double geometric_standard_deviation, double spreads);
  static SizeDistribution modified_gamma(double mode_radius_m, double alpha, double gamma);
  static SizeDistribution marshall_palmer(double rain_rate_mm_per_h);

  /// The same distribution cut to [r_min, r_max] (and renormalised to one particle in it).
  SizeDistribution truncated(double r_min_m, double r_max_m) const;

  Kind kind() const { return kind_; }
  std::string description() const;
  /// dN/dr, m^-1, normalised to one particle over [min_radius_m, max_radius_m].
  double density_per_m(double r_m) const;
  double min_radius_m() const { return r_min_; }
  double max_radius_m() const { return r_max_; }
  /// Particles per m^3: Marshall-Palmer's N0 / Lambda (within the range); 0 where the distribution
  /// gives a shape only (lognormal, modified gamma: the concentration is the medium's business).
  double number_per_m3() const { return number_per_m3_; }
  /// The k-th moment <r^k> = integral r^k dN/dr dr over the range, m^k (by quadrature; the tests
  /// check it against the closed forms).
  double moment(int k) const;
  /// Nodes for integrals over the distribution: composite 8-point Gauss-Legendre in ln r over the
  /// range, in panels at most max_ln_step wide in ln r and max_step_m wide in r (the Lorenz-Mie
  /// integrals bound the step in size parameter so).
  std::vector<RadiusNode> quadrature(double max_ln_step, double max_step_m) const;

 private:
  SizeDistribution() = default;
  double unnormalised(double r_m) const;
  void normalise();

  Kind kind_ = Kind::Lognormal;
  double p1_ = 0.0, p2_ = 0.0, p3_ = 0.0;  // lognormal: ln r_m, ln s; gamma: alpha, B, gamma; MP: 2 Lambda
  double r_min_ = 0.0, r_max_ = 0.0;
  double norm_ = 1.0;  // 1 / integral of unnormalised over the range
  bool truncated_ = false;
  double number_per_m3_ = 0.0;
  double rain_rate_mm_per_h_ = 0.0;
};

}  // namespace skyspec
