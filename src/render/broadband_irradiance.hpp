// Broadband irradiance: what a pyranometer measures (about 285-2800 nm), as the whole solar
// spectrum from 300 to 4000 nm reaching a horizontal surface at the camera, with the gases'
// absorption bands (water vapour; oxygen, carbon dioxide and the other uniformly mixed gases).
//
// The light transport is solved on Bird & Riordan's 122 wavelengths (gas_bands.hpp), once per
// term of the bands' exponential sums: term 0 on every wavelength, the other terms on those where
// a gas absorbs; each run is an ordinary render of the scene's irradiance (irradiance.hpp: direct
// from the transmittance, diffuse over the hemisphere, all scattering orders) with
// AtmosphereSpec::gas_band_term set. Per wavelength the runs are summed with the terms' weights,
// then the spectrum is integrated over wavelength with the trapezoid rule. Approximations and
// their measured errors: docs/physics.md, "Gas bands".
#pragma once

#include <vector>

#include "skyspec/scene.hpp"
#include "skyspec/spectrum.hpp"

namespace skyspec {

struct BroadbandIrradiance {
  /// Bird & Riordan's wavelengths, nm, and the irradiances there, W m^-2 nm^-1, with the gases.
  std::vector<double> wavelengths_nm;
  SpectrumD direct_normal, diffuse_horizontal;
  double cos_sun = 0.0;  ///< the sun's elevation's sine: direct horizontal = direct normal * cos_sun
  double direct_normal_W_m2 = 0, direct_horizontal_W_m2 = 0, diffuse_horizontal_W_m2 = 0;
  double global_horizontal_W_m2() const { return direct_horizontal_W_m2 + diffuse_horizontal_W_m2; }
  double band_min_nm() const { return wavelengths_nm.front(); }
  double band_max_nm() const { return wavelengths_nm.back(); }
  int runs = 0;  ///< light-transport runs it took
};

/// The broadband irradiance at the scene's camera (its position, sun, atmosphere and ground; its
/// spectrum, camera and output settings are not used). Throws InputError naming
/// irradiance.broadband when a medium of the scene is not defined from 300 to 4000 nm, or
/// the render path is not spectral. zenith_nodes and azimuth_nodes set each run's hemisphere
/// quadrature (irradiance_at_camera's).
BroadbandIrradiance broadband_irradiance(const Scene& scene, int zenith_nodes = 32, int azimuth_nodes = 64);

/// The scenes of its runs (AtmosphereSpec::gas_band_term set, Bird & Riordan's wavelengths where the
/// term matters, a 1x1 camera): each builds (or takes from the cache) scattering-order tables of its
/// own, which a job's plan counts (job_tables.hpp).
std::vector<Scene> broadband_run_scenes(const Scene& scene);

}  // namespace skyspec
