#include "render/scene_terrain.hpp"

#include "base/text_format.hpp"
#include "io/elevation_raster.hpp"
#include "skyspec/error.hpp"

namespace skyspec {

std::shared_ptr<const Terrain> scene_terrain(const Scene& s) {
  const TerrainSpec& spec = s.terrain;
  const double R = s.atmosphere.planet_radius_m;
  HeightGrid grid;
  switch (spec.model) {
    case TerrainSpec::Model::None:
      return nullptr;
    case TerrainSpec::Model::Ridge:
      grid = ridge_heights(spec.ridge, spec.spacing_m);
      break;
    case TerrainSpec::Model::File: {
      ElevationSampling sampling;
      sampling.latitude_deg = s.location.latitude_deg;
      sampling.longitude_deg = s.location.longitude_deg;
      sampling.extent_m = spec.extent_m;
      sampling.spacing_m = spec.spacing_m;
      sampling.planet_radius_m = R;
      grid = read_elevation_raster(spec.file, sampling);
      break;
    }
  }
  auto terrain = std::make_shared<const Terrain>(std::move(grid), R);
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
