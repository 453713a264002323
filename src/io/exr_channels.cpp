#include "io/exr_channels.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>

#include <cmath>
#include <exception>

#include "base/atomic_file.hpp"
#include "io/exr_open.hpp"
#include "skyspec/colour.hpp"
#include "skyspec/error.hpp"

namespace skyspec {

std::vector<std::string> exr_channel_names(const std::filesystem::path& path) {
  try {
    const auto file = open_exr_input(path);
    std::vector<std::string> names;
    for (auto it = file->header().channels().begin(); it != file->header().channels().end(); ++it)
      names.emplace_back(it.name());
    return names;
  } catch (const std::exception& e) {
    throw IoError("cannot read " + path.string() + " as OpenEXR: " + e.what());
  }
}

ExrChannels read_exr_channels(const std::filesystem::path& path, const std::vector<std::string>& names) {
  try {
    const auto input = open_exr_input(path);
    Imf::InputFile& file = *input;
    require_float_channels(file.header(), names, path.string() + ": ");
    const Imath::Box2i dw = file.header().dataWindow();
    ExrChannels out;
    out.width = dw.max.x - dw.min.x + 1;
    out.height = dw.max.y - dw.min.y + 1;
    Imf::FrameBuffer fb;
    for (const auto& name : names) {
      if (!file.header().channels().findChannel(name)) {
        std::string have;
        for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it)
          have += std::string(have.empty() ? "" : ", ") + it.name();
        throw IoError(path.string() + " has no channel \"" + name + "\" (it has: " + have + ")");
      }
      auto& v = out.channels[name];
      v.assign(static_cast<size_t>(out.width) * out.height, 0.0f);
      char* base = reinterpret_cast<char*>(v.data()) -
                   (static_cast<ptrdiff_t>(dw.min.x) + static_cast<ptrdiff_t>(dw.min.y) * out.width) *
                       static_cast<ptrdiff_t>(sizeof(float));
      fb.insert(name, Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * static_cast<size_t>(out.width)));
    }
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    return out;
  } catch (const IoError&) {
    throw;
  } catch (const std::exception& e) {
    throw IoError("cannot read " + path.string() + " as OpenEXR: " + e.what());
  }
}

void write_exr_channels(const std::filesystem::path& path, int width, int height,
                        const std::vector<std::pair<std::string, const std::vector<float>*>>& channels,
                        const std::map<std::string, std::string>& string_attributes) {
  for (const auto& [name, data] : channels) {
    if (data->size() != static_cast<size_t>(width) * height)
      throw IoError("internal error: channel " + name + " has the wrong size for " + path.string());
    for (float v : *data)
      if (!std::isfinite(v))
        throw IoError("refusing to write a non-finite value into " + name + " of " + path.string());
  }
  AtomicOutputFile file(path);
  try {
    Imf::Header header(width, height);
    header.compression() = Imf::ZIP_COMPRESSION;
    for (const auto& [name, data] : channels) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    for (const auto& [k, v] : string_attributes) header.insert(k, Imf::StringAttribute(v));
    const Chromaticities c = rec709_chromaticities();
    Imf::addChromaticities(header, Imf::Chromaticities(Imath::V2f(float(c.red[0]), float(c.red[1])),
                                                       Imath::V2f(float(c.green[0]), float(c.green[1])),
                                                       Imath::V2f(float(c.blue[0]), float(c.blue[1])),
                                                       Imath::V2f(float(c.white[0]), float(c.white[1]))));
    {
      Imf::OutputFile out(file.temporary_path().string().c_str(), header);
      Imf::FrameBuffer fb;
      for (const auto& [name, data] : channels)
        fb.insert(name, Imf::Slice(Imf::FLOAT, const_cast<char*>(reinterpret_cast<const char*>(data->data())),
                                   sizeof(float), sizeof(float) * static_cast<size_t>(width)));
      out.setFrameBuffer(fb);
      out.writePixels(height);
    }
    file.commit();
  } catch (const IoError&) {
    throw;
  } catch (const std::exception& e) {
    throw IoError("cannot write " + path.string() + ": " + e.what());
  }
}

}  // namespace skyspec
