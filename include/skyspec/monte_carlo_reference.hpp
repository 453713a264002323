// The Monte Carlo reference of a scene: the sky's radiance in chosen directions and the diffuse
// horizontal irradiance at the camera, with every scattering order, each with its standard error.
//
// It shares with the renderer only the physical inputs (the atmosphere on the grid, the sun's
// spectrum and direction, the camera's position); the light transport is its own (backward path
// tracing with delta and ratio tracking, no tables; src/transport/monte_carlo.hpp), so that it can
// check the renderer's multiple scattering. Refraction is ignored, as in the renderer; the sun is a
// point, and its disk and direct beam are not part of the sky radiance or the diffuse irradiance.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "skyspec/render.hpp"
#include "skyspec/scene.hpp"

namespace skyspec {

/// A direction of the sky seen from the scene's camera position (the sun's angle conventions:
/// azimuth clockwise from north, elevation above the horizon).
struct ReferenceProbe {
  std::string label;
  double azimuth_deg = 0.0;
  double elevation_deg = 90.0;
};

struct ReferenceSettings {
  std::int64_t paths = 100000;  ///< per probe and wavelength
  std::uint64_t seed = 1;
  int max_orders = 0;               ///< 0: all orders; 1: single scattering (air and ground); k: up to k events
  bool diffuse_irradiance = false;  ///< also the diffuse horizontal irradiance at the camera
  /// The share of scatterings whose direction is drawn about the sun rather than the path (0 to
  /// 0.5; unbiased either way): for media with forward peaks (fog), whose paths otherwise score
  /// rarely and hugely when they turn towards the sun.
  double sun_peak_share = 0.0;
  /// Also the Stokes vector of each probe (vector transport; as many paths again): see
  /// ReferenceResult::stokes.
  bool stokes = false;
};

struct ReferenceResult {
  std::vector<double> wavelengths_nm;
  std::vector<ReferenceProbe> probes;
  /// [probe][wavelength]: W m^-2 sr^-1 nm^-1 (or the flat sun's units per sr), and its standard error.
  std::vector<std::vector<double>> radiance, radiance_standard_error;
  /// [wavelength]: W m^-2 nm^-1 on a horizontal surface at the camera, the sun's direct beam
  /// excluded (empty unless asked for).
  std::vector<double> diffuse_horizontal, diffuse_horizontal_standard_error;
  /// [probe][wavelength]: [I, Q, U, V] in the radiance's units, and their standard errors (empty
  /// unless settings.stokes). The frame of each probe: e1 in the vertical plane through the line
  /// of sight, pointing up (Q > 0: light polarised in that vertical plane), e2 = k x e1 with k the
  /// light's direction (towards the observer), which is the observer's left; the angle of
  /// polarisation 1/2 atan2(U, Q) counts from the vertical towards the left, counterclockwise as
  /// the observer sees it. At the zenith (and nadir) e1 points north. I includes polarisation's coupling into
  /// intensity, which `radiance` (scalar transport, as in the renderer) leaves out. Aerosols neither polarise nor
  /// depolarise (physics/scattering_matrix.hpp); the ground depolarises.
  std::vector<std::vector<std::array<double, 4>>> stokes, stokes_standard_error;
  ReferenceSettings settings;
  double seconds = 0.0;
};

/// The first axis of a probe's Stokes frame (ReferenceResult::stokes) for an observer looking
/// along `look` (unit, the scene's east-north-up frame): the vertical through the line of sight
/// made perpendicular to it, pointing up; straight up or down, north.
Vec3 stokes_frame_axis(const Vec3& look);

/// The probes of the validation table (docs/validation.md): the zenith, 45 degrees up towards the
/// sun, and 1 degree above the horizon towards, across (90 degrees to the right of) and away from it.
std::vector<ReferenceProbe> standard_reference_probes(const Scene& scene);

/// "label=azimuth,elevation" or "azimuth,elevation" (degrees) -> a probe; InputError naming
/// `setting` otherwise (elevation -90..90, azimuth any finite number).
ReferenceProbe parse_reference_probe(const std::string& text, const std::string& setting);

/// Runs the reference on all threads render.threads allows. Each estimate depends only on the
/// seed, the number of paths, the probe's direction and the wavelength: not on the other probes,
/// the threads or the machine. `progress` gets (estimates done, estimates in total).
/// Throws InputError for paths < 2 or max_orders < 0.
ReferenceResult monte_carlo_reference(const Scene& scene, const std::vector<ReferenceProbe>& probes,
                                      const ReferenceSettings& settings, const ProgressFn& progress = {});

}  // namespace skyspec
