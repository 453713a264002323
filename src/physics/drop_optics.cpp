#include "skyspec/drop_optics.hpp"

#include <algorithm>
#include <cmath>

#include "skyspec/error.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

double descartes_scattering_angle(double n, int k) {
  const double i = std::acos(std::sqrt((n * n - 1.0) / (k * (k + 2.0))));
  const double r = std::asin(std::sin(i) / n);
  const double d = 2.0 * (i - r) + k * (kPi - 2.0 * r);
  const double folded = std::fmod(d, 2.0 * kPi);
  return folded > kPi ? 2.0 * kPi - folded : folded;
}

namespace {
constexpr long kImpactParameters = 400000;

// Fresnel reflectances for s and p from index 1 into n at incidence cosine cos_i (the same values
// leaving, by reciprocity); cos_t the refracted cosine.
void fresnel(double n, double cos_i, double cos_t, double& rs, double& rp) {
  const double s = (cos_i - n * cos_t) / (cos_i + n * cos_t);
  const double p = (n * cos_i - cos_t) / (n * cos_i + cos_t);
  rs = s * s;
  rp = p * p;
}
}  // namespace

std::vector<double> drop_geometric_scattering(double n, const std::vector<double>& mu) {
  if (!(n > 1.0) || mu.size() < 2 || mu.front() != -1.0 || mu.back() != 1.0)
    throw Error("drop_geometric_scattering: needs an index > 1 and cosines from -1 to 1");
  std::vector<double> share(mu.size() - 1, 0.0);
  const auto add = [&](double deviation, double weight) {
    double theta = std::fmod(deviation, 2.0 * kPi);
    if (theta > kPi) theta = 2.0 * kPi - theta;
    const double c = std::clamp(std::cos(theta), -1.0, 1.0);
    const size_t j =
        std::min(static_cast<size_t>(std::upper_bound(mu.begin(), mu.end(), c) - mu.begin()), mu.size() - 1) - 1;
    share[j] += weight;
  };
  const double w = 1.0 / static_cast<double>(kImpactParameters);  // each ring carries the same area
  for (long j = 0; j < kImpactParameters; ++j) {
    const double b2 = (static_cast<double>(j) + 0.5) * w;  // b^2 = sin^2 i, evenly spaced
    const double sin_i = std::sqrt(b2), cos_i = std::sqrt(1.0 - b2);
    const double i = std::asin(sin_i), r = std::asin(sin_i / n), cos_t = std::cos(r);
    double rs = 0.0, rp = 0.0;
    fresnel(n, cos_i, cos_t, rs, rp);
    add(kPi - 2.0 * i, w * 0.5 * (rs + rp));  // reflected off the outside
    double ts = (1.0 - rs) * (1.0 - rs), tp = (1.0 - rp) * (1.0 - rp);
    for (int k = 0; k <= kMaxDropReflections; ++k) {
      add(2.0 * (i - r) + k * (kPi - 2.0 * r), w * 0.5 * (ts + tp));
      ts *= rs;
      tp *= rp;
    }
  }
  return share;
}

}  // namespace skyspec
