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
#include "base/output_lock.hpp"
#include "skyspec/colour.hpp"
#include "skyspec/error.hpp"
#include "io/exr_channels.hpp"
#include "io/provenance.hpp"
#include "physics/unmodelled_absorption.hpp"
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
    throw InputError("--depth-is", "\"" + o.depth_is + "\"", "one of: distance (along each ray), z (along the view axis)");
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
    if (in.spectral_image) in.spectral = read_spectral_exr(o.image);
    else in.image = read_exr_channels(o.image, {"R", "G", "B"});
  }
  auto take_size = [&](int w, int h, const std::string& what) {
    if (in.width == 0) {
      in.width = w;
      in.height = h;
    } else if (w != in.width || h != in.height) {
      throw InputError(what, std::to_string(w) + "x" + std::to_string(h),
                       "the same size as the other input (" + std::to_string(in.width) + "x" +
                           std::to_string(in.height) + ")");
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
  plan.png = false;
  const double n_lambda = plan.wavelengths;
  const int w = in.width, h = in.height;
  plan.extra_output_bytes = in.spectral_image ? 2 * spectral_exr_bytes(w, h, plan.wavelengths)
                                              : spectral_exr_bytes(w, h, plan.wavelengths) +
                                                    (in.image ? rgb_exr_bytes(w, h) : 0);
  plan.extra_bytes_per_pixel = 4 + 2 * 4 * n_lambda + 2 * 12 +
                               (in.spectral_image ? 2 * (4 * n_lambda + 12) : in.image ? 2 * 12 : 0) +
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
// cosine between the ray and the view axis).
std::vector<float> ray_distances(const AerialOptions& o, const AerialInputs& in, const Scene& scene) {
  std::vector<float> dist(static_cast<size_t>(in.width) * in.height, static_cast<float>(o.distance_m.value_or(0.0)));
  if (!in.depth) return dist;
  const auto& z = in.depth->channels.at(o.depth_channel);
  const auto camera = make_camera(scene);
  Vec3 forward;
  camera->direction(0.5 * in.width, 0.5 * in.height, forward);
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < in.width; ++x) {
      const size_t i = static_cast<size_t>(y) * in.width + x;
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
  return dist;
}

// Transmittance and inscatter per pixel and wavelength, and their RGB versions: inscatter through
// the colour-matching functions; transmittance as the ratio of the sun's light after and before
// the path, per Rec.709 channel (what multiplies an RGB image lit by the sun).
struct AerialSpectra {
  std::vector<float> trans, light, trans_rgb, light_rgb;
};
AerialSpectra aerial_spectra(const SkyRenderer& r, const std::vector<float>& dist, int width, int height, bool quiet) {
  const int n = r.grid().size();
  AerialSpectra s;
  s.trans.resize(static_cast<size_t>(width) * height * n);
  s.light.resize(s.trans.size());
  ProgressBar bar("aerial perspective", quiet);
  const int band = 16;
  for (int y = 0; y < height; y += band) {
    const int rows = std::min(band, height - y);
    const size_t off = static_cast<size_t>(y) * width;
    r.aerial_rows(y, rows, dist.data() + off, s.trans.data() + off * n, s.light.data() + off * n);
    bar.update(y + rows, height);
  }
  bar.finish();
  s.trans_rgb.resize(static_cast<size_t>(width) * height * 3);
  s.light_rgb.resize(s.trans_rgb.size());
  const Rgb sun_rgb = r.spectrum_to_rgb(r.sun_irradiance());
  for (size_t i = 0; i < dist.size(); ++i) {
    const Eigen::Map<const Spectrum> inscatter(s.light.data() + i * n, n), transmittance(s.trans.data() + i * n, n);
    Eigen::Map<Rgb>(s.light_rgb.data() + i * 3) = r.spectrum_to_rgb(inscatter);
    const Rgb t_rgb = r.spectrum_to_rgb(transmittance * r.sun_irradiance());
    for (int c = 0; c < 3; ++c) s.trans_rgb[i * 3 + c] = sun_rgb[c] > 0 ? t_rgb[c] / sun_rgb[c] : 0.0f;
  }
  return s;
}

// Writes <name>_transmittance.exr, <name>_inscatter.exr and, with an image, <name>_composite.exr
// (image x transmittance + inscatter; spectral when the image is).
void write_outputs(const Scene& scene, const SkyRenderer& r, const AerialInputs& in, const AerialSpectra& s,
                   bool quiet) {
  const int width = in.width, height = in.height, n = r.grid().size();
  ensure_writable_directory(scene.output.directory, "output.directory");
  const std::filesystem::path dir(scene.output.directory);
  SpectralExrMetadata meta;
  meta.strings = provenance_attributes(scene, false);  // version, scene, data tables
  meta.strings["skyspec:notModelled"] = unmodelled_absorption_note(r.grid());
  meta.latlong_envmap = is_latlong_envmap(scene.camera);  // the depth of a whole-sphere panorama
  auto write_spectral = [&](const std::string& suffix, const std::vector<float>& spectral,
                            const std::vector<float>& rgb, const std::string& what) {
    SpectralExrMetadata m = meta;
    m.strings["skyspec:content"] = what;
    SpectralExrWriter w(dir / (scene.output.name + suffix), width, height, r.grid().nanometres(), m);
    w.write_rows(height, spectral.data(), rgb.data());
    w.finish();
    if (!quiet) std::cout << "wrote " << (dir / (scene.output.name + suffix)).string() << "\n";
  };
  write_spectral("_transmittance.exr", s.trans, s.trans_rgb,
                 "aerial perspective: transmittance camera -> surface (S0 channels: unitless, per wavelength; R,G,B: "
                 "ratio of sunlight after/before the path per Rec.709 channel)");
  write_spectral("_inscatter.exr", s.light, s.light_rgb,
                 "aerial perspective: light scattered into the path (S0: W m^-2 sr^-1 nm^-1; R,G,B: linear Rec.709, "
                 "Y in cd m^-2)");
  if (in.spectral_image) {
    std::vector<float> comp(s.trans.size()), comp_rgb(s.trans_rgb.size());
    for (size_t i = 0; i < comp.size(); ++i) comp[i] = in.spectral.spectral[i] * s.trans[i] + s.light[i];
    for (size_t i = 0; i < comp_rgb.size() / 3; ++i)
      Eigen::Map<Rgb>(comp_rgb.data() + i * 3) = r.spectrum_to_rgb(Eigen::Map<const Spectrum>(comp.data() + i * n, n));
    write_spectral("_composite.exr", comp, comp_rgb, "aerial perspective: image x transmittance + inscatter");
  } else if (in.image) {
    std::vector<float> ch[3];
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
      const auto& src = in.image->channels.at(names[c]);
      ch[c].resize(src.size());
      for (size_t i = 0; i < src.size(); ++i) ch[c][i] = src[i] * s.trans_rgb[i * 3 + c] + s.light_rgb[i * 3 + c];
    }
    const auto path = dir / (scene.output.name + "_composite.exr");
    write_exr_channels(path, width, height, {{"R", &ch[0]}, {"G", &ch[1]}, {"B", &ch[2]}},
                       {{"skyspec:content", "aerial perspective: image x transmittance + inscatter (linear Rec.709)"},
                        {kVersionAttribute, meta.strings[kVersionAttribute]},
                        {kSceneAttribute, meta.strings[kSceneAttribute]},
                        {kDataAttribute, meta.strings[kDataAttribute]}});
    if (!quiet) std::cout << "wrote " << path.string() << "\n";
  }
}

int run(AerialOptions& o) {
  check_options(o);
  const AerialInputs in = read_inputs(o);
  const Scene scene = load_scene(o.scene, [&](SceneLoader& l) {
    l.apply_override("camera.width", std::to_string(in.width), "the input's size");
    l.apply_override("camera.height", std::to_string(in.height), "the input's size");
  });
  if (scene.render.path != RenderSpec::Path::Spectral)
    throw InputError("render.path", "\"rgb-fast\"", "\"spectral\" for aerial perspective");
  if (scene.output.polarisation)
    throw InputError("output.polarisation", "true",
                     "false for aerial perspective (its transmittance and inscatter are not polarised; render the sky "
                     "with skyspec render)");
  const RenderPlan plan = check_budget(scene, in, o.force);
  std::vector<NamedInput> inputs = scene_input_files(o.scene);
  inputs.push_back({"--image", o.image});
  inputs.push_back({"--depth", o.depth});
  for (const char* suffix : {"_transmittance.exr", "_inscatter.exr", "_composite.exr"})
    refuse_output_replacing_input(std::filesystem::path(scene.output.directory) / (scene.output.name + suffix),
                                  "--out / --name", inputs);
  const OutputLock lock(scene.output.directory, scene.output.name, "--out / --name");  // one writer per name
  const SkyRenderer r(scene);
  if (!o.force) {  // the time, once the renderer is built
    RenderEstimate estimate = estimate_render(plan);
    estimate.seconds = measure_render_seconds(r, plan);
    refuse_if_over_budget(estimate);
  }
  if (in.spectral_image && in.spectral.wavelengths_nm != r.grid().nanometres())
    throw InputError("--image", "its " + std::to_string(in.spectral.wavelengths_nm.size()) + " wavelengths",
                     "the scene's wavelength grid (" + r.grid().describe() + "); set --lambda-* to match");
  const std::vector<float> dist = ray_distances(o, in, scene);
  const AerialSpectra spectra = aerial_spectra(r, dist, in.width, in.height, o.quiet);
  write_outputs(scene, r, in, spectra, o.quiet);
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
