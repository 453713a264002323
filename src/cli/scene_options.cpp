#include "scene_options.hpp"

#include <iostream>

#include "io/provenance.hpp"
#include "skyspec/error.hpp"
#include "skyspec/version.hpp"

namespace skyspec::cli {

std::string as_toml_array(const std::string& csv) {
  if (!csv.empty() && csv.front() == '[') return csv;
  return "[" + csv + "]";
}

std::vector<KeyFlag> output_flags() {
  return {
      {"--out", "output.directory", "output folder (created if missing)", {}, false},
      {"--name", "output.name", "base name of the output files", {}, false},
  };
}

std::vector<KeyFlag> camera_flags(bool size) {
  std::vector<KeyFlag> flags;
  if (size) {
    flags.push_back({"--width", "camera.width", "image width in pixels", {}, false});
    flags.push_back({"--height", "camera.height", "image height in pixels", {}, false});
  }
  append_flags(flags, {
                          {"--camera", "camera.type", "fisheye, perspective or equirectangular", {}, false},
                          {"--position", "camera.position_m", "camera position east,north,height in m", {}, true},
                          {"--look-at", "camera.look_at_m", "perspective: target east,north,height in m", {}, true},
                          {"--fov", "camera.fov_deg", "perspective: vertical field of view, degrees", {}, false},
                          {"--panorama-convention",
                           "camera.panorama_convention",
                           "equirectangular: skyspec, blender (Cycles, north on +Y) or openexr (lat-long envmap)",
                           {},
                           false},
                      });
  return flags;
}

std::vector<KeyFlag> sun_flags() {
  return {
      {"--sun-elevation", "sun.elevation_deg", "sun elevation, degrees", {}, false},
      {"--sun-azimuth", "sun.azimuth_deg", "sun azimuth, degrees clockwise from north", {}, false},
  };
}

void append_flags(std::vector<KeyFlag>& flags, const std::vector<KeyFlag>& more) {
  flags.insert(flags.end(), more.begin(), more.end());
}

std::vector<KeyFlag> spectrum_flags() {
  return {
      {"--lambda-min", "spectrum.min_nm", "first wavelength, nm", {}, false},
      {"--lambda-max", "spectrum.max_nm", "last wavelength, nm", {}, false},
      {"--lambda-step", "spectrum.step_nm", "wavelength step, nm", {}, false},
      {"--lambda-count", "spectrum.count", "number of wavelengths over min..max (replaces the step)", {}, false},
      {"--wavelengths", "spectrum.wavelengths_nm", "explicit wavelengths, nm, comma-separated", {}, true},
  };
}

void add_scene_options(CLI::App& app, SceneOptions& o) {
  std::string presets;
  for (const auto& p : preset_names()) presets += (presets.empty() ? "" : " or ") + p;
  app.add_option("--preset", o.preset, "built-in starting scene: " + presets)->capture_default_str();
  app.add_option("--scene", o.scene_file, "TOML scene file applied over the preset");
  for (auto& f : o.flags)
    app.add_option(f.flag, f.value, f.help + " [" + f.key + "]")->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  app.add_option("--set", o.sets, "override any scene key: KEY=VALUE (repeatable)");
}

void add_quality_option(CLI::App& app, SceneOptions& o) {
  std::string names;
  for (const auto& q : quality_names()) names += (names.empty() ? "" : ", ") + q;
  app.add_option("--quality", o.quality,
                 "sample counts of a quality level: " + names +
                     " (data/quality/*.toml; explicit render.* keys and flags override it)");
}

void add_from_option(CLI::App& app, SceneOptions& o) {
  app.add_option("--from", o.from_file,
                 "render the scene recorded in a skyspec EXR (its skyspec:scene header); other flags override it. "
                 "Its recorded output folder and name are not used: --out and --name choose, as for any scene")
      ->excludes(app.get_option("--scene"))
      ->excludes(app.get_option("--preset"));
}

namespace {
// The skyspec:scene of the --from file. Not an OpenEXR file: IoError (exit 3); no scene in it:
// InputError (exit 2); another skyspec version: a warning, since the scene is still valid input.
std::string recorded_scene(const std::string& path) {
  FileProvenance p;
  try {
    p = read_exr_provenance(path);
  } catch (const IoError& e) {
    throw IoError("--from: " + std::string(e.what()));
  }
  if (p.scene.empty())
    throw InputError("--from", "\"" + path + "\"",
                     "an OpenEXR file written by skyspec, with the scene in its header (this one has no " +
                         std::string(kSceneAttribute) + " attribute)");
  if (p.version != version_string())
    std::cerr << "skyspec: warning: --from " << path << " was written by skyspec "
              << (p.version.empty() ? std::string("of an unknown version") : p.version) << ", this is skyspec "
              << version_string() << ": the same scene may not give the same pixels\n";
  return p.scene;
}
}  // namespace

std::vector<NamedInput> scene_input_files(const SceneOptions& o) {
  std::vector<NamedInput> files;
  if (!o.scene_file.empty()) files.push_back({"--scene", o.scene_file});
  if (!o.from_file.empty()) files.push_back({"--from", o.from_file});
  return files;
}

Scene load_scene(const SceneOptions& o, const std::function<void(SceneLoader&)>& before_sets, SceneUse use) {
  SceneLoader loader(o.preset);
  if (!o.from_file.empty()) {
    if (!o.from_scene) o.from_scene = recorded_scene(o.from_file);
    // A file we did not necessarily write never chooses where we write: the recorded
    // output.directory and output.name are replaced by the preset's (skyspec-out/sky), and --out,
    // --name and --set choose as they do for any scene.
    const Scene preset = SceneLoader(o.preset).finish();
    loader.apply_toml(*o.from_scene, "--from " + o.from_file);
    loader.apply_override("output.directory", preset.output.directory,
                          "--from (its recorded output.directory is not used)");
    loader.apply_override("output.name", preset.output.name, "--from (its recorded output.name is not used)");
  }
  if (!o.quality.empty()) loader.apply_quality(o.quality, "--quality");
  if (!o.scene_file.empty()) loader.apply_file(o.scene_file);
  for (const auto& f : o.flags)
    if (f.value) loader.apply_override(f.key, f.is_list ? as_toml_array(*f.value) : *f.value, f.flag);
  if (before_sets) before_sets(loader);
  for (const auto& s : o.sets) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("--set", "\"" + s + "\"", "KEY=VALUE, e.g. --set atmosphere.mie.g=0.8");
    std::string key = s.substr(0, eq), value = s.substr(eq + 1);
    while (!key.empty() && key.back() == ' ') key.pop_back();
    loader.apply_override(key, value, "--set " + key);
  }
  return loader.finish(use);
}

}  // namespace skyspec::cli
