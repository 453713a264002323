// What a scene says about its camera: the projection, image size, placement and, for panoramas,
// the layout convention. The cameras themselves (pixel -> direction) are camera.hpp's, one layer up.
//
// Camera types and panorama conventions are each named in ONE table (camera_types(),
// panorama_conventions()): the scene reader's choices, its TOML writer, --help-keys and every
// message take their names from there. A new camera is a new Type, a row of camera_types() and its
// factory entry in render/camera_factory.cpp (docs/architecture.md, "The files you touch").
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "skyspec/vec3.hpp"

namespace skyspec {

/// How a latitude-longitude panorama lays the directions out across the image: which azimuth a
/// column shows and where pixel centres sit (docs/other-tools.md#panoramas-hdris). All three put the
/// zenith at the top and turn clockwise seen from above (north, east, south, west) from left to
/// right, as seen from inside the sphere.
enum class PanoramaConvention {
  /// skyspec's own: north at the left edge, east a quarter of the way in (azimuth = 360 u), pixel
  /// centres at u = (i + 1/2) / width; rows from +90 down to min_elevation_deg.
  Skyspec,
  /// Blender/Cycles: Cycles' equirectangular mapping (kernel/camera/projection.h,
  /// direction_to_equirectangular: u = 1/2 - atan2(y, x) / 2 pi, v = 1 - acos(z) / pi, v = 0 the
  /// bottom row) in Blender's world frame with north on +Y, east on +X and up +Z (the Sun
  /// Position add-on's north at north offset 0): azimuth = 360 (u - 1/4), east at the centre.
  /// Whole sphere only.
  Blender,
  /// OpenEXR's lat-long map (ImfEnvmap.h, LatLongMap): longitude +pi at the first column's centre
  /// to -pi at the last's, latitude +pi/2 at the first row's centre to -pi/2 at the last's; with
  /// up = +Y, east = +X, north = -Z (the right-handed, -Z-forward frame of OpenGL and USD):
  /// azimuth = pi - longitude. Whole sphere only; at least 2 x 2 pixels.
  OpenExr,
};

struct CameraSpec {
  enum class Type { Fisheye, Perspective, Equirectangular };
  Type type = Type::Fisheye;
  int width = 512, height = 512;
  Vec3 position_m = Vec3(0, 0, 1);  ///< east, north, height above sea level at the reference point
  /// When set, the camera stands this high above the ground under it (the terrain's surface or
  /// the sphere) and position_m's height is computed from it (SceneLoader::finish).
  std::optional<double> above_ground_m;
  Vec3 look_at_m = Vec3(0, 1000, 1);
  double fov_deg = 60.0;             ///< perspective: vertical field of view
  double min_elevation_deg = -90.0;  ///< equirectangular: elevation of the bottom edge (0: upper hemisphere)
  /// equirectangular: how columns and rows map to directions (skyspec, Blender/Cycles, OpenEXR).
  PanoramaConvention panorama_convention = PanoramaConvention::Skyspec;
};

/// A row of a name table: the enum value and its name in scene files.
template <typename Enum>
struct NamedValue {
  Enum value;
  const char* name;
};

/// Every camera type, in the order help texts list them: fisheye, perspective, equirectangular.
const std::vector<NamedValue<CameraSpec::Type>>& camera_types();
/// Every panorama convention: skyspec, blender, openexr.
const std::vector<NamedValue<PanoramaConvention>>& panorama_conventions();

/// The name of a camera type ("fisheye", "perspective", "equirectangular").
const char* camera_type_name(CameraSpec::Type type);
/// "skyspec", "blender" or "openexr".
const char* panorama_convention_name(PanoramaConvention c);

/// The names of a table, in its order (for choice keys and messages).
template <typename Enum>
std::vector<std::string> names_of(const std::vector<NamedValue<Enum>>& table) {
  std::vector<std::string> names;
  for (const auto& row : table) names.emplace_back(row.name);
  return names;
}
/// The value named `name` in a table; InputError(setting, name, the names) when there is none.
template <typename Enum>
Enum value_named(const std::vector<NamedValue<Enum>>& table, const std::string& name, const std::string& setting);

}  // namespace skyspec
