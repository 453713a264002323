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
}  // namespace

DropMatrixShares drop_geometric_matrix(double n, const std::vector<double>& mu) {
  if (!(n > 1.0) || mu.size() < 2 || mu.front() != -1.0 || mu.back() != 1.0)
    throw Error("drop_geometric_matrix: needs an index > 1 and cosines from -1 to 1");
  DropMatrixShares out;
  out.p11.assign(mu.size() - 1, 0.0);
  out.p12 = out.p33 = out.p11;
  // A ray of amplitudes a_s, a_p (and relative weight w) leaving at deviation D.
  const auto add = [&](double deviation, double w, double as, double ap) {
    double theta = std::fmod(deviation, 2.0 * kPi);
    if (theta > kPi) theta = 2.0 * kPi - theta;
    const double c = std::clamp(std::cos(theta), -1.0, 1.0);
    const size_t j =
        std::min(static_cast<size_t>(std::upper_bound(mu.begin(), mu.end(), c) - mu.begin()), mu.size() - 1) - 1;
    out.p11[j] += w * 0.5 * (as * as + ap * ap);
    out.p12[j] += w * 0.5 * (ap * ap - as * as);
    out.p33[j] += w * as * ap;
  };
  const double w = 1.0 / static_cast<double>(kImpactParameters);  // each ring carries the same area
  for (long j = 0; j < kImpactParameters; ++j) {
    const double b2 = (static_cast<double>(j) + 0.5) * w;  // b^2 = sin^2 i, evenly spaced
    const double sin_i = std::sqrt(b2), cos_i = std::sqrt(1.0 - b2);
    const double i = std::asin(sin_i), r = std::asin(sin_i / n), cos_t = std::cos(r);
    // Fresnel amplitude coefficients from outside (Bohren & Huffman's signs: at normal incidence
    // r_s = -r_p, so that a sphere's backscatter has P33 = -P11).
    const double rs = (cos_i - n * cos_t) / (cos_i + n * cos_t), rp = (n * cos_i - cos_t) / (n * cos_i + cos_t);
    add(kPi - 2.0 * i, w, rs, rp);  // reflected off the outside
    double as = 1.0 - rs * rs, ap = 1.0 - rp * rp;
    for (int k = 0; k <= kMaxDropReflections; ++k) {
      add(2.0 * (i - r) + k * (kPi - 2.0 * r), w, as, ap);
      as *= -rs;
      ap *= -rp;
    }
  }
  return out;
}

std::vector<double> drop_geometric_scattering(double n, const std::vector<double>& mu) {
  return drop_geometric_matrix(n, mu).p11;
}

}  // namespace skyspec
