#include "skyspec/size_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "base/quadrature.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

namespace {
constexpr double kTail = 1e-9;  // the share of each moment r^0 .. r^3 left outside the range

[[noreturn]] void refuse(const std::string& what, double value, const std::string& allowed) {
  std::ostringstream s;
  s << "size distribution: " << what << " = " << value << " is not allowed: " << allowed;
  throw std::invalid_argument(s.str());
}

// The radius beyond the peak of r^k f(r) (f decreasing faster than any power there) where it has
// fallen below kTail^1.5 of its peak value, found by stepping outwards by 1 % at a time.
template <class F>
double upper_tail(double r_peak, F f, int k) {
  const double peak = std::pow(r_peak, k) * f(r_peak);
  double r = r_peak;
  while (std::pow(r, k) * f(r) > kTail * std::sqrt(kTail) * peak) r *= 1.01;
  return r;
}
}  // namespace

SizeDistribution SizeDistribution::lognormal(double median_radius_m, double geometric_standard_deviation) {
  if (!(median_radius_m > 0.0) || !std::isfinite(median_radius_m))
    refuse("median radius (m)", median_radius_m, "a positive length");
  if (!(geometric_standard_deviation > 1.0 && geometric_standard_deviation <= 10.0))
    refuse("geometric standard deviation", geometric_standard_deviation, "1 < sigma <= 10");
  SizeDistribution d;
  d.kind_ = Kind::Lognormal;
  d.p1_ = std::log(median_radius_m);
  d.p2_ = std::log(geometric_standard_deviation);
  // In ln r the moment r^k dN is a normal distribution of mean ln r_m + k s^2 and deviation s:
  // 6.5 deviations on either side of k = 0 .. 3 leave 4e-11 outside.
  d.r_min_ = std::exp(d.p1_ - 6.5 * d.p2_);
  d.r_max_ = std::exp(d.p1_ + 3.0 * d.p2_ * d.p2_ + 6.5 * d.p2_);
  d.normalise();
  return d;
}

SizeDistribution SizeDistribution::lognormal_within(double median_radius_m, double geometric_standard_deviation,
                                                    double spreads) {
  if (!(spreads > 0.0) || !std::isfinite(spreads)) refuse("spreads either side", spreads, "a positive number");
  const SizeDistribution d = lognormal(median_radius_m, geometric_standard_deviation);
  const double cut = std::pow(geometric_standard_deviation, spreads);
  return d.truncated(median_radius_m / cut, median_radius_m * cut);
}

SizeDistribution SizeDistribution::modified_gamma(double mode_radius_m, double alpha, double gamma) {
  if (!(mode_radius_m > 0.0) || !std::isfinite(mode_radius_m))
    refuse("mode radius (m)", mode_radius_m, "a positive length");
  if (!(alpha > 0.0 && alpha <= 100.0)) refuse("alpha", alpha, "0 < alpha <= 100");
  if (!(gamma > 0.0 && gamma <= 10.0)) refuse("gamma", gamma, "0 < gamma <= 10");
  SizeDistribution d;
  d.kind_ = Kind::ModifiedGamma;
  d.p1_ = alpha;
  d.p2_ = alpha / (gamma * std::pow(mode_radius_m, gamma));
  d.p3_ = gamma;
  // Below r_min (where exp(-B r^gamma) is about 1) lies A r_min^(alpha + 1) / (alpha + 1) of the
  // number, and the whole is A Gamma((alpha + 1) / gamma) / (gamma B^((alpha + 1) / gamma)).
  const double a1 = alpha + 1.0;
  d.r_min_ = std::exp((std::log(kTail * a1 / gamma) + std::lgamma(a1 / gamma) - (a1 / gamma) * std::log(d.p2_)) / a1);
  const double r3 = std::pow((alpha + 3.0) / (gamma * d.p2_), 1.0 / gamma);  // the peak of r^3 dN/dr
  d.r_max_ = upper_tail(
      r3, [&d](double r) { return d.unnormalised(r); }, 3);
  d.normalise();
  return d;
}

SizeDistribution SizeDistribution::marshall_palmer(double rain_rate_mm_per_h) {
  if (!(rain_rate_mm_per_h > 0.0 && rain_rate_mm_per_h <= 500.0))
    refuse("rain rate (mm/h)", rain_rate_mm_per_h, "0 < R <= 500");
  SizeDistribution d;
  d.kind_ = Kind::MarshallPalmer;
  d.rain_rate_mm_per_h_ = rain_rate_mm_per_h;
  const double lambda_per_m = 4.1e3 * std::pow(rain_rate_mm_per_h, -0.21);  // 4.1 R^-0.21 mm^-1
  d.p1_ = 2.0 * lambda_per_m;                                               // in radius
  // dN/dr is flat near r = 0: below r_min lies 2 Lambda r_min of the number.
  d.r_min_ = kTail / d.p1_;
  d.r_max_ = upper_tail(
      3.0 / d.p1_, [&d](double r) { return d.unnormalised(r); }, 3);
  d.normalise();
  d.number_per_m3_ = 8e6 / lambda_per_m;  // N0 = 8000 m^-3 mm^-1 = 8e6 m^-4
  return d;
}

SizeDistribution SizeDistribution::truncated(double r_min_m, double r_max_m) const {
  if (!(r_min_m > 0.0) || !std::isfinite(r_min_m)) refuse("minimum radius (m)", r_min_m, "a positive length");
  if (!(r_max_m > r_min_m) || !std::isfinite(r_max_m))
    refuse("maximum radius (m)", r_max_m, "a length above the minimum radius");
  SizeDistribution d = *this;
  const double before = d.norm_;
  d.r_min_ = r_min_m;
  d.r_max_ = r_max_m;
  d.truncated_ = true;
  d.normalise();
  // The concentration keeps only the drops inside the range.
  d.number_per_m3_ = number_per_m3_ * before / d.norm_;
  return d;
}

std::string SizeDistribution::description() const {
  std::ostringstream s;
  switch (kind_) {
    case Kind::Lognormal:
      s << "lognormal, median radius " << std::exp(p1_) * 1e6 << " um, sigma " << std::exp(p2_);
      break;
    case Kind::ModifiedGamma:
      s << "modified gamma, mode radius " << std::pow(p1_ / (p3_ * p2_), 1.0 / p3_) * 1e6 << " um, alpha " << p1_
        << ", gamma " << p3_;
      break;
    case Kind::MarshallPalmer:
      s << "Marshall-Palmer, rain rate " << rain_rate_mm_per_h_ << " mm/h";
      break;
  }
  if (truncated_) s << ", radii " << r_min_ * 1e6 << "-" << r_max_ * 1e6 << " um";
  return s.str();
}

double SizeDistribution::unnormalised(double r) const {
  switch (kind_) {
    case Kind::Lognormal: {
      const double z = (std::log(r) - p1_) / p2_;
      return std::exp(-0.5 * z * z) / (std::sqrt(2.0 * kPi) * r * p2_);
    }
    case Kind::ModifiedGamma:
      return std::pow(r, p1_) * std::exp(-p2_ * std::pow(r, p3_));
    case Kind::MarshallPalmer:
      return std::exp(-p1_ * r);
  }
  return 0.0;
}

double SizeDistribution::density_per_m(double r_m) const {
  if (!(r_m >= r_min_ && r_m <= r_max_)) return 0.0;
  return norm_ * unnormalised(r_m);
}

std::vector<RadiusNode> SizeDistribution::quadrature(double max_ln_step, double max_step_m) const {
  if (!(max_ln_step > 0.0)) refuse("largest step in ln r", max_ln_step, "a positive number");
  if (!(max_step_m > 0.0)) refuse("largest step in r (m)", max_step_m, "a positive length");
  constexpr int kPoints = 8;
  std::vector<double> x, w;
  gauss_legendre(kPoints, 0.0, 1.0, x, w);
  std::vector<RadiusNode> nodes;
  double a = std::log(r_min_);
  const double end = std::log(r_max_);
  while (a < end) {
    const double b = std::min(end, a + std::min(max_ln_step, max_step_m / std::exp(a)));
    for (int k = 0; k < kPoints; ++k) {
      const double u = a + (b - a) * x[static_cast<size_t>(k)];
      const double r = std::exp(u);
      // dr = r du
      nodes.push_back({r, (b - a) * w[static_cast<size_t>(k)] * r * density_per_m(r)});
    }
    a = b;
  }
  return nodes;
}

void SizeDistribution::normalise() {
  norm_ = 1.0;
  double total = 0.0;
  for (const RadiusNode& n : quadrature(0.05, std::numeric_limits<double>::infinity())) total += n.weight;
  norm_ = 1.0 / total;
}

double SizeDistribution::moment(int k) const {
  double sum = 0.0;
  for (const RadiusNode& n : quadrature(0.05, std::numeric_limits<double>::infinity()))
    sum += n.weight * std::pow(n.radius_m, k);
  return sum;
}

}  // namespace skyspec
