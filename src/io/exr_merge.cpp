#include "io/exr_merge.hpp"

#include <ImfChannelList.h>
#include <ImfChromaticitiesAttribute.h>
#include <ImfDoubleAttribute.h>
#include <ImfEnvmapAttribute.h>
#include <ImfFloatAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStringAttribute.h>
#include <ImfVecAttribute.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

#include "base/atomic_file.hpp"
#include "io/exr_open.hpp"
#include "io/exr_streams.hpp"
#include "io/spectral_exr.hpp"
#include "skyspec/colour.hpp"
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

// What the spectral EXR writer needs to write the tiles' image: their wavelengths and the header
// attributes of SpectralExrMetadata, read back from the first tile. A header the writer would not
// have written (another attribute type, other standard values, other channels) is refused by
// name: the merged file is written by the same writer as a whole render's, so that for tiles of
// one render it is that render's file byte for byte.
SpectralExrMetadata metadata_of(const Imf::Header& h, const fs::path& path, std::vector<double>& wavelengths_nm) {
  const auto refuse = [&](const std::string& what) {
    throw InputError("TILES", "\"" + path.string() + "\"", "tiles of a skyspec spectral EXR: " + what);
  };
  SpectralExrMetadata meta;
  switch (h.compression()) {
    case Imf::PIZ_COMPRESSION:
      meta.compression = "piz";
      break;
    case Imf::ZIP_COMPRESSION:
      meta.compression = "zip";
      break;
    case Imf::ZIPS_COMPRESSION:
      meta.compression = "zips";
      break;
    case Imf::RLE_COMPRESSION:
      meta.compression = "rle";
      break;
    case Imf::NO_COMPRESSION:
      meta.compression = "none";
      break;
    default:
      refuse("its compression is not one skyspec writes (piz, zip, zips, rle, none)");
  }
  if (h.lineOrder() != Imf::INCREASING_Y || h.pixelAspectRatio() != 1.0f ||
      h.screenWindowCenter() != IMATH_NAMESPACE::V2f(0.0f, 0.0f) || h.screenWindowWidth() != 1.0f ||
      h.displayWindow().min != IMATH_NAMESPACE::V2i(0, 0))
    refuse("its line order, pixel aspect ratio, screen window or display window origin is not skyspec's");
  // Channels: S0 at each wavelength, S1-S3 at each or none, R, G, B.
  std::map<int, std::map<double, std::string>> stokes;
  int rgb = 0;
  Imf::PixelType spectral_type = Imf::FLOAT;
  bool first_spectral = true;
  for (auto c = h.channels().begin(); c != h.channels().end(); ++c) {
    const std::string name = c.name();
    if (name == "R" || name == "G" || name == "B") {
      ++rgb;
      if (c.channel().type != Imf::FLOAT) refuse("its channel " + name + " is not 32-bit float");
      continue;
    }
    const auto s = parse_stokes_channel_name(name);
    if (!s || spectral_channel_name(s->second, s->first) != name)
      refuse("it has a channel " + name + " (skyspec writes S0-S3.<wavelength>nm, R, G, B)");
    if (!first_spectral && c.channel().type != spectral_type) refuse("its spectral channels mix half and float");
    spectral_type = c.channel().type;
    first_spectral = false;
    stokes[s->first][s->second] = name;
  }
  if (rgb != 3 || stokes[0].empty()) refuse("it has no S0 channels or not all of R, G, B");
  for (const auto& [lambda, name] : stokes[0]) wavelengths_nm.push_back(lambda);
  meta.polarised = stokes.size() > 1;
  for (int component = 1; component <= 3 && meta.polarised; ++component)
    if (stokes[component].size() != wavelengths_nm.size() ||
        !std::equal(stokes[component].begin(), stokes[component].end(), stokes[0].begin(),
                    [](const auto& a, const auto& b) { return a.first == b.first; }))
      refuse("its S" + std::to_string(component) + " channels are not at the S0 channels' wavelengths");
  meta.half_spectral = spectral_type == Imf::HALF;

  const Chromaticities rec709 = rec709_chromaticities();
  const auto near = [](const IMATH_NAMESPACE::V2f& v, const double xy[2]) {
    return v.x == static_cast<float>(xy[0]) && v.y == static_cast<float>(xy[1]);
  };
  for (auto it = h.begin(); it != h.end(); ++it) {
    const std::string name = it.name();
    const Imf::Attribute& a = it.attribute();
    if (name == "channels" || name == "compression" || name == "dataWindow" || name == "displayWindow" ||
        name == "lineOrder" || name == "pixelAspectRatio" || name == "screenWindowCenter" ||
        name == "screenWindowWidth" || name == "type")  // set by the writer (type: "scanlineimage")
      continue;
    const auto* text = dynamic_cast<const Imf::StringAttribute*>(&a);
    if (name == "chromaticities") {
      const auto* c = dynamic_cast<const Imf::ChromaticitiesAttribute*>(&a);
      if (!c || !near(c->value().red, rec709.red) || !near(c->value().green, rec709.green) ||
          !near(c->value().blue, rec709.blue) || !near(c->value().white, rec709.white))
        refuse("its chromaticities are not Rec.709's, which skyspec writes");
    } else if (name == "spectralLayoutVersion" || name == "emissiveUnits" || name == "polarisationHandedness") {
      const std::string expected = name == "spectralLayoutVersion" ? "1.0"
                                   : name == "emissiveUnits"       ? "W.m^-2.sr^-1"
                                                                   : "right";
      if (!text || text->value() != expected) refuse("its " + name + " is not \"" + expected + "\"");
    } else if (name == "EV") {
      const auto* ev = dynamic_cast<const Imf::FloatAttribute*>(&a);
      if (!ev) refuse("its EV is not a float");
      meta.ev = ev->value();
    } else if (name == "envmap") {
      const auto* envmap = dynamic_cast<const Imf::EnvmapAttribute*>(&a);
      if (!envmap || envmap->value() != Imf::ENVMAP_LATLONG) refuse("its envmap is not latlong");
      meta.latlong_envmap = true;
    } else if (text) {
      meta.strings[name] = text->value();
    } else if (const auto* d = dynamic_cast<const Imf::DoubleAttribute*>(&a)) {
      meta.doubles[name] = d->value();
    } else if (const auto* v = dynamic_cast<const Imf::V3dAttribute*>(&a)) {
      meta.vectors[name] = {v->value().x, v->value().y, v->value().z};
    } else {
      refuse("its attribute " + name + " is of type " + a.typeName() + ", which skyspec does not write");
    }
  }
  if (meta.polarised != (h.findTypedAttribute<Imf::StringAttribute>("polarisationHandedness") != nullptr))
    refuse("it has S1-S3 channels without polarisationHandedness, or the attribute without them");
  return meta;
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

  // 2. The output, written by the spectral EXR writer with the tiles' header (the whole image as
  // data window), a band at a time. Each band is read from the tiles it crosses straight into the
  // writer's layout: per pixel the spectral values (S0 at every wavelength, then S1-S3), and R, G, B.
  std::vector<double> wavelengths_nm;
  const SpectralExrMetadata meta = metadata_of(*header, paths.front(), wavelengths_nm);
  const int width = display.max.x - display.min.x + 1, height = display.max.y - display.min.y + 1;
  const int n = static_cast<int>(wavelengths_nm.size());
  const int values = meta.polarised ? 4 * n : n;
  SpectralExrWriter writer(output, width, height, wavelengths_nm, meta);
  const int block = writer.rows_per_block();
  const int band = block * ((16 + block - 1) / block);  // at least 16 rows, whole line blocks
  std::vector<float> spectral(static_cast<std::size_t>(band) * width * values);
  std::vector<float> rgb(static_cast<std::size_t>(band) * width * 3);
  const auto frame_for = [&](int y0) {
    Imf::FrameBuffer frame;
    const std::size_t pixel = static_cast<std::size_t>(values) * sizeof(float);
    for (int component = 0; component < (meta.polarised ? 4 : 1); ++component)
      for (int k = 0; k < n; ++k)
        frame.insert(spectral_channel_name(wavelengths_nm[static_cast<std::size_t>(k)], component),
                     Imf::Slice::Make(Imf::FLOAT, spectral.data() + component * n + k,
                                      IMATH_NAMESPACE::V2i(display.min.x, y0), width, band, pixel, pixel * width));
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c)
      frame.insert(names[c], Imf::Slice::Make(Imf::FLOAT, rgb.data() + c, IMATH_NAMESPACE::V2i(display.min.x, y0),
                                              width, band, 3 * sizeof(float), 3 * sizeof(float) * width));
    return frame;
  };
  try {
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
      const std::size_t pixels = static_cast<std::size_t>(y1 - y0 + 1) * width;
      const bool finite = std::all_of(spectral.begin(), spectral.begin() + static_cast<long>(pixels * values),
                                      [](float v) { return std::isfinite(v); }) &&
                          std::all_of(rgb.begin(), rgb.begin() + static_cast<long>(pixels * 3),
                                      [](float v) { return std::isfinite(v); });
      if (!finite)
        throw IoError("merge: a value is not finite in rows " + std::to_string(y0) + ".." + std::to_string(y1) +
                      " of the tiles: nothing written");
      writer.write_rows(y1 - y0 + 1, spectral.data(), rgb.data());
      if (progress) progress(y1 - display.min.y + 1, height);
    }
    writer.finish();
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw IoError(std::string("merge into '") + output.string() + "': " + e.what());
  }
  return {static_cast<int>(tiles.size()), width, height, values + 3, band};
}

}  // namespace skyspec
