// The Lee diagram: the colour of light scattered by water drops against scattering angle and drop
// radius (Lee 1998, "Mie theory, Airy theory, and the natural rainbow", Appl. Opt. 37, 1506), the
// map of every rainbow, fogbow and supernumerary a sky can show. skyspec computes it by Lorenz-Mie
// theory (lorenz_mie.hpp) for one drop radius per row, at every wavelength of a grid, with water's
// refractive index (IAPWS R9-97, water.hpp) over that of standard air (Peck & Reeder), under the
// sun's extraterrestrial spectrum:
//
//   L(theta, r, lambda) = E_sun(lambda) P_11(theta; r, lambda),  P_11 = S11 / (pi x^2 Q_sca)
//
// the radiance of sunlight singly scattered by an optically thin layer of such drops, per unit
// scattering optical depth (W m^-2 sr^-1 nm^-1); P_11 integrates to 1 over
// the sphere. Polarised, also Q = -E_sun P_12 in the frame whose first axis is perpendicular to
// the scattering plane (positive: polarised perpendicular to it, as a rainbow is); U = V = 0 for
// unpolarised sunlight. Each pixel averages its column's angles (angle_subsamples of them), which
// smooths the fine ripple of large drops; each row is one radius (no average over sizes).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "skyspec/display.hpp"

namespace skyspec {

struct LeeDiagramSettings {
  double radius_min_um = 10.0, radius_max_um = 1000.0;  ///< rows, logarithmically spaced
  double angle_min_deg = 125.0, angle_max_deg = 145.0;  ///< columns: scattering angle
  int width = 400, height = 100;
  double lambda_min_nm = 380.0, lambda_max_nm = 780.0, lambda_step_nm = 10.0;
  double water_temperature_C = 10.0;  ///< liquid: 0-100 degC
  int angle_subsamples = 4;
  bool polarisation = false;
};

/// The neutral ids of the settings above, as InputError::setting() reports them.
namespace lee_setting {
inline constexpr const char* kRadiusMin = "lee.radius_min_um";
inline constexpr const char* kRadiusMax = "lee.radius_max_um";
inline constexpr const char* kAngleMin = "lee.angle_min_deg";
inline constexpr const char* kAngleMax = "lee.angle_max_deg";
inline constexpr const char* kWidth = "lee.width";
inline constexpr const char* kHeight = "lee.height";
inline constexpr const char* kLambdaMin = "lee.lambda_min_nm";
inline constexpr const char* kLambdaMax = "lee.lambda_max_nm";
inline constexpr const char* kLambdaStep = "lee.lambda_step_nm";
inline constexpr const char* kTemperature = "lee.water_temperature_C";
inline constexpr const char* kSubsamples = "lee.angle_subsamples";
inline constexpr const char* kDirectory = "lee.directory";  ///< write_lee_diagram's folder
inline constexpr const char* kName = "lee.name";            ///< and its files' base name
}  // namespace lee_setting

struct LeeDiagram {
  LeeDiagramSettings settings;
  int width = 0, height = 0;
  std::vector<double> wavelengths_nm;
  std::vector<double> angles_deg;  ///< column centres, left to right (increasing)
  std::vector<double> radii_um;    ///< row centres, top to bottom (largest first)
  std::vector<float> spectral;     ///< [y][x][lambda]: L, W m^-2 sr^-1 nm^-1
  std::vector<float> stokes;       ///< polarised: [y][x][Q, U, V][lambda]; else empty
};

/// Throws InputError naming a lee.* setting when a value is out of range (radii whose size
/// parameter would exceed the solver's 2e4 at the shortest wavelength, an angle outside 0-180
/// degrees, wavelengths outside 280-1100 nm, a too large image). `progress` (may be empty)
/// is called with (rows done, rows) from the calling thread.
LeeDiagram compute_lee_diagram(const LeeDiagramSettings& settings, const std::function<void(int, int)>& progress = {});

/// The checks compute_lee_diagram makes, without computing.
void check_lee_diagram_settings(const LeeDiagramSettings& settings);

struct LeeDiagramFiles {
  std::filesystem::path exr, png;
};
/// Writes DIR/NAME.exr (the spectral layout; polarised: S0-S3) and, unless png is false,
/// DIR/NAME.png: each row's colour through the display pipeline, every row scaled so that its
/// brightest pixel has luminance 1 (rows of small drops scatter far less into these angles than
/// rows of large ones; the EXR keeps the values unscaled). Atomic files; if the PNG fails, the EXR
/// is removed again.
LeeDiagramFiles write_lee_diagram(const LeeDiagram& diagram, const std::filesystem::path& dir, const std::string& name,
                                  const DisplaySettings& display, bool png);

}  // namespace skyspec
