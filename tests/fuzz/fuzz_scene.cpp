// Fuzz target: the scene-file loader (SceneLoader::apply_toml, finish) and its round trip.
//
// The input is TOML scene text applied over the default preset, as `skyspec render --scene FILE`
// does. skyspec::Error (InputError, IoError) is the expected outcome of bad input. For a scene
// that loads, the effective scene (scene_to_toml) must load again and print the same text: what
// `skyspec:scene` in an EXR records must reproduce the scene. Any other exception, a failed round
// trip, a crash, a sanitizer report or a hang is a finding.
//
// Built with libFuzzer (-DSKYSPEC_FUZZ=ON, clang) or with replay_main.cpp, which runs the corpus
// and the regressions once (CTest fuzz_replay_scene, any compiler).

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "skyspec/error.hpp"
#include "skyspec/scene.hpp"

namespace {

[[noreturn]] void finding(const std::string& what, const std::string& detail, const std::string& input) {
  std::fprintf(stderr, "fuzz_scene: %s\n  %s\n--- input ---\n%s\n--- end ---\n", what.c_str(), detail.c_str(),
               input.c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 64 * 1024) return -1;  // scene files are small; longer inputs only slow the search
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string first;
  try {
    skyspec::SceneLoader loader;
    loader.apply_toml(text, "fuzz.toml");
    first = skyspec::scene_to_toml(loader.finish());
  } catch (const skyspec::Error&) {
    return 0;  // rejected with a message: the expected outcome for bad input
  } catch (const std::exception& e) {
    finding("unexpected exception while loading", e.what(), text);
  }
  std::string second;
  try {
    skyspec::SceneLoader again;
    again.apply_toml(first, "round trip");
    second = skyspec::scene_to_toml(again.finish());
  } catch (const std::exception& e) {
    finding("the effective scene (scene_to_toml) does not load again", e.what(), first);
  }
  if (second != first) finding("the round trip changed the scene", "second print:\n" + second, first);
  return 0;
}
