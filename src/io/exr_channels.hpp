// Reading named float channels from any scanline OpenEXR file (depth passes, RGB images).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace skyspec {

struct ExrChannels {
  int width = 0, height = 0;
  std::map<std::string, std::vector<float>> channels;  ///< [y][x], top row first
};

/// Reads the channels `names` (all must exist; IoError naming the file and the missing channel,
/// and listing the channels it has). The data window is taken as the image.
ExrChannels read_exr_channels(const std::filesystem::path& path, const std::vector<std::string>& names);
/// Writes float channels ([y][x] each, in the order given) to a ZIP-compressed scanline EXR,
/// atomically, with string attributes; non-finite values are rejected (IoError, no file).
void write_exr_channels(const std::filesystem::path& path, int width, int height,
                        const std::vector<std::pair<std::string, const std::vector<float>*>>& channels,
                        const std::map<std::string, std::string>& string_attributes);

/// The names of all channels of a file.
std::vector<std::string> exr_channel_names(const std::filesystem::path& path);

}  // namespace skyspec
