#include "io/exr_input.hpp"

#include <ImfChannelList.h>
#include <ImfCompression.h>
#include <ImfFrameBuffer.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>

#include "io/exr_open.hpp"
#include "skyspec/error.hpp"

namespace skyspec {
namespace fs = std::filesystem;

namespace {

// Little-endian integers of the file (OpenEXR stores everything little-endian).
std::int64_t le(const unsigned char* p, int bytes) {
  std::uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | p[i];
  if (bytes == 4) return static_cast<std::int32_t>(static_cast<std::uint32_t>(v));
  return static_cast<std::int64_t>(v);
}

// What check_exr_declared_sizes needs of one part's header.
struct PartHeader {
  bool has_window = false;
  std::int64_t x_min = 0, y_min = 0, x_max = -1, y_max = -1;
  std::int64_t bytes_per_pixel = 0;  // sum over channels, per sampled pixel
  int compression = 0;
  bool tiled = false, deep = false;  // from the header's type and tiles attributes
};

// The scan lines one chunk of a scan-line part holds.
int lines_per_chunk(int compression) {
  switch (compression) {
    case Imf::ZIP_COMPRESSION:
    case Imf::PXR24_COMPRESSION:
      return 16;
    case Imf::PIZ_COMPRESSION:
    case Imf::B44_COMPRESSION:
    case Imf::B44A_COMPRESSION:
    case Imf::DWAA_COMPRESSION:
      return 32;
    case Imf::DWAB_COMPRESSION:
      return 256;
    default:
      return 1;  // none, RLE, ZIPS
  }
}

class HeaderWalker {
 public:
  HeaderWalker(const fs::path& path, std::string bytes) : path_(path), data_(std::move(bytes)) {}

  [[noreturn]] void fail(const std::string& why) const { throw IoError("EXR '" + path_.string() + "': " + why); }

  // A null-terminated name of at most max_length characters.
  std::string name(std::size_t max_length) {
    const std::size_t end = data_.find('\0', pos_);
    if (end == std::string::npos) fail("the header ends inside an attribute name");
    if (end - pos_ > max_length) fail("an attribute name longer than " + std::to_string(max_length) + " characters");
    std::string s = data_.substr(pos_, end - pos_);
    pos_ = end + 1;
    return s;
  }

  // One header (a part's): its attributes up to the empty name.
  PartHeader part(std::size_t max_name, std::uint64_t file_size) {
    PartHeader h;
    for (;;) {
      const std::string attribute = name(max_name);
      if (attribute.empty()) return h;
      const std::string type = name(max_name);
      if (pos_ + 4 > data_.size()) fail("the header ends inside attribute \"" + attribute + "\"");
      const std::int64_t size = le(bytes(pos_), 4);
      pos_ += 4;
      if (size >= 0 && static_cast<std::uint64_t>(size) <= file_size - std::min<std::uint64_t>(file_size, pos_) &&
          pos_ + static_cast<std::size_t>(size) > data_.size())
        fail("attribute \"" + attribute + "\" of " + std::to_string(size) +
             " bytes ends beyond the first MiB of the file, "
             "where skyspec expects the whole header");
      if (size < 0 || static_cast<std::uint64_t>(size) > file_size - std::min<std::uint64_t>(file_size, pos_))
        fail("attribute \"" + attribute + "\" declares " + std::to_string(size) +
             " bytes, more than the file holds after it (" +
             std::to_string(file_size - std::min<std::uint64_t>(file_size, pos_)) + " bytes)");
      const unsigned char* v = bytes(pos_);
      if (attribute == "dataWindow" && type == "box2i" && size == 16) {
        h.has_window = true;
        h.x_min = le(v, 4), h.y_min = le(v + 4, 4), h.x_max = le(v + 8, 4), h.y_max = le(v + 12, 4);
      } else if (attribute == "compression" && size == 1) {
        h.compression = v[0];
      } else if (attribute == "channels" && type == "chlist") {
        h.bytes_per_pixel = channel_bytes(v, static_cast<std::size_t>(size));
      } else if (attribute == "type" && type == "string") {
        const std::string t(reinterpret_cast<const char*>(v), static_cast<std::size_t>(size));
        h.tiled = t == "tiledimage";
        h.deep = t.rfind("deep", 0) == 0;
      } else if (attribute == "tiles") {
        h.tiled = true;
      }
      pos_ += static_cast<std::size_t>(size);
    }
  }

  // Bytes per pixel of a channel list (name, int32 type, uchar pLinear, 3 reserved, int32
  // xSampling, int32 ySampling; ends with an empty name), for full-resolution sampling.
  std::int64_t channel_bytes(const unsigned char* v, std::size_t size) const {
    std::int64_t total = 0;
    std::size_t p = 0;
    while (p < size && v[p] != 0) {
      while (p < size && v[p] != 0) ++p;  // the name
      if (p + 1 + 16 > size) fail("a channel list that ends inside a channel");
      const std::int64_t type = le(v + p + 1, 4);
      total += type == 1 ? 2 : 4;  // HALF 2 bytes, UINT and FLOAT 4
      p += 1 + 16;
    }
    return total;
  }

  std::size_t position() const { return pos_; }
  const unsigned char* bytes(std::size_t at) const { return reinterpret_cast<const unsigned char*>(data_.data()) + at; }

 private:
  fs::path path_;
  std::string data_;
  std::size_t pos_ = 8;  // after the magic number and the version field
};

}  // namespace

double exr_max_compression_ratio(int compression) {
  switch (compression) {
    case Imf::NO_COMPRESSION:
      return 1.0;
    case Imf::RLE_COMPRESSION:
      return 64.0;
    case Imf::ZIPS_COMPRESSION:
    case Imf::ZIP_COMPRESSION:
      return 1100.0;
    default:
      return 4096.0;  // PIZ, PXR24, B44(A), DWAA/B: generous
  }
}

void check_exr_declared_sizes(const fs::path& path) {
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (ec || !fs::exists(status)) throw IoError("cannot read " + path.string() + " as OpenEXR: it does not exist");
  if (!fs::is_regular_file(status))
    throw IoError("cannot read " + path.string() +
                  " as OpenEXR: " + (fs::is_directory(status) ? "it is a folder" : "it is not a regular file"));
  const std::uint64_t file_size = fs::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  if (ec || !in) throw IoError("cannot read " + path.string() + " as OpenEXR: cannot open it");
  // The header is at most the first megabyte in any file skyspec reads (its own headers are a few
  // kilobytes); an attribute declared larger than what is read is checked against the file size.
  std::string head(static_cast<std::size_t>(std::min<std::uint64_t>(file_size, 1u << 20)), '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  const auto* b = reinterpret_cast<const unsigned char*>(head.data());
  if (head.size() < 8 || le(b, 4) != 20000630)
    throw IoError("cannot read " + path.string() + " as OpenEXR: it does not start with the OpenEXR magic number");
  const std::int64_t flags = le(b + 4, 4);
  const bool single_tiled = flags & 0x200, long_names = flags & 0x400, multipart = flags & 0x1000;
  // Only what skyspec writes and what its readers need: one part of scan lines. Tiled, deep and
  // multi-part files have offset tables this check does not walk, and OpenEXR rebuilds damaged
  // ones from the chunks' own declared sizes.
  if (single_tiled || multipart || (flags & 0x800))
    throw IoError("cannot read " + path.string() + ": it is a " +
                  (multipart         ? "multi-part"
                   : (flags & 0x800) ? "deep"
                                     : "tiled") +
                  " OpenEXR file; skyspec reads single-part scan-line images (convert with "
                  "`oiiotool IN.exr --scanline -o OUT.exr`)");
  HeaderWalker walker(path, head);
  const PartHeader p = walker.part(long_names ? 255 : 31, file_size);
  if (p.tiled || p.deep) walker.fail("a tiled or deep image; skyspec reads scan-line images");
  const std::uint64_t header_end = walker.position();
  if (!p.has_window) walker.fail("no dataWindow attribute");
  if (p.x_max < p.x_min || p.y_max < p.y_min) walker.fail("an empty or inverted dataWindow");
  const long double width = static_cast<long double>(p.x_max - p.x_min + 1);
  const long double height = static_cast<long double>(p.y_max - p.y_min + 1);
  const long double decoded = width * height * static_cast<long double>(p.bytes_per_pixel);
  const long double bound = static_cast<long double>(file_size) * exr_max_compression_ratio(p.compression) + 65536.0L;
  if (decoded > bound)
    walker.fail("it declares " + std::to_string(static_cast<long long>(width)) + " x " +
                std::to_string(static_cast<long long>(height)) + " pixels (" +
                std::to_string(static_cast<long long>(decoded / 1e6L)) + " MB decoded) but holds only " +
                std::to_string(file_size) + " bytes, which that compression cannot expand to more than " +
                std::to_string(static_cast<long long>(bound / 1e6L)) + " MB");
  // Every chunk's offset, and the data size the chunk declares, must lie inside the file.
  const std::uint64_t chunks =
      static_cast<std::uint64_t>((height + lines_per_chunk(p.compression) - 1) / lines_per_chunk(p.compression));
  if (header_end + 8 * chunks > file_size)
    walker.fail("its offset table of " + std::to_string(chunks) + " chunks is longer than the file");
  std::string table(static_cast<std::size_t>(8 * chunks), '\0');
  in.clear();
  in.seekg(static_cast<std::streamoff>(header_end));
  in.read(table.data(), static_cast<std::streamsize>(table.size()));
  if (!in) walker.fail("cannot read its offset table");
  const auto* t = reinterpret_cast<const unsigned char*>(table.data());
  for (std::uint64_t c = 0; c < chunks; ++c) {
    const std::int64_t offset = le(t + 8 * c, 8);
    // 0 marks a chunk never written: the writer did not finish. OpenEXR would rebuild the table
    // by walking the chunks, believing each one's declared size; such a file is refused.
    if (offset == 0)
      walker.fail("its offset table is incomplete (chunk " + std::to_string(c) +
                  " was never written: the file was not finished)");
    if (offset < static_cast<std::int64_t>(header_end + 8 * chunks) ||
        static_cast<std::uint64_t>(offset) + 8 > file_size)
      walker.fail("chunk " + std::to_string(c) + " of its offset table points outside the file");
    // The chunk starts with its first line's y and the size of its data (int32 each); OpenEXR
    // allocates that size before reading, so it must fit in the file.
    unsigned char chunk_header[8];
    in.seekg(offset);
    in.read(reinterpret_cast<char*>(chunk_header), 8);
    const std::int64_t packed = le(chunk_header + 4, 4);
    if (!in || packed < 0 || static_cast<std::uint64_t>(offset) + 8 + static_cast<std::uint64_t>(packed) > file_size)
      walker.fail("chunk " + std::to_string(c) + " declares " + std::to_string(packed) +
                  " bytes of data, more than the file holds after it");
  }
}

std::unique_ptr<Imf::InputFile> open_exr_input(const fs::path& path) {
  check_exr_declared_sizes(path);
  return std::make_unique<Imf::InputFile>(path.c_str());
}

void verify_exr_pixels(const fs::path& path) {
  try {
    const auto file = open_exr_input(path);
    const Imath::Box2i window = file->header().dataWindow();
    const std::size_t width = static_cast<std::size_t>(window.max.x - window.min.x + 1);
    std::size_t channels = 0;
    for (auto it = file->header().channels().begin(); it != file->header().channels().end(); ++it) ++channels;
    constexpr int kRows = 16;
    std::vector<float> band(static_cast<std::size_t>(kRows) * width * std::max<std::size_t>(channels, 1));
    for (int y0 = window.min.y; y0 <= window.max.y; y0 += kRows) {
      const int y1 = std::min(window.max.y, y0 + kRows - 1);
      // Row y of channel c lands at band[((y - y0) * channels + c) * width]: the slice's base is
      // moved so that (window.min.x, y0) is the start of the buffer.
      Imf::FrameBuffer frame;
      std::size_t c = 0;
      for (auto it = file->header().channels().begin(); it != file->header().channels().end(); ++it, ++c) {
        char* origin = reinterpret_cast<char*>(band.data() + c * width);
        const std::ptrdiff_t x_stride = sizeof(float),
                             y_stride = static_cast<std::ptrdiff_t>(channels * width * sizeof(float));
        char* base =
            origin - static_cast<std::ptrdiff_t>(window.min.x) * x_stride - static_cast<std::ptrdiff_t>(y0) * y_stride;
        frame.insert(it.name(), Imf::Slice(Imf::FLOAT, base, x_stride, static_cast<std::size_t>(y_stride)));
      }
      file->setFrameBuffer(frame);
      file->readPixels(y0, y1);
    }
  } catch (const IoError&) {
    throw;
  } catch (const std::exception& e) {
    throw IoError("EXR '" + path.string() + "' is damaged or incomplete: " + e.what());
  }
}

void require_float_channels(const Imf::Header& header, const std::vector<std::string>& names,
                            const std::string& where) {
  for (const auto& name : names)
    if (const Imf::Channel* c = header.channels().findChannel(name); c && c->type == Imf::UINT)
      throw IoError(where + "channel " + name +
                    " holds UINT samples (integers: an id or a mask); skyspec reads HALF or FLOAT");
}

}  // namespace skyspec
