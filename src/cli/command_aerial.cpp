// `skyspec aerial`: aerial perspective for an image with a depth pass. For every pixel, the
// spectral transmittance from the camera to the surface and the light the air scatters into the
// view ray on the way; composite = image x transmittance + inscatter.

#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "progress.hpp"
#include "scene_options.hpp"
#include "base/atomic_file.hpp"
#include "skyspec/colour.hpp"
#include "skyspec/error.hpp"
#include "io/exr_channels.hpp"
#include "io/provenance.hpp"
#include "skyspec/render.hpp"
#include "render/render_budget.hpp"
#include "io/spectral_exr.hpp"
#include "skyspec/units.hpp"

namespace skyspec::cli {
namespace {

std::vector<KeyFlag> aerial_flags() {
  // The image's size comes from the inputs, so there are no --width and --height.
  std::vector<KeyFlag> flags = output_flags();
  append_flags(flags, camera_flags(false));
  append_flags(flags, sun_flags());
  append_flags(flags, {{"--threads", "render.threads", "worker threads (0: all cores)", {}, false}});
  append_flags(flags, spectrum_flags());
  return flags;
}

struct AerialOptions {
  SceneOptions scene{"default", {}, {}, aerial_flags()};
  std::string image, depth, depth_channel = "Z", depth_is = "distance";
  std::optional<double> distance_m;
  bool quiet = false, force = false;
};

int run(AerialOptions& o) {
  if (o.depth.empty() == !o.distance_m.has_value())
    throw InputError("--depth / --distance", o.depth.empty() ? "(neither)" : "(both)",
                     "exactly one: a depth EXR (--depth FILE) or a constant distance in metres (--distance M)");
  if (o.depth_is != "distance" && o.depth_is != "z")
    throw InputError("--depth-is", "\"" + o.depth_is + "\"", "one of: distance (along each ray), z (along the view axis)");
  if (o.distance_m && !(*o.distance_m > 0.0 && std::isfinite(*o.distance_m)))
    throw InputError("--distance", std::to_string(*o.distance_m), "a distance in metres > 0");

  // The image size comes from the depth pass or the image.
  std::optional<ExrChannels> depth, image;
  if (!o.depth.empty()) depth = read_exr_channels(o.depth, {o.depth_channel});
  bool spectral_image = false;
  SpectralImage spectral;
  if (!o.image.empty()) {
    for (const auto& name : exr_channel_names(o.image))
      if (parse_spectral_channel_name(name)) spectral_image = true;
    if (spectral_image) spectral = read_spectral_exr(o.image);
    else image = read_exr_channels(o.image, {"R", "G", "B"});
  }
  int width = 0, height = 0;
  auto take_size = [&](int w, int h, const std::string& what) {
    if (width == 0) {
      width = w;
      height = h;
    } else if (w != width || h != height) {
      throw InputError(what, std::to_string(w) + "x" + std::to_string(h),
                       "the same size as the other input (" + std::to_string(width) + "x" + std::to_string(height) + ")");
    }
  };
  if (depth) take_size(depth->width, depth->height, "--depth");
  if (image) take_size(image->width, image->height, "--image");
  if (spectral_image) take_size(spectral.width, spectral.height, "--image");
  if (width == 0) throw InputError("--image", "(missing)", "an image or a depth pass to take the size from");

  const Scene scene = load_scene(o.scene, [&](SceneLoader& l) {
    l.apply_override("camera.width", std::to_string(width), "the input's size");
    l.apply_override("camera.height", std::to_string(height), "the input's size");
  });
  if (scene.render.path != RenderSpec::Path::Spectral)
    throw InputError("render.path", "\"rgb-fast\"", "\"spectral\" for aerial perspective");
  // Absurd requests are refused up front (render_budget.hpp): two or three spectral EXRs (or an RGB
  // composite), and whole images in memory: distances, transmittance and inscatter (spectral and
  // RGB), the composite and the input image; the time once the renderer is built.
  RenderPlan plan = RenderPlan::for_scene(scene);
  plan.png = false;
  const double n_lambda = plan.wavelengths;
  plan.extra_output_bytes = spectral_image ? 2 * spectral_exr_bytes(width, height, plan.wavelengths)
                                           : spectral_exr_bytes(width, height, plan.wavelengths) +
                                                 (image ? rgb_exr_bytes(width, height) : 0);
  plan.extra_bytes_per_pixel = 4 + 2 * 4 * n_lambda + 2 * 12 +
                               (spectral_image ? 2 * (4 * n_lambda + 12) : image ? 2 * 12 : 0) + (depth ? 4 : 0);
  ensure_writable_directory(scene.output.directory, "output.directory");  // its errors first
  RenderEstimate estimate = estimate_render(plan);
  if (!o.force) refuse_if_over_budget(estimate);
  const SkyRenderer r(scene);
  if (!o.force) {
    estimate.seconds = measure_render_seconds(r, plan);
    refuse_if_over_budget(estimate);
  }
  const int n = r.grid().size();
  if (spectral_image && spectral.wavelengths_nm != r.grid().nanometres())
    throw InputError("--image", "its " + std::to_string(spectral.wavelengths_nm.size()) + " wavelengths",
                     "the scene's wavelength grid (" + r.grid().describe() + "); set --lambda-* to match");

  // Distances along each ray.
  std::vector<float> dist(static_cast<size_t>(width) * height, static_cast<float>(o.distance_m.value_or(0.0)));
  if (depth) {
    const auto& z = depth->channels.at(o.depth_channel);
    const auto camera = make_camera(scene);
    Vec3 forward;
    camera->direction(0.5 * width, 0.5 * height, forward);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const size_t i = static_cast<size_t>(y) * width + x;
        float d = z[i];
        if (std::isnan(d) || d < 0.0f)
          throw InputError("--depth", "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") = " + std::to_string(d),
                           "distances >= 0 (infinity for the sky)");
        if (o.depth_is == "z" && std::isfinite(d)) {
          Vec3 dir;
          camera->direction(x + 0.5, y + 0.5, dir);
          d = static_cast<float>(d / std::max(1e-6, dir.dot(forward)));
        }
        dist[i] = d;
      }
  }

  std::vector<float> trans(static_cast<size_t>(width) * height * n), light(trans.size());
  ProgressBar bar("aerial perspective", o.quiet);
  const int band = 16;
  for (int y = 0; y < height; y += band) {
    const int rows = std::min(band, height - y);
    const size_t off = static_cast<size_t>(y) * width;
    r.aerial_rows(y, rows, dist.data() + off, trans.data() + off * n, light.data() + off * n);
    bar.update(y + rows, height);
  }
  bar.finish();

  // RGB versions: inscatter through the colour-matching functions; transmittance as the ratio of
  // the sun's light after and before the path, per Rec.709 channel (what multiplies an RGB image
  // lit by the sun).
  std::vector<float> trans_rgb(static_cast<size_t>(width) * height * 3), light_rgb(trans_rgb.size());
  const Rgb sun_rgb = r.spectrum_to_rgb(r.sun_irradiance());
  for (size_t i = 0; i < dist.size(); ++i) {
    const Eigen::Map<const Spectrum> inscatter(light.data() + i * n, n), transmittance(trans.data() + i * n, n);
    Eigen::Map<Rgb>(light_rgb.data() + i * 3) = r.spectrum_to_rgb(inscatter);
    const Rgb t_rgb = r.spectrum_to_rgb(transmittance * r.sun_irradiance());
    for (int c = 0; c < 3; ++c) trans_rgb[i * 3 + c] = sun_rgb[c] > 0 ? t_rgb[c] / sun_rgb[c] : 0.0f;
  }

  ensure_writable_directory(scene.output.directory, "output.directory");
  const std::filesystem::path dir(scene.output.directory);
  SpectralExrMetadata meta;
  meta.strings = provenance_attributes(scene, false);  // version, scene, data tables
  auto write_spectral = [&](const std::string& suffix, const std::vector<float>& s, const std::vector<float>& rgb,
                            const std::string& what) {
    SpectralExrMetadata m = meta;
    m.strings["skyspec:content"] = what;
    SpectralExrWriter w(dir / (scene.output.name + suffix), width, height, r.grid().nanometres(), m);
    w.write_rows(height, s.data(), rgb.data());
    w.finish();
    if (!o.quiet) std::cout << "wrote " << (dir / (scene.output.name + suffix)).string() << "\n";
  };
  write_spectral("_transmittance.exr", trans, trans_rgb,
                 "aerial perspective: transmittance camera -> surface (S0 channels: unitless, per wavelength; R,G,B: "
                 "ratio of sunlight after/before the path per Rec.709 channel)");
  write_spectral("_inscatter.exr", light, light_rgb,
                 "aerial perspective: light scattered into the path (S0: W m^-2 sr^-1 nm^-1; R,G,B: linear Rec.709, "
                 "Y in cd m^-2)");
  if (spectral_image) {
    std::vector<float> comp(trans.size()), comp_rgb(trans_rgb.size());
    for (size_t i = 0; i < comp.size(); ++i) comp[i] = spectral.spectral[i] * trans[i] + light[i];
    for (size_t i = 0; i < dist.size(); ++i)
      Eigen::Map<Rgb>(comp_rgb.data() + i * 3) = r.spectrum_to_rgb(Eigen::Map<const Spectrum>(comp.data() + i * n, n));
    write_spectral("_composite.exr", comp, comp_rgb, "aerial perspective: image x transmittance + inscatter");
  } else if (image) {
    std::vector<float> ch[3];
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
      const auto& src = image->channels.at(names[c]);
      ch[c].resize(src.size());
      for (size_t i = 0; i < src.size(); ++i) ch[c][i] = src[i] * trans_rgb[i * 3 + c] + light_rgb[i * 3 + c];
    }
    const auto path = dir / (scene.output.name + "_composite.exr");
    write_exr_channels(path, width, height, {{"R", &ch[0]}, {"G", &ch[1]}, {"B", &ch[2]}},
                       {{"skyspec:content", "aerial perspective: image x transmittance + inscatter (linear Rec.709)"},
                        {kVersionAttribute, meta.strings[kVersionAttribute]},
                        {kSceneAttribute, meta.strings[kSceneAttribute]},
                        {kDataAttribute, meta.strings[kDataAttribute]}});
    if (!o.quiet) std::cout << "wrote " << path.string() << "\n";
  }
  return kExitOk;
}

}  // namespace

Command add_aerial_command(CLI::App& app) {
  auto o = std::make_shared<AerialOptions>();
  auto* cmd = app.add_subcommand("aerial", "Aerial perspective: transmittance and in-scattered light for an image with depth");
  cmd->footer(
      "Example:\n"
      "  skyspec aerial --image beauty.exr --depth depth.exr --camera perspective --position 0,0,2 \\\n"
      "      --look-at 0,1000,2 --fov 40 --sun-elevation 20 --out ap\n"
      "Writes <name>_transmittance.exr and <name>_inscatter.exr (spectral + RGB) and, with --image,\n"
      "<name>_composite.exr = image x transmittance + inscatter. Depth: distance along each ray in metres\n"
      "(--depth-is z: along the view axis); infinite depth is sky. Use the camera the image was made with.");
  add_scene_options(*cmd, o->scene);
  add_quality_option(*cmd, o->scene);
  cmd->add_option("--image", o->image, "the scene's image: linear Rec.709 R,G,B or spectral S0 channels");
  cmd->add_option("--depth", o->depth, "EXR with the depth pass");
  cmd->add_option("--depth-channel", o->depth_channel, "channel of the depth pass")->capture_default_str();
  cmd->add_option("--depth-is", o->depth_is, "distance (along each ray) or z (along the view axis)")->capture_default_str();
  cmd->add_option("--distance", o->distance_m, "instead of a depth pass: one distance in metres for every pixel");
  cmd->add_flag("-q,--quiet", o->quiet, "no progress bar and no summary");
  cmd->add_flag("--force", o->force,
                "compute even if the outputs exceed the free disk, the images need more memory than is available "
                "or the estimated time exceeds 24 hours");
  return {cmd, [o] { return run(*o); },
          [o] {  // run's scene checks, without reading the images (Command::validate)
            load_scene(o->scene, [](SceneLoader& l) { l.apply_override("camera.width", "1", "the input's size"); });
          }};
}

}  // namespace skyspec::cli
