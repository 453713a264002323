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

/// The camera height (camera.position_m's third value, metres above sea level at the reference
/// point) that puts the camera at (east, north) above_ground_m above the scene's ground along its
/// own vertical: the terrain's surface as scene_terrain() samples it (only the grid's samples
/// around the camera are read), or the sphere. For camera.above_ground_m (SceneLoader::finish).
double camera_height_above_ground(const Scene& s, double east_m, double north_m, double above_ground_m);

}  // namespace skyspec
