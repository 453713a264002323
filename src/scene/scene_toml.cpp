// The scene as TOML (scene_to_toml), its keys' help (--help-keys, Python's scene_keys()) and
// docs/scene-keys.md, all from the key registry.
#include "scene/key_registry.hpp"
#include "skyspec/scene.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include <toml++/toml.h>

#include "base/embedded_data.hpp"
#include "base/text_format.hpp"
#include "physics/date_time.hpp"
#include "physics/ozone.hpp"
#include "physics/solar_position.hpp"
#include "physics/solar_spectrum.hpp"
#include "scene/toml_limits.hpp"
#include "skyspec/error.hpp"
#include "skyspec/refractive_index.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

using namespace scene_keys;

std::string scene_to_toml(const Scene& scene, SceneTomlKeys keys) {
  const Scene& s = scene;
  std::map<std::string, std::vector<std::pair<std::string, std::string>>> tables;
  std::vector<std::string> order;
  for (const auto& k : registry()) {
    if (keys == SceneTomlKeys::Recorded &&
        (k.key == "output.directory" || k.key == "output.name" || k.key == "render.threads"))
      continue;
    const std::string value = k.get(s);
    if (value.empty()) continue;
    const auto dot = k.key.rfind('.');
    const std::string table = k.key.substr(0, dot), leaf = k.key.substr(dot + 1);
    if (!tables.count(table)) order.push_back(table);
    tables[table].push_back({leaf, value});
  }
  std::ostringstream out;
  for (const auto& t : order) {
    out << "[" << t << "]\n";
    for (const auto& [leaf, value] : tables[t]) out << leaf << " = " << value << "\n";
    out << "\n";
  }
  return out.str();
}

namespace {
// "; read only with CONDITION" for a key with a condition (KeyDef::needs), else "".
std::string read_only_with(const KeyDef& k) {
  return k.needs_text.empty() ? std::string() : "; read only with " + k.needs_text;
}
}  // namespace

std::vector<std::pair<std::string, std::string>> scene_key_help() {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& k : registry()) out.push_back({k.key, k.doc + read_only_with(k)});
  return out;
}

std::string scene_keys_markdown() {
  const Scene defaults = default_scene();
  std::ostringstream out;
  out << "# Scene keys\n\n"
      << "Generated from the key registry (src/scene/key_registry.cpp) by `skyspec render --help-keys=markdown`;\n"
      << "do not edit by hand. A scene file (TOML) or `--set KEY=VALUE` sets these; the default is the\n"
      << "built-in default scene (data/scenes/default.toml, equal to `Scene{}`). Values outside the allowed\n"
      << "range are refused with a message naming the key, and so is a flag or `--set` of a key the scene does\n"
      << "not read (another camera's, or one whose \"read only with\" condition does not hold).\n\n"
      << "| key | default | allowed | meaning |\n|---|---|---|---|\n";
  for (const auto& k : registry()) {
    const auto [allowed, meaning] = split_doc(k.doc);
    std::string value = k.get(defaults);
    if (value.empty()) value = "(none)";
    out << "| `" << k.key << "` | " << markdown_cell(value) << " | " << markdown_cell(allowed) << " | "
        << markdown_cell(meaning + read_only_with(k)) << " |\n";
  }
  return out.str();
}

Scene default_scene() { return SceneLoader("default").finish(); }

}  // namespace skyspec
