#include "skyspec/density_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "skyspec/standard_atmosphere.hpp"

namespace skyspec {

DensityProfile DensityProfile::exponential(double scale_height_m) {
  DensityProfile p;
  p.kind_ = Kind::Exponential;
  p.scale_height_m_ = scale_height_m;
  return p;
}

DensityProfile DensityProfile::constant() { return DensityProfile(); }

DensityProfile DensityProfile::tent(double bottom_m, double peak_m, double top_m) {
  DensityProfile p;
  p.kind_ = Kind::Tent;
  p.bottom_m_ = bottom_m;
  p.peak_m_ = peak_m;
  p.top_m_ = top_m;
  return p;
}

DensityProfile DensityProfile::layer(double base_m, double top_m, double edge_m) {
  DensityProfile p;
  p.kind_ = Kind::Layer;
  p.bottom_m_ = base_m;
  p.top_m_ = top_m;
  p.edge_m_ = edge_m;
  return p;
}

double DensityProfile::layer_column_m() const {
  return edge_m_ * -std::expm1(-bottom_m_ / edge_m_) + (top_m_ - bottom_m_) + edge_m_;
}

std::vector<double> DensityProfile::breakpoints_m() const {
  if (kind_ == Kind::Layer) return {bottom_m_, top_m_};
  return {};
}

double DensityProfile::relative(double altitude_m) const {
  if (kind_ != Kind::Tent) return std::exp(log_relative(altitude_m));
  if (altitude_m <= bottom_m_ || altitude_m >= top_m_) return 0.0;
  if (altitude_m <= peak_m_) return (altitude_m - bottom_m_) / (peak_m_ - bottom_m_);
  return (top_m_ - altitude_m) / (top_m_ - peak_m_);
}

DensityProfile DensityProfile::us_standard_1976(double top_m) {
  DensityProfile p;
  p.kind_ = Kind::UsStandard1976;
  const double top = std::min(std::max(top_m, 1000.0), 100000.0);
  const size_t n = static_cast<size_t>(std::ceil(top / p.step_m_)) + 2;
  auto table = std::make_shared<std::vector<double>>(n);
  const double n0 = us_standard_atmosphere_1976(0.0).number_density_per_m3;
  for (size_t i = 0; i < n; ++i) {
    const double z = std::min(static_cast<double>(i) * p.step_m_, 100000.0);
    (*table)[i] = std::log(us_standard_atmosphere_1976(z).number_density_per_m3 / n0);
  }
  p.log_table_ = std::move(table);
  return p;
}

double DensityProfile::log_relative(double altitude_m) const {
  switch (kind_) {
    case Kind::Exponential:
      return -altitude_m / scale_height_m_;
    case Kind::Constant:
      return 0.0;
    case Kind::Layer:
      if (altitude_m < bottom_m_) return (altitude_m - bottom_m_) / edge_m_;
      if (altitude_m > top_m_) return (top_m_ - altitude_m) / edge_m_;
      return 0.0;
    case Kind::Tent: {
      const double rho = relative(altitude_m);
      return rho > 0.0 ? std::log(rho) : -std::numeric_limits<double>::infinity();
    }
    case Kind::UsStandard1976: {
      const auto& t = *log_table_;
      const double x = altitude_m / step_m_;
      // Linear in ln rho between table points; beyond either end, extend the end segment's slope.
      const double last = static_cast<double>(t.size() - 2);
      const double xi = std::clamp(std::floor(x), 0.0, last);
      const size_t i = static_cast<size_t>(xi);
      const double f = x - xi;
      return t[i] + (t[i + 1] - t[i]) * f;
    }
  }
  return 0.0;
}

std::string DensityProfile::describe() const {
  std::ostringstream s;
  s.precision(12);  // the tables' cache keys hold this text
  switch (kind_) {
    case Kind::Exponential:
      s << "exponential, scale height " << scale_height_m_ << " m";
      break;
    case Kind::Constant:
      s << "constant (homogeneous layer)";
      break;
    case Kind::UsStandard1976:
      s << "U.S. Standard Atmosphere 1976 (N = P / kT)";
      break;
    case Kind::Layer:
      s << "layer from " << bottom_m_ << " m to " << top_m_ << " m, edges falling by e every " << edge_m_ << " m";
      break;
    case Kind::Tent:
      s << "layer from " << bottom_m_ << " m, peak at " << peak_m_ << " m, to " << top_m_ << " m (tent)";
      break;
  }
  return s.str();
}

}  // namespace skyspec
