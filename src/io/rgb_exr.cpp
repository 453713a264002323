// Scene-linear RGB OpenEXR with the chromaticities attribute (OpenEXR 3.1 C++ API).
#include "io/rgb_exr.hpp"

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
#include <ImfVecAttribute.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>

#include "base/atomic_file.hpp"
#include "io/exr_open.hpp"
#include "io/exr_streams.hpp"
#include "skyspec/error.hpp"

namespace skyspec {
namespace {

IMATH_NAMESPACE::V2f v2f(const double xy[2]) {
  return IMATH_NAMESPACE::V2f(static_cast<float>(xy[0]), static_cast<float>(xy[1]));
}

}  // namespace

namespace {

// Float channels `names`, interleaved per pixel in `values` ([y][x][channel]), ZIP-compressed,
// with the chromaticities attribute when given; atomic.
void write_channels(const std::filesystem::path& path, const std::string& where, int width, int height,
                    const std::vector<std::string>& names, const std::vector<float>& values, const Chromaticities* c,
                    const std::map<std::string, std::string>& strings, const std::map<std::string, float>& floats,
                    const std::map<std::string, double>& doubles, bool latlong_envmap) {
  if (width <= 0 || height <= 0)
    throw IoError(where + "image size " + std::to_string(width) + " x " + std::to_string(height) + " must be positive");
  const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height), k = names.size();
  if (values.size() != pixels * k) throw IoError(where + "wrong number of values for the image size");
  for (size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      throw IoError(where + "non-finite value at x = " + std::to_string(i / k % static_cast<size_t>(width)) +
                    ", y = " + std::to_string(i / k / static_cast<size_t>(width)) + ", channel " + names[i % k]);

  MemoryOStream memory;
  try {
    Imf::Header header(width, height);
    header.compression() = Imf::ZIP_COMPRESSION;
    for (const std::string& name : names) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    if (c) Imf::addChromaticities(header, Imf::Chromaticities(v2f(c->red), v2f(c->green), v2f(c->blue), v2f(c->white)));
    for (const auto& [key, value] : strings) header.insert(key, Imf::StringAttribute(value));
    for (const auto& [key, value] : floats) header.insert(key, Imf::FloatAttribute(value));
    for (const auto& [key, value] : doubles) header.insert(key, Imf::DoubleAttribute(value));
    if (latlong_envmap) Imf::addEnvmap(header, Imf::ENVMAP_LATLONG);
    Imf::FrameBuffer frame;
    const size_t x_stride = k * sizeof(float), y_stride = static_cast<size_t>(width) * x_stride;
    for (size_t ch = 0; ch < k; ++ch)
      frame.insert(names[ch],
                   Imf::Slice(Imf::FLOAT, const_cast<char*>(reinterpret_cast<const char*>(values.data() + ch)),
                              x_stride, y_stride));
    Imf::OutputFile out(memory, header);
    out.setFrameBuffer(frame);
    out.writePixels(height);
  } catch (const std::exception& e) {
    throw IoError(where + e.what());
  }

  AtomicOutputFile file(path);
  FILE* out = std::fopen(file.temporary_path().c_str(), "wb");
  if (!out) throw IoError(where + "cannot open '" + file.temporary_path().string() + "': " + std::strerror(errno));
  const auto& bytes = memory.bytes();
  const bool written = std::fwrite(bytes.data(), 1, bytes.size(), out) == bytes.size();
  const bool closed = std::fclose(out) == 0;
  if (!written || !closed) throw IoError(where + "cannot write '" + file.temporary_path().string() + "'");
  file.commit();
}

}  // namespace

void write_rgb_exr(const std::filesystem::path& path, int width, int height, const std::vector<float>& rgb,
                   const Chromaticities& c, const std::map<std::string, std::string>& strings,
                   const std::map<std::string, float>& floats, const std::map<std::string, double>& doubles,
                   bool latlong_envmap) {
  write_channels(path, "RGB EXR '" + path.string() + "': ", width, height, {"R", "G", "B"}, rgb, &c, strings, floats,
                 doubles, latlong_envmap);
}

void write_float_channels_exr(const std::filesystem::path& path, int width, int height,
                              const std::vector<std::string>& names, const std::vector<float>& values,
                              const std::map<std::string, std::string>& strings, bool latlong_envmap) {
  write_channels(path, "EXR '" + path.string() + "': ", width, height, names, values, nullptr, strings, {}, {},
                 latlong_envmap);
}

RgbExrImage read_rgb_exr(const std::filesystem::path& path) {
  const std::string where = "EXR '" + path.string() + "': ";
  try {
    const auto input = open_exr_input(path);
    Imf::InputFile& in = *input;
    const Imf::Header& header = in.header();
    require_float_channels(header, {"R", "G", "B"}, where);
    const IMATH_NAMESPACE::Box2i window = header.dataWindow();
    RgbExrImage image;
    image.width = window.max.x - window.min.x + 1;
    image.height = window.max.y - window.min.y + 1;
    const char* names[3] = {"R", "G", "B"};
    for (const char* name : names)
      if (!header.channels().findChannel(name)) throw IoError(where + "no channel " + name);
    image.rgb.assign(static_cast<size_t>(image.width) * static_cast<size_t>(image.height) * 3, 0.0f);
    Imf::FrameBuffer frame;
    for (int ch = 0; ch < 3; ++ch)
      frame.insert(names[ch], Imf::Slice::Make(Imf::FLOAT, image.rgb.data() + ch, window, 3 * sizeof(float),
                                               static_cast<size_t>(image.width) * 3 * sizeof(float)));
    in.setFrameBuffer(frame);
    in.readPixels(window.min.y, window.max.y);
    image.has_chromaticities = Imf::hasChromaticities(header);
    image.latlong_envmap = Imf::hasEnvmap(header) && Imf::envmap(header) == Imf::ENVMAP_LATLONG;
    const Imf::Chromaticities chroma = image.has_chromaticities ? Imf::chromaticities(header) : Imf::Chromaticities();
    const auto put = [](double out[2], const IMATH_NAMESPACE::V2f& v) {
      out[0] = v.x;
      out[1] = v.y;
    };
    put(image.chromaticities.red, chroma.red);
    put(image.chromaticities.green, chroma.green);
    put(image.chromaticities.blue, chroma.blue);
    put(image.chromaticities.white, chroma.white);
    for (auto it = header.begin(); it != header.end(); ++it) {
      if (const auto* text = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
        image.strings[it.name()] = text->value();
      if (const auto* number = dynamic_cast<const Imf::FloatAttribute*>(&it.attribute()))
        image.floats[it.name()] = number->value();
      if (const auto* number = dynamic_cast<const Imf::DoubleAttribute*>(&it.attribute()))
        image.doubles[it.name()] = number->value();
      if (const auto* v = dynamic_cast<const Imf::V3dAttribute*>(&it.attribute()))
        image.vectors[it.name()] = {v->value().x, v->value().y, v->value().z};
      if (const auto* v = dynamic_cast<const Imf::V3fAttribute*>(&it.attribute()))
        image.vectors[it.name()] = {v->value().x, v->value().y, v->value().z};
    }
    return image;
  } catch (const IoError&) {
    throw;
  } catch (const std::exception& e) {
    throw IoError(where + e.what());
  }
}

}  // namespace skyspec
