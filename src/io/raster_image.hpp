// A small RGB raster for figures that must be drawn without outside tools (internal): filled
// rectangles, nearest-neighbour blits, a 5 x 7 pixel bitmap font, the cubehelix colour map.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "io/png_image.hpp"

namespace skyspec::raster {

using Rgb = std::array<float, 3>;  ///< display code values in [0, 1] (sRGB)

class Canvas {
 public:
  Canvas(int width, int height, Rgb background);
  int width() const { return width_; }
  int height() const { return height_; }
  void set(int x, int y, Rgb c);  ///< ignored outside the canvas
  Rgb get(int x, int y) const;
  void fill_rect(int x0, int y0, int w, int h, Rgb c);
  /// Draws an image of code values ([y][x][c]) with its top-left corner at (x0, y0), each pixel
  /// as a scale x scale block.
  void blit(const std::vector<float>& code_values, int w, int h, int x0, int y0, int scale);
  /// Text in the 5 x 7 font (upper-case letters, digits and . , - + < > = % ( ) : / and space;
  /// lower case is drawn as upper case), each font pixel a scale x scale block, one pixel between
  /// letters. Returns the width drawn.
  int text(int x0, int y0, const std::string& s, Rgb c, int scale = 1);
  static int text_width(const std::string& s, int scale = 1);
  /// Writes an 8-bit PNG (atomically), tagged as sRGB unless told otherwise.
  void write_png(const std::filesystem::path& path, PngColourTag tag = PngColourTag::Srgb) const;
  const std::vector<float>& pixels() const { return pixels_; }

 private:
  int width_, height_;
  std::vector<float> pixels_;
};

/// Dave Green's cubehelix colour scheme (Bulletin of the Astronomical Society of India 39, 289,
/// 2011) with start 0.5, rotations -1.5, hue 1, gamma 1: black to white with monotonically
/// increasing perceived brightness. t in [0, 1] (clamped); sRGB code values.
Rgb cubehelix(double t);

}  // namespace skyspec::raster
