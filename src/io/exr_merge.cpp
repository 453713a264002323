#include "io/exr_merge.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfThreading.h>
#include <half.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <thread>

#include "base/atomic_file.hpp"
#include "io/exr_open.hpp"
#include "io/exr_streams.hpp"
#include "skyspec/error.hpp"

namespace skyspec {
namespace {

namespace fs = std::filesystem;
using Box = IMATH_NAMESPACE::Box2i;

std::string box_text(const Box& b) {
  return "x " + std::to_string(b.min.x) + ".." + std::to_string(b.max.x) + ", y " + std::to_string(b.min.y) + ".." +
         std::to_string(b.max.y);
}

long long area(const Box& b) {
  return static_cast<long long>(b.max.x - b.min.x + 1) * static_cast<long long>(b.max.y - b.min.y + 1);
}

// An attribute's value as bytes, to compare two headers attribute by attribute.
std::vector<char> value_bytes(const Imf::Attribute& a) {
  MemoryOStream s;
  a.writeValueTo(s, 2);
  return s.bytes();
}

struct Tile {
  fs::path path;
  Box window;  // its data window
};

// Throws unless `h` is a tile of the same image as `first`: every attribute but the data window
// the same, with the same value.
void require_same_image(const Imf::Header& first, const Imf::Header& h, const fs::path& path,
                        const fs::path& first_path) {
  const auto refuse = [&](const std::string& why) {
    throw InputError("TILES", "\"" + path.string() + "\"",
                     "tiles of one image (as the first, " + first_path.string() + "): " + why);
  };
  for (auto it = first.begin(); it != first.end(); ++it) {
    const std::string name = it.name();
    if (name == "dataWindow") continue;
    if (h.find(name) == h.end()) refuse("it has no attribute " + name);
    const Imf::Attribute& mine = h[name];
    if (std::string(mine.typeName()) != it.attribute().typeName() || value_bytes(mine) != value_bytes(it.attribute()))
      refuse("its " + name + " differs");
  }
  for (auto it = h.begin(); it != h.end(); ++it)
    if (first.find(it.name()) == first.end())
      refuse(std::string("it has an attribute the first has not: ") + it.name());
}

int block_rows(Imf::Compression c) {
  switch (c) {
    case Imf::PIZ_COMPRESSION:
    case Imf::PXR24_COMPRESSION:
    case Imf::B44_COMPRESSION:
    case Imf::B44A_COMPRESSION:
      return 32;
    case Imf::ZIP_COMPRESSION:
      return 16;
    case Imf::DWAA_COMPRESSION:
      return 32;
    case Imf::DWAB_COMPRESSION:
      return 256;
    default:
      return 1;
  }
}

}  // namespace

MergeSummary merge_spectral_exr_tiles(const std::vector<fs::path>& paths, const fs::path& output,
                                      const std::function<void(int, int)>& progress) {
  if (paths.empty()) throw InputError("TILES", "(none)", "one or more tile EXRs");
  // 1. Headers: the same image, windows that cover it exactly once.
  std::unique_ptr<Imf::Header> header;
  std::vector<Tile> tiles;
  try {
    for (const auto& p : paths) {
      const auto file = open_exr_input(p);
      const Imf::Header& h = file->header();
      std::vector<std::string> names;
      for (auto c = h.channels().begin(); c != h.channels().end(); ++c) names.emplace_back(c.name());
      require_float_channels(h, names, "tile '" + p.string() + "': ");
      if (!header)
        header = std::make_unique<Imf::Header>(h);
      else
        require_same_image(*header, h, p, paths.front());
      tiles.push_back({p, h.dataWindow()});
    }
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {  // OpenEXR's: not a readable EXR
    throw IoError(std::string("merge: ") + e.what());
  }
  const Box display = header->displayWindow();
  // A band holds the image's width: a header declaring more than any skyspec image is refused
  // before anything is allocated for it.
  if (display.max.x - display.min.x + 1 > 65536 || display.max.y - display.min.y + 1 > 65536 ||
      display.max.x < display.min.x || display.max.y < display.min.y)
    throw InputError(
        "TILES", "\"" + paths.front().string() + "\"",
        "tiles of an image of at most 65536 x 65536 pixels (its display window is " + box_text(display) + ")");
  long long covered = 0;
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    const Box& a = tiles[i].window;
    if (a.min.x < display.min.x || a.min.y < display.min.y || a.max.x > display.max.x || a.max.y > display.max.y)
      throw InputError(
          "TILES", "\"" + tiles[i].path.string() + "\"",
          "a tile inside the display window (" + box_text(display) + "); its data window is " + box_text(a));
    for (std::size_t j = 0; j < i; ++j) {
      const Box& b = tiles[j].window;
      if (a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y)
        throw InputError(
            "TILES", "\"" + tiles[i].path.string() + "\"",
            "tiles that do not overlap: it and " + tiles[j].path.string() + " both hold pixels of " +
                box_text(Box(IMATH_NAMESPACE::V2i(std::max(a.min.x, b.min.x), std::max(a.min.y, b.min.y)),
                             IMATH_NAMESPACE::V2i(std::min(a.max.x, b.max.x), std::min(a.max.y, b.max.y)))));
    }
    covered += area(a);
  }
  if (covered != area(display))
    throw InputError("TILES", std::to_string(tiles.size()) + " tile(s)",
                     "tiles that cover the whole image (" + box_text(display) +
                         "): " + std::to_string(area(display) - covered) + " pixel(s) are in no tile");

  // 2. The output: the tiles' header with the whole image as data window, a band at a time.
  header->dataWindow() = display;
  const int width = display.max.x - display.min.x + 1, height = display.max.y - display.min.y + 1;
  const int band = std::max(16, block_rows(header->compression()));
  struct Channel {
    std::string name;
    Imf::PixelType type;
    std::vector<char> values;  // band x width samples
  };
  std::vector<Channel> channels;
  for (auto c = header->channels().begin(); c != header->channels().end(); ++c) {
    const std::size_t size = c.channel().type == Imf::HALF ? 2 : 4;
    channels.push_back({c.name(), c.channel().type, std::vector<char>(size * width * band)});
  }
  const auto frame_for = [&](int y0) {
    Imf::FrameBuffer frame;
    for (auto& c : channels) {
      const std::size_t size = c.type == Imf::HALF ? 2 : 4;
      frame.insert(c.name, Imf::Slice::Make(c.type, c.values.data(), IMATH_NAMESPACE::V2i(display.min.x, y0), width,
                                            band, size, size * width));
    }
    return frame;
  };
  const int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (Imf::globalThreadCount() < threads) Imf::setGlobalThreadCount(threads);

  AtomicOutputFile file(output);
  {
    StdioOStream stream(file.temporary_path());
    try {
      Imf::OutputFile out(stream, *header, threads);
      std::map<std::size_t, std::unique_ptr<Imf::InputFile>> open;  // the tiles the band crosses
      for (int y0 = display.min.y; y0 <= display.max.y; y0 += band) {
        const int y1 = std::min(display.max.y, y0 + band - 1);
        const Imf::FrameBuffer frame = frame_for(y0);
        for (std::size_t k = 0; k < tiles.size(); ++k) {
          const Box& w = tiles[k].window;
          if (w.max.y < y0 || w.min.y > y1) {
            if (w.max.y < y0) open.erase(k);  // done with it
            continue;
          }
          auto& in = open[k];
          if (!in) in = open_exr_input(tiles[k].path);
          in->setFrameBuffer(frame);
          in->readPixels(std::max(y0, w.min.y), std::min(y1, w.max.y));
        }
        const std::size_t samples = static_cast<std::size_t>(y1 - y0 + 1) * width;
        for (const auto& c : channels) {
          bool finite = true;
          if (c.type == Imf::HALF) {
            const auto* v = reinterpret_cast<const IMATH_NAMESPACE::half*>(c.values.data());
            for (std::size_t i = 0; i < samples; ++i) finite &= v[i].isFinite();
          } else if (c.type == Imf::FLOAT) {
            const auto* v = reinterpret_cast<const float*>(c.values.data());
            for (std::size_t i = 0; i < samples; ++i) finite &= std::isfinite(v[i]);
          }
          if (!finite)
            throw IoError("merge: channel " + c.name + " has a value that is not finite in rows " + std::to_string(y0) +
                          ".." + std::to_string(y1) + " of the tiles: nothing written");
        }
        out.setFrameBuffer(frame);
        out.writePixels(y1 - y0 + 1);
        stream.start_writeback();
        if (progress) progress(y1 - display.min.y + 1, height);
      }
    } catch (const Error&) {
      throw;
    } catch (const std::exception& e) {
      throw IoError(std::string("merge into '") + output.string() + "': " + e.what());
    }
    stream.close();
  }
  file.commit();
  return {static_cast<int>(tiles.size()), width, height, static_cast<int>(channels.size()), band};
}

}  // namespace skyspec
