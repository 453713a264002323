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

struct Scene;

inline constexpr const char* kVersionAttribute = "skyspec:version";
inline constexpr const char* kSceneAttribute = "skyspec:scene";
/// The exposure's scale factor (linear RGB x scale = what the preview encodes): a double
/// attribute; files before it was one hold it as text.
inline constexpr const char* kExposureScaleAttribute = "skyspec:exposureScale";
inline constexpr const char* kDataAttribute = "skyspec:data";
/// The sun's top-of-atmosphere irradiance in the spectral EXR's R, G, B (linear Rec.709): a v3d
/// attribute; files before it was one hold it as text ("r g b").
inline constexpr const char* kSunRgbAttribute = "skyspec:sunRGB";

/// The embedded tables (paths below data/) a render of the scene reads: the CIE 1931 observer
/// (spectral path), the ASTM G173 sun (sun.spectrum = "solar"), the ozone cross-sections (ozone
/// on), the solar position tables (sun.date_time set) and, when builtin_display_config, skyspec's
/// OpenColorIO config (a PNG or a working-space EXR through the built-in config).
std::vector<std::string> data_tables_used(const Scene& scene, bool builtin_display_config);

/// The skyspec:data text: EmbeddedTableInfo::describe() of each table, one per line.
std::string data_tables_text(const Scene& scene, bool builtin_display_config);

/// skyspec:version, skyspec:scene and skyspec:data for a render of the scene.
std::map<std::string, std::string> provenance_attributes(const Scene& scene, bool builtin_display_config);

/// The provenance attributes of a file (empty strings where absent).
struct FileProvenance {
  std::string version, scene, data;
};
/// Reads skyspec:version, skyspec:scene and skyspec:data from an OpenEXR header (the pixels are
/// not read). Throws IoError naming the file when it cannot be read as OpenEXR.
FileProvenance read_exr_provenance(const std::filesystem::path& path);

}  // namespace skyspec
