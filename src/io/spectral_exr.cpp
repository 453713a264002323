// Spectral OpenEXR (Fichet, Pacanowski & Wilkie 2021, JCGT 10(3)) with the OpenEXR 3.1 C++ API.
#include "io/spectral_exr.hpp"

#include <ImfChannelList.h>
#include <ImfChromaticities.h>
#include <ImfDoubleAttribute.h>
#include <ImfFloatAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <ImfThreading.h>
#include <ImfVecAttribute.h>
#include <half.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <future>
#include <iomanip>
#include <locale>
#include <memory>
#include <mutex>
#include <sstream>
#include <thread>
#include <type_traits>
#include <utility>

#include <unistd.h>  // fdatasync

#include "base/atomic_file.hpp"
#include "base/text_format.hpp"
#include "io/exr_open.hpp"
#include "io/exr_streams.hpp"
#include "io/spectral_exr_encode.hpp"
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

/// A FLOAT slice over a pixel-major buffer that holds `rows` rows starting at row y0: channel
/// `channel` of `n_channels` interleaved values per pixel. OpenEXR addresses a scan-line slice as
/// base + x * xStride + y * yStride with the absolute y, so the origin (0, y0) is passed on.
template <class T>
Imf::Slice interleaved_slice(const T* first_row, int channel, int n_channels, int x0, int width, int y0, int rows) {
  const size_t x_stride = static_cast<size_t>(n_channels) * sizeof(T);
  const size_t y_stride = static_cast<size_t>(width) * x_stride;
  return Imf::Slice::Make(std::is_same_v<T, float> ? Imf::FLOAT : Imf::HALF, first_row + channel,
                          IMATH_NAMESPACE::V2i(x0, y0), width, rows, x_stride, y_stride);
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
// Writer
// ---------------------------------------------------------------------------------------------

struct SpectralExrWriter::Impl {
  // Declaration order matters: the OutputFile is destroyed first (it still writes through the
  // stream), then the stream closes, then the AtomicOutputFile removes an uncommitted file.
  fs::path final_path;
  int width = 0, height = 0, rows_written = 0;   // of the data window
  int x0 = 0, y0 = 0;                            // the data window's first pixel
  std::vector<std::string> channel_names;        // spectral channels in the caller's order
  bool half = false;                             // S0 channels stored as half
  std::vector<IMATH_NAMESPACE::half> half_band;  // a band's S0 values converted, when half
  AtomicOutputFile file;
  std::unique_ptr<StdioOStream> stream;
  std::unique_ptr<Imf::OutputFile> exr;
  bool broken = false;  // an earlier write failed: the file is unusable

  Impl(const fs::path& path, int w, int h) : final_path(path), width(w), height(h), file(path) {}

  IoError error(const std::string& why) const { return IoError("spectral EXR '" + final_path.string() + "': " + why); }
};

namespace {

// The largest finite half float (Imath's HALF_MAX).
constexpr float kHalfMax = 65504.0f;

// The lossless compressions a spectral EXR may use (lossy ones would change the radiances).
Imf::Compression compression_of(const std::string& name) {
  if (name == "piz") return Imf::PIZ_COMPRESSION;
  if (name == "zip") return Imf::ZIP_COMPRESSION;
  if (name == "zips") return Imf::ZIPS_COMPRESSION;
  if (name == "rle") return Imf::RLE_COMPRESSION;
  if (name == "none") return Imf::NO_COMPRESSION;
  throw IoError("spectral EXR: unknown compression \"" + name + "\" (allowed: piz, zip, zips, rle, none)");
}

Imf::Header spectral_header(int width, int height, const std::vector<std::string>& channel_names,
                            const SpectralExrMetadata& meta) {
  Imf::Header header(width, height);
  if (meta.data_window) {
    const auto& [x0, x1, y0, y1] = *meta.data_window;
    if (!(0 <= x0 && x0 < x1 && x1 <= width && 0 <= y0 && y0 < y1 && y1 <= height))
      throw IoError("spectral EXR: data window x " + std::to_string(x0) + ".." + std::to_string(x1) + ", y " +
                    std::to_string(y0) + ".." + std::to_string(y1) + " is not inside the " + std::to_string(width) +
                    " x " + std::to_string(height) + " image");
    header.dataWindow() = IMATH_NAMESPACE::Box2i(IMATH_NAMESPACE::V2i(x0, y0), IMATH_NAMESPACE::V2i(x1 - 1, y1 - 1));
  }
  header.compression() = compression_of(meta.compression);
  header.lineOrder() = Imf::INCREASING_Y;
  const Imf::PixelType spectral_type = meta.half_spectral ? Imf::HALF : Imf::FLOAT;
  for (const std::string& name : channel_names) header.channels().insert(name, Imf::Channel(spectral_type));
  for (const char* name : kRgbNames) header.channels().insert(name, Imf::Channel(Imf::FLOAT));

  const Chromaticities c = rec709_chromaticities();
  const auto v2f = [](const double xy[2]) {
    return IMATH_NAMESPACE::V2f(static_cast<float>(xy[0]), static_cast<float>(xy[1]));
  };
  Imf::addChromaticities(header, Imf::Chromaticities(v2f(c.red), v2f(c.green), v2f(c.blue), v2f(c.white)));

  for (const auto& [key, value] : meta.strings) header.insert(key, Imf::StringAttribute(value));
  for (const auto& [key, value] : meta.doubles) header.insert(key, Imf::DoubleAttribute(value));
  for (const auto& [key, v] : meta.vectors)
    header.insert(key, Imf::V3dAttribute(IMATH_NAMESPACE::V3d(v[0], v[1], v[2])));
  // The layout's own attributes last, so that they win over a clashing extra string.
  header.insert("spectralLayoutVersion", Imf::StringAttribute("1.0"));
  header.insert("emissiveUnits", Imf::StringAttribute("W.m^-2.sr^-1"));
  if (meta.ev) header.insert("EV", Imf::FloatAttribute(*meta.ev));
  // Polarised files only (the layout): Stokes frames with e1 x e2 = the light's direction.
  if (meta.polarised) header.insert("polarisationHandedness", Imf::StringAttribute("right"));
  if (meta.latlong_envmap) Imf::addEnvmap(header, Imf::ENVMAP_LATLONG);
  return header;
}

// Compression runs on OpenEXR's thread pool, one line block (32 rows for PIZ, 16 for ZIP) per
// task. The file keeps two line buffers per thread, each a block of uncompressed rows plus its
// compressed copy: for very wide images (8192 x 84 channels: 88 MB a PIZ block) the thread
// count is lowered so that they stay within about 256 MiB.
int pool_threads(const Imf::Header& header, const SpectralExrMetadata& meta) {
  const Imf::Compression c = header.compression();
  const size_t block_rows = c == Imf::PIZ_COMPRESSION ? 32 : c == Imf::ZIP_COMPRESSION ? 16 : 1;
  const IMATH_NAMESPACE::Box2i& window = header.dataWindow();
  const size_t width = static_cast<size_t>(window.max.x - window.min.x + 1);
  size_t channels = 0;
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it) ++channels;
  const size_t block_bytes = block_rows * width * channels * sizeof(float);
  const size_t by_memory = (size_t{256} << 20) / std::max<size_t>(1, 4 * block_bytes);
  const size_t cores =
      meta.threads > 0 ? static_cast<size_t>(meta.threads) : std::max(1u, std::thread::hardware_concurrency());
  // OpenEXR's count is of pool threads besides the caller's: 0 compresses on the calling thread.
  // Uncompressed files have nothing to do in parallel: a task per scanline that only copies it
  // costs more in hand-offs between threads than the copy itself.
  const bool parallel = cores > 1 && c != Imf::NO_COMPRESSION;
  const int threads = parallel ? static_cast<int>(std::clamp<size_t>(by_memory, 1, cores)) : 0;
  // The file's tasks run on OpenEXR's global thread pool, which has no threads until someone
  // gives it some: without this every line block is compressed on the calling thread, one
  // after the other. Only ever raised, so that other files being written are not starved.
  static std::mutex pool_mutex;  // writers opened at the same time must not lower each other's count
  std::lock_guard<std::mutex> lock(pool_mutex);
  if (Imf::globalThreadCount() < threads) Imf::setGlobalThreadCount(threads);
  return threads;
}

// The frame buffer of a band of `rows` rows of `width` pixels starting at pixel (x0, y0): the
// spectral channels (in `names`' order) and R, G, B, interleaved per pixel.
template <class T>
Imf::FrameBuffer band_frame_buffer(const std::vector<std::string>& names, int x0, int width, int y0, int rows,
                                   const T* spectral, const float* rgb) {
  const int n = static_cast<int>(names.size());
  Imf::FrameBuffer frame;
  for (int c = 0; c < n; ++c)
    frame.insert(names[static_cast<size_t>(c)], interleaved_slice(spectral, c, n, x0, width, y0, rows));
  for (int c = 0; c < 3; ++c) frame.insert(kRgbNames[c], interleaved_slice(rgb, c, 3, x0, width, y0, rows));
  return frame;
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

uint64_t detail::encode_spectral_rows(int width, int rows, const std::vector<double>& wavelengths_nm,
                                      const SpectralExrMetadata& meta, const float* spectral, const float* rgb) {
  const std::vector<std::string> names = channel_names_of(wavelengths_nm, "spectral EXR sample: ", meta.polarised);
  const Imf::Header header = spectral_header(width, rows, names, meta);
  DiscardingOStream stream;
  {
    Imf::OutputFile exr(stream, header, pool_threads(header, meta));
    std::vector<IMATH_NAMESPACE::half> half_values;  // the conversion is part of the work measured
    if (meta.half_spectral) {
      half_values.assign(spectral, spectral + static_cast<size_t>(width) * rows * names.size());
      exr.setFrameBuffer(band_frame_buffer(names, 0, width, 0, rows, half_values.data(), rgb));
    } else {
      exr.setFrameBuffer(band_frame_buffer(names, 0, width, 0, rows, spectral, rgb));
    }
    exr.writePixels(rows);
  }  // the destructor writes the line offsets
  return stream.length();
}

SpectralExrWriter::SpectralExrWriter(const fs::path& final_path, int width, int height,
                                     const std::vector<double>& wavelengths_nm, const SpectralExrMetadata& meta) {
  const std::string where = "spectral EXR '" + final_path.string() + "': ";
  if (width <= 0 || height <= 0)
    throw IoError(where + "image size " + std::to_string(width) + " x " + std::to_string(height) + " must be positive");
  std::vector<std::string> names = channel_names_of(wavelengths_nm, where, meta.polarised);

  impl_ = std::make_unique<Impl>(final_path, width, height);
  if (meta.data_window) {  // a tile: rows of the window (spectral_header checks it lies inside)
    impl_->x0 = (*meta.data_window)[0];
    impl_->y0 = (*meta.data_window)[2];
    impl_->width = (*meta.data_window)[1] - impl_->x0;
    impl_->height = (*meta.data_window)[3] - impl_->y0;
  }
  impl_->channel_names = std::move(names);
  impl_->half = meta.half_spectral;
  try {
    const Imf::Header header = spectral_header(width, height, impl_->channel_names, meta);
    impl_->stream = std::make_unique<StdioOStream>(impl_->file.temporary_path());
    impl_->exr = std::make_unique<Imf::OutputFile>(*impl_->stream, header, pool_threads(header, meta));
  } catch (const IoError&) {
    throw;
  } catch (const std::exception& e) {
    throw impl_->error(e.what());
  }
}

SpectralExrWriter::~SpectralExrWriter() = default;

void SpectralExrWriter::write_rows(int rows, const float* spectral, const float* rgb) {
  Impl& w = *impl_;
  if (!w.exr) throw w.error(w.broken ? "an earlier write failed" : "write_rows after finish()");
  if (rows <= 0 || rows > w.height - w.rows_written)
    throw w.error("cannot write " + std::to_string(rows) + " rows: " + std::to_string(w.height - w.rows_written) +
                  " remain");
  if (!spectral || !rgb) throw w.error("write_rows needs both spectral and RGB values");

  // Validate the whole band before any of it reaches the file.
  const int n = static_cast<int>(w.channel_names.size());
  const size_t pixels = static_cast<size_t>(rows) * static_cast<size_t>(w.width);
  if (const long i = first_non_finite(spectral, pixels * static_cast<size_t>(n)); i >= 0) {
    const long pixel = i / n;
    throw w.error("non-finite spectral value at x = " + std::to_string(w.x0 + pixel % w.width) +
                  ", y = " + std::to_string(w.y0 + w.rows_written + pixel / w.width) + ", channel " +
                  w.channel_names[static_cast<size_t>(i % n)]);
  }
  if (w.half) {  // OpenEXR would store a value beyond half's range as infinity
    const float* end = spectral + pixels * static_cast<size_t>(n);
    const float* big = std::find_if(spectral, end, [](float v) { return std::abs(v) > kHalfMax; });
    if (big != end) {
      const long i = big - spectral, pixel = i / n;
      throw w.error("spectral value " + format_number(*big) + " at x = " + std::to_string(w.x0 + pixel % w.width) +
                    ", y = " + std::to_string(w.y0 + w.rows_written + pixel / w.width) + ", channel " +
                    w.channel_names[static_cast<size_t>(i % n)] + " is beyond a half float's 65504: write it with " +
                    "output.exr_spectral_type = \"float\"");
    }
  }
  if (const long i = first_non_finite(rgb, pixels * 3); i >= 0) {
    const long pixel = i / 3;
    throw w.error("non-finite RGB value at x = " + std::to_string(w.x0 + pixel % w.width) +
                  ", y = " + std::to_string(w.y0 + w.rows_written + pixel / w.width));
  }

  try {
    if (w.half) {
      w.half_band.resize(pixels * static_cast<size_t>(n));
      std::copy(spectral, spectral + pixels * static_cast<size_t>(n), w.half_band.begin());  // rounds to nearest
      w.exr->setFrameBuffer(
          band_frame_buffer(w.channel_names, w.x0, w.width, w.y0 + w.rows_written, rows, w.half_band.data(), rgb));
    } else {
      w.exr->setFrameBuffer(
          band_frame_buffer(w.channel_names, w.x0, w.width, w.y0 + w.rows_written, rows, spectral, rgb));
    }
    w.exr->writePixels(rows);
    w.stream->start_writeback();
  } catch (const std::exception& e) {
    w.broken = true;
    w.exr.reset();
    throw w.error(e.what());
  }
  w.rows_written += rows;
}

void SpectralExrWriter::finish() {
  Impl& w = *impl_;
  if (!w.exr) throw w.error(w.broken ? "an earlier write failed" : "finish() called twice");
  if (w.rows_written != w.height)
    throw w.error("only " + std::to_string(w.rows_written) + " of " + std::to_string(w.height) + " rows were written");
  try {
    w.exr.reset();      // writes the scan-line offset table
    w.stream->close();  // throws if any write or flush failed
  } catch (const std::exception& e) {
    w.broken = true;
    throw w.error(e.what());  // named like write_rows's errors: the file, then the cause
  }
  w.file.commit();
}

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
