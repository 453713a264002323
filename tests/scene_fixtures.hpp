// Scenes for tests: the default scene with a few keys changed, and a substring check for messages.
#pragma once

#include <string>

#include "skyspec/scene.hpp"

namespace skyspec::test {

/// The preset with the keys of `toml` applied, validated.
inline Scene scene_with(const std::string& toml, const std::string& preset = "default") {
  SceneLoader loader(preset);
  loader.apply_toml(toml, "test.toml");
  return loader.finish();
}

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace skyspec::test
