// The camera a scene describes: one factory per camera type (camera_spec.hpp names the types).
// A new camera is its class (camera.hpp / its own file), a row of camera_types() and a row here.
#include <array>
#include <memory>

#include "skyspec/camera.hpp"
#include "skyspec/render.hpp"

namespace skyspec {

namespace {

using CameraFactory = std::unique_ptr<Camera> (*)(const CameraSpec& c, const Vec3& origin_m, const Vec3& look_at_m);

struct CameraFactoryRow {
  CameraSpec::Type type;
  CameraFactory make;
};

const std::array<CameraFactoryRow, 3> kCameraFactories = {{
    {CameraSpec::Type::Fisheye,
     [](const CameraSpec& c, const Vec3& origin_m, const Vec3&) -> std::unique_ptr<Camera> {
       return std::make_unique<FisheyeCamera>(c.width, c.height, origin_m);
     }},
    {CameraSpec::Type::Perspective,
     [](const CameraSpec& c, const Vec3& origin_m, const Vec3& look_at_m) -> std::unique_ptr<Camera> {
       return std::make_unique<PerspectiveCamera>(c.width, c.height, origin_m, look_at_m, c.fov_deg);
     }},
    {CameraSpec::Type::Equirectangular,
     [](const CameraSpec& c, const Vec3& origin_m, const Vec3&) -> std::unique_ptr<Camera> {
       return std::make_unique<EquirectangularCamera>(c.width, c.height, origin_m, c.min_elevation_deg,
                                                      c.panorama_convention);
     }},
}};

}  // namespace

std::unique_ptr<Camera> make_camera(const Scene& scene) {
  const double R = scene.atmosphere.planet_radius_m;
  auto world = [R](const Vec3& p) { return Vec3(p.x(), p.y(), R + p.z()); };
  const CameraSpec& c = scene.camera;
  for (const auto& row : kCameraFactories)
    if (row.type == c.type) return row.make(c, world(c.position_m), world(c.look_at_m));
  return nullptr;
}

bool is_latlong_envmap(const CameraSpec& camera) {
  return camera.type == CameraSpec::Type::Equirectangular && camera.min_elevation_deg == -90.0;
}

}  // namespace skyspec
