// The sun's spectral irradiance at the top of the atmosphere that a scene asks for, on a grid.
#pragma once

#include "skyspec/scene.hpp"
#include "skyspec/spectrum.hpp"

namespace skyspec {

/// sun.spectrum = "solar": the measured spectrum on the grid (its bands) scaled by (1 au / d)^2
/// (the inverse-square law); "flat": sun.spectral_irradiance_W_m2_nm everywhere. W m^-2 nm^-1.
Spectrum scene_sun_irradiance(const Scene& scene, const WavelengthGrid& grid);

}  // namespace skyspec
