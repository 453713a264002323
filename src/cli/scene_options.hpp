// Command-line options that describe a scene, shared by the subcommands that take one (render,
// coefficients, ...): --preset, --scene, --set KEY=VALUE and flags that each set one scene key.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "base/atomic_file.hpp"
#include "skyspec/scene.hpp"

namespace skyspec::cli {

/// A flag that sets one scene key; the value goes through the scene's validation so that an error
/// names both the flag and the key.
struct KeyFlag {
  std::string flag, key, help;
  std::optional<std::string> value;
  bool is_list = false;  ///< "a,b,c" -> [a, b, c]
};

struct SceneOptions {
  SceneOptions() = default;
  SceneOptions(std::string preset_name, std::string file, std::vector<std::string> set_values,
               std::vector<KeyFlag> key_flags)
      : preset(std::move(preset_name)),
        scene_file(std::move(file)),
        sets(std::move(set_values)),
        flags(std::move(key_flags)) {}
  std::string preset = "default", scene_file;
  std::vector<std::string> sets;
  std::vector<KeyFlag> flags;
  std::string quality;    ///< --quality: sample counts of a quality level (data/quality/)
  std::string from_file;  ///< --from: a skyspec EXR whose recorded scene replaces the scene file
  mutable std::optional<std::string> from_scene;  ///< its skyspec:scene, read once
};

/// The flags of the wavelength grid (spectrum.*), shared by every command that takes a grid.
std::vector<KeyFlag> spectrum_flags();
/// --out and --name (output.*).
std::vector<KeyFlag> output_flags();
/// The camera: --camera, --position, --look-at, --fov, and, with `size`, --width and --height.
std::vector<KeyFlag> camera_flags(bool size);
/// --sun-elevation and --sun-azimuth.
std::vector<KeyFlag> sun_flags();
/// Appends the flags of `more` to `flags`.
void append_flags(std::vector<KeyFlag>& flags, const std::vector<KeyFlag>& more);

/// Registers --preset, --scene, every flag of o.flags and --set on the subcommand. A flag given
/// twice takes its last value, so a command can be amended by appending to it.
void add_scene_options(CLI::App& app, SceneOptions& o);

/// Registers --from FILE.exr (after add_scene_options): the scene recorded in a skyspec EXR's
/// header takes the place of --scene (and excludes --scene and --preset); flags and --set still
/// override it.
void add_from_option(CLI::App& app, SceneOptions& o);

/// Loads the scene: preset, scene file (or --from), flags, then `before_sets` (e.g. --no-exr),
/// then --set.
Scene load_scene(const SceneOptions& o, const std::function<void(SceneLoader&)>& before_sets = {},
                 SceneUse use = SceneUse::Render);

/// --quality draft|lean|default|high|reference, for the commands that render a sky: the sample counts
/// of that level, applied after the preset (and --from) and before the scene file, flags and --set,
/// so that sample counts given explicitly win.
void add_quality_option(CLI::App& app, SceneOptions& o);

/// The files the scene options read (--scene, --from), for refuse_output_replacing_input.
std::vector<NamedInput> scene_input_files(const SceneOptions& o);

/// "a,b,c" as a TOML array "[a,b,c]" (unchanged when it already is one).
std::string as_toml_array(const std::string& csv);

}  // namespace skyspec::cli
