// The checks of a whole scene that no single key can make (SceneLoader::finish): panorama
// conventions against the camera, and the wavelengths every table the scene reads covers.
#pragma once

#include <set>
#include <string>

#include "skyspec/scene.hpp"

namespace skyspec {

/// The Blender and OpenEXR lat-long conventions map the whole image to the whole sphere.
void check_panorama(const CameraSpec& c);
/// The terrain keys together: a file for model = file, a ridge longer than its foot is wide, a
/// camera not inside the ridge (a file's terrain is checked when it is read, scene/scene_terrain).
void check_terrain(const Scene& s);
/// An equirectangular camera that sees below the horizon (it gets kPanoramaGroundAlbedo).
bool sees_below_horizon_as_panorama(const CameraSpec& c);
/// Whether any ground albedo key was given.
bool ground_albedo_given(const std::set<std::string>& given);
/// The refractive index formula's range covers the grid (coefficient derivations of the air).
void check_refractive_index_range(const Scene& s, const WavelengthGrid& grid);

}  // namespace skyspec
