#include "colour/polarisation_colour.hpp"

#include <algorithm>
#include <cmath>

#include "skyspec/units.hpp"

namespace skyspec {

LinearPolarisation linear_polarisation(double s0, double s1, double s2) {
  LinearPolarisation p;
  if (!(s0 > 0.0)) return p;
  p.degree = std::hypot(s1, s2) / s0;
  p.angle_deg = 0.5 * std::atan2(s2, s1) * 180.0 / kPi;
  if (p.angle_deg <= -90.0) p.angle_deg += 180.0;
  return p;
}

std::array<float, 3> polarisation_colour(const LinearPolarisation& p) {
  // HSV with S = 1: six sectors of the hue circle, each a ramp of one channel.
  const double h = std::clamp((p.angle_deg + 90.0) / 180.0, 0.0, 1.0) * 6.0;
  const double v = std::clamp(p.degree, 0.0, 1.0);
  const int sector = std::min(5, static_cast<int>(h));
  const double f = h - sector;
  const double rising = v * f, falling = v * (1.0 - f);
  double r = 0, g = 0, b = 0;
  switch (sector) {
    case 0:
      r = v, g = rising, b = 0;
      break;
    case 1:
      r = falling, g = v, b = 0;
      break;
    case 2:
      r = 0, g = v, b = rising;
      break;
    case 3:
      r = 0, g = falling, b = v;
      break;
    case 4:
      r = rising, g = 0, b = v;
      break;
    default:
      r = v, g = 0, b = falling;
      break;
  }
  return {static_cast<float>(r), static_cast<float>(g), static_cast<float>(b)};
}

}  // namespace skyspec
