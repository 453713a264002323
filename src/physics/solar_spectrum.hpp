// The extraterrestrial solar spectral irradiance: sunlight at the top of the atmosphere.
//
// Table: the extraterrestrial ("ETR", air mass zero) column of ASTM G173-03, Standard Tables for
// Reference Solar Spectral Irradiances (2003, reapproved 2012), 280-4000 nm, in W m^-2 nm^-1 at the
// mean Earth-Sun distance of 1 AU, read as the linear interpolant of its samples (data/solar/,
// provenance in data/README.md): the extraterrestrial spectrum from which the standard computed its
// terrestrial spectra with the SMARTS v2.9.2 model; the standard says it differs only slightly from
// ASTM E-490. Its integral over the whole table is 1347.93 W m^-2; the rest of the ~1361-1366
// W m^-2 total solar irradiance lies below 280 nm and above 4000 nm.
//
// At another Earth-Sun distance d (solar_position.hpp gives it) the irradiance scales as
// (1 AU / d)^2: +3.4 % at perihelion in early January, -3.3 % at aphelion in early July.
#pragma once

#include "base/tabulated_spectrum.hpp"
#include "skyspec/spectrum.hpp"

namespace skyspec {

/// The ASTM G173-03 extraterrestrial table, W m^-2 nm^-1 at 1 AU (parsed once, thread-safe).
const TabulatedSpectrum& solar_irradiance_table();

/// The table's mean over each grid sample's band, lambda +- bandwidth/2 (tabulated_spectrum.hpp),
/// W m^-2 nm^-1 at 1 AU. Throws InputError(setting, ...) if a grid
/// wavelength lies outside 280-4000 nm.
SpectrumD solar_irradiance_on_grid(const WavelengthGrid& grid, const std::string& setting = "spectrum");

/// integral_lo^hi E(lambda) dlambda, W m^-2 at 1 AU (exact for the interpolated table).
/// Throws InputError(setting, ...) unless 280 <= lo_nm <= hi_nm <= 4000.
double solar_irradiance_integral_W_m2(double lo_nm, double hi_nm, const std::string& setting = "wavelength range");

/// (1 AU / d)^2: the factor that takes irradiance at 1 AU to irradiance at distance d.
/// Throws InputError("earth_sun_distance_au", ...) unless 0.9 <= d <= 1.1.
double inverse_square_distance_factor(double earth_sun_distance_au);

}  // namespace skyspec
