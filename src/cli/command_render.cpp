// `skyspec render`: a scene (preset + file + flags) to a spectral EXR and a PNG preview.

#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "progress.hpp"
#include "skyspec/error.hpp"
#include "skyspec/render.hpp"
#include "skyspec/scene.hpp"

namespace skyspec::cli {
namespace {

// A flag that sets one scene key; the value goes through the scene's validation so that an error
// names both the flag and the key.
struct KeyFlag {
  std::string flag, key, help;
  std::optional<std::string> value;
  bool is_list = false;  // "a,b,c" -> [a, b, c]
};

std::string as_toml_array(const std::string& csv) {
  if (!csv.empty() && csv.front() == '[') return csv;
  return "[" + csv + "]";
}

struct RenderOptions {
  std::string preset = "default", scene_file;
  std::vector<std::string> sets;
  bool no_exr = false, no_png = false, quiet = false, help_keys = false, print_scene = false;
  std::vector<KeyFlag> flags = {
      {"--out", "output.directory", "output folder (created if missing)", {}, false},
      {"--name", "output.name", "base name of the output files", {}, false},
      {"--width", "camera.width", "image width in pixels", {}, false},
      {"--height", "camera.height", "image height in pixels", {}, false},
      {"--camera", "camera.type", "fisheye, perspective or equirectangular", {}, false},
      {"--position", "camera.position_m", "camera position east,north,height in m", {}, true},
      {"--look-at", "camera.look_at_m", "perspective: target east,north,height in m", {}, true},
      {"--fov", "camera.fov_deg", "perspective: vertical field of view, degrees", {}, false},
      {"--sun-elevation", "sun.elevation_deg", "sun elevation, degrees", {}, false},
      {"--sun-azimuth", "sun.azimuth_deg", "sun azimuth, degrees clockwise from north", {}, false},
      {"--lambda-min", "spectrum.min_nm", "first wavelength, nm", {}, false},
      {"--lambda-max", "spectrum.max_nm", "last wavelength, nm", {}, false},
      {"--lambda-step", "spectrum.step_nm", "wavelength step, nm", {}, false},
      {"--lambda-count", "spectrum.count", "number of wavelengths over min..max (replaces the step)", {}, false},
      {"--wavelengths", "spectrum.wavelengths_nm", "explicit wavelengths, nm, comma-separated", {}, true},
      {"--path", "render.path", "spectral or rgb-fast", {}, false},
      {"--view-segments", "render.view_segments", "quadrature segments per view ray", {}, false},
      {"--threads", "render.threads", "worker threads (0: all cores)", {}, false},
      {"--exposure", "output.exposure_ev", "preview exposure in EV (default: automatic)", {}, false},
  };
};

Scene load_scene(RenderOptions& o) {
  SceneLoader loader(o.preset);
  if (!o.scene_file.empty()) loader.apply_file(o.scene_file);
  for (auto& f : o.flags)
    if (f.value) loader.apply_override(f.key, f.is_list ? as_toml_array(*f.value) : *f.value, f.flag);
  if (o.no_exr) loader.apply_override("output.exr", "false", "--no-exr");
  if (o.no_png) loader.apply_override("output.png", "false", "--no-png");
  for (const auto& s : o.sets) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("--set", "\"" + s + "\"", "KEY=VALUE, e.g. --set atmosphere.mie.g=0.8");
    std::string key = s.substr(0, eq), value = s.substr(eq + 1);
    while (!key.empty() && key.back() == ' ') key.pop_back();
    loader.apply_override(key, value, "--set " + key);
  }
  return loader.finish();
}

int run_render(RenderOptions& o) {
  if (o.help_keys) {
    for (const auto& [key, doc] : scene_key_help()) std::cout << key << "  " << doc << "\n";
    return kExitOk;
  }
  const Scene scene = load_scene(o);
  if (o.print_scene) {
    std::cout << scene_to_toml(scene);
    return kExitOk;
  }
  ProgressBar bar("rendering", o.quiet);
  const auto out = render_scene_to_files(scene, [&](int done, int total) { bar.update(done, total); });
  bar.finish();
  if (!o.quiet) {
    if (!out.exr.empty()) std::cout << "wrote " << out.exr.string() << "\n";
    if (!out.png.empty()) std::cout << "wrote " << out.png.string() << " (preview exposure " << out.preview_ev << " EV)\n";
    std::printf("rendered %dx%d, %s, in %.2f s\n", scene.camera.width, scene.camera.height,
                make_wavelength_grid(scene).describe().c_str(), out.seconds);
  }
  return kExitOk;
}

}  // namespace

Command add_render_command(CLI::App& app) {
  auto opts = std::make_shared<RenderOptions>();
  auto* render = app.add_subcommand("render", "Render a sky to a spectral OpenEXR and a PNG preview");
  render->footer(
      "Examples:\n"
      "  skyspec render                                  # built-in default scene -> skyspec-out/sky.exr, sky.png\n"
      "  skyspec render --sun-elevation 5 --out dusk     # low sun\n"
      "  skyspec render --preset seed                    # the seed tutorial's RGB-fast sky\n"
      "  skyspec render --scene my.toml --set atmosphere.mie.g=0.8\n"
      "  skyspec render --camera equirectangular --width 1024 --height 512\n"
      "Scene files are TOML; data/scenes/default.toml documents every key, --help-keys lists units and ranges.");
  render->add_option("--preset", opts->preset, "built-in starting scene: default or seed")->capture_default_str();
  render->add_option("--scene", opts->scene_file, "TOML scene file applied over the preset");
  // A flag given twice takes its last value, so a command can be amended by appending to it.
  for (auto& f : opts->flags)
    render->add_option(f.flag, f.value, f.help + " [" + f.key + "]")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  render->add_option("--set", opts->sets, "override any scene key: KEY=VALUE (repeatable)");
  render->add_flag("--no-exr", opts->no_exr, "do not write the spectral EXR");
  render->add_flag("--no-png", opts->no_png, "do not write the PNG preview");
  render->add_flag("-q,--quiet", opts->quiet, "no progress bar and no summary");
  render->add_flag("--help-keys", opts->help_keys, "list every scene key with its unit and range, then exit");
  render->add_flag("--print-scene", opts->print_scene, "print the effective scene as TOML, then exit");
  return {render, [opts] { return run_render(*opts); }};
}

}  // namespace skyspec::cli
