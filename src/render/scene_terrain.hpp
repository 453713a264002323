// The terrain a scene asks for (terrain.model): none, the synthetic ridge, or an elevation raster.
#pragma once

#include <memory>

#include "skyspec/scene.hpp"
#include "skyspec/terrain.hpp"

namespace skyspec {

/// The scene's terrain on its map grid, or null for terrain.model = "none". Throws InputError
/// naming terrain.file for a raster that cannot be used (io/elevation_raster.hpp) and
/// camera.position_m for a camera at or below the terrain's surface.
std::shared_ptr<const Terrain> scene_terrain(const Scene& s);

}  // namespace skyspec
