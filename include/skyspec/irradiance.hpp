// The irradiance at a scene's camera for a list of sun elevations: what `skyspec irradiance`
// prints and a job's irradiance tables hold (docs/jobs.md, "Irradiance and pyranometers"), for
// programs (the Python module's skyspec.irradiance).
//
// The direct beam is the sun's spectrum times its transmittance to the camera; the diffuse light a
// quadrature of the sky's radiance over the upper hemisphere (every scattering order the scene asks
// for, its ground; the sun's disk excluded). W m^-2 integrate over the scene's wavelength grid
// (380-780 nm by default), illuminance is 683 lm/W times the CIE 1931 y-bar-weighted integral, the
// colour temperature is CIE 015's; with irradiance.broadband also 300-4000 nm with the gases'
// absorption bands.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "skyspec/render.hpp"
#include "skyspec/scene.hpp"

namespace skyspec {

/// The irradiance on a horizontal surface at the camera (and on one facing the sun) for one sun
/// elevation.
struct CameraIrradiance {
  double sun_elevation_deg = 0.0;
  /// The scene's wavelength grid, nm: the spectra's samples and the band of the W m^-2 values.
  std::vector<double> wavelengths_nm;
  /// The numbers, named and ordered as the irradiance tables' columns ("direct_normal_W_m2",
  /// "global_horizontal_lux", ...; the broadband ones only with irradiance.broadband).
  std::vector<std::pair<std::string, double>> values;
  /// The spectra, W m^-2 nm^-1 at wavelengths_nm, named likewise ("global_horizontal_W_m2_nm", ...).
  std::vector<std::pair<std::string, std::vector<double>>> spectra;
  /// Correlated colour temperature (K) and Duv of the global and of the diffuse light; empty where
  /// the light has none (no light, or far from the Planckian locus).
  std::optional<double> global_cct_K, global_duv, diffuse_cct_K, diffuse_duv;
};

/// One entry per sun elevation (degrees, -90 to 90; empty: the scene's sun.elevation_deg), the sun
/// at the scene's azimuth. The spectral path only (the colour-matching functions), at least two
/// wavelengths. progress(done, total) after each elevation; the tables' build before the first
/// shows in skyspec/preparation_progress.hpp. Throws InputError naming the key or value it cannot
/// serve (before any work), Cancelled on request (skyspec/cancellation.hpp).
std::vector<CameraIrradiance> camera_irradiance(const Scene& scene, const std::vector<double>& sun_elevations_deg = {},
                                                const ProgressFn& progress = {});

}  // namespace skyspec
