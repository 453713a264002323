// Command-line options that describe a scene, shared by the subcommands that take one (render,
// coefficients, ...): --preset, --scene, --set KEY=VALUE and flags that each set one scene key.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

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
  std::string preset = "default", scene_file;
  std::vector<std::string> sets;
  std::vector<KeyFlag> flags;
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

/// Loads the scene: preset, scene file, flags, then `before_sets` (e.g. --no-exr), then --set.
Scene load_scene(const SceneOptions& o, const std::function<void(SceneLoader&)>& before_sets = {});

/// "a,b,c" as a TOML array "[a,b,c]" (unchanged when it already is one).
std::string as_toml_array(const std::string& csv);

}  // namespace skyspec::cli
