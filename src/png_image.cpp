// 8-bit sRGB PNG previews with libpng, written through AtomicOutputFile.
#include "skyspec/png_image.hpp"

#include <png.h>

#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <string>

#include "skyspec/atomic_file.hpp"
#include "skyspec/colour.hpp"
#include "skyspec/error.hpp"

namespace skyspec {
namespace {

/// Where libpng's error callback leaves its message before jumping back to encode_png.
struct PngErrorMessage {
  char text[256] = "unknown libpng error";
};

void on_png_error(png_structp png, png_const_charp message) {
  auto* error = static_cast<PngErrorMessage*>(png_get_error_ptr(png));
  std::snprintf(error->text, sizeof error->text, "%s", message);
  png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}  // warnings do not make the file wrong

/// Linear value -> 8-bit sRGB code: round(255 * srgb_encode(clamp(linear, 0, 1))).
png_byte encode_srgb8(double linear) {
  return static_cast<png_byte>(std::lround(255.0 * srgb_encode(linear)));
}

/// Writes an RGB8 image (rows of width * 3 bytes) to `out`. libpng reports errors by longjmp, so
/// this function holds only plain C objects; returns false with the message in `error`.
bool encode_png(FILE* out, int width, int height, const png_byte* pixels, PngErrorMessage* error) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, error, on_png_error, on_png_warning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, out);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  // sRGB chunk, plus the gAMA and cHRM values the PNG specification (section 11.3.3.5) recommends
  // beside it for decoders that do not know sRGB.
  png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_write_info(png, info);
  const size_t row_bytes = static_cast<size_t>(width) * 3;
  for (int y = 0; y < height; ++y) png_write_row(png, pixels + static_cast<size_t>(y) * row_bytes);
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

void write_png_srgb8(const std::filesystem::path& path, int width, int height,
                     const std::vector<float>& linear_rgb, double scale) {
  const std::string where = "PNG '" + path.string() + "': ";
  if (width <= 0 || height <= 0)
    throw IoError(where + "image size " + std::to_string(width) + " x " + std::to_string(height) +
                  " must be positive");
  const size_t values = static_cast<size_t>(width) * static_cast<size_t>(height) * 3;
  if (linear_rgb.size() != values)
    throw IoError(where + std::to_string(linear_rgb.size()) + " values given for " + std::to_string(width) +
                  " x " + std::to_string(height) + " RGB pixels");
  if (!std::isfinite(scale)) throw IoError(where + "non-finite exposure scale");

  // Encode everything first: a bad value leaves no file behind.
  std::vector<png_byte> pixels(values);
  for (size_t i = 0; i < values; ++i) {
    if (!std::isfinite(linear_rgb[i]))
      throw IoError(where + "non-finite value at x = " + std::to_string(i / 3 % static_cast<size_t>(width)) +
                    ", y = " + std::to_string(i / 3 / static_cast<size_t>(width)));
    pixels[i] = encode_srgb8(scale * static_cast<double>(linear_rgb[i]));
  }

  AtomicOutputFile file(path);
  FILE* out = std::fopen(file.temporary_path().c_str(), "wb");
  if (!out) throw IoError(where + "cannot open '" + file.temporary_path().string() + "': " + std::strerror(errno));
  PngErrorMessage error;
  const bool encoded = encode_png(out, width, height, pixels.data(), &error);
  const bool stream_ok = std::ferror(out) == 0;
  const bool closed = std::fclose(out) == 0;
  if (!encoded) throw IoError(where + error.text);
  if (!stream_ok || !closed) throw IoError(where + "cannot write '" + file.temporary_path().string() + "'");
  file.commit();
}

}  // namespace skyspec
