// U.S. Standard Atmosphere 1976 (NOAA/NASA/USAF, 1976), implemented from its defining layers:
// geopotential base altitudes and temperature lapse rates up to 84.852 km geometric (86 km is
// outside the definition used here: above 84.852 km we continue the last layer, which suffices for
// optical work since the density there is ~1e-5 of sea level).
//
//   T(H) = T_b + L_b (H - H_b),
//   P(H) = P_b [T_b / T(H)]^(g0 M0 / (R* L_b))      (L_b != 0)
//   P(H) = P_b exp(-g0 M0 (H - H_b) / (R* T_b))      (L_b == 0)
//   N = P / (k T)
// with geopotential altitude H = r0 z / (r0 + z), r0 = 6356.766 km, g0 = 9.80665 m s^-2,
// M0 = 28.9644 g/mol, R* = 8.31432 J mol^-1 K^-1 (the standard's own constant).
#pragma once

namespace skyspec {

struct AtmosphereState {
  double temperature_K;
  double pressure_Pa;
  double number_density_per_m3;
};

/// State at geometric altitude z (metres above mean sea level). Valid for z in [-5 km, 100 km];
/// throws InputError("altitude_m", ...) outside.
AtmosphereState us_standard_atmosphere_1976(double geometric_altitude_m);

/// Geopotential altitude (m') of a geometric altitude (m).
double geopotential_altitude_m(double geometric_altitude_m);

}  // namespace skyspec
