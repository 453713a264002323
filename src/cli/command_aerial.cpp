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

#include "base/atomic_file.hpp"
#include "base/output_lock.hpp"
#include "commands.hpp"
#include "io/exr_channels.hpp"
#include "io/spectral_exr.hpp"
#include "physics/unmodelled_absorption.hpp"
#include "progress.hpp"
#include "render/render_budget.hpp"
#include "render/scene_provenance.hpp"
#include "scene_options.hpp"
#include "skyspec/aerial_perspective.hpp"
#include "skyspec/colour.hpp"
#include "skyspec/error.hpp"
#include "skyspec/render.hpp"
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

// The inputs: a depth pass and/or an image (RGB or spectral EXR), all of one size.
struct AerialInputs {
  std::optional<ExrChannels> depth, image;  ///< image: R, G, B when it is not spectral
  bool spectral_image = false;
  SpectralImage spectral;
  int width = 0, height = 0;
};

void check_options(const AerialOptions& o) {
  if (o.depth.empty() == !o.distance_m.has_value())
    throw InputError("--depth / --distance", o.depth.empty() ? "(neither)" : "(both)",
                     "exactly one: a depth EXR (--depth FILE) or a constant distance in metres (--distance M)");
  if (o.depth_is != "distance" && o.depth_is != "z")
    throw InputError("--depth-is", "\"" + o.depth_is + "\"",
                     "one of: distance (along each ray), z (along the view axis)");
  if (o.distance_m && !(*o.distance_m > 0.0 && std::isfinite(*o.distance_m)))
    throw InputError("--distance", std::to_string(*o.distance_m), "a distance in metres > 0");
}

// Reads the inputs; the image size comes from the depth pass or the image, which must agree.
AerialInputs read_inputs(const AerialOptions& o) {
  AerialInputs in;
  if (!o.depth.empty()) in.depth = read_exr_channels(o.depth, {o.depth_channel});
  if (!o.image.empty()) {
    for (const auto& name : exr_channel_names(o.image))
      if (parse_spectral_channel_name(name)) in.spectral_image = true;
    if (in.spectral_image)
      in.spectral = read_spectral_exr(o.image);
    else
      in.image = read_exr_channels(o.image, {"R", "G", "B"});
  }
  auto take_size = [&](int w, int h, const std::string& what) {
    if (in.width == 0) {
      in.width = w;
      in.height = h;
    } else if (w != in.width || h != in.height) {
      throw InputError(
          what, std::to_string(w) + "x" + std::to_string(h),
          "the same size as the other input (" + std::to_string(in.width) + "x" + std::to_string(in.height) + ")");
    }
  };
  if (in.depth) take_size(in.depth->width, in.depth->height, "--depth");
  if (in.image) take_size(in.image->width, in.image->height, "--image");
  if (in.spectral_image) take_size(in.spectral.width, in.spectral.height, "--image");
  if (in.width == 0) throw InputError("--image", "(missing)", "an image or a depth pass to take the size from");
  return in;
}

// Absurd requests are refused up front (render_budget.hpp): two or three spectral EXRs (or an RGB
// composite), and whole images in memory: distances, transmittance and inscatter (spectral and
// RGB), the composite and the input image. Returns the plan for the time check once the renderer
// is built.
RenderPlan check_budget(const Scene& scene, const AerialInputs& in, bool force) {
  RenderPlan plan = RenderPlan::for_scene(scene);
  plan.drop("png");  // no preview PNG of the sky alone
  const double n_lambda = plan.wavelengths;
  const int w = in.width, h = in.height;
  plan.extra_output_bytes = in.spectral_image
                                ? 2 * spectral_exr_bytes(w, h, plan.wavelengths)
                                : spectral_exr_bytes(w, h, plan.wavelengths) + (in.image ? rgb_exr_bytes(w, h) : 0);
  plan.extra_bytes_per_pixel = 4 + 2 * 4 * n_lambda + 2 * 12 +
                               (in.spectral_image ? 2 * (4 * n_lambda + 12)
                                : in.image        ? 2 * 12
                                                  : 0) +
                               (in.depth ? 4 : 0);
  ensure_writable_directory(scene.output.directory, "output.directory");  // its errors first
  if (!force) {
    const RenderEstimate estimate = estimate_render(plan);
    refuse_if_over_budget(estimate);
    refuse_if_tables_over_budget(scene, estimate);  // before the tables are built
  }
  return plan;
}

// Distances along each ray: the constant --distance, or the depth pass (a z depth divided by the
// cosine between the ray and the view axis: ray_distances_from_z).
std::vector<float> ray_distances(const AerialOptions& o, const AerialInputs& in, const Scene& scene) {
  if (!in.depth)
    return std::vector<float>(static_cast<size_t>(in.width) * in.height, static_cast<float>(*o.distance_m));
  const auto& depth = in.depth->channels.at(o.depth_channel);
  if (o.depth_is == "z") return ray_distances_from_z(scene, depth, "--depth");
  return depth;
}

int run(AerialOptions& o) {
  check_options(o);
  const AerialInputs in = read_inputs(o);
  const Scene scene = load_scene(o.scene, [&](SceneLoader& l) {
    l.apply_override("camera.width", std::to_string(in.width), "the input's size");
    l.apply_override("camera.height", std::to_string(in.height), "the input's size");
  });
  check_aerial_perspective_scene(scene);  // before the budget's pilot builds anything
  const RenderPlan plan = check_budget(scene, in, o.force);
  std::vector<NamedInput> inputs = scene_input_files(o.scene);
  inputs.push_back({"--image", o.image});
  inputs.push_back({"--depth", o.depth});
  for (const char* suffix : {"_transmittance.exr", "_inscatter.exr", "_composite.exr"})
    refuse_output_replacing_input(std::filesystem::path(scene.output.directory) / (scene.output.name + suffix),
                                  "--out / --name", inputs);
  const OutputLock lock(scene.output.directory, scene.output.name, "--out / --name");  // one writer per name
  if (in.spectral_image && in.spectral.wavelengths_nm != make_wavelength_grid(scene).nanometres())
    throw InputError(
        "--image", "its " + std::to_string(in.spectral.wavelengths_nm.size()) + " wavelengths",
        "the scene's wavelength grid (" + make_wavelength_grid(scene).describe() + "); set --lambda-* to match");
  const std::vector<float> dist = ray_distances(o, in, scene);
  ProgressBar bar("aerial perspective", o.quiet);
  bar.watch_preparation();
  const AerialPerspectiveImage ap = aerial_perspective(
      scene, dist, [&bar](int done, int total) { bar.update(done, total); },
      [&](const SkyRenderer& r) {
        if (o.force) return;  // the time, once the renderer is built
        RenderEstimate estimate = estimate_render(plan);
        estimate.seconds = measure_render_seconds(r, plan);
        refuse_if_over_budget(estimate);
      },
      "--depth");
  bar.finish();
  std::vector<std::filesystem::path> written = write_aerial_perspective(ap);
  if (in.spectral_image)
    written.push_back(write_aerial_composite(ap, in.spectral.spectral, true));
  else if (in.image) {
    std::vector<float> rgb(static_cast<size_t>(in.width) * in.height * 3);
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
      const auto& src = in.image->channels.at(names[c]);
      for (size_t i = 0; i < src.size(); ++i) rgb[i * 3 + c] = src[i];
    }
    written.push_back(write_aerial_composite(ap, rgb, false));
  }
  if (!o.quiet)
    for (const auto& path : written) std::cout << "wrote " << path.string() << "\n";
  return kExitOk;
}

}  // namespace

Command add_aerial_command(CLI::App& app) {
  auto o = std::make_shared<AerialOptions>();
  auto* cmd =
      app.add_subcommand("aerial", "Aerial perspective: transmittance and in-scattered light for an image with depth");
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
  cmd->add_option("--depth-is", o->depth_is, "distance (along each ray) or z (along the view axis)")
      ->capture_default_str();
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
