#include "render/surface_pass.hpp"

#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "scene/scene_terrain.hpp"
#include "skyspec/camera.hpp"
#include "skyspec/geometry.hpp"
#include "skyspec/render.hpp"

namespace skyspec {

std::vector<float> surface_channels(const Scene& scene) {
  const std::unique_ptr<Camera> camera = make_camera(scene);
  const std::shared_ptr<const Terrain> terrain = scene_terrain(scene);
  const double R = scene.atmosphere.planet_radius_m;
  const int w = camera->width(), h = camera->height();
  const size_t channels = surface_channel_names().size();
  std::vector<float> out(static_cast<size_t>(w) * static_cast<size_t>(h) * channels, 0.0f);
  const Vec3 o = camera->origin_m();
  const int threads = scene.render.threads > 0 ? scene.render.threads : tbb::this_task_arena::max_concurrency();
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(0, h, [&](int y) {
      for (int x = 0; x < w; ++x) {
        Vec3 d;
        if (!camera->direction(x + 0.5, y + 0.5, d)) continue;
        const double ground = sphere_entry_distance(o, d, R);
        // The terrain within the ground's distance (or far past the atmosphere when the ray
        // misses the ground): it stands on the sphere.
        const double limit = std::isfinite(ground) ? ground : 4.0e6;
        const double t = terrain ? terrain->intersect(o, d, 0.0, limit) : std::numeric_limits<double>::infinity();
        float* px = &out[(static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)) * channels];
        if (std::isfinite(t)) {
          px[0] = static_cast<float>(t);
          px[1] = 1.0f;
        } else if (std::isfinite(ground)) {
          px[0] = static_cast<float>(ground);
          px[2] = 1.0f;
        }
      }
    });
  });
  return out;
}

}  // namespace skyspec
