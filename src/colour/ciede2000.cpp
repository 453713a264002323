// CIELAB (CIE 015:2004) and CIEDE2000 after Sharma, Wu & Dalal 2005; equation numbers are theirs.
#include "colour/ciede2000.hpp"

#include <algorithm>
#include <cmath>

#include "skyspec/units.hpp"

namespace skyspec {
namespace {

// CIE 015:2004 eq. 8.9: f(t) = t^(1/3) above (6/29)^3, else the linear segment that meets it
// with the same slope, t / (3 (6/29)^2) + 4/29.
double lab_f(double t) {
  constexpr double delta = 6.0 / 29.0;
  if (t > delta * delta * delta) return std::cbrt(t);
  return t / (3.0 * delta * delta) + 4.0 / 29.0;
}

double sin_deg(double deg) { return std::sin(degrees_to_radians(deg)); }
double cos_deg(double deg) { return std::cos(degrees_to_radians(deg)); }

// Hue angle in degrees in [0, 360); 0 for a' = b = 0 (eq. 4, which defines it so).
double hue_deg(double b, double a_prime) {
  if (b == 0.0 && a_prime == 0.0) return 0.0;
  double h = radians_to_degrees(std::atan2(b, a_prime));
  if (h < 0.0) h += 360.0;
  return h;
}

}  // namespace

Lab xyz_to_lab(const Eigen::Vector3d& xyz, const Eigen::Vector3d& white_xyz) {
  const double fx = lab_f(xyz.x() / white_xyz.x());
  const double fy = lab_f(xyz.y() / white_xyz.y());
  const double fz = lab_f(xyz.z() / white_xyz.z());
  return Lab{116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

Ciede2000Terms ciede2000_terms(const Lab& lab1, const Lab& lab2, double k_L, double k_C, double k_H) {
  Ciede2000Terms t{};
  // 1. C'_i and h'_i (eqs. 2-7): a* is stretched by (1 + G) so that near-neutral colours, where
  // CIELAB's hue spacing is poor, get a larger a' axis.
  const double C1_ab = std::hypot(lab1.a, lab1.b), C2_ab = std::hypot(lab2.a, lab2.b);  // (2)
  const double mean_C_ab = 0.5 * (C1_ab + C2_ab);                                       // (3)
  const double pow25_7 = 6103515625.0;                                                   // 25^7
  const double mean_C_ab7 = std::pow(mean_C_ab, 7.0);
  t.G = 0.5 * (1.0 - std::sqrt(mean_C_ab7 / (mean_C_ab7 + pow25_7)));  // (4)
  t.a1_prime = (1.0 + t.G) * lab1.a;                                     // (5)
  t.a2_prime = (1.0 + t.G) * lab2.a;
  t.C1_prime = std::hypot(t.a1_prime, lab1.b);  // (6)
  t.C2_prime = std::hypot(t.a2_prime, lab2.b);
  t.h1_prime_deg = hue_deg(lab1.b, t.a1_prime);  // (7)
  t.h2_prime_deg = hue_deg(lab2.b, t.a2_prime);

  // 2. Delta L', Delta C', Delta H' (eqs. 8-11). The hue difference is taken the short way round
  // the circle; it is 0 when either colour is neutral (C' = 0), where hue is undefined.
  const double dL = lab2.L - lab1.L;                // (8)
  const double dC = t.C2_prime - t.C1_prime;        // (9)
  const double C_product = t.C1_prime * t.C2_prime;
  double dh = 0.0;                                  // (10)
  if (C_product != 0.0) {
    dh = t.h2_prime_deg - t.h1_prime_deg;
    if (dh > 180.0) dh -= 360.0;
    else if (dh < -180.0) dh += 360.0;
  }
  const double dH = 2.0 * std::sqrt(C_product) * sin_deg(0.5 * dh);  // (11)

  // 3. Weighting functions (eqs. 12-22).
  const double mean_L = 0.5 * (lab1.L + lab2.L);               // (12)
  const double mean_C = 0.5 * (t.C1_prime + t.C2_prime);       // (13)
  const double h_sum = t.h1_prime_deg + t.h2_prime_deg;        // (14): the mean hue, also the
  if (C_product == 0.0) {                                      // short way round; the plain sum
    t.mean_h_prime_deg = h_sum;                                // when a colour is neutral
  } else if (std::abs(t.h1_prime_deg - t.h2_prime_deg) <= 180.0) {
    t.mean_h_prime_deg = 0.5 * h_sum;
  } else if (h_sum < 360.0) {
    t.mean_h_prime_deg = 0.5 * (h_sum + 360.0);
  } else {
    t.mean_h_prime_deg = 0.5 * (h_sum - 360.0);
  }
  const double h = t.mean_h_prime_deg;
  t.T = 1.0 - 0.17 * cos_deg(h - 30.0) + 0.24 * cos_deg(2.0 * h) + 0.32 * cos_deg(3.0 * h + 6.0) -
        0.20 * cos_deg(4.0 * h - 63.0);                                  // (15)
  const double d_theta = 30.0 * std::exp(-std::pow((h - 275.0) / 25.0, 2.0));  // (16)
  const double mean_C7 = std::pow(mean_C, 7.0);
  const double R_C = 2.0 * std::sqrt(mean_C7 / (mean_C7 + pow25_7));  // (17)
  const double L50 = (mean_L - 50.0) * (mean_L - 50.0);
  t.S_L = 1.0 + 0.015 * L50 / std::sqrt(20.0 + L50);  // (18)
  t.S_C = 1.0 + 0.045 * mean_C;                       // (19)
  t.S_H = 1.0 + 0.015 * mean_C * t.T;                 // (20)
  t.R_T = -sin_deg(2.0 * d_theta) * R_C;              // (21)

  // 4. The total difference (eq. 22): a rotation term couples chroma and hue in the blue region.
  const double l = dL / (k_L * t.S_L), c = dC / (k_C * t.S_C), hh = dH / (k_H * t.S_H);
  t.delta_E = std::sqrt(std::max(0.0, l * l + c * c + hh * hh + t.R_T * c * hh));
  return t;
}

double ciede2000(const Lab& lab1, const Lab& lab2, double k_L, double k_C, double k_H) {
  return ciede2000_terms(lab1, lab2, k_L, k_C, k_H).delta_E;
}

}  // namespace skyspec
