// Where each pixel's ray ends: the distance to the surface it meets (the terrain or the planet's
// ground) and which surface that is, for compositing and masks (output.surface).
#pragma once

#include <string>
#include <vector>

#include "skyspec/scene.hpp"

namespace skyspec {

/// The channels of <name>-surface.exr, in their order.
inline const std::vector<std::string>& surface_channel_names() {
  static const std::vector<std::string> names = {"Z", "mask.terrain", "mask.ground"};
  return names;
}

/// Per pixel [y][x][channel] (surface_channel_names): Z, the distance in metres from the camera
/// along the pixel's central ray to the first surface it meets (0 where it meets none: the sky,
/// or no ray), and two masks, 1 where that surface is the terrain, or the planet's ground (the
/// sphere of the atmosphere's planet radius), 0 elsewhere. The same geometry the renderer uses
/// (the terrain of scene_terrain, the camera of make_camera); on render.threads threads.
std::vector<float> surface_channels(const Scene& scene);

}  // namespace skyspec
