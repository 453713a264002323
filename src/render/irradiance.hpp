// Irradiance at the camera: what the sky and the sun deliver to a horizontal surface there, so
// that a scene can be lit consistently with the rendered sky.
//
//   direct normal      E_dn(lambda) = E_sun(lambda) T(camera -> sun)
//   direct horizontal  E_dh = E_dn max(0, cos theta_sun)
//   diffuse horizontal E_d  = integral over the upper hemisphere of L_sky(omega) cos(theta) d omega
//
// The hemisphere integral uses Gauss-Legendre nodes in cos(theta) and the midpoint rule in
// azimuth; the sky radiance excludes the sun's disk (that is the direct part). "Broadband" values
// integrate the spectrum over the grid's range only (trapezoid; 380-780 nm by default: not the
// whole solar spectrum a pyranometer sees, docs/jobs.md); illuminance is 683 lm/W times the
// integral weighted by the CIE 1931 y-bar function.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "colour/colour_temperature.hpp"
#include "render/broadband_irradiance.hpp"

#include "skyspec/irradiance.hpp"
#include "skyspec/render.hpp"
#include "skyspec/spectrum.hpp"

namespace skyspec {

struct IrradianceReport {
  std::vector<double> wavelengths_nm;
  SpectrumD direct_normal, direct_horizontal, diffuse_horizontal;  ///< W m^-2 nm^-1
  double direct_normal_W_m2 = 0, direct_horizontal_W_m2 = 0, diffuse_horizontal_W_m2 = 0;
  double direct_normal_lux = 0, direct_horizontal_lux = 0, diffuse_horizontal_lux = 0;
  double global_horizontal_lux() const { return direct_horizontal_lux + diffuse_horizontal_lux; }
  double global_horizontal_W_m2() const { return direct_horizontal_W_m2 + diffuse_horizontal_W_m2; }
  SpectrumD global_horizontal() const { return direct_horizontal + diffuse_horizontal; }
  /// The band the W m^-2 values integrate over: the grid's first and last wavelength, nm.
  double band_min_nm() const { return wavelengths_nm.front(); }
  double band_max_nm() const { return wavelengths_nm.back(); }
  /// Correlated colour temperature of the global (direct + diffuse) and the diffuse horizontal
  /// light (colour_temperature.hpp); empty when the light has no colour or lies off the locus.
  std::optional<ColourTemperature> global_horizontal_cct, diffuse_horizontal_cct;
  /// 300-4000 nm with the gases' bands, when the scene asks for it (irradiance.broadband).
  std::optional<BroadbandIrradiance> broadband;
  /// A few lines for people, e.g. for the render summary.
  std::string describe() const;
};

/// One quantity of an IrradianceReport as the irradiance tables name it: the CLI's CSV, a job's
/// task records, its CSV and its NetCDF all iterate irradiance_quantities(), so a new quantity is
/// one row there.
struct IrradianceQuantity {
  const char* key;        ///< JSON key and CSV column (spectral: one column per wavelength, "_<nm>" appended)
  const char* variable;   ///< NetCDF variable name
  const char* long_name;  ///< what it is (NetCDF long_name)
  const char* units;      ///< UDUNITS
  int decimals;           ///< in tables for people (the CLI's CSV)
  double (*value)(const IrradianceReport&);        ///< a number; null for a spectral quantity
  SpectrumD (*spectrum)(const IrradianceReport&);  ///< spectral; null for a number
  /// Of IrradianceReport::broadband (300-4000 nm, the gases' bands): present only when the scene
  /// asks for it (irradiance.broadband).
  bool of_broadband = false;
  /// Its CF standard name (the broadband irradiance's: surface_*_shortwave_flux_in_air), or null.
  const char* standard_name = nullptr;
  bool spectral() const { return spectrum != nullptr; }
  /// True for an integral of W m^-2 nm^-1 over the render's band (illuminance is complete once the
  /// band holds y-bar's range; spectral values are per wavelength; the broadband values have their
  /// own band).
  bool band_limited() const;
  /// Whether a report (or a task record's irradiance) has this quantity.
  bool present_in(const IrradianceReport& r) const { return !of_broadband || r.broadband.has_value(); }
};
const std::vector<IrradianceQuantity>& irradiance_quantities();

/// Irradiance on a horizontal surface at the renderer's camera position. zenith_nodes and
/// azimuth_nodes set the hemisphere quadrature. For the spectral path only (needs the CMFs).
IrradianceReport irradiance_at_camera(const SkyRenderer& renderer, int zenith_nodes = 32, int azimuth_nodes = 64);

/// irradiance_at_camera(renderer), and the broadband irradiance (broadband_irradiance.hpp) when
/// `scene` (the renderer's) has irradiance.broadband: what the irradiance outputs hold.
IrradianceReport irradiance_report(const Scene& scene, const SkyRenderer& renderer);

/// irradiance_report for each sun elevation (camera_irradiance's contract: the checks before any
/// work, progress after each elevation, the scene's elevation when the list is empty).
std::vector<IrradianceReport> irradiance_reports(const Scene& scene, const std::vector<double>& sun_elevations_deg,
                                                 const ProgressFn& progress = {});

}  // namespace skyspec
