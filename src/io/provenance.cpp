#include "io/provenance.hpp"

#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStringAttribute.h>

#include <exception>

#include "base/embedded_data.hpp"
#include "io/exr_open.hpp"
#include "skyspec/error.hpp"

namespace skyspec {

std::string data_tables_text(const std::vector<std::string>& paths) {
  std::string text;
  for (const auto& path : paths) text += (text.empty() ? "" : "\n") + embedded_table_info(path).describe();
  return text.empty() ? std::string("(no embedded data tables)") : text;
}

FileProvenance read_exr_provenance(const std::filesystem::path& path) {
  try {
    const auto file = open_exr_input(path);
    const Imf::Header& header = file->header();
    auto text = [&](const char* name) {
      const auto* a = header.findTypedAttribute<Imf::StringAttribute>(name);
      return a ? a->value() : std::string();
    };
    return {text(kVersionAttribute), text(kSceneAttribute), text(kDataAttribute)};
  } catch (const std::exception& e) {
    throw IoError("cannot read " + path.string() + " as OpenEXR: " + e.what());
  }
}

}  // namespace skyspec
