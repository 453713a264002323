// PNG output for previews (8-bit sRGB), written atomically.
#pragma once

#include <filesystem>
#include <vector>

namespace skyspec {

/// Writes an 8-bit sRGB PNG from linear Rec.709 values rgb ([y][x][c], width*height*3 floats),
/// each multiplied by `scale` before encoding with the sRGB transfer function and clamping to
/// [0, 1]. Non-finite values are rejected with IoError. Atomic (temporary file + rename).
void write_png_srgb8(const std::filesystem::path& path, int width, int height,
                     const std::vector<float>& linear_rgb, double scale);

}  // namespace skyspec
