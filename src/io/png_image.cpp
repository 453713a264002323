// PNG images with libpng (8-bit sRGB previews; 8/16-bit display-encoded images), written through
// AtomicOutputFile.
#include "io/png_image.hpp"

#include <png.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "base/atomic_file.hpp"
#include "skyspec/colour.hpp"
#include "skyspec/error.hpp"

namespace skyspec {
namespace {

/// Where libpng's error callback leaves its message before jumping back to encode_png.
struct PngErrorMessage {
  char text[256] = "unknown libpng error";
};

void on_png_error(png_structp png, png_const_charp message) {
  const int error_number = errno;  // libpng's stdio writer says only "Write Error": add the reason
  auto* error = static_cast<PngErrorMessage*>(png_get_error_ptr(png));
  if (error_number != 0 && std::strcmp(message, "Write Error") == 0)
    std::snprintf(error->text, sizeof error->text, "cannot write: %s", std::strerror(error_number));
  else
    std::snprintf(error->text, sizeof error->text, "%s", message);
  png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}  // warnings do not make the file wrong

/// Linear value -> 8-bit sRGB code: round(255 * srgb_encode(clamp(linear, 0, 1))).
}  // namespace

void write_png_srgb8(const std::filesystem::path& path, int width, int height, const std::vector<float>& linear_rgb,
                     double scale) {
  const std::string where = "PNG '" + path.string() + "': ";
  if (!std::isfinite(scale)) throw IoError(where + "non-finite exposure scale");
  // sRGB code values; non-finite input is rejected here because srgb_encode maps NaN to 0.
  const size_t row = static_cast<size_t>(std::max(width, 1));
  std::vector<float> codes(linear_rgb.size());
  for (size_t i = 0; i < linear_rgb.size(); ++i) {
    if (!std::isfinite(linear_rgb[i]))
      throw IoError(where + "non-finite value at x = " + std::to_string(i / 3 % row) +
                    ", y = " + std::to_string(i / 3 / row));
    codes[i] = static_cast<float>(srgb_encode(scale * static_cast<double>(linear_rgb[i])));
  }
  write_png_display(path, width, height, codes, 8, PngColourTag::Srgb, {});
}

// ---------------------------------------------------------------------------------------------
// Display-encoded PNGs, 8 or 16 bits, with the chunks that say how to read them.
// ---------------------------------------------------------------------------------------------

namespace {

struct DisplayPngLayout {
  int width, height, bit_depth;
  PngColourTag tag;
  // Text chunks, prepared by the caller: encode_display_png may longjmp out, so it must not own
  // anything with a destructor (a std::vector there leaked on a write error, found by ASan).
  const png_text* chunks;
  int chunk_count;
  PngCompression compression = PngCompression::Smallest;
};

void set_chrm(png_structp png, png_infop info, double rx, double ry, double gx, double gy, double bx, double by) {
  png_set_cHRM(png, info, 0.3127, 0.3290, rx, ry, gx, gy, bx, by);  // all of them have a D65 white
}

/// Writes rows of width * 3 * (bit_depth / 8) bytes (16-bit samples big-endian, as PNG stores
/// them). libpng reports errors by longjmp, so this holds only plain C objects.
bool encode_display_png(FILE* out, const DisplayPngLayout& layout, const png_byte* pixels, PngErrorMessage* error) {
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
  png_set_IHDR(png, info, static_cast<png_uint_32>(layout.width), static_cast<png_uint_32>(layout.height),
               layout.bit_depth, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  // ITU-T H.273 code points: colour primaries, transfer characteristics, matrix (0 = RGB), full range.
  png_byte cicp[4] = {0, 0, 0, 1};
  switch (layout.tag) {
    case PngColourTag::Srgb:
      png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
      break;
    case PngColourTag::DisplayP3:
      cicp[0] = 12, cicp[1] = 13;  // P3-D65 (SMPTE EG 432-1), the sRGB transfer function
      set_chrm(png, info, 0.680, 0.320, 0.265, 0.690, 0.150, 0.060);
      png_set_gAMA(png, info, 1.0 / 2.2);
      break;
    case PngColourTag::Rec709:
      cicp[0] = 1, cicp[1] = 1;  // BT.709 primaries and transfer (displayed with the BT.1886 EOTF)
      set_chrm(png, info, 0.64, 0.33, 0.30, 0.60, 0.15, 0.06);
      png_set_gAMA(png, info, 1.0 / 2.4);
      break;
    case PngColourTag::Rec2100Pq:
      cicp[0] = 9, cicp[1] = 16;  // BT.2020 primaries, SMPTE ST 2084 (PQ)
      set_chrm(png, info, 0.708, 0.292, 0.170, 0.797, 0.131, 0.046);
      break;
    case PngColourTag::None:
      break;
  }
  if (layout.compression == PngCompression::Fastest) {
    png_set_compression_level(png, 1);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  }
  if (layout.chunk_count > 0) png_set_text(png, info, layout.chunks, layout.chunk_count);
  png_write_info(png, info);
  // libpng 1.6.39 has no cICP support: the chunk is written by hand, after IHDR and before IDAT
  // as the PNG 3rd edition requires.
  if (cicp[0] != 0) png_write_chunk(png, reinterpret_cast<png_const_bytep>("cICP"), cicp, 4);
  const size_t row_bytes = static_cast<size_t>(layout.width) * 3 * static_cast<size_t>(layout.bit_depth / 8);
  for (int y = 0; y < layout.height; ++y) png_write_row(png, pixels + static_cast<size_t>(y) * row_bytes);
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

namespace {

// Checks the arguments and quantises every value first, so that a bad value leaves no file behind:
// rows of width * 3 samples of bit_depth bits (16-bit samples big-endian, as PNG stores them).
std::vector<png_byte> quantised_pixels(const std::string& where, int width, int height,
                                       const std::vector<float>& code_values, int bit_depth) {
  if (width <= 0 || height <= 0)
    throw IoError(where + "image size " + std::to_string(width) + " x " + std::to_string(height) + " must be positive");
  if (bit_depth != 8 && bit_depth != 16)
    throw IoError(where + "bit depth " + std::to_string(bit_depth) + " is not 8 or 16");
  const size_t values = static_cast<size_t>(width) * static_cast<size_t>(height) * 3;
  if (code_values.size() != values)
    throw IoError(where + std::to_string(code_values.size()) + " values given for " + std::to_string(width) + " x " +
                  std::to_string(height) + " RGB pixels");
  const size_t bytes_per_sample = static_cast<size_t>(bit_depth / 8);
  const double max_code = bit_depth == 8 ? 255.0 : 65535.0;
  std::vector<png_byte> pixels(values * bytes_per_sample);
  for (size_t i = 0; i < values; ++i) {
    if (!std::isfinite(code_values[i]))
      throw IoError(where + "non-finite value at x = " + std::to_string(i / 3 % static_cast<size_t>(width)) +
                    ", y = " + std::to_string(i / 3 / static_cast<size_t>(width)));
    const double v = std::clamp(static_cast<double>(code_values[i]), 0.0, 1.0);
    const long code = std::lround(max_code * v);
    if (bit_depth == 8) {
      pixels[i] = static_cast<png_byte>(code);
    } else {
      pixels[2 * i] = static_cast<png_byte>(code >> 8);
      pixels[2 * i + 1] = static_cast<png_byte>(code & 0xff);
    }
  }
  return pixels;
}

}  // namespace

namespace {

// The text chunks as libpng takes them (pointing into `text`, which must outlive them); keywords
// checked first.
std::vector<png_text> text_chunks(const std::string& where,
                                  const std::vector<std::pair<std::string, std::string>>& text) {
  std::vector<png_text> chunks;
  for (const auto& [key, value] : text) {
    if (key.empty() || key.size() > 79)
      throw IoError(where + "text keyword '" + key + "' must have 1 to 79 characters");
    png_text t{};
    t.compression = PNG_TEXT_COMPRESSION_NONE;
    t.key = const_cast<png_charp>(key.c_str());
    t.text = const_cast<png_charp>(value.c_str());
    t.text_length = value.size();
    chunks.push_back(t);
  }
  return chunks;
}

}  // namespace

void write_png_display(const std::filesystem::path& path, int width, int height, const std::vector<float>& code_values,
                       int bit_depth, PngColourTag tag, const std::vector<std::pair<std::string, std::string>>& text) {
  const std::string where = "PNG '" + path.string() + "': ";
  std::vector<png_text> chunks = text_chunks(where, text);
  const std::vector<png_byte> pixels = quantised_pixels(where, width, height, code_values, bit_depth);

  AtomicOutputFile file(path);
  FILE* out = std::fopen(file.temporary_path().c_str(), "wb");
  if (!out) throw IoError(where + "cannot open '" + file.temporary_path().string() + "': " + std::strerror(errno));
  PngErrorMessage error;
  const DisplayPngLayout layout{width, height, bit_depth, tag, chunks.data(), static_cast<int>(chunks.size())};
  const bool encoded = encode_display_png(out, layout, pixels.data(), &error);
  const bool stream_ok = std::ferror(out) == 0;
  const bool closed = std::fclose(out) == 0;
  if (!encoded) throw IoError(where + error.text);
  if (!stream_ok || !closed)
    throw IoError(where + "cannot write '" + file.temporary_path().string() + "': " + std::strerror(errno));
  file.commit();
}

std::string png_display_in_memory(int width, int height, const std::vector<float>& code_values, int bit_depth,
                                  PngColourTag tag, const std::vector<std::pair<std::string, std::string>>& text,
                                  PngCompression compression) {
  const std::string where = "PNG (in memory): ";
  std::vector<png_text> chunks = text_chunks(where, text);
  const std::vector<png_byte> pixels = quantised_pixels(where, width, height, code_values, bit_depth);
  char* buffer = nullptr;
  size_t size = 0;
  FILE* out = open_memstream(&buffer, &size);
  if (!out) throw IoError(where + "cannot open a memory stream: " + std::strerror(errno));
  PngErrorMessage error;
  DisplayPngLayout layout{width, height, bit_depth, tag, chunks.data(), static_cast<int>(chunks.size())};
  layout.compression = compression;
  const bool encoded = encode_display_png(out, layout, pixels.data(), &error);
  std::fclose(out);  // sets buffer and size
  std::string bytes(buffer ? buffer : "", buffer ? size : 0);
  std::free(buffer);
  if (!encoded) throw IoError(where + error.text);
  return bytes;
}

std::size_t encoded_png_display_bytes(int width, int height, const std::vector<float>& code_values, int bit_depth,
                                      PngColourTag tag) {
  return png_display_in_memory(width, height, code_values, bit_depth, tag).size();
}

namespace {
// What decode_png leaves for its caller to read and free (libpng's own allocations only).
struct PngReadState {
  png_structp png = nullptr;
  png_infop info = nullptr;
  png_bytep row = nullptr;
};

// Decodes every row. No C++ object lives in this frame: libpng's error handler longjmps out of it.
bool decode_png(FILE* in, PngErrorMessage* error, PngReadState* st) {
  st->png = png_create_read_struct(PNG_LIBPNG_VER_STRING, error, on_png_error, on_png_warning);
  if (!st->png) return false;
  st->info = png_create_info_struct(st->png);
  if (!st->info || setjmp(png_jmpbuf(st->png))) return false;
  png_set_crc_action(st->png, PNG_CRC_ERROR_QUIT, PNG_CRC_ERROR_QUIT);  // ancillary chunks (the text) too
  png_init_io(st->png, in);
  png_read_info(st->png, st->info);
  st->row = static_cast<png_bytep>(png_malloc(st->png, png_get_rowbytes(st->png, st->info)));
  const int passes = png_set_interlace_handling(st->png);
  for (int pass = 0; pass < passes; ++pass)
    for (png_uint_32 y = 0; y < png_get_image_height(st->png, st->info); ++y) png_read_row(st->png, st->row, nullptr);
  png_read_end(st->png, st->info);
  return true;
}
}  // namespace

std::map<std::string, std::string> read_png_text_verified(const std::filesystem::path& path) {
  FILE* in = std::fopen(path.c_str(), "rb");
  if (!in) throw IoError("cannot read PNG '" + path.string() + "': " + std::strerror(errno));
  PngErrorMessage error;
  PngReadState st;
  const bool intact = decode_png(in, &error, &st);
  std::map<std::string, std::string> text;
  if (intact) {
    png_textp chunks = nullptr;
    const int count = png_get_text(st.png, st.info, &chunks, nullptr);
    for (int i = 0; i < count; ++i) text[chunks[i].key] = chunks[i].text ? std::string(chunks[i].text) : std::string();
  }
  if (st.row) png_free(st.png, st.row);
  if (st.png) png_destroy_read_struct(&st.png, st.info ? &st.info : nullptr, nullptr);
  std::fclose(in);
  if (!intact) throw IoError("PNG '" + path.string() + "' is damaged or incomplete: " + error.text);
  return text;
}

}  // namespace skyspec
