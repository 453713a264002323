// Scene-linear RGB OpenEXR files in a named working space (ACEScg, linear Rec.709, ...), for
// interchange with compositing and grading tools.
//
// The OpenEXR `chromaticities` attribute (OpenEXR Technical Introduction, "RGB Color") says which
// primaries and white the R, G, B values refer to: the CIE xy of RGB (1,0,0), (0,1,0), (0,0,1) and
// of (1,1,1). Readers such as OpenImageIO and Nuke use it to convert; Imf::RGBtoXYZ turns it into
// the RGB -> XYZ matrix.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "skyspec/colour.hpp"

namespace skyspec {

/// Writes R, G, B float channels ([y][x][c]) with the chromaticities attribute, extra string,
/// float and double attributes and, for a whole-sphere latitude-longitude panorama, OpenEXR's
/// envmap = latlong (ZIP compression). Non-finite values are rejected with IoError; atomic.
void write_rgb_exr(const std::filesystem::path& path, int width, int height, const std::vector<float>& rgb,
                   const Chromaticities& chromaticities, const std::map<std::string, std::string>& strings = {},
                   const std::map<std::string, float>& floats = {}, const std::map<std::string, double>& doubles = {},
                   bool latlong_envmap = false);

/// Float channels `names` ([y][x][channel] in `values`) with extra string attributes and the
/// latlong envmap attribute when asked (ZIP compression); no chromaticities (the channels are not
/// colours). Non-finite values are rejected with IoError naming the channel; atomic.
void write_float_channels_exr(const std::filesystem::path& path, int width, int height,
                              const std::vector<std::string>& names, const std::vector<float>& values,
                              const std::map<std::string, std::string>& strings = {}, bool latlong_envmap = false);

struct RgbExrImage {
  int width = 0, height = 0;
  std::vector<float> rgb;  ///< [y][x][c]
  bool has_chromaticities = false;
  Chromaticities chromaticities{};  ///< OpenEXR's default (Rec.709, D65) when absent
  std::map<std::string, std::string> strings;
  std::map<std::string, float> floats;
  std::map<std::string, double> doubles;
  std::map<std::string, std::array<double, 3>> vectors;  ///< v3f and v3d attributes
  bool latlong_envmap = false;                           ///< the file has envmap = latlong
};
/// Reads R, G, B (and the attributes) of any OpenEXR file; throws IoError naming the file.
RgbExrImage read_rgb_exr(const std::filesystem::path& path);

}  // namespace skyspec
