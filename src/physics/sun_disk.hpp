// The sun's disk: its angular size and its limb-darkened radiance.
//
// Radius: the IAU 2015 nominal solar radius, 695700 km, seen from the Earth-Sun distance
// (1 au = 149597870.7 km): 0.2666 degrees at 1 au.
// Limb darkening: Hestroffer & Magnan 1998 (A&A 333, 338), eq. 5, a one-parameter law fitted
// to Pierce & Slaughter 1977 and Neckel & Labs 1994:
//   I(mu) / I(1) = mu^alpha(lambda),  alpha = -0.023 + 0.292 / lambda_um   (lambda > 417 nm)
//                                     alpha = -0.507 + 0.441 / lambda_um   (lambda <= 417 nm)
// with mu the cosine of the angle between the line of sight and the normal of the solar
// surface: mu = sqrt(1 - (theta / theta_sun)^2) at angular distance theta from the disk's centre.
// The disk's radiance is normalised so that its integral over the disk is the solar irradiance:
//   E = int I dOmega = I(1) pi theta_sun^2 * 2 / (alpha + 2)   (small-angle disk).
#pragma once

#include "skyspec/spectrum.hpp"

namespace skyspec {

constexpr double kSolarRadius_m = 695700e3;            ///< IAU 2015 Resolution B3 nominal radius
constexpr double kAstronomicalUnit_m = 149597870.7e3;  ///< IAU 2012 Resolution B2

/// Angular radius of the sun, radians, at a distance in astronomical units.
double sun_angular_radius_rad(double distance_au);

/// The limb-darkening exponent alpha at a wavelength (Hestroffer & Magnan 1998, eq. 5).
double limb_darkening_exponent(double lambda_nm);

/// Radiance at the centre of the disk, I(1), per unit irradiance, sr^-1: (alpha + 2) / (2 pi theta^2).
double disk_centre_radiance_per_irradiance(double lambda_nm, double angular_radius_rad);

/// Limb-darkened radiance per unit irradiance at fractional radius x = theta / theta_sun in [0, 1]
/// (0 outside the disk), for every wavelength of a grid: out = I(1) mu^alpha.
void disk_radiance_per_irradiance(const WavelengthGrid& grid, double angular_radius_rad, double x, Spectrum& out);

}  // namespace skyspec
