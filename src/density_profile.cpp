#include "skyspec/density_profile.hpp"

#include <algorithm>
#include <cmath>
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
  }
  return s.str();
}

}  // namespace skyspec
