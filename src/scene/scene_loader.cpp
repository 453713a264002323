// SceneLoader: a preset, then scene files, TOML text, quality levels and overrides, each value
// checked by the key registry; finish() checks the relations between keys.
#include "scene/key_registry.hpp"
#include "scene/scene_checks.hpp"
#include "scene/scene_terrain.hpp"
#include "skyspec/scene.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include <toml++/toml.h>

#include "base/embedded_data.hpp"
#include "base/text_format.hpp"
#include "physics/date_time.hpp"
#include "physics/ozone.hpp"
#include "physics/solar_position.hpp"
#include "physics/solar_spectrum.hpp"
#include "scene/toml_limits.hpp"
#include "skyspec/error.hpp"
#include "skyspec/refractive_index.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

using namespace scene_keys;

namespace {

// scene_dir: the folder of the scene file the table comes from (input paths are taken from it), or
// null.
void apply_table(Scene& scene, const toml::table& tbl, const std::string& prefix, const std::string& fallback_origin,
                 std::set<std::string>& applied, const std::filesystem::path* scene_dir = nullptr) {
  for (const auto& [k, node] : tbl) {
    const std::string key = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    // A table where the registry has a value ([sun] elevation_deg = {a = 1}) is that key's wrong
    // value, not an unknown key (it said: did you mean "sun.elevation_deg"?).
    if (auto sub = node.as_table(); sub && !find_key(key)) {
      // A table is a group of keys, unless the registry has no key below it.
      bool any = false;
      for (const auto& def : registry())
        if (def.key.rfind(key + ".", 0) == 0) any = true;
      if (!any) unknown_key(key, origin_of_key(k, fallback_origin));
      apply_table(scene, *sub, key, fallback_origin, applied, scene_dir);
      continue;
    }
    const KeyDef* def = find_key(key);
    if (!def) unknown_key(key, origin_of_key(k, fallback_origin));
    const auto* text = node.as_string();
    if (def->input_path && scene_dir && text && !text->get().empty() &&
        std::filesystem::path(text->get()).is_relative()) {
      const toml::value<std::string> resolved((*scene_dir / text->get()).lexically_normal().string());
      def->set(scene, resolved, origin_of(node, fallback_origin));
    } else {
      def->set(scene, node, origin_of(node, fallback_origin));
    }
    applied.insert(key);
  }
}

toml::table parse_toml(const std::string& text, const std::string& origin) {
  check_toml_limits(text, "scene file", origin);  // before the (recursive) parser sees it
  try {
    return toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    std::ostringstream s;
    s << origin << ":" << e.source().begin.line << ":" << e.source().begin.column
      << ": not valid TOML: " << e.description();
    throw InputError(
        "scene file", origin, "valid TOML (" + std::string(e.description()) + ")",
        origin + ":" + std::to_string(e.source().begin.line) + ":" + std::to_string(e.source().begin.column));
  }
}

}  // namespace

std::vector<std::string> preset_names() {
  std::vector<std::string> names;
  for (const auto& [path, content] : embedded_files()) {
    std::string p(path);
    if (p.rfind("scenes/", 0) == 0 && p.size() > 12 && p.substr(p.size() - 5) == ".toml")
      names.push_back(p.substr(7, p.size() - 12));
  }
  std::sort(names.begin(), names.end());
  return names;
}

SceneLoader::SceneLoader(const std::string& preset) {
  const auto names = preset_names();
  if (std::find(names.begin(), names.end(), preset) == names.end())
    throw InputError("preset", "\"" + preset + "\"", "one of: " + join(names, ", "));
  // Every preset is the default scene plus the keys its file changes.
  apply_toml(std::string(embedded_file("scenes/default.toml")), "preset default");
  given_.clear();  // the defaults are not choices
  if (preset != "default") apply_toml(std::string(embedded_file("scenes/" + preset + ".toml")), "preset " + preset);
}

std::vector<std::string> quality_names() { return {"draft", "lean", "default", "high", "reference"}; }

void SceneLoader::apply_quality(const std::string& name, const std::string& origin) {
  const auto names = quality_names();
  if (std::find(names.begin(), names.end(), name) == names.end())
    throw InputError(origin, "\"" + name + "\"", "one of: " + join(names, ", "));
  const bool single = scene_.render.scattering_orders == 1;
  apply_toml(std::string(embedded_file("quality/" + name + ".toml")), "quality " + name);
  if (single) scene_.render.scattering_orders = 1;
}

void SceneLoader::apply_toml(const std::string& text, const std::string& origin) {
  const toml::table tbl = parse_toml(text, origin);
  apply_table(scene_, tbl, "", origin, given_);
}

void SceneLoader::apply_file(const std::string& path) {
  // A folder, a FIFO or a device is refused before it is opened (opening a FIFO blocks until a
  // writer comes; a folder reads as an empty scene).
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw InputError(kSceneFileSetting, "\"" + path + "\"",
                     std::string("a TOML scene file (this is ") +
                         (std::filesystem::is_directory(status) ? "a folder"
                          : std::filesystem::is_fifo(status)    ? "a FIFO"
                                                                : "not a regular file") +
                         ")");
  std::string text;
  {
    FILE* f = std::fopen(path.c_str(), "rb");
    if (!f)
      throw InputError(kSceneFileSetting, "\"" + path + "\"",
                       "a readable TOML scene file (" + std::string(std::strerror(errno)) + ")");
    char buf[65536];
    size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) {
      text.append(buf, n);
      if (text.size() > kMaxTomlBytes) {
        std::fclose(f);
        throw InputError(kSceneFileSetting, "\"" + path + "\"",
                         "a scene file of at most " + std::to_string(kMaxTomlBytes >> 20) + " MiB");
      }
    }
    std::fclose(f);
  }
  const std::filesystem::path dir = std::filesystem::absolute(path).parent_path();
  apply_table(scene_, parse_toml(text, path), "", path, given_, &dir);
}

namespace {

// TOML value text of typed C++ values, for SceneLoader::set ("nan" and "inf" are TOML too: the
// key's own check refuses them).
std::string toml_number(double v) { return format_shortest(v); }

// A spectral albedo's lists (<prefix>.albedo_wavelengths_nm, <prefix>.albedo_values): as long as
// each other, wavelengths strictly increasing.
void check_spectral_albedo(const std::string& prefix, const std::vector<double>& wavelengths_nm,
                           const std::vector<double>& values) {
  if (wavelengths_nm.size() != values.size())
    throw InputError(
        prefix + ".albedo_values", std::to_string(values.size()) + " values",
        "one value per entry of " + prefix + ".albedo_wavelengths_nm (" + std::to_string(wavelengths_nm.size()) + ")");
  for (size_t i = 1; i < wavelengths_nm.size(); ++i)
    if (!(wavelengths_nm[i] > wavelengths_nm[i - 1]))
      throw InputError(prefix + ".albedo_wavelengths_nm", format_number(wavelengths_nm[i]),
                       "strictly increasing wavelengths");
}

}  // namespace

std::string toml_quoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char u[8];
          std::snprintf(u, sizeof u, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
          out += u;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

void SceneLoader::set(const std::string& key, double value, const std::string& origin) {
  apply_override(key, toml_number(value), origin.empty() ? key : origin);
}
void SceneLoader::set(const std::string& key, int value, const std::string& origin) {
  apply_override(key, std::to_string(value), origin.empty() ? key : origin);
}
void SceneLoader::set(const std::string& key, bool value, const std::string& origin) {
  apply_override(key, value ? "true" : "false", origin.empty() ? key : origin);
}
void SceneLoader::set(const std::string& key, const std::string& value, const std::string& origin) {
  apply_override(key, toml_quoted(value), origin.empty() ? key : origin);
}
void SceneLoader::set(const std::string& key, const char* value, const std::string& origin) {
  set(key, std::string(value ? value : ""), origin);
}
void SceneLoader::set(const std::string& key, const std::vector<double>& values, const std::string& origin) {
  std::string text = "[";
  for (size_t i = 0; i < values.size(); ++i) text += (i ? ", " : "") + toml_number(values[i]);
  apply_override(key, text + "]", origin.empty() ? key : origin);
}

void SceneLoader::apply_override(const std::string& key, const std::string& toml_value, const std::string& origin) {
  const KeyDef* def = find_key(key);
  if (!def) unknown_key(key, origin);
  toml::table tbl;
  check_toml_limits(toml_value, origin, origin);
  try {
    tbl = toml::parse("v = " + toml_value, origin);
  } catch (const toml::parse_error&) {
    // Not a TOML literal: take it as a bare string (e.g. --camera fisheye).
    tbl = toml::table{{"v", toml_value}};
  }
  // A bare word for a text key is that word, even where TOML reads a number or a boolean
  // (--name nan, --name 2026, --out true).
  if (def->text && !tbl.get("v")->is_string()) tbl = toml::table{{"v", toml_value}};
  const toml::node* n = tbl.get("v");
  // Strip source positions: the origin is the flag, not a line of a file.
  if (auto s = n->as_string()) {
    toml::value<std::string> v(s->get());
    def->set(scene_, v, origin);
  } else if (auto i = n->as_integer()) {
    toml::value<int64_t> v(i->get());
    def->set(scene_, v, origin);
  } else if (auto fp = n->as_floating_point()) {
    toml::value<double> v(fp->get());
    def->set(scene_, v, origin);
  } else if (auto b = n->as_boolean()) {
    toml::value<bool> v(b->get());
    def->set(scene_, v, origin);
  } else {
    def->set(scene_, *n, origin);
  }
  given_.insert(key);
  overridden_[key] = origin;
}

Scene SceneLoader::finish(SceneUse use) const {
  Scene s = scene_;
  const double R = s.atmosphere.planet_radius_m;
  check_terrain(s);                                        // before the terrain is read for the camera's height
  if (s.camera.above_ground_m && use == SceneUse::Render)  // the height from the ground under the camera
    s.camera.position_m.z() =
        camera_height_above_ground(s, s.camera.position_m.x(), s.camera.position_m.y(), *s.camera.above_ground_m);
  // Camera: not inside the planet.
  const Vec3 world = Vec3(s.camera.position_m.x(), s.camera.position_m.y(), R + s.camera.position_m.z());
  if (world.norm() < R)
    throw InputError(
        "camera.position_m",
        "[" + format_number(s.camera.position_m.x()) + ", " + format_number(s.camera.position_m.y()) + ", " +
            format_number(s.camera.position_m.z()) + "]",
        "a position on or above the ground (this one is " + format_number(R - world.norm()) + " m below it)");
  if (s.camera.type == CameraSpec::Type::Perspective && (s.camera.look_at_m - s.camera.position_m).norm() < 1e-6)
    throw InputError("camera.look_at_m", "the camera position", "a point different from camera.position_m");
  if (static_cast<double>(s.camera.width) * s.camera.height > 1.0e9)
    throw InputError("camera.width x camera.height",
                     std::to_string(s.camera.width) + "x" + std::to_string(s.camera.height), "at most 1e9 pixels");
  if (s.camera.type == CameraSpec::Type::Equirectangular) check_panorama(s.camera);
  if (sees_below_horizon_as_panorama(s.camera) && !ground_albedo_given(given_))
    s.atmosphere.ground.albedo = kPanoramaGroundAlbedo;
  if (!s.sun.date_time.empty()) {
    // The sun's position and distance for the date, time and place (NREL SPA).
    Observer where;
    where.latitude_deg = s.location.latitude_deg;
    where.longitude_deg = s.location.longitude_deg;
    where.altitude_m = s.camera.position_m.z();
    SolarPositionOptions opt;
    opt.refraction = s.sun.refraction;
    const SolarPosition sp = solar_position(parse_iso8601(s.sun.date_time, "sun.date_time"), where, opt);
    s.sun.elevation_deg = sp.elevation_deg;
    s.sun.azimuth_deg = sp.azimuth_deg;
    s.sun.distance_au = sp.earth_sun_distance_au;
  }
  const auto& oz = s.atmosphere.ozone;
  if (oz.enabled && !(oz.bottom_m < oz.peak_m && oz.peak_m < oz.top_m))
    throw InputError("atmosphere.ozone.peak_m", format_number(oz.peak_m),
                     "bottom_m < peak_m < top_m (here " + format_number(oz.bottom_m) + ", " + format_number(oz.peak_m) +
                         ", " + format_number(oz.top_m) + ")");
  const auto& mie = s.atmosphere.mie;
  const size_t n_table = mie.table_wavelengths_nm.size();
  if (n_table > 0) {
    const std::pair<const char*, size_t> tables[] = {
        {"atmosphere.mie.table_extinction_efficiency", mie.table_extinction_efficiency.size()},
        {"atmosphere.mie.table_single_scattering_albedo", mie.table_single_scattering_albedo.size()},
        {"atmosphere.mie.table_g", mie.table_g.size()}};
    for (const auto& [key, size] : tables)
      if (size != n_table)
        throw InputError(
            key, std::to_string(size) + " values",
            "one value per entry of atmosphere.mie.table_wavelengths_nm (" + std::to_string(n_table) + ")");
    for (size_t i = 1; i < n_table; ++i)
      if (!(mie.table_wavelengths_nm[i] > mie.table_wavelengths_nm[i - 1]))
        throw InputError("atmosphere.mie.table_wavelengths_nm", format_number(mie.table_wavelengths_nm[i]),
                         "strictly increasing wavelengths");
  }
  check_spectral_albedo("ground", s.atmosphere.ground.albedo_wavelengths_nm, s.atmosphere.ground.albedo_values);
  check_spectral_albedo("terrain", s.terrain.albedo_wavelengths_nm, s.terrain.albedo_values);
  const IceSpec& ice = s.atmosphere.ice;
  if (ice.enabled && ice.layer == IceSpec::Layer::Cloud) {
    if (!(ice.top_m > ice.base_m))
      throw InputError("atmosphere.ice.top_m", format_number(ice.top_m),
                       "above atmosphere.ice.base_m (" + format_number(ice.base_m) + " m)");
    if (!(ice.top_m < s.atmosphere.top_altitude_m))
      throw InputError("atmosphere.ice.top_m", format_number(ice.top_m),
                       "below atmosphere.top_altitude_m (" + format_number(s.atmosphere.top_altitude_m) + " m)");
  }
  if (s.output.polarisation && s.atmosphere.ice.enabled)
    throw InputError("atmosphere.ice.enabled", "true",
                     "false with output.polarisation = true (the ice crystals' scattering is computed for intensity "
                     "only)");
  if (s.output.polarisation_png && !s.output.polarisation)
    throw InputError("output.polarisation_png", "true",
                     "false unless output.polarisation = true (it draws the polarisation)");
  if (s.output.polarisation && s.render.scattering_orders >= 2 && s.render.ms_angular_degree < 2)
    throw InputError("render.ms_angular_degree", std::to_string(s.render.ms_angular_degree),
                     "2 or more with output.polarisation = true and multiple scattering (the polarisation of light "
                     "scattered more than once comes from its field's quadrupole; the draft quality's 0 has none)");
  // Grid and colour path.
  const WavelengthGrid grid = make_wavelength_grid(s);
  // Every sample's band lambda +- bandwidth/2 must stay above 0 nm (1000 nm around 380 nm reached
  // -120 nm, and the tables were averaged over it without a word).
  if (grid.size() > 0 && grid.bandwidth_nm() / 2 >= grid.nanometres().front())
    throw InputError("spectrum.bandwidth_nm", format_number(grid.bandwidth_nm()),
                     "less than twice the shortest wavelength (" + format_number(grid.nanometres().front()) +
                         " nm), so that no band reaches 0 nm");
  if (s.render.path == RenderSpec::Path::RgbFast) {
    const bool ok = grid.size() == 3 && grid.index_of(440) >= 0 && grid.index_of(550) >= 0 && grid.index_of(680) >= 0;
    if (!ok)
      throw InputError("spectrum", grid.describe(),
                       "exactly 440, 550 and 680 nm when render.path = \"rgb-fast\" (they become B, G, R)");
  } else if (use == SceneUse::Render) {
    check_spectral_range(s, grid);
  } else {
    check_refractive_index_range(s, grid);
  }
  if (s.atmosphere.rayleigh.source == RayleighSpec::Source::Fixed) {
    // AtmosphereModel reports the details; evaluate once here so errors surface before rendering.
    AtmosphereModel check(s.atmosphere, grid);
    (void)check;
  }
  // A flag or an override that the camera would ignore is a mistake (a scene file may carry every
  // key: recorded scenes do).
  for (const auto& [key, origin] : overridden_) {
    const KeyDef* def = find_key(key);
    if (def->needs && !def->needs(s))
      throw InputError(key, def->get(s), "only with " + def->needs_text + " (this scene does not read it)", origin);
    if (def->cameras.empty() ||
        std::find(def->cameras.begin(), def->cameras.end(), s.camera.type) != def->cameras.end())
      continue;
    std::vector<std::string> names;
    for (CameraSpec::Type t : def->cameras) names.push_back(std::string("\"") + camera_type_name(t) + "\"");
    throw InputError(key, def->get(s),
                     "only with camera.type = " + join(names, " or ") + " (this camera is \"" +
                         camera_type_name(s.camera.type) + "\" and does not read it)",
                     origin);
  }
  return s;
}

WavelengthGrid make_wavelength_grid(const Scene& s) {
  const double w = s.spectrum.bandwidth_nm;
  if (!s.spectrum.wavelengths_nm.empty()) return WavelengthGrid::from_list(s.spectrum.wavelengths_nm).with_bandwidth(w);
  if (s.spectrum.count > 0)
    return WavelengthGrid::with_count(s.spectrum.min_nm, s.spectrum.max_nm, s.spectrum.count).with_bandwidth(w);
  return WavelengthGrid::uniform(s.spectrum.min_nm, s.spectrum.max_nm, s.spectrum.step_nm).with_bandwidth(w);
}

Vec3 sun_direction(const Scene& s) { return direction_from_angles(s.sun.azimuth_deg, s.sun.elevation_deg); }

}  // namespace skyspec
