#include "render/scene_provenance.hpp"

#include <string_view>

#include "physics/ozone.hpp"
#include "skyspec/version.hpp"

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
  return data_tables_text(data_tables_used(scene, builtin_display_config));
}

std::map<std::string, std::string> provenance_attributes(const Scene& scene, bool builtin_display_config) {
  return {{kVersionAttribute, version_string()},
          {kSceneAttribute, scene_to_toml(scene, SceneTomlKeys::Recorded)},
          {kDataAttribute, data_tables_text(scene, builtin_display_config)}};
}

}  // namespace skyspec
