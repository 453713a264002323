// A scene's Monte Carlo reference: the scene's atmosphere, sun and camera position handed to the
// transport layer's path tracer, one estimate per probe and wavelength.

#include "skyspec/monte_carlo_reference.hpp"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "base/text_format.hpp"
#include "render/sun_irradiance.hpp"
#include "scene/scene_terrain.hpp"
#include "skyspec/atmosphere.hpp"
#include "skyspec/camera.hpp"
#include "skyspec/error.hpp"
#include "transport/monte_carlo.hpp"

namespace skyspec {

namespace {
// A stream number from the bits of the values an estimate depends on, so that a probe's result
// does not depend on which other probes or wavelengths are asked for.
std::uint64_t stream_of(double a, double b, double lambda_nm, std::uint64_t kind) {
  std::uint64_t h = 0xCBF29CE484222325ull ^ kind;
  for (double v : {a, b, lambda_nm}) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    h = (h ^ bits) * 0x100000001B3ull;
    h ^= h >> 29;
  }
  return h;
}
}  // namespace

Vec3 stokes_frame_axis(const Vec3& look) {
  // The vertical plane through the line of sight; straight up or down, where that plane is
  // undefined, the vertical plane towards azimuth 0.
  const Vec3 up(0, 0, 1);
  const Vec3 d = look.normalized();
  const Vec3 reference = std::abs(d.dot(up)) > 1.0 - 1e-12 ? direction_from_angles(0.0, 0.0) : up;
  return (reference - reference.dot(d) * d).normalized();
}

std::vector<ReferenceProbe> standard_reference_probes(const Scene& scene) {
  const double sun = scene.sun.azimuth_deg;
  auto wrap = [](double az) { return std::fmod(std::fmod(az, 360.0) + 360.0, 360.0); };
  return {{"zenith", wrap(sun), 90.0},
          {"45 deg towards sun", wrap(sun), 45.0},
          {"horizon towards sun", wrap(sun), 1.0},
          {"horizon across sun", wrap(sun + 90.0), 1.0},
          {"horizon away from sun", wrap(sun + 180.0), 1.0}};
}

ReferenceProbe parse_reference_probe(const std::string& text, const std::string& setting) {
  const std::string allowed = "\"azimuth,elevation\" or \"label=azimuth,elevation\" in degrees, elevation -90 to 90";
  ReferenceProbe p;
  std::string rest = text;
  const auto eq = text.find('=');
  if (eq != std::string::npos) {
    p.label = text.substr(0, eq);
    rest = text.substr(eq + 1);
  }
  const auto comma = rest.find(',');
  if (comma == std::string::npos) throw InputError(setting, "\"" + text + "\"", allowed);
  const std::string a = rest.substr(0, comma), e = rest.substr(comma + 1);
  char* end_a = nullptr;
  char* end_e = nullptr;
  p.azimuth_deg = std::strtod(a.c_str(), &end_a);
  p.elevation_deg = std::strtod(e.c_str(), &end_e);
  if (a.empty() || e.empty() || *end_a != '\0' || *end_e != '\0' || !std::isfinite(p.azimuth_deg) ||
      !(p.elevation_deg >= -90.0 && p.elevation_deg <= 90.0))
    throw InputError(setting, "\"" + text + "\"", allowed);
  if (p.label.empty()) p.label = format_number(p.azimuth_deg) + "," + format_number(p.elevation_deg);
  return p;
}

ReferenceResult monte_carlo_reference(const Scene& scene, const std::vector<ReferenceProbe>& probes,
                                      const ReferenceSettings& settings, const ProgressFn& progress) {
  if (settings.paths < 2 || settings.paths > 1000000000000LL)
    throw InputError("paths", std::to_string(settings.paths), "2 to 1e12 paths per estimate");
  if (!(settings.sun_peak_share >= 0.0 && settings.sun_peak_share <= 0.5))
    throw InputError("sun_peak_share", format_shortest(settings.sun_peak_share), "a share from 0 to 0.5");
  if (settings.max_orders < 0)
    throw InputError("orders", std::to_string(settings.max_orders), "0 (all orders) or a positive number of orders");
  const auto start = std::chrono::steady_clock::now();
  const WavelengthGrid grid = make_wavelength_grid(scene);
  const AtmosphereModel atmosphere(scene.atmosphere, grid, scene.render.cache_tables);
  const Spectrum sun_irradiance = scene_sun_irradiance(scene, grid);
  const Vec3 sun = sun_direction(scene);
  const std::shared_ptr<const Terrain> terrain = scene_terrain(scene);  // checks the camera is above it
  // Scene coordinates (east, north, height) to world space: the planet's centre at (0, 0, -R).
  const Vec3& p = scene.camera.position_m;
  const Vec3 origin(p.x(), p.y(), atmosphere.planet_radius_m() + p.z());
  const Vec3 up(0, 0, 1);
  // The irradiance estimate starts its paths at the observer: it must be in the air.
  if (settings.diffuse_irradiance && origin.norm() >= atmosphere.top_radius_m())
    throw InputError(
        "camera.position_m",
        "[" + format_number(p.x()) + ", " + format_number(p.y()) + ", " + format_number(p.z()) + "]",
        "an observer below the top of the atmosphere (atmosphere.top_altitude_m) for the diffuse irradiance");

  ReferenceResult out;
  out.wavelengths_nm = grid.nanometres();
  out.probes = probes;
  out.settings = settings;
  const int n = grid.size();
  MonteCarloSettings mc;
  mc.paths = settings.paths;
  mc.seed = settings.seed;
  mc.max_orders = settings.max_orders;
  mc.sun_peak_share = settings.sun_peak_share;
  mc.threads = scene.render.threads;
  const int total =
      static_cast<int>(probes.size()) * n * (settings.stokes ? 2 : 1) + (settings.diffuse_irradiance ? n : 0);
  int done = 0;
  out.radiance.assign(probes.size(), std::vector<double>(static_cast<size_t>(n)));
  out.radiance_standard_error = out.radiance;
  if (settings.stokes) {
    out.stokes.assign(probes.size(), std::vector<std::array<double, 4>>(static_cast<size_t>(n)));
    out.stokes_standard_error = out.stokes;
  }
  if (settings.diffuse_irradiance) {
    out.diffuse_horizontal.assign(static_cast<size_t>(n), 0.0);
    out.diffuse_horizontal_standard_error = out.diffuse_horizontal;
  }
  for (int i = 0; i < n; ++i) {
    MonteCarloMedium medium = MonteCarloMedium::from_atmosphere(atmosphere, i);
    medium.terrain = terrain;
    if (terrain && terrain->own_albedo().size() > 0) medium.terrain_albedo = terrain->own_albedo()[i];
    const MonteCarloIntegrator integrator(std::move(medium), sun);
    const double e = sun_irradiance[i];
    for (size_t k = 0; k < probes.size(); ++k) {
      const Vec3 dir = direction_from_angles(probes[k].azimuth_deg, probes[k].elevation_deg);
      const MonteCarloValue v = integrator.radiance(
          origin, dir, mc, stream_of(probes[k].azimuth_deg, probes[k].elevation_deg, grid.nm(i), 1));
      out.radiance[k][static_cast<size_t>(i)] = e * v.mean;
      out.radiance_standard_error[k][static_cast<size_t>(i)] = e * v.standard_error;
      if (progress) progress(++done, total);
      if (settings.stokes) {
        const MonteCarloStokes s =
            integrator.stokes_radiance(origin, dir, stokes_frame_axis(dir), mc,
                                       stream_of(probes[k].azimuth_deg, probes[k].elevation_deg, grid.nm(i), 3));
        for (size_t c = 0; c < 4; ++c) {
          out.stokes[k][static_cast<size_t>(i)][c] = e * s[c].mean;
          out.stokes_standard_error[k][static_cast<size_t>(i)][c] = e * s[c].standard_error;
        }
        if (progress) progress(++done, total);
      }
    }
    if (settings.diffuse_irradiance) {
      const MonteCarloValue v = integrator.irradiance(origin, up, mc, stream_of(0.0, 0.0, grid.nm(i), 2));
      out.diffuse_horizontal[static_cast<size_t>(i)] = e * v.mean;
      out.diffuse_horizontal_standard_error[static_cast<size_t>(i)] = e * v.standard_error;
      if (progress) progress(++done, total);
    }
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace skyspec
