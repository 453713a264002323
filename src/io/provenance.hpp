// What every output file says about how it was made, and reading it back.
//
// Each EXR header and PNG text of a render carries three attributes:
//   skyspec:version  the library version ("MAJOR.MINOR.PATCH");
//   skyspec:scene    the effective scene as TOML (scene_to_toml), every key but where the file
//                    was written (output.directory, output.name) and render.threads: loading it
//                    gives the same image, so `skyspec render --from FILE.exr` renders the same
//                    pixels, and one render written into two folders, or with other threads,
//                    gives two identical files;
//   skyspec:data     one line per embedded data table the render read: path below data/, FNV-1a
//                    64 hash and size of the compiled-in bytes, and the table's source and version.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace skyspec {

inline constexpr const char* kVersionAttribute = "skyspec:version";
inline constexpr const char* kSceneAttribute = "skyspec:scene";
/// The exposure's scale factor (linear RGB x scale = what the preview encodes): a double
/// attribute; files before it was one hold it as text.
inline constexpr const char* kExposureScaleAttribute = "skyspec:exposureScale";
inline constexpr const char* kDataAttribute = "skyspec:data";
/// The sun's top-of-atmosphere irradiance in the spectral EXR's R, G, B (linear Rec.709): a v3d
/// attribute; files before it was one hold it as text ("r g b").
inline constexpr const char* kSunRgbAttribute = "skyspec:sunRGB";

/// The skyspec:data text of a render that read these embedded tables (paths below data/):
/// EmbeddedTableInfo::describe() of each, one per line. Which tables a scene reads is the render
/// layer's knowledge (render/scene_provenance.hpp).
std::string data_tables_text(const std::vector<std::string>& paths);

/// The provenance attributes of a file (empty strings where absent).
struct FileProvenance {
  std::string version, scene, data;
};
/// Reads skyspec:version, skyspec:scene and skyspec:data from an OpenEXR header (the pixels are
/// not read). Throws IoError naming the file when it cannot be read as OpenEXR.
FileProvenance read_exr_provenance(const std::filesystem::path& path);

}  // namespace skyspec
