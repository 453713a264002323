// The scene key registry: one entry per scene key, with its unit, allowed values, setter and
// getter. Everything that reads or writes scene keys goes through it: the TOML reader and --set
// (scene_loader.cpp), scene_to_toml, --help-keys, Python's overrides and docs/scene-keys.md
// (scene_toml.cpp). The kinds of key (a number with a unit and range, a whole number, a choice,
// a list, a date-time ...) are made by key_types.hpp; the keys themselves are listed in
// key_registry.cpp.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <toml++/toml.h>

#include "skyspec/scene.hpp"

namespace skyspec::scene_keys {

struct KeyDef {
  std::string key;
  std::string doc;  // "(unit, range) help"
  std::function<void(Scene&, const toml::node&, const std::string& origin)> set;
  std::function<std::string(const Scene&)> get;  // TOML value text
  bool text = false;  // the value is a string (a flag's bare word is taken as one, even "nan" or "1")
  std::string unit;   // of a number, as the help writes it ("m", "m^-1", "degrees"); "" when it has none
  /// The camera types that read this key (empty: every one). Its help starts with their names, and
  /// a flag or an override that sets it for another camera is refused (SceneLoader::finish).
  std::vector<CameraSpec::Type> cameras;
  /// When the scene reads this key at all, beyond the camera (empty: always; add_conditions in
  /// key_registry.cpp lists them): a flag or an override that sets it when `needs` is false is
  /// refused (SceneLoader::finish), naming the condition, needs_text.
  std::function<bool(const Scene&)> needs;
  std::string needs_text;
  /// A file the render reads (terrain.file, ...): a relative path given in a scene file is taken
  /// from that file's folder (SceneLoader::apply_file), one given elsewhere from the current folder.
  bool input_path = false;
};

/// Every scene key, in the order help texts and scene_to_toml list them.
const std::vector<KeyDef>& registry();
/// The key's entry, or null.
const KeyDef* find_key(const std::string& key);
/// InputError::unknown_key with a "did you mean" hint from the registry.
[[noreturn]] void unknown_key(const std::string& key, const std::string& origin);

/// A key's documentation is "(allowed values) meaning": the two parts.
std::pair<std::string, std::string> split_doc(const std::string& doc);

/// A TOML value as the user wrote it, for messages.
std::string node_text(const toml::node& n);
/// "file:line:column" of a node (or of a key), else the fallback (a flag's name).
std::string origin_of(const toml::node& n, const std::string& fallback);
std::string origin_of_key(const toml::key& k, const std::string& fallback);
/// Strings joined with a separator.
std::string join(const std::vector<std::string>& v, const std::string& sep);

}  // namespace skyspec::scene_keys
