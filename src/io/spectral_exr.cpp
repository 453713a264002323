// Spectral OpenEXR (Fichet, Pacanowski & Wilkie 2021, JCGT 10(3)): written with OpenEXR 3.1's C core
// library (OpenEXRCore), read with its C++ library.
#include "io/spectral_exr.hpp"

#include <ImfChannelList.h>
#include <ImfFloatAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfStringAttribute.h>
#include <half.h>
#include <openexr.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iomanip>
#include <locale>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <utility>

#include "base/atomic_file.hpp"
#include "base/text_format.hpp"
#include "io/exr_open.hpp"
#include "io/exr_streams.hpp"
#include "skyspec/colour.hpp"
#include "skyspec/error.hpp"

namespace skyspec {
namespace fs = std::filesystem;
namespace {

// ---------------------------------------------------------------------------------------------
// Channel names: "S0.<number><prefix><unit>", the number with a decimal comma.
// ---------------------------------------------------------------------------------------------

constexpr double kSpeedOfLight_m_per_s = 299792458.0;  // exact (SI)

/// 10^exponent, exact for |exponent| <= 22 (every SI prefix).
double power_of_ten(int exponent) {
  double p = 1.0;
  for (int i = 0; i < std::abs(exponent); ++i) p *= 10.0;
  return exponent >= 0 ? p : 1.0 / p;
}

/// Decimal exponent of an SI prefix ("" -> 0, "n" -> -9, "u" or "µ" -> -6, "da" -> 1, ...).
std::optional<int> si_prefix_exponent(const std::string& prefix) {
  static const std::pair<const char*, int> kPrefixes[] = {{"", 0},
                                                          {"Y", 24},
                                                          {"Z", 21},
                                                          {"E", 18},
                                                          {"P", 15},
                                                          {"T", 12},
                                                          {"G", 9},
                                                          {"M", 6},
                                                          {"k", 3},
                                                          {"h", 2},
                                                          {"da", 1},
                                                          {"d", -1},
                                                          {"c", -2},
                                                          {"m", -3},
                                                          {"u", -6},
                                                          {"\xC2\xB5", -6} /* U+00B5 micro sign */,
                                                          {"\xCE\xBC", -6} /* U+03BC mu */,
                                                          {"n", -9},
                                                          {"p", -12},
                                                          {"f", -15},
                                                          {"a", -18},
                                                          {"z", -21},
                                                          {"y", -24}};
  for (const auto& [name, exponent] : kPrefixes)
    if (prefix == name) return exponent;
  return std::nullopt;
}

/// Length of the number at the start of `text`: digits [',' digits] [('e'|'E') [sign] digits],
/// at least one digit before the exponent. 0 if there is none.
size_t number_length(const std::string& text) {
  const auto is_digit = [&](size_t i) { return i < text.size() && text[i] >= '0' && text[i] <= '9'; };
  size_t i = 0, digits = 0;
  while (is_digit(i)) ++i, ++digits;
  if (i < text.size() && text[i] == ',') {
    ++i;
    while (is_digit(i)) ++i, ++digits;
  }
  if (digits == 0) return 0;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    size_t j = i + 1;
    if (j < text.size() && (text[j] == '+' || text[j] == '-')) ++j;
    if (is_digit(j)) {  // otherwise the 'E' is the exa prefix
      while (is_digit(j)) ++j;
      i = j;
    }
  }
  return i;
}

/// The value of a number written with a decimal comma, read in the C locale.
double parse_comma_decimal(std::string number) {
  std::replace(number.begin(), number.end(), ',', '.');
  std::istringstream in(number);
  in.imbue(std::locale::classic());
  double value = 0.0;
  in >> value;
  return in.fail() ? std::nan("") : value;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

constexpr const char* kRgbNames[3] = {"R", "G", "B"};

/// Index of the first non-finite value among count floats, or -1.
long first_non_finite(const float* values, size_t count) {
  // Blocks of 256 checked without an early exit, so that the check vectorises (a band of an
  // uncompressed RGB-fast image is 200 000 values): a float is not finite when its exponent
  // bits are all set.
  constexpr size_t kBlock = 256;
  for (size_t first = 0; first < count; first += kBlock) {
    const size_t end = std::min(count, first + kBlock);
    unsigned bad = 0;
    for (size_t i = first; i < end; ++i) {
      std::uint32_t bits;
      std::memcpy(&bits, values + i, sizeof bits);
      bad |= (bits & 0x7f800000u) == 0x7f800000u;
    }
    if (bad)
      for (size_t i = first; i < end; ++i)
        if (!std::isfinite(values[i])) return static_cast<long>(i);
  }
  return -1;
}

}  // namespace

// ---------------------------------------------------------------------------------------------

std::string spectral_channel_name(double lambda_nm, int stokes_component) {
  if (!std::isfinite(lambda_nm) || lambda_nm <= 0.0)
    throw Error("spectral_channel_name: wavelength must be positive and finite");
  if (stokes_component < 0 || stokes_component > 3)
    throw Error("spectral_channel_name: Stokes component " + std::to_string(stokes_component) + " is not 0 to 3");
  std::ostringstream number;
  number.imbue(std::locale::classic());
  number << std::fixed << std::setprecision(6) << lambda_nm;
  std::string text = number.str();
  std::replace(text.begin(), text.end(), '.', ',');
  return "S" + std::to_string(stokes_component) + "." + text + "nm";
}

// Accepted: "S" 0-3 "." number [SI prefix] ("m" | "Hz"). Lengths are converted to nm; a frequency f
// is converted to the vacuum wavelength c / f. Anything else, including a decimal point, which the
// reference reader also ignores ("S0.400.5nm"), is not a spectral channel.
std::optional<double> parse_spectral_channel_name(const std::string& name) {
  const auto stokes = parse_stokes_channel_name(name);
  if (!stokes || stokes->first != 0) return std::nullopt;
  return stokes->second;
}

std::optional<std::pair<int, double>> parse_stokes_channel_name(const std::string& name) {
  if (name.size() < 3 || name[0] != 'S' || name[1] < '0' || name[1] > '3' || name[2] != '.') return std::nullopt;
  const int component = name[1] - '0';
  const std::string prefix = name.substr(0, 3);
  const std::string rest = name.substr(prefix.size());
  const size_t length = number_length(rest);
  if (length == 0) return std::nullopt;
  const double value = parse_comma_decimal(rest.substr(0, length));
  if (!std::isfinite(value) || value <= 0.0) return std::nullopt;

  const std::string unit = rest.substr(length);
  const bool hertz = ends_with(unit, "Hz");
  if (!hertz && !ends_with(unit, "m")) return std::nullopt;
  const std::optional<int> exponent = si_prefix_exponent(unit.substr(0, unit.size() - (hertz ? 2 : 1)));
  if (!exponent) return std::nullopt;

  double lambda_nm = 0.0;
  if (hertz) {
    const double frequency_Hz = value * power_of_ten(*exponent);
    lambda_nm = kSpeedOfLight_m_per_s / frequency_Hz * 1e9;
  } else {
    // value x 10^exponent m = value x 10^(exponent + 9) nm.
    lambda_nm = value * power_of_ten(*exponent + 9);
  }
  if (!std::isfinite(lambda_nm) || lambda_nm <= 0.0) return std::nullopt;
  return std::pair<int, double>{component, lambda_nm};
}

// ---------------------------------------------------------------------------------------------
// Writer: OpenEXR's C core library (OpenEXRCore), whose encoder compresses a line block on any
// thread that asks, so that blocks are compressed where their rows were rendered and written in
// order afterwards (encode_rows, write_encoded). The C++ library's OutputFile compresses on its own
// thread pool, which gained less from a second thread (docs/performance.md, "Where a render's two
// threads go").
// ---------------------------------------------------------------------------------------------

namespace {

// The largest finite half float (Imath's HALF_MAX).
constexpr float kHalfMax = 65504.0f;

// The lossless compressions a spectral EXR may use (lossy ones would change the radiances).
exr_compression_t compression_of(const std::string& name) {
  if (name == "piz") return EXR_COMPRESSION_PIZ;
  if (name == "zip") return EXR_COMPRESSION_ZIP;
  if (name == "zips") return EXR_COMPRESSION_ZIPS;
  if (name == "rle") return EXR_COMPRESSION_RLE;
  if (name == "none") return EXR_COMPRESSION_NONE;
  throw IoError("spectral EXR: unknown compression \"" + name + "\" (allowed: piz, zip, zips, rle, none)");
}

// S0 at every wavelength, then (polarised) S1, S2 and S3: a pixel's values in that order.
std::vector<std::string> channel_names_of(const std::vector<double>& wavelengths_nm, const std::string& where,
                                          bool polarised) {
  if (wavelengths_nm.empty()) throw IoError(where + "no wavelengths to write");
  std::vector<std::string> names;
  for (int component = 0; component < (polarised ? 4 : 1); ++component)
    for (double lambda_nm : wavelengths_nm) {
      if (!std::isfinite(lambda_nm) || lambda_nm <= 0.0)
        throw IoError(where + "wavelength " + std::to_string(lambda_nm) + " nm is not positive and finite");
      names.push_back(spectral_channel_name(lambda_nm, component));
    }
  std::vector<std::string> sorted = names;
  std::sort(sorted.begin(), sorted.end());
  if (const auto dup = std::adjacent_find(sorted.begin(), sorted.end()); dup != sorted.end())
    throw IoError(where + "two wavelengths share the channel name " + *dup);
  return names;
}

}  // namespace

// One thread's encoder: the core library's pipeline for a line block, whose buffers (the block's
// values in the file's layout, the compressed bytes, the codec's scratch) are kept from block to
// block, and the block's spectral values as half floats when the file stores them so. The pipeline
// points into itself: an Encoder never moves (tbb::enumerable_thread_specific keeps it in place).
struct SpectralExrWriter::Encoder {
  exr_const_context_t context = nullptr;
  exr_encode_pipeline_t pipeline = EXR_ENCODE_PIPELINE_INITIALIZER;
  bool initialised = false;
  std::vector<IMATH_NAMESPACE::half> half_values;
  Encoder() = default;
  Encoder(const Encoder&) = delete;
  Encoder& operator=(const Encoder&) = delete;
  ~Encoder() {
    if (initialised) exr_encoding_destroy(context, &pipeline);
  }
};

struct SpectralExrWriter::Impl {
  std::string where;                            // "spectral EXR '<path>': ", the start of every error
  int width = 0, height = 0, rows_written = 0;  // of the data window
  int x0 = 0, y0 = 0;                           // the data window's first pixel
  int block_rows = 1;                           // the codec's line block
  int threads = 0;                              // meta.threads
  std::vector<std::string> channel_names;       // spectral channels in the caller's order
  bool half = false;                            // S0 channels stored as half
  // Each of the file's channels (in the file's order, by name): its index among the pixel's
  // spectral values, or -1 - c for R, G, B's c.
  std::vector<int> source_of_channel;
  // Declaration order matters: the context is finished first (it still writes through the
  // stream), then the stream closes, then the AtomicOutputFile removes an uncommitted file.
  std::optional<AtomicOutputFile> file;  // none when encoding for the render-time estimate
  std::unique_ptr<Imf::OStream> stream;
  StdioOStream* file_stream = nullptr;  // stream, when it is a file
  uint64_t stream_position = 0, bytes_written = 0;
  exr_context_t context = nullptr;
  tbb::enumerable_thread_specific<Encoder> encoders;
  // What the core library said when a call failed, and a write's own error (the core library
  // reports it as a failed write).
  std::mutex error_mutex;
  std::string library_message;
  std::exception_ptr write_error;
  bool abandoned = false;  // finishing the context must write nothing: the file will be removed
  bool broken = false;     // an earlier write failed: the file is unusable
  // Byte strings of blocks already written, kept for the next blocks' bytes: fresh ones are
  // faulted in page by page (as the heap is trimmed and grown again), which slowed uncompressed
  // files' one-row blocks most (docs/performance.md has the measurement).
  std::mutex spare_mutex;
  std::vector<std::vector<unsigned char>> spare_blocks;
  std::size_t spare_bytes = 0;
  static constexpr std::size_t kSpareBytes = std::size_t{64} << 20, kLargestSpare = std::size_t{1} << 20;
  std::vector<unsigned char> take_spare() {
    std::lock_guard<std::mutex> lock(spare_mutex);
    if (spare_blocks.empty()) return {};
    std::vector<unsigned char> block = std::move(spare_blocks.back());
    spare_blocks.pop_back();
    spare_bytes -= block.capacity();
    return block;
  }
  void give_back(std::vector<std::vector<unsigned char>>& blocks) {
    std::lock_guard<std::mutex> lock(spare_mutex);
    for (auto& block : blocks)
      if (block.capacity() <= kLargestSpare && spare_bytes + block.capacity() <= kSpareBytes) {
        spare_bytes += block.capacity();
        spare_blocks.push_back(std::move(block));
      }
    blocks.clear();
  }
  // Rows handed to write_rows that do not yet fill a line block.
  std::vector<float> pending_spectral, pending_rgb;
  int pending_rows = 0;

  IoError error(const std::string& why) const { return IoError(where + why); }

  // The core library's result: an IoError with its message (or the stream's own) unless it is
  // success.
  void check(exr_result_t result, const char* doing) {
    if (result == EXR_ERR_SUCCESS) return;
    std::lock_guard<std::mutex> lock(error_mutex);
    if (write_error) std::rethrow_exception(write_error);
    const std::string message = library_message.empty() ? exr_get_default_error_message(result) : library_message;
    throw error(std::string(doing) + ": " + message);
  }

  ~Impl() {
    abandoned = true;  // set before finishing: a file not finished is removed, not completed
    encoders.clear();  // their buffers are the context's
    if (context) exr_finish(&context);
  }
};

namespace {

// The core library's error messages go to the writer, which throws them with the file's name
// (the library's default prints them to the standard error).
void remember_library_error(exr_const_context_t context, exr_result_t, const char* message) {
  void* user = nullptr;
  if (exr_get_user_data(context, &user) != EXR_ERR_SUCCESS || !user) return;
  auto& w = *static_cast<SpectralExrWriter::Impl*>(user);
  std::lock_guard<std::mutex> lock(w.error_mutex);
  w.library_message = message ? message : "";
}

// The core library writes the header, the blocks (in order: write_encoded) and finally the
// offset table, each at its offset in the file, through the writer's stream.
int64_t write_to_stream(exr_const_context_t, void* user, const void* buffer, uint64_t size, uint64_t offset,
                        exr_stream_error_func_ptr_t) {
  auto& w = *static_cast<SpectralExrWriter::Impl*>(user);
  if (w.abandoned) return static_cast<int64_t>(size);
  try {
    if (offset != w.stream_position) w.stream->seekp(offset);
    const char* bytes = static_cast<const char*>(buffer);
    for (uint64_t done = 0; done < size;) {
      const int piece = static_cast<int>(std::min<uint64_t>(size - done, uint64_t{1} << 30));
      w.stream->write(bytes + done, piece);
      done += static_cast<uint64_t>(piece);
    }
    w.stream_position = offset + size;
    w.bytes_written = std::max(w.bytes_written, w.stream_position);
    return static_cast<int64_t>(size);
  } catch (...) {
    std::lock_guard<std::mutex> lock(w.error_mutex);
    w.write_error = std::current_exception();
    return -1;
  }
}

// The header: the image and data windows, the channels, the compression, the Rec.709
// chromaticities of R, G, B, the caller's attributes, then the layout's own (so that they win
// over a clashing extra string).
void define_header(SpectralExrWriter::Impl& w, int image_width, int image_height, const SpectralExrMetadata& meta) {
  exr_context_t c = w.context;
  int part = 0;
  w.check(exr_add_part(c, "", EXR_STORAGE_SCANLINE, &part), "cannot add the image");
  const exr_attr_box2i_t display{{{0, 0}}, {{image_width - 1, image_height - 1}}};
  const exr_attr_box2i_t data{{{w.x0, w.y0}}, {{w.x0 + w.width - 1, w.y0 + w.height - 1}}};
  const exr_attr_v2f_t centre{{{0.0f, 0.0f}}};
  w.check(exr_initialize_required_attr(c, part, &display, &data, 1.0f, &centre, 1.0f, EXR_LINEORDER_INCREASING_Y,
                                       compression_of(meta.compression)),
          "cannot set the required attributes");
  // OpenEXR's attribute and channel names are at most 31 characters unless the file says it
  // has longer ones.
  bool long_names = false;
  for (const auto& entry : meta.strings) long_names = long_names || entry.first.size() > 31;
  for (const auto& entry : meta.doubles) long_names = long_names || entry.first.size() > 31;
  for (const auto& entry : meta.vectors) long_names = long_names || entry.first.size() > 31;
  if (long_names) w.check(exr_set_longname_support(c, 1), "cannot allow long names");

  const exr_pixel_type_t spectral_type = meta.half_spectral ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT;
  for (const std::string& name : w.channel_names)
    w.check(exr_add_channel(c, part, name.c_str(), spectral_type, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1),
            "cannot add a channel");
  for (const char* name : kRgbNames)
    w.check(exr_add_channel(c, part, name, EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1),
            "cannot add a channel");

  const Chromaticities rec709 = rec709_chromaticities();
  const auto f = [](double v) { return static_cast<float>(v); };
  const exr_attr_chromaticities_t chromaticities{f(rec709.red[0]),   f(rec709.red[1]),  f(rec709.green[0]),
                                                 f(rec709.green[1]), f(rec709.blue[0]), f(rec709.blue[1]),
                                                 f(rec709.white[0]), f(rec709.white[1])};
  w.check(exr_attr_set_chromaticities(c, part, "chromaticities", &chromaticities), "cannot set chromaticities");
  for (const auto& [key, value] : meta.strings)
    w.check(exr_attr_set_string(c, part, key.c_str(), value.c_str()), "cannot set a string attribute");
  for (const auto& [key, value] : meta.doubles)
    w.check(exr_attr_set_double(c, part, key.c_str(), value), "cannot set a double attribute");
  for (const auto& [key, v] : meta.vectors) {
    const exr_attr_v3d_t value{{{v[0], v[1], v[2]}}};
    w.check(exr_attr_set_v3d(c, part, key.c_str(), &value), "cannot set a vector attribute");
  }
  w.check(exr_attr_set_string(c, part, "spectralLayoutVersion", "1.0"), "cannot set spectralLayoutVersion");
  w.check(exr_attr_set_string(c, part, "emissiveUnits", "W.m^-2.sr^-1"), "cannot set emissiveUnits");
  if (meta.ev) w.check(exr_attr_set_float(c, part, "EV", *meta.ev), "cannot set EV");
  // Polarised files only (the layout): Stokes frames with e1 x e2 = the light's direction.
  if (meta.polarised)
    w.check(exr_attr_set_string(c, part, "polarisationHandedness", "right"), "cannot set polarisationHandedness");
  if (meta.latlong_envmap) w.check(exr_attr_set_envmap(c, part, "envmap", EXR_ENVMAP_LATLONG), "cannot set envmap");
}

// Opens the core library's context over w.stream and writes the header.
void open_file(SpectralExrWriter::Impl& w, int image_width, int image_height, const SpectralExrMetadata& meta) {
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = &remember_library_error;
  init.user_data = &w;
  init.write_fn = &write_to_stream;
  init.zip_level = 4;  // the C++ library's default in OpenEXR 3.1: files of the same size (bench/exr_codecs.cpp)
  const std::string file_name = w.file ? w.file->temporary_path().string() : std::string("(encoded in memory)");
  w.check(exr_start_write(&w.context, file_name.c_str(), EXR_WRITE_FILE_DIRECTLY, &init), "cannot start writing");
  define_header(w, image_width, image_height, meta);
  w.check(exr_write_header(w.context), "cannot write the header");
  int32_t rows = 1;
  w.check(exr_get_scanlines_per_chunk(w.context, 0, &rows), "cannot read the line block's height");
  w.block_rows = std::max(1, rows);
  const exr_attr_chlist_t* channels = nullptr;
  w.check(exr_get_channels(w.context, 0, &channels), "cannot read the channel list");
  for (int c = 0; c < channels->num_channels; ++c) {
    const std::string name(channels->entries[c].name.str, static_cast<size_t>(channels->entries[c].name.length));
    const auto spectral = std::find(w.channel_names.begin(), w.channel_names.end(), name);
    if (spectral != w.channel_names.end()) {
      w.source_of_channel.push_back(static_cast<int>(spectral - w.channel_names.begin()));
      continue;
    }
    int rgb = 0;
    while (rgb < 3 && name != kRgbNames[rgb]) ++rgb;
    if (rgb == 3) throw w.error("the file has a channel " + name + " the writer did not add");
    w.source_of_channel.push_back(-1 - rgb);
  }
}

// Throws an IoError naming the pixel and channel of the first value the file cannot hold: a
// non-finite value, or one beyond a half float's range when the spectral channels are half.
void validate(const SpectralExrWriter::Impl& w, int first_row, int rows, const float* spectral, const float* rgb) {
  const int n = static_cast<int>(w.channel_names.size());
  const size_t pixels = static_cast<size_t>(rows) * static_cast<size_t>(w.width);
  const auto at = [&](long pixel) {
    return "x = " + std::to_string(w.x0 + pixel % w.width) +
           ", y = " + std::to_string(w.y0 + first_row + pixel / w.width);
  };
  if (const long i = first_non_finite(spectral, pixels * static_cast<size_t>(n)); i >= 0)
    throw w.error("non-finite spectral value at " + at(i / n) + ", channel " +
                  w.channel_names[static_cast<size_t>(i % n)]);
  if (w.half) {  // OpenEXR would store a value beyond half's range as infinity
    const float* end = spectral + pixels * static_cast<size_t>(n);
    const float* big = std::find_if(spectral, end, [](float v) { return std::abs(v) > kHalfMax; });
    if (big != end) {
      const long i = big - spectral;
      throw w.error("spectral value " + format_number(*big) + " at " + at(i / n) + ", channel " +
                    w.channel_names[static_cast<size_t>(i % n)] + " is beyond a half float's 65504: write it with " +
                    "output.exr_spectral_type = \"float\"");
    }
  }
  if (const long i = first_non_finite(rgb, pixels * 3); i >= 0) throw w.error("non-finite RGB value at " + at(i / 3));
}

// One line block of `rows` rows starting at row `first_row` of the data window, compressed with
// this thread's encoder into `out`.
void encode_block(SpectralExrWriter::Impl& w, SpectralExrWriter::Encoder& e, int first_row, int rows,
                  const float* spectral, const float* rgb, std::vector<unsigned char>& out) {
  const size_t n = w.channel_names.size(), width = static_cast<size_t>(w.width);
  exr_chunk_info_t chunk{};
  w.check(exr_write_scanline_chunk_info(w.context, 0, w.y0 + first_row, &chunk), "cannot place a line block");
  exr_encode_pipeline_t& p = e.pipeline;
  if (!e.initialised) {
    e.context = w.context;
    w.check(exr_encoding_initialize(w.context, 0, &chunk, &p), "cannot start encoding");
    e.initialised = true;
  } else {
    w.check(exr_encoding_update(w.context, 0, &chunk, &p), "cannot encode a line block");
  }
  const void* spectral_values = spectral;
  size_t element = sizeof(float);
  if (w.half) {  // rounded to nearest, as Imath converts
    e.half_values.assign(spectral, spectral + static_cast<size_t>(rows) * width * n);
    spectral_values = e.half_values.data();
    element = sizeof(IMATH_NAMESPACE::half);
  }
  for (int c = 0; c < p.channel_count; ++c) {
    exr_coding_channel_info_t& ch = p.channels[c];
    const int source = w.source_of_channel[static_cast<size_t>(c)];
    if (source >= 0) {
      ch.encode_from_ptr = static_cast<const uint8_t*>(spectral_values) + static_cast<size_t>(source) * element;
      ch.user_pixel_stride = static_cast<int32_t>(n * element);
      ch.user_data_type = static_cast<uint16_t>(w.half ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT);
      ch.user_bytes_per_element = static_cast<int16_t>(element);
    } else {
      ch.encode_from_ptr = reinterpret_cast<const uint8_t*>(rgb + (-1 - source));
      ch.user_pixel_stride = static_cast<int32_t>(3 * sizeof(float));
      ch.user_data_type = EXR_PIXEL_FLOAT;
      ch.user_bytes_per_element = sizeof(float);
    }
    ch.user_line_stride = static_cast<int32_t>(width) * ch.user_pixel_stride;
  }
  if (!p.convert_and_pack_fn) w.check(exr_encoding_choose_default_routines(w.context, 0, &p), "cannot encode");
  // Packed and compressed here; the caller writes the bytes in the file's order (write_encoded).
  p.yield_until_ready_fn = nullptr;
  p.write_fn = nullptr;
  w.check(exr_encoding_run(w.context, 0, &p), "cannot compress a line block");
  // A block that compression does not make smaller is stored as it is (OpenEXR's rule, by which
  // readers tell the two apart).
  const bool compressed = p.compressed_buffer && p.compressed_bytes < p.packed_bytes;
  const auto* bytes = static_cast<const unsigned char*>(compressed ? p.compressed_buffer : p.packed_buffer);
  out.assign(bytes, bytes + (compressed ? p.compressed_bytes : p.packed_bytes));
}

}  // namespace

int spectral_exr_block_rows(const std::string& compression) {
  switch (compression_of(compression)) {
    case EXR_COMPRESSION_PIZ:
      return 32;
    case EXR_COMPRESSION_ZIP:
      return 16;
    default:
      return 1;
  }
}

int SpectralExrWriter::rows_per_block() const { return impl_->block_rows; }

SpectralExrWriter::EncodedRows SpectralExrWriter::encode_rows(int first_row, int rows, const float* spectral,
                                                              const float* rgb) const {
  Impl& w = *impl_;
  if (!w.context) throw w.error(w.broken ? "an earlier write failed" : "encode_rows after finish()");
  if (first_row < 0 || rows <= 0 || first_row + rows > w.height || first_row % w.block_rows != 0 ||
      (rows % w.block_rows != 0 && first_row + rows != w.height))
    throw w.error("cannot encode rows " + std::to_string(first_row) + ".." + std::to_string(first_row + rows) + " of " +
                  std::to_string(w.height) + ": a band starts on a line block (" + std::to_string(w.block_rows) +
                  " rows) and ends on one or at the last row");
  if (!spectral || !rgb) throw w.error("encoding needs both spectral and RGB values");
  validate(w, first_row, rows, spectral, rgb);
  EncodedRows encoded;
  encoded.first_row = first_row;
  encoded.rows = rows;
  const int blocks = (rows + w.block_rows - 1) / w.block_rows;
  encoded.blocks.resize(static_cast<size_t>(blocks));
  const size_t n = w.channel_names.size(), width = static_cast<size_t>(w.width);
  const auto encode = [&](int b) {
    const int row = b * w.block_rows, count = std::min(w.block_rows, rows - row);
    std::vector<unsigned char>& bytes = encoded.blocks[static_cast<size_t>(b)];
    bytes = w.take_spare();
    encode_block(w, w.encoders.local(), first_row + row, count, spectral + static_cast<size_t>(row) * width * n,
                 rgb + static_cast<size_t>(row) * width * 3, bytes);
  };
  if (blocks == 1 || w.threads == 1) {
    for (int b = 0; b < blocks; ++b) encode(b);
  } else {
    tbb::parallel_for(0, blocks, encode);  // in the caller's arena
  }
  return encoded;
}

void SpectralExrWriter::write_encoded(EncodedRows&& encoded) {
  Impl& w = *impl_;
  if (!w.context || w.broken) throw w.error(w.broken ? "an earlier write failed" : "write_encoded after finish()");
  if (w.pending_rows != 0 || encoded.first_row != w.rows_written)
    throw w.error("rows " + std::to_string(encoded.first_row) + ".. come out of order: the next row to write is " +
                  std::to_string(w.rows_written + w.pending_rows));
  try {
    for (size_t b = 0; b < encoded.blocks.size(); ++b) {
      const int y = w.y0 + encoded.first_row + static_cast<int>(b) * w.block_rows;
      const auto& bytes = encoded.blocks[b];
      w.check(exr_write_scanline_chunk(w.context, 0, y, bytes.data(), bytes.size()), "cannot write a line block");
    }
    if (w.file_stream) w.file_stream->start_writeback();
    w.give_back(encoded.blocks);
  } catch (...) {
    // The file is unusable; the context is finished when the writer goes (other threads may
    // still be encoding with it), writing nothing more.
    w.broken = true;
    w.abandoned = true;
    throw;
  }
  w.rows_written += encoded.rows;
}

SpectralExrWriter::SpectralExrWriter(const fs::path& final_path, int width, int height,
                                     const std::vector<double>& wavelengths_nm, const SpectralExrMetadata& meta) {
  open(final_path, false, width, height, wavelengths_nm, meta);
}

SpectralExrWriter::SpectralExrWriter(Discarding, int width, int height, const std::vector<double>& wavelengths_nm,
                                     const SpectralExrMetadata& meta) {
  open("(encoded in memory)", true, width, height, wavelengths_nm, meta);
}

void SpectralExrWriter::open(const fs::path& final_path, bool discard, int width, int height,
                             const std::vector<double>& wavelengths_nm, const SpectralExrMetadata& meta) {
  const std::string where = "spectral EXR '" + final_path.string() + "': ";
  if (width <= 0 || height <= 0)
    throw IoError(where + "image size " + std::to_string(width) + " x " + std::to_string(height) + " must be positive");
  std::vector<std::string> names = channel_names_of(wavelengths_nm, where, meta.polarised);
  compression_of(meta.compression);  // an unknown compression is refused before a file is opened

  impl_ = std::make_unique<Impl>();
  Impl& w = *impl_;
  w.where = where;
  w.width = width;
  w.height = height;
  if (meta.data_window) {  // a tile: rows of the window
    const auto& [x0, x1, y0, y1] = *meta.data_window;
    if (!(0 <= x0 && x0 < x1 && x1 <= width && 0 <= y0 && y0 < y1 && y1 <= height))
      throw IoError("spectral EXR: data window x " + std::to_string(x0) + ".." + std::to_string(x1) + ", y " +
                    std::to_string(y0) + ".." + std::to_string(y1) + " is not inside the " + std::to_string(width) +
                    " x " + std::to_string(height) + " image");
    w.x0 = x0;
    w.y0 = y0;
    w.width = x1 - x0;
    w.height = y1 - y0;
  }
  w.channel_names = std::move(names);
  w.half = meta.half_spectral;
  w.threads = meta.threads;
  if (discard) {
    w.stream = std::make_unique<DiscardingOStream>();
  } else {
    w.file.emplace(final_path);
    auto file = std::make_unique<StdioOStream>(w.file->temporary_path());
    w.file_stream = file.get();
    w.stream = std::move(file);
  }
  open_file(w, width, height, meta);
}

SpectralExrWriter::~SpectralExrWriter() = default;

void SpectralExrWriter::write_rows(int rows, const float* spectral, const float* rgb) {
  Impl& w = *impl_;
  if (!w.context || w.broken) throw w.error(w.broken ? "an earlier write failed" : "write_rows after finish()");
  const int next = w.rows_written + w.pending_rows;
  if (rows <= 0 || rows > w.height - next)
    throw w.error("cannot write " + std::to_string(rows) + " rows: " + std::to_string(w.height - next) + " remain");
  if (!spectral || !rgb) throw w.error("write_rows needs both spectral and RGB values");
  // The whole band is checked before any of it is kept or reaches the file.
  validate(w, next, rows, spectral, rgb);

  const size_t n = w.channel_names.size(), width = static_cast<size_t>(w.width);
  const auto encode_and_write = [&](int first_row, int count, const float* s, const float* c) {
    if (w.threads > 1 || w.threads == 0) {
      tbb::task_arena arena(w.threads > 0 ? w.threads : tbb::task_arena::automatic);
      EncodedRows encoded;
      arena.execute([&] { encoded = encode_rows(first_row, count, s, c); });
      write_encoded(std::move(encoded));
    } else {
      write_encoded(encode_rows(first_row, count, s, c));
    }
  };
  while (rows > 0) {
    const int start = w.rows_written + w.pending_rows;
    if (w.pending_rows == 0 && (rows >= w.block_rows || start + rows == w.height)) {
      // Whole line blocks (or the image's last rows) straight from the caller's values.
      const int count = start + rows == w.height ? rows : rows - rows % w.block_rows;
      encode_and_write(start, count, spectral, rgb);
      spectral += static_cast<size_t>(count) * width * n;
      rgb += static_cast<size_t>(count) * width * 3;
      rows -= count;
      continue;
    }
    // Rows that do not fill a block wait for the next ones.
    const int count = std::min(rows, w.block_rows - w.pending_rows);
    w.pending_spectral.insert(w.pending_spectral.end(), spectral, spectral + static_cast<size_t>(count) * width * n);
    w.pending_rgb.insert(w.pending_rgb.end(), rgb, rgb + static_cast<size_t>(count) * width * 3);
    w.pending_rows += count;
    spectral += static_cast<size_t>(count) * width * n;
    rgb += static_cast<size_t>(count) * width * 3;
    rows -= count;
    if (w.pending_rows == w.block_rows || w.rows_written + w.pending_rows == w.height) {
      const int pending = std::exchange(w.pending_rows, 0);
      encode_and_write(w.rows_written, pending, w.pending_spectral.data(), w.pending_rgb.data());
      w.pending_spectral.clear();
      w.pending_rgb.clear();
    }
  }
}

void SpectralExrWriter::finish() {
  Impl& w = *impl_;
  if (!w.context || w.broken) throw w.error(w.broken ? "an earlier write failed" : "finish() called twice");
  if (w.rows_written != w.height)
    throw w.error("only " + std::to_string(w.rows_written + w.pending_rows) + " of " + std::to_string(w.height) +
                  " rows were written");
  try {
    w.encoders.clear();
    w.check(exr_finish(&w.context), "cannot write the line offsets");  // writes the offset table
    if (w.file_stream) w.file_stream->close();                         // throws if any write or flush failed
  } catch (const std::exception& e) {
    w.broken = true;
    if (const auto* io = dynamic_cast<const IoError*>(&e); io && std::string(io->what()).rfind(w.where, 0) == 0) throw;
    throw w.error(e.what());  // named like write_rows's errors: the file, then the cause
  }
  if (w.file) w.file->commit();
}

std::uint64_t SpectralExrWriter::bytes_written() const { return impl_->bytes_written; }

// ---------------------------------------------------------------------------------------------
// Reader
// ---------------------------------------------------------------------------------------------

namespace {

SpectralImage read_spectral_exr_unchecked(const fs::path& path) {
  const auto input = open_exr_input(path);
  Imf::InputFile& in = *input;
  const Imf::Header& header = in.header();
  const IMATH_NAMESPACE::Box2i window = header.dataWindow();
  SpectralImage image;
  image.width = window.max.x - window.min.x + 1;
  image.height = window.max.y - window.min.y + 1;
  const auto fail = [&](const std::string& why) { return IoError("spectral EXR '" + path.string() + "': " + why); };

  // Spectral channels, ascending in wavelength; S1-S3 of a polarised file.
  std::vector<std::pair<double, std::string>> spectral_channels;
  std::map<std::pair<int, double>, std::string> stokes_channels;
  bool has_rgb = true;
  for (const char* name : kRgbNames) has_rgb = has_rgb && header.channels().findChannel(name);
  require_float_channels(header, {kRgbNames[0], kRgbNames[1], kRgbNames[2]}, "spectral EXR '" + path.string() + "': ");
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
    if (it.channel().xSampling != 1 || it.channel().ySampling != 1)
      throw fail(std::string("channel ") + it.name() + " is subsampled (not supported)");
    if (const auto stokes = parse_stokes_channel_name(it.name())) {
      if (it.channel().type == Imf::UINT)
        throw fail(std::string("channel ") + it.name() + " holds UINT samples; skyspec reads HALF or FLOAT");
      if (stokes->first == 0)
        spectral_channels.emplace_back(stokes->second, it.name());
      else
        stokes_channels[*stokes] = it.name();
    }
  }
  if (spectral_channels.empty()) throw fail("no S0.<wavelength> spectral channels");
  std::sort(spectral_channels.begin(), spectral_channels.end());
  for (size_t i = 1; i < spectral_channels.size(); ++i)
    if (spectral_channels[i].first == spectral_channels[i - 1].first)
      throw fail("channels " + spectral_channels[i - 1].second + " and " + spectral_channels[i].second +
                 " are the same wavelength");

  // Pixels, interleaved per pixel exactly as the writer takes them.
  const size_t n = spectral_channels.size();
  const size_t pixels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
  image.spectral.resize(pixels * n);
  if (has_rgb) image.rgb.resize(pixels * 3);
  Imf::FrameBuffer frame;
  for (size_t c = 0; c < n; ++c) {
    image.wavelengths_nm.push_back(spectral_channels[c].first);
    frame.insert(spectral_channels[c].second,
                 Imf::Slice::Make(Imf::FLOAT, image.spectral.data() + c, window, n * sizeof(float),
                                  static_cast<size_t>(image.width) * n * sizeof(float)));
  }
  if (has_rgb)
    for (size_t c = 0; c < 3; ++c)
      frame.insert(kRgbNames[c], Imf::Slice::Make(Imf::FLOAT, image.rgb.data() + c, window, 3 * sizeof(float),
                                                  static_cast<size_t>(image.width) * 3 * sizeof(float)));
  // S1-S3: all of them at every wavelength, or none (a file with some is not one this reads).
  if (!stokes_channels.empty()) {
    if (stokes_channels.size() != 3 * n)
      throw fail("it has " + std::to_string(stokes_channels.size()) +
                 " S1-S3 channels; a polarised file has S1, S2 and S3 "
                 "at each of its " +
                 std::to_string(n) + " wavelengths");
    image.stokes.resize(pixels * 3 * n);
    for (int component = 1; component <= 3; ++component)
      for (size_t c = 0; c < n; ++c) {
        const auto found = stokes_channels.find({component, spectral_channels[c].first});
        if (found == stokes_channels.end())
          throw fail("S" + std::to_string(component) + " is missing at " + spectral_channels[c].second);
        frame.insert(found->second,
                     Imf::Slice::Make(Imf::FLOAT, image.stokes.data() + (component - 1) * n + c, window,
                                      3 * n * sizeof(float), static_cast<size_t>(image.width) * 3 * n * sizeof(float)));
      }
  }
  in.setFrameBuffer(frame);
  in.readPixels(window.min.y, window.max.y);

  for (auto it = header.begin(); it != header.end(); ++it)
    if (const auto* text = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
      image.string_attributes[it.name()] = text->value();
  if (const auto* ev = header.findTypedAttribute<Imf::FloatAttribute>("EV")) image.ev = ev->value();
  return image;
}

}  // namespace

SpectralImage read_spectral_exr(const fs::path& path) {
  try {
    return read_spectral_exr_unchecked(path);
  } catch (const IoError&) {
    throw;
  } catch (const std::exception& e) {
    throw IoError("cannot read spectral EXR '" + path.string() + "': " + e.what());
  }
}

}  // namespace skyspec
