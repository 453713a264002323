// The name tables of camera_spec.hpp: the one place a camera type or a panorama convention is named
// (and the name look-ups of the other tables, such as scene.hpp's terrain_models()).
#include "skyspec/camera_spec.hpp"

#include <string>

#include "skyspec/error.hpp"
#include "skyspec/scene.hpp"

namespace skyspec {

const std::vector<NamedValue<CameraSpec::Type>>& camera_types() {
  static const std::vector<NamedValue<CameraSpec::Type>> table = {
      {CameraSpec::Type::Fisheye, "fisheye"},
      {CameraSpec::Type::Perspective, "perspective"},
      {CameraSpec::Type::Equirectangular, "equirectangular"},
  };
  return table;
}

const std::vector<NamedValue<PanoramaConvention>>& panorama_conventions() {
  static const std::vector<NamedValue<PanoramaConvention>> table = {
      {PanoramaConvention::Skyspec, "skyspec"},
      {PanoramaConvention::Blender, "blender"},
      {PanoramaConvention::OpenExr, "openexr"},
  };
  return table;
}

namespace {
template <typename Enum>
const char* name_in(const std::vector<NamedValue<Enum>>& table, Enum value) {
  for (const auto& row : table)
    if (row.value == value) return row.name;
  return table.front().name;  // unreachable for a value of the enum: every value has a row
}
}  // namespace

const char* camera_type_name(CameraSpec::Type type) { return name_in(camera_types(), type); }
const char* panorama_convention_name(PanoramaConvention c) { return name_in(panorama_conventions(), c); }
const char* terrain_model_name(TerrainSpec::Model model) { return name_in(terrain_models(), model); }

template <typename Enum>
Enum value_named(const std::vector<NamedValue<Enum>>& table, const std::string& name, const std::string& setting) {
  for (const auto& row : table)
    if (name == row.name) return row.value;
  std::string allowed = "one of";
  for (const auto& row : table) allowed += std::string(" ") + row.name;
  throw InputError(setting, name, allowed);
}
template CameraSpec::Type value_named(const std::vector<NamedValue<CameraSpec::Type>>&, const std::string&,
                                      const std::string&);
template PanoramaConvention value_named(const std::vector<NamedValue<PanoramaConvention>>&, const std::string&,
                                        const std::string&);
template TerrainSpec::Model value_named(const std::vector<NamedValue<TerrainSpec::Model>>&, const std::string&,
                                        const std::string&);

}  // namespace skyspec
