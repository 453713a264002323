// PNG output: 8-bit sRGB previews and display-encoded 8/16-bit images, written atomically.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "colour/png_colour_tag.hpp"
#include "skyspec/display.hpp"

namespace skyspec {

/// Writes an 8-bit sRGB PNG from linear Rec.709 values rgb ([y][x][c], width*height*3 floats),
/// each multiplied by `scale` before encoding with the sRGB transfer function and clamping to
/// [0, 1]. Non-finite values are rejected with IoError. Atomic (temporary file + rename).
void write_png_srgb8(const std::filesystem::path& path, int width, int height, const std::vector<float>& linear_rgb,
                     double scale);

/// Writes display code values ([y][x][c], width*height*3 floats, already encoded for the
/// display; clamped to [0, 1]) as an RGB PNG of bit_depth 8 or 16, tagged as `tag`, with tEXt
/// chunks `text` (keyword, value). Non-finite values are rejected with IoError. Atomic.
void write_png_display(const std::filesystem::path& path, int width, int height, const std::vector<float>& code_values,
                       int bit_depth, PngColourTag tag,
                       const std::vector<std::pair<std::string, std::string>>& text = {});

/// The file write_png_display writes, as bytes in memory (the viewer's frames), compressed as
/// `compression` says (the same pixels either way). Throws IoError as write_png_display does.
std::string png_display_in_memory(int width, int height, const std::vector<float>& code_values, int bit_depth,
                                  PngColourTag tag, const std::vector<std::pair<std::string, std::string>>& text = {},
                                  PngCompression compression = PngCompression::Smallest);

/// The bytes write_png_display would write for these values (without text chunks), encoded into
/// memory: the same quantisation and libpng compression, no file (the render budget times it on a
/// sample of rows). Throws IoError as write_png_display does.
std::size_t encoded_png_display_bytes(int width, int height, const std::vector<float>& code_values, int bit_depth,
                                      PngColourTag tag);

/// Reads a PNG completely (every row decoded: libpng checks each chunk's CRC and the image
/// data's Adler-32) and returns its text chunks (keyword -> text). Throws IoError naming the file
/// when it is not a complete, intact PNG. Used to verify files before they are kept.
std::map<std::string, std::string> read_png_text_verified(const std::filesystem::path& path);

}  // namespace skyspec
