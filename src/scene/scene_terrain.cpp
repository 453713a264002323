#include "scene/scene_terrain.hpp"

#include <algorithm>
#include <cmath>

#include "base/text_format.hpp"
#include "io/elevation_raster.hpp"
#include "skyspec/error.hpp"

namespace skyspec {

const std::vector<NamedValue<TerrainSpec::Model>>& terrain_models() {
  static const std::vector<NamedValue<TerrainSpec::Model>> table = {
      {TerrainSpec::Model::None, "none"},
      {TerrainSpec::Model::Ridge, "ridge"},
      {TerrainSpec::Model::File, "file"},
      {TerrainSpec::Model::HeightMap, "heightmap"},
  };
  return table;
}

namespace {
// The grid of the scene's terrain; for a raster or a height map, only the samples within extent_m
// of the reference point (the grid is centred there with the same spacing, so its samples are the
// full grid's).
ElevationSampling georeferenced_sampling(const Scene& s, double extent_m) {
  ElevationSampling sampling;
  sampling.latitude_deg = s.location.latitude_deg;
  sampling.longitude_deg = s.location.longitude_deg;
  sampling.extent_m = extent_m;
  sampling.spacing_m = s.terrain.spacing_m;
  sampling.planet_radius_m = s.atmosphere.planet_radius_m;
  return sampling;
}

HeightGrid terrain_grid(const Scene& s, double extent_m) {
  const TerrainSpec& spec = s.terrain;
  if (spec.model == TerrainSpec::Model::Ridge) return ridge_heights(spec.ridge, spec.spacing_m);
  if (spec.model == TerrainSpec::Model::HeightMap) {
    HeightMapSampling sampling;
    sampling.pixel_m = spec.heightmap.pixel_m.value_or(0.0);
    sampling.height_scale_m = spec.heightmap.height_scale_m;
    sampling.height_offset_m = spec.heightmap.height_offset_m;
    sampling.extent_m = extent_m;
    sampling.spacing_m = spec.spacing_m;
    return read_height_map(spec.file, sampling);
  }
  return read_elevation_raster(spec.file, georeferenced_sampling(s, extent_m));
}

// The terrain's own albedo (terrain.albedo*, on the scene's wavelength grid) and its albedo map
// on the grid's samples (terrain.albedo_map: georeferenced like a DEM, or over a height map's ground).
TerrainAlbedo terrain_albedo(const Scene& s, const HeightGrid& grid) {
  const TerrainSpec& spec = s.terrain;
  TerrainAlbedo albedo;
  if (spec.albedo || !spec.albedo_values.empty()) {
    GroundSpec own;
    own.albedo = spec.albedo.value_or(0.0);
    own.albedo_wavelengths_nm = spec.albedo_wavelengths_nm;
    own.albedo_values = spec.albedo_values;
    albedo.spectrum = albedo_on_grid(own, make_wavelength_grid(s));
  }
  if (spec.albedo_map.empty()) return albedo;
  if (spec.model == TerrainSpec::Model::File) {
    albedo.map = read_georeferenced_albedo_map(spec.albedo_map, grid, georeferenced_sampling(s, spec.extent_m));
  } else if (spec.model == TerrainSpec::Model::HeightMap) {
    int width = 0, height = 0;
    height_map_pixels(spec.file, width, height);
    const double pixel_m = spec.heightmap.pixel_m.value_or(0.0);
    albedo.map = read_albedo_image(spec.albedo_map, grid, width * pixel_m, height * pixel_m);
  }
  return albedo;
}
}  // namespace

double camera_height_above_ground(const Scene& s, double east_m, double north_m, double above_ground_m) {
  const double R = s.atmosphere.planet_radius_m;
  std::unique_ptr<Terrain> terrain;
  if (s.terrain.model != TerrainSpec::Model::None) {
    const double reach = std::max(std::abs(east_m), std::abs(north_m)) + 2.0 * s.terrain.spacing_m;
    terrain = std::make_unique<Terrain>(terrain_grid(s, std::min(s.terrain.extent_m, reach)), R);
  }
  // The height z with |P| - R - h(P) = above for P = (east, north, R + z): a fixed point, reached
  // in a few steps (h changes little over the metres z moves).
  double z = above_ground_m;
  for (int i = 0; i < 8; ++i) {
    const Vec3 p(east_m, north_m, R + z);
    const double clearance = terrain ? terrain->clearance(p) : p.norm() - R;
    z += above_ground_m - clearance;
  }
  return z;
}

std::shared_ptr<const Terrain> scene_terrain(const Scene& s) {
  const TerrainSpec& spec = s.terrain;
  const double R = s.atmosphere.planet_radius_m;
  if (spec.model == TerrainSpec::Model::None) return nullptr;
  HeightGrid grid = terrain_grid(s, spec.extent_m);
  TerrainAlbedo albedo = terrain_albedo(s, grid);
  auto terrain = std::make_shared<const Terrain>(std::move(grid), R, std::move(albedo));
  const Vec3& c = s.camera.position_m;
  const Vec3 camera(c.x(), c.y(), R + c.z());
  const double under = terrain->height_under(camera);
  if (!(terrain->clearance(camera) > 0.0))
    throw InputError("camera.position_m",
                     "[" + format_number(c.x()) + ", " + format_number(c.y()) + ", " + format_number(c.z()) + "]",
                     "a position above the terrain (its surface is " + format_number(under) + " m high there)");
  return terrain;
}

}  // namespace skyspec
