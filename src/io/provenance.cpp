#include "io/provenance.hpp"

#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStringAttribute.h>

#include <exception>

#include "base/embedded_data.hpp"
#include "physics/ozone.hpp"
#include "skyspec/error.hpp"
#include "skyspec/scene.hpp"
#include "skyspec/version.hpp"
#include "io/exr_open.hpp"

namespace skyspec {

std::vector<std::string> data_tables_used(const Scene& scene, bool builtin_display_config) {
  std::vector<std::string> paths;
  if (scene.render.path == RenderSpec::Path::Spectral) paths.emplace_back("cie/cie1931_2deg_5nm.csv");
  if (scene.sun.spectrum == SunSpec::Spectrum::Solar) paths.emplace_back("solar/astm_g173_etr.csv");
  const OzoneSpec& ozone = scene.atmosphere.ozone;
  if (ozone.enabled && ozone.cross_section_m2.empty())
    for (std::string_view file : ozone_cross_section_files()) paths.emplace_back(file);
  if (!scene.sun.date_time.empty()) {
    paths.emplace_back("solar_position/spa_earth_periodic_terms.csv");
    paths.emplace_back("solar_position/spa_nutation_terms.csv");
  }
  if (builtin_display_config) paths.emplace_back("ocio/config.ocio");
  return paths;
}

std::string data_tables_text(const Scene& scene, bool builtin_display_config) {
  std::string text;
  for (const auto& path : data_tables_used(scene, builtin_display_config))
    text += (text.empty() ? "" : "\n") + embedded_table_info(path).describe();
  return text.empty() ? std::string("(no embedded data tables)") : text;
}

std::map<std::string, std::string> provenance_attributes(const Scene& scene, bool builtin_display_config) {
  return {{kVersionAttribute, version_string()},
          {kSceneAttribute, scene_to_toml(scene, SceneTomlKeys::Recorded)},
          {kDataAttribute, data_tables_text(scene, builtin_display_config)}};
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
