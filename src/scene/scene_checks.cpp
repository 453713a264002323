// Whole-scene checks (scene_checks.hpp) and check_spectral_range (scene.hpp).
#include "scene/scene_checks.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include <toml++/toml.h>

#include "base/embedded_data.hpp"
#include "base/text_format.hpp"
#include "physics/date_time.hpp"
#include "physics/ozone.hpp"
#include "physics/solar_position.hpp"
#include "physics/solar_spectrum.hpp"
#include "scene/toml_limits.hpp"
#include "skyspec/aerosol_components.hpp"
#include "skyspec/error.hpp"
#include "skyspec/refractive_index.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

void check_terrain(const Scene& s) {
  const TerrainSpec& t = s.terrain;
  if (t.model == TerrainSpec::Model::File && t.file.empty())
    throw InputError("terrain.file", "(not set)", "the path of an elevation raster (terrain.model = \"file\")");
  if (t.model == TerrainSpec::Model::HeightMap) {
    if (t.file.empty())
      throw InputError("terrain.file", "(not set)", "the path of a height map (terrain.model = \"heightmap\")");
    if (!t.heightmap.pixel_m)
      throw InputError("terrain.heightmap.pixel_m", "(not set)",
                       "the distance between the height map's pixel centres on the ground, in metres "
                       "(terrain.model = \"heightmap\")");
  }
  if (!t.albedo_map.empty() && t.model != TerrainSpec::Model::File && t.model != TerrainSpec::Model::HeightMap)
    throw InputError("terrain.albedo_map", t.albedo_map,
                     "an albedo map only with terrain.model = \"file\" (georeferenced, like the heights) or "
                     "\"heightmap\" (over the height map's ground), not \"" +
                         std::string(terrain_model_name(t.model)) + "\"");
  if (t.model != TerrainSpec::Model::Ridge) return;
  const RidgeSpec& r = t.ridge;
  if (!(r.length_m > 2.0 * r.half_width_m))
    throw InputError("terrain.ridge.length_m", format_number(r.length_m),
                     "more than twice terrain.ridge.half_width_m (" + format_number(2.0 * r.half_width_m) + " m)");
  const double under = ridge_height_at(r, s.camera.position_m.x(), s.camera.position_m.y());
  if (!s.camera.above_ground_m && s.camera.position_m.z() <= under)  // (above_ground_m places it above)
    throw InputError("camera.position_m", format_number(s.camera.position_m.z()) + " m high",
                     "a position above the terrain (the ridge is " + format_number(under) + " m high there)");
}

// The Blender and OpenEXR lat-long conventions map the whole image to the whole sphere.
void check_panorama(const CameraSpec& c) {
  if (c.panorama_convention == PanoramaConvention::Skyspec) return;
  const std::string name = panorama_convention_name(c.panorama_convention);
  if (c.min_elevation_deg != -90.0)
    throw InputError(
        "camera.min_elevation_deg", format_number(c.min_elevation_deg),
        "-90 with camera.panorama_convention = \"" + name +
            "\" (its lat-long map covers the whole sphere; a partial panorama takes the skyspec convention)");
  if (c.panorama_convention == PanoramaConvention::OpenExr && (c.width < 2 || c.height < 2))
    throw InputError("camera.width x camera.height", std::to_string(c.width) + "x" + std::to_string(c.height),
                     "at least 2x2 pixels with camera.panorama_convention = \"openexr\" (its first and last pixel "
                     "centres are the poles and the seam)");
}

bool sees_below_horizon_as_panorama(const CameraSpec& c) {
  return c.type == CameraSpec::Type::Equirectangular && c.min_elevation_deg < 0.0;
}

bool ground_albedo_given(const std::set<std::string>& given) {
  for (const char* key : {"ground.albedo", "ground.albedo_wavelengths_nm", "ground.albedo_values"})
    if (given.count(key)) return true;
  return false;
}

namespace {
// The wavelengths a spectral render can take: where every built-in table the scene uses is
// defined. Colour (XYZ, RGB, PNG) integrates over the grid's overlap with the CIE colour-matching
// functions (360-830 nm), so it sets no limit here.
struct SpectralLimit {
  double min_nm, max_nm;
  std::string reason;
};
// The refractive index of air bounds any derivation of air's Rayleigh coefficients.
std::optional<SpectralLimit> refractive_index_limit(const Scene& s) {
  if (s.atmosphere.rayleigh.source != RayleighSpec::Source::Derived ||
      s.atmosphere.rayleigh.derivation.gas != ScatteringGas::Air)
    return std::nullopt;
  const RefractiveIndexValidity v = validity(s.atmosphere.rayleigh.derivation.formula);
  return SpectralLimit{v.min_nm, v.max_nm, "the refractive index of air: " + v.reason};
}
std::vector<SpectralLimit> spectral_limits(const Scene& s) {
  std::vector<SpectralLimit> limits;
  // A broadband irradiance's run continues air's coefficients and ozone's table beyond their ends
  // (AtmosphereSpec::gas_band_term).
  const bool broadband_run = s.atmosphere.gas_band_term >= 0;
  if (const auto air = refractive_index_limit(s); air && !broadband_run) limits.push_back(*air);
  if (s.sun.spectrum == SunSpec::Spectrum::Solar) {
    const TabulatedSpectrum& sun = solar_irradiance_table();
    limits.push_back(
        {sun.min_nm(), sun.max_nm(), "the extraterrestrial solar spectrum (ASTM G173-03, sun.spectrum = \"solar\")"});
  }
  if (s.atmosphere.mie.enabled && s.atmosphere.mie.model == MieSpec::Model::Opac) {
    const AerosolComponentWavelengths opac = aerosol_component_wavelengths();
    limits.push_back({opac.min_nm, opac.max_nm,
                      "OPAC's refractive indices of the aerosol components (atmosphere.mie.model = \"opac\")"});
  }
  if (s.atmosphere.fog.enabled)
    limits.push_back({200.0, 1100.0, "water's refractive index (IAPWS R9-97; atmosphere.fog.enabled = true)"});
  const OzoneSpec& o3 = s.atmosphere.ozone;
  if (o3.enabled && o3.cross_section_m2.empty() && !broadband_run) {
    const TabulatedSpectrum& table = ozone_cross_section_table();
    limits.push_back({table.min_nm(), table.max_nm(),
                      "the built-in ozone cross-sections (laboratory data at 233 K; ozone.enabled = true)"});
  }
  return limits;
}

void check_limits(const WavelengthGrid& grid, const std::vector<SpectralLimit>& limits, const std::string& what) {
  double lo = 0.0, hi = std::numeric_limits<double>::infinity();
  std::string lo_reason, hi_reason;
  for (const SpectralLimit& l : limits) {
    if (l.min_nm > lo) lo = l.min_nm, lo_reason = l.reason;
    if (l.max_nm < hi) hi = l.max_nm, hi_reason = l.reason;
  }
  if (grid.min_nm() >= lo && grid.max_nm() <= hi) return;
  if (lo_reason == hi_reason)
    throw InputError(
        "spectrum", grid.describe(),
        "wavelengths from " + format_number(lo) + " to " + format_number(hi) + " nm" + what + ": " + lo_reason);
  throw InputError("spectrum", grid.describe(),
                   "wavelengths from " + format_number(lo) + " nm (" + lo_reason + ") to " + format_number(hi) +
                       " nm (" + hi_reason + ")" + what);
}

}  // namespace

void check_refractive_index_range(const Scene& s, const WavelengthGrid& grid) {
  if (const auto air = refractive_index_limit(s)) check_limits(grid, {*air}, "");
}

void check_spectral_range(const Scene& s, const WavelengthGrid& grid) {
  if (grid.size() < 2)
    throw InputError("spectrum", grid.describe(), "at least 2 wavelengths when render.path = \"spectral\"");
  check_limits(grid, spectral_limits(s), " when render.path = \"spectral\"");
}

}  // namespace skyspec
