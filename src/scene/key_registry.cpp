// The scene key registry (key_registry.hpp): every key of a scene, its unit, range and meaning.
// docs/scene-keys.md is generated from it (scene_keys_markdown).
#include "scene/key_registry.hpp"
#include "scene/key_types.hpp"

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
#include <stdexcept>

#include <toml++/toml.h>

#include "base/embedded_data.hpp"
#include "base/text_format.hpp"
#include "physics/date_time.hpp"
#include "physics/ozone.hpp"
#include "physics/solar_position.hpp"
#include "physics/solar_spectrum.hpp"
#include "scene/toml_limits.hpp"
#include "skyspec/aerosol_components.hpp"
#include "skyspec/error.hpp"
#include "skyspec/refractive_index.hpp"
#include "skyspec/units.hpp"

namespace skyspec::scene_keys {

// Split at the parenthesis that closes the first.
std::pair<std::string, std::string> split_doc(const std::string& doc) {
  if (doc.empty() || doc.front() != '(') return {"", doc};
  int depth = 0;
  for (size_t i = 0; i < doc.size(); ++i) {
    if (doc[i] == '(') ++depth;
    if (doc[i] == ')' && --depth == 0) {
      const size_t start = doc.find_first_not_of(' ', i + 1);
      return {doc.substr(1, i - 1), start == std::string::npos ? std::string() : doc.substr(start)};
    }
  }
  return {"", doc};
}

namespace {
// A key that only this camera type reads: "(allowed) meaning" becomes "(allowed) type: meaning".
KeyDef only_for(CameraSpec::Type type, KeyDef k) {
  k.cameras = {type};
  const auto [allowed, meaning] = split_doc(k.doc);
  k.doc = "(" + allowed + ") " + camera_type_name(type) + ": " + meaning;
  return k;
}

// The keys a scene reads only when other keys say so (a medium turned on, a terrain model): one
// list, which SceneLoader::finish enforces for flags and overrides.
void add_conditions(std::vector<KeyDef>& r) {
  struct Condition {
    std::vector<std::string> keys;
    std::function<bool(const Scene&)> holds;
    std::string text;
  };
  using Model = TerrainSpec::Model;
  const auto ice_in = [](IceSpec::Layer layer) {
    return [layer](const Scene& s) { return s.atmosphere.ice.enabled && s.atmosphere.ice.layer == layer; };
  };
  const std::vector<Condition> conditions = {
      {{"atmosphere.fog.visibility_m", "atmosphere.fog.scale_height_m", "atmosphere.fog.droplets"},
       [](const Scene& s) { return s.atmosphere.fog.enabled; },
       "atmosphere.fog.enabled = true"},
      {{"atmosphere.water_vapour.column_cm", "atmosphere.water_vapour.scale_height_m"},
       [](const Scene& s) { return s.irradiance.broadband; },
       "irradiance.broadband = true"},
      {{"atmosphere.rain.drops", "atmosphere.rain.rate_mm_per_h", "atmosphere.rain.scale_height_m",
        "atmosphere.rain.extent"},
       [](const Scene& s) { return s.atmosphere.rain.enabled; },
       "atmosphere.rain.enabled = true"},
      {{"atmosphere.fog.median_radius_um", "atmosphere.fog.radius_spread"},
       [](const Scene& s) {
         return s.atmosphere.fog.enabled && s.atmosphere.fog.droplets == FogSpec::Droplets::Lognormal;
       },
       "atmosphere.fog.enabled = true and atmosphere.fog.droplets = \"lognormal\""},
      {{"atmosphere.rain.median_radius_mm", "atmosphere.rain.radius_spread"},
       [](const Scene& s) {
         return s.atmosphere.rain.enabled && s.atmosphere.rain.drops == RainSpec::Drops::Lognormal;
       },
       "atmosphere.rain.enabled = true and atmosphere.rain.drops = \"lognormal\""},
      {{"atmosphere.rain.shower_distance_m", "atmosphere.rain.shower_azimuth_deg", "atmosphere.rain.shower_radius_m"},
       [](const Scene& s) { return s.atmosphere.rain.enabled && s.atmosphere.rain.extent == RainSpec::Extent::Shower; },
       "atmosphere.rain.enabled = true and atmosphere.rain.extent = \"shower\""},
      {{"atmosphere.ice.layer", "atmosphere.ice.aspect_ratio"},
       [](const Scene& s) { return s.atmosphere.ice.enabled; },
       "atmosphere.ice.enabled = true"},
      {{"atmosphere.ice.visibility_m", "atmosphere.ice.scale_height_m"},
       ice_in(IceSpec::Layer::Ground),
       "atmosphere.ice.enabled = true and atmosphere.ice.layer = \"ground\""},
      {{"atmosphere.ice.base_m", "atmosphere.ice.top_m", "atmosphere.ice.optical_depth"},
       ice_in(IceSpec::Layer::Cloud),
       "atmosphere.ice.enabled = true and atmosphere.ice.layer = \"cloud\""},
      {{"terrain.ridge.height_m", "terrain.ridge.distance_m", "terrain.ridge.azimuth_deg", "terrain.ridge.half_width_m",
        "terrain.ridge.length_m", "terrain.ridge.notch_spacing_m", "terrain.ridge.notch_depth"},
       [](const Scene& s) { return s.terrain.model == Model::Ridge; },
       "terrain.model = \"ridge\""},
      {{"terrain.heightmap.pixel_m", "terrain.heightmap.height_scale_m", "terrain.heightmap.height_offset_m"},
       [](const Scene& s) { return s.terrain.model == Model::HeightMap; },
       "terrain.model = \"heightmap\""},
      {{"terrain.file", "terrain.albedo_map", "terrain.extent_m"},
       [](const Scene& s) { return s.terrain.model == Model::File || s.terrain.model == Model::HeightMap; },
       "terrain.model = \"file\" or \"heightmap\""},
      {{"terrain.spacing_m", "terrain.albedo", "terrain.albedo_wavelengths_nm", "terrain.albedo_values"},
       [](const Scene& s) { return s.terrain.model != Model::None; },
       "terrain.model = \"ridge\", \"file\" or \"heightmap\""},
  };
  for (const Condition& c : conditions)
    for (const std::string& key : c.keys) {
      const auto it = std::find_if(r.begin(), r.end(), [&key](const KeyDef& k) { return k.key == key; });
      if (it == r.end()) throw std::logic_error("add_conditions: no key " + key);
      it->needs = c.holds;
      it->needs_text = c.text;
    }
}
}  // namespace

const std::vector<KeyDef>& registry() {
  static const std::vector<KeyDef> keys = [] {
    std::vector<KeyDef> r;
    const double kMaxRadius = 1e9, kMaxLength = 1e9;
    // planet and atmosphere
    r.push_back(number_key("planet.radius_m", "m", {1e3, kMaxRadius}, "radius of the planet (sea level)",
                           [](Scene& s) -> double& { return s.atmosphere.planet_radius_m; }));
    r.push_back(number_key("atmosphere.top_altitude_m", "m", {1.0, 1e7}, "thickness of the atmosphere shell",
                           [](Scene& s) -> double& { return s.atmosphere.top_altitude_m; }));
    // Rayleigh
    r.push_back(choice_key(
        "atmosphere.rayleigh.source", {"derived", "fixed"},
        "derived: beta = sigma(n(lambda), King factor) N; fixed: typed-in coefficients (seed preset)",
        [](Scene& s, const std::string& v) {
          s.atmosphere.rayleigh.source = v == "fixed" ? RayleighSpec::Source::Fixed : RayleighSpec::Source::Derived;
        },
        [](const Scene& s) {
          return std::string(s.atmosphere.rayleigh.source == RayleighSpec::Source::Fixed ? "fixed" : "derived");
        }));
    auto profile_key = [](std::string key, std::function<ProfileKind&(Scene&)> ref, std::string help) {
      return choice_key(
          std::move(key), {"exponential", "us1976", "constant"}, std::move(help),
          [ref](Scene& s, const std::string& v) {
            ref(s) = v == "us1976"     ? ProfileKind::UsStandard1976
                     : v == "constant" ? ProfileKind::Constant
                                       : ProfileKind::Exponential;
          },
          [ref](const Scene& s) { return to_string(ref(const_cast<Scene&>(s))); });
    };
    r.push_back(choice_key(
        "atmosphere.rayleigh.gas", {"air", "co2"},
        "air: Earth's dry air (refractive_index formula, co2_ppm); co2: pure carbon dioxide (Sneep & Ubachs 2005)",
        [](Scene& s, const std::string& v) {
          s.atmosphere.rayleigh.derivation.gas = v == "co2" ? ScatteringGas::CarbonDioxide : ScatteringGas::Air;
        },
        [](const Scene& s) { return to_string(s.atmosphere.rayleigh.derivation.gas); }));
    r.push_back(profile_key(
        "atmosphere.rayleigh.profile", [](Scene& s) -> ProfileKind& { return s.atmosphere.rayleigh.profile; },
        "number density profile of air"));
    r.push_back(number_key("atmosphere.rayleigh.scale_height_m", "m", {1.0, kMaxLength, true},
                           "scale height of the exponential profile",
                           [](Scene& s) -> double& { return s.atmosphere.rayleigh.scale_height_m; }));
    r.push_back(number_key("atmosphere.rayleigh.surface_pressure_Pa", "Pa", {0.0, 1e8, true},
                           "pressure at altitude 0 (exponential/constant profiles): N(0) = P / kT",
                           [](Scene& s) -> double& { return s.atmosphere.rayleigh.surface_pressure_Pa; }));
    r.push_back(number_key("atmosphere.rayleigh.surface_temperature_K", "K", {1.0, 2000.0},
                           "temperature at altitude 0 (exponential/constant profiles)",
                           [](Scene& s) -> double& { return s.atmosphere.rayleigh.surface_temperature_K; }));
    r.push_back(choice_key(
        "atmosphere.rayleigh.refractive_index", {"peck-reeder", "edlen", "ciddor"},
        "formula for n(lambda) of standard air",
        [](Scene& s, const std::string& v) {
          s.atmosphere.rayleigh.derivation.formula =
              parse_refractive_index_formula(v, "atmosphere.rayleigh.refractive_index");
        },
        [](const Scene& s) { return to_string(s.atmosphere.rayleigh.derivation.formula); }));
    r.push_back(number_key(
        "atmosphere.rayleigh.co2_ppm", "ppm", {0.0, 1e6},
        "CO2 mole fraction (refractive index correction, King factor)",
        [](Scene& s) -> double& { return s.atmosphere.rayleigh.derivation.co2_ppv; }, 1e-6));
    r.push_back(list_key("atmosphere.rayleigh.wavelengths_nm", "nm", {1.0, 1e5}, 64,
                         "source = fixed: wavelengths of the typed-in coefficients",
                         [](Scene& s) -> std::vector<double>& { return s.atmosphere.rayleigh.fixed_wavelengths_nm; }));
    r.push_back(list_key("atmosphere.rayleigh.beta_per_m", "m^-1", {0.0, 1.0}, 64,
                         "source = fixed: scattering coefficients at altitude 0, one per wavelength",
                         [](Scene& s) -> std::vector<double>& { return s.atmosphere.rayleigh.fixed_beta_per_m; }));
    // Mie
    r.push_back(bool_key("atmosphere.mie.enabled", "aerosols on or off",
                         [](Scene& s) -> bool& { return s.atmosphere.mie.enabled; }));
    r.push_back(choice_key(
        "atmosphere.mie.model", {"angstrom", "opac"},
        "angstrom: the Angstrom law (or the spectral tables) with an analytic phase function that does not "
        "polarise; opac: OPAC components by Lorenz-Mie theory (atmosphere.mie.opac.*: extinction, "
        "scattering and the full scattering matrix from number concentrations and humidity)",
        [](Scene& s, const std::string& v) {
          s.atmosphere.mie.model = v == "opac" ? MieSpec::Model::Opac : MieSpec::Model::Angstrom;
        },
        [](const Scene& s) {
          return std::string(s.atmosphere.mie.model == MieSpec::Model::Opac ? "opac" : "angstrom");
        }));
    for (int c = 0; c < kAerosolComponentCount; ++c) {
      const std::string name = aerosol_component_names()[static_cast<size_t>(c)];
      r.push_back(number_key(
          "atmosphere.mie.opac." + name + "_per_cm3", "cm^-3", {0.0, 1e7},
          "model = opac: number concentration of OPAC's " + aerosol_component_description(c) +
              " component at altitude 0 (all radii, OPAC's unit)",
          [c](Scene& s) -> double& { return s.atmosphere.mie.opac.number_per_cm3[static_cast<size_t>(c)]; }));
    }
    r.push_back(number_key("atmosphere.mie.opac.relative_humidity_percent", "%", {0.0, 99.0},
                           "model = opac: relative humidity, which swells the components that take up water "
                           "(OPAC's tables at 0, 50, 70, 80, 90, 95, 98 and 99 %, linear between them)",
                           [](Scene& s) -> double& { return s.atmosphere.mie.opac.relative_humidity_percent; }));
    r.push_back(profile_key(
        "atmosphere.mie.profile", [](Scene& s) -> ProfileKind& { return s.atmosphere.mie.profile; },
        "aerosol density profile (us1976 is not meaningful for aerosols but allowed)"));
    r.push_back(number_key("atmosphere.mie.scale_height_m", "m", {1.0, kMaxLength, true},
                           "scale height of the aerosol profile",
                           [](Scene& s) -> double& { return s.atmosphere.mie.scale_height_m; }));
    r.push_back(number_key("atmosphere.mie.scattering_per_m", "m^-1", {0.0, 1.0},
                           "aerosol scattering coefficient at altitude 0 and the reference wavelength",
                           [](Scene& s) -> double& { return s.atmosphere.mie.scattering_per_m; }));
    r.push_back(number_key("atmosphere.mie.reference_wavelength_nm", "nm", {1.0, 1e5},
                           "wavelength at which scattering_per_m is given",
                           [](Scene& s) -> double& { return s.atmosphere.mie.reference_wavelength_nm; }));
    r.push_back(number_key("atmosphere.mie.angstrom_exponent", "", {-4.0, 4.0},
                           "Angstrom exponent alpha: beta(lambda) = beta_ref (lambda / lambda_ref)^-alpha",
                           [](Scene& s) -> double& { return s.atmosphere.mie.angstrom_exponent; }));
    r.push_back(number_key("atmosphere.mie.extinction_to_scattering", "", {1.0, 100.0},
                           "extinction / scattering ratio (1 = no absorption; seed: 1.1)",
                           [](Scene& s) -> double& { return s.atmosphere.mie.extinction_to_scattering; }));
    r.push_back(choice_key(
        "atmosphere.mie.phase", {"cornette-shanks", "henyey-greenstein"}, "aerosol phase function",
        [](Scene& s, const std::string& v) {
          s.atmosphere.mie.phase.model = parse_aerosol_phase_model(v, "atmosphere.mie.phase");
        },
        [](const Scene& s) { return to_string(s.atmosphere.mie.phase.model); }));
    r.push_back(number_key("atmosphere.mie.g", "", {-0.999, 0.999}, "asymmetry parameter of the phase function",
                           [](Scene& s) -> double& { return s.atmosphere.mie.phase.g; }));
    r.push_back(list_key("atmosphere.mie.table_wavelengths_nm", "nm", {1.0, 1e5}, 1024,
                         "spectral aerosol tables: wavelengths (when given, the tables replace the Angstrom law, "
                         "extinction_to_scattering and g)",
                         [](Scene& s) -> std::vector<double>& { return s.atmosphere.mie.table_wavelengths_nm; }));
    r.push_back(
        list_key("atmosphere.mie.table_extinction_efficiency", "", {0.0, 1e6}, 1024,
                 "spectral aerosol tables: extinction efficiency Q (any scale)",
                 [](Scene& s) -> std::vector<double>& { return s.atmosphere.mie.table_extinction_efficiency; }));
    r.push_back(list_key("atmosphere.mie.table_single_scattering_albedo", "", {1e-6, 1.0}, 1024,
                         "spectral aerosol tables: single-scattering albedo", [](Scene& s) -> std::vector<double>& {
                           return s.atmosphere.mie.table_single_scattering_albedo;
                         }));
    r.push_back(list_key("atmosphere.mie.table_g", "", {-0.999, 0.999}, 1024,
                         "spectral aerosol tables: asymmetry parameter",
                         [](Scene& s) -> std::vector<double>& { return s.atmosphere.mie.table_g; }));
    // ozone
    r.push_back(bool_key("atmosphere.ozone.enabled", "absorbing ozone layer on or off",
                         [](Scene& s) -> bool& { return s.atmosphere.ozone.enabled; }));
    r.push_back(number_key("atmosphere.ozone.column_DU", "Dobson units", {0.0, 2000.0},
                           "total ozone column (about 300 DU on Earth)",
                           [](Scene& s) -> double& { return s.atmosphere.ozone.column_DU; }));
    r.push_back(number_key("atmosphere.ozone.bottom_m", "m", {0.0, 1e7}, "bottom of the ozone layer (tent profile)",
                           [](Scene& s) -> double& { return s.atmosphere.ozone.bottom_m; }));
    r.push_back(number_key("atmosphere.ozone.peak_m", "m", {0.0, 1e7}, "altitude of the ozone maximum",
                           [](Scene& s) -> double& { return s.atmosphere.ozone.peak_m; }));
    r.push_back(number_key("atmosphere.ozone.top_m", "m", {0.0, 1e7}, "top of the ozone layer",
                           [](Scene& s) -> double& { return s.atmosphere.ozone.top_m; }));
    // fog
    r.push_back(
        bool_key("atmosphere.fog.enabled",
                 "fog: water droplets near the ground (Lorenz-Mie: corona, fogbow, glory; atmosphere.fog.droplets says "
                 "which) on or off",
                 [](Scene& s) -> bool& { return s.atmosphere.fog.enabled; }));
    r.push_back(
        number_key("atmosphere.fog.visibility_m", "m", {1.0, 1e5},
                   "fog: visibility at the ground (meteorological optical range, 550 nm: extinction ln 20 / V); "
                   "fog is below 1000 m",
                   [](Scene& s) -> double& { return s.atmosphere.fog.visibility_m; }));
    r.push_back(number_key("atmosphere.fog.scale_height_m", "m", {1.0, 1e5},
                           "fog: its density falls as exp(-z / H) above the ground",
                           [](Scene& s) -> double& { return s.atmosphere.fog.scale_height_m; }));
    r.push_back(choice_key(
        "atmosphere.fog.droplets", {"opac", "lognormal"},
        "fog: opac: OPAC's fog droplets (a broad distribution, mode radius 8 um: a white aureole about the sun); "
        "lognormal: droplets of about median_radius_um (geometric standard deviation radius_spread), a cloud's, "
        "whose corona shows coloured rings (both by Lorenz-Mie theory, computed once per wavelength grid and kept "
        "in the cache of tables)",
        [](Scene& s, const std::string& v) {
          s.atmosphere.fog.droplets = v == "lognormal" ? FogSpec::Droplets::Lognormal : FogSpec::Droplets::Opac;
        },
        [](const Scene& s) {
          return std::string(s.atmosphere.fog.droplets == FogSpec::Droplets::Lognormal ? "lognormal" : "opac");
        }));
    r.push_back(number_key("atmosphere.fog.median_radius_um", "um", {2.0, 25.0},
                           "fog, droplets = lognormal: the droplets' median radius (the corona's first ring stands "
                           "at about 5.14 / (2 pi r / wavelength) radians from the sun: 4.3 degrees for 6 um at "
                           "550 nm)",
                           [](Scene& s) -> double& { return s.atmosphere.fog.median_radius_um; }));
    r.push_back(number_key("atmosphere.fog.radius_spread", "", {1.01, 1.5},
                           "fog, droplets = lognormal: the geometric standard deviation of the droplets' radii (cut "
                           "at 3 of them either side); the wider, the fewer and fainter the corona's rings",
                           [](Scene& s) -> double& { return s.atmosphere.fog.radius_spread; }));
    // ice
    r.push_back(bool_key("atmosphere.ice.enabled",
                         "ice crystals near the ground (diamond dust) or in a cloud (cirrostratus): randomly oriented "
                         "hexagonal prisms, ray-traced (22 and 46 degree halos), on or off; intensity only (not with "
                         "output.polarisation)",
                         [](Scene& s) -> bool& { return s.atmosphere.ice.enabled; }));
    r.push_back(choice_key(
        "atmosphere.ice.layer", {"ground", "cloud"},
        "ice: where the crystals are: ground (diamond dust: visibility_m, scale_height_m) or cloud (cirrostratus: "
        "a layer from base_m to top_m with optical_depth; its edges fall by e every quarter of its thickness)",
        [](Scene& s, const std::string& v) {
          s.atmosphere.ice.layer = v == "cloud" ? IceSpec::Layer::Cloud : IceSpec::Layer::Ground;
        },
        [](const Scene& s) {
          return std::string(s.atmosphere.ice.layer == IceSpec::Layer::Cloud ? "cloud" : "ground");
        }));
    r.push_back(number_key("atmosphere.ice.visibility_m", "m", {1.0, 1e6},
                           "ice, layer = ground: visibility at the ground (meteorological optical range, 550 nm: the "
                           "crystals' whole extinction, diffraction included, is ln 20 / V)",
                           [](Scene& s) -> double& { return s.atmosphere.ice.visibility_m; }));
    r.push_back(number_key("atmosphere.ice.scale_height_m", "m", {1.0, 1e5},
                           "ice, layer = ground: its density falls as exp(-z / H) above the ground",
                           [](Scene& s) -> double& { return s.atmosphere.ice.scale_height_m; }));
    r.push_back(number_key("atmosphere.ice.base_m", "m", {0.0, 1e5}, "ice, layer = cloud: the layer's base",
                           [](Scene& s) -> double& { return s.atmosphere.ice.base_m; }));
    r.push_back(number_key("atmosphere.ice.top_m", "m", {1.0, 1e5},
                           "ice, layer = cloud: the layer's top (above base_m, below atmosphere.top_altitude_m)",
                           [](Scene& s) -> double& { return s.atmosphere.ice.top_m; }));
    r.push_back(number_key("atmosphere.ice.optical_depth", "", {1e-4, 10.0},
                           "ice, layer = cloud: the layer's vertical optical depth at 550 nm, diffraction included "
                           "(thin cirrostratus: about 0.03-0.3)",
                           [](Scene& s) -> double& { return s.atmosphere.ice.optical_depth; }));
    r.push_back(number_key("atmosphere.ice.aspect_ratio", "", {0.05, 20.0},
                           "ice: the prisms' length over their width across corners (columns > 1, plates < 1)",
                           [](Scene& s) -> double& { return s.atmosphere.ice.aspect_ratio; }));
    // rain
    r.push_back(bool_key("atmosphere.rain.enabled",
                         "rain: water drops (primary and secondary rainbows, Alexander's dark band, their "
                         "polarisation; atmosphere.rain.drops says which drops and how their light is computed) "
                         "on or off",
                         [](Scene& s) -> bool& { return s.atmosphere.rain.enabled; }));
    r.push_back(choice_key(
        "atmosphere.rain.drops", {"marshall-palmer", "lognormal"},
        "rain: marshall-palmer: the sizes of a rain of rate_mm_per_h by geometric optics (no supernumeraries); "
        "lognormal: drops of about median_radius_mm (geometric standard deviation radius_spread) by Lorenz-Mie "
        "theory, the bows with their supernumeraries (computed once per wavelength grid and kept in the cache of "
        "tables: docs/bows-and-halos.md gives the time)",
        [](Scene& s, const std::string& v) {
          s.atmosphere.rain.drops = v == "lognormal" ? RainSpec::Drops::Lognormal : RainSpec::Drops::MarshallPalmer;
        },
        [](const Scene& s) {
          return std::string(s.atmosphere.rain.drops == RainSpec::Drops::Lognormal ? "lognormal" : "marshall-palmer");
        }));
    r.push_back(number_key("atmosphere.rain.rate_mm_per_h", "mm/h", {0.01, 500.0},
                           "rain: rain rate R (marshall-palmer: the drops' number and sizes; lognormal: their "
                           "number, R over each drop's volume times its fall speed), hence its extinction",
                           [](Scene& s) -> double& { return s.atmosphere.rain.rate_mm_per_h; }));
    r.push_back(number_key("atmosphere.rain.median_radius_mm", "mm", {0.15, 0.5},
                           "rain, drops = lognormal: the drops' median radius (supernumeraries are widest and "
                           "clearest for small drops; below 0.15 mm the fall-speed law does not hold)",
                           [](Scene& s) -> double& { return s.atmosphere.rain.median_radius_mm; }));
    r.push_back(number_key("atmosphere.rain.radius_spread", "", {1.01, 1.2},
                           "rain, drops = lognormal: the geometric standard deviation of the drops' radii (the "
                           "distribution is cut at 3 of them either side); the wider, the fainter the "
                           "supernumeraries and the longer the drops' optics take",
                           [](Scene& s) -> double& { return s.atmosphere.rain.radius_spread; }));
    r.push_back(number_key("atmosphere.rain.scale_height_m", "m", {1.0, 1e5},
                           "rain: its density falls as exp(-z / H) above the ground",
                           [](Scene& s) -> double& { return s.atmosphere.rain.scale_height_m; }));
    r.push_back(choice_key(
        "atmosphere.rain.extent", {"everywhere", "shower"},
        "rain: everywhere: a layer over the whole planet; shower: only inside a vertical cylinder (radius "
        "shower_radius_m, its axis shower_distance_m from the reference point towards shower_azimuth_deg), so that "
        "the bows stand where the shower does, over clear sky. Every pixel is then marched (no sky-view table) and "
        "the shower's own multiple scattering computed for the camera (a few seconds); docs/bows-and-halos.md, "
        "\"A shower at a distance\", gives its accuracy",
        [](Scene& s, const std::string& v) {
          s.atmosphere.rain.extent = v == "shower" ? RainSpec::Extent::Shower : RainSpec::Extent::Everywhere;
        },
        [](const Scene& s) {
          return std::string(s.atmosphere.rain.extent == RainSpec::Extent::Shower ? "shower" : "everywhere");
        }));
    r.push_back(number_key("atmosphere.rain.shower_distance_m", "m", {0.0, 2e5},
                           "rain, extent = shower: distance from the reference point to the shower's axis (less than "
                           "its radius: the camera stands in the rain)",
                           [](Scene& s) -> double& { return s.atmosphere.rain.shower_distance_m; }));
    r.push_back(number_key("atmosphere.rain.shower_azimuth_deg", "degrees", {0.0, 360.0},
                           "rain, extent = shower: direction from the reference point to the shower's axis, clockwise "
                           "from north (a rainbow needs it opposite the sun)",
                           [](Scene& s) -> double& { return s.atmosphere.rain.shower_azimuth_deg; }));
    r.push_back(number_key("atmosphere.rain.shower_radius_m", "m", {100.0, 1e5},
                           "rain, extent = shower: the shower's radius (its walls are vertical and sharp)",
                           [](Scene& s) -> double& { return s.atmosphere.rain.shower_radius_m; }));
    // water vapour (the broadband irradiance's gas bands)
    r.push_back(
        number_key("atmosphere.water_vapour.column_cm", "cm", {0.0, 15.0},
                   "water vapour: precipitable water (the column as liquid) above the ground at altitude 0, for "
                   "the broadband irradiance's gas bands (a camera raised by a site's altitude has less above "
                   "it); 1.42 cm is ASTM G173's reference atmosphere, about 0.1 in polar air to 7 in the tropics",
                   [](Scene& s) -> double& { return s.atmosphere.water_vapour.column_cm; }));
    r.push_back(number_key("atmosphere.water_vapour.scale_height_m", "m", {100.0, 1e4},
                           "water vapour: its density falls as exp(-z / H) above the ground",
                           [](Scene& s) -> double& { return s.atmosphere.water_vapour.scale_height_m; }));
    // ground
    r.push_back(number_key("ground.albedo", "", {0.0, 1.0},
                           "Lambertian albedo of the ground (0: black); unless a preset, file or flag sets a ground "
                           "albedo, a panorama that sees below the horizon (equirectangular, min_elevation_deg < 0) "
                           "gets " +
                               format_number(kPanoramaGroundAlbedo) + " (pvlib's default ground albedo)",
                           [](Scene& s) -> double& { return s.atmosphere.ground.albedo; }));
    r.push_back(list_key("ground.albedo_wavelengths_nm", "nm", {1.0, 1e5}, 1024,
                         "spectral albedo: wavelengths (replaces ground.albedo when not empty)",
                         [](Scene& s) -> std::vector<double>& { return s.atmosphere.ground.albedo_wavelengths_nm; }));
    r.push_back(list_key("ground.albedo_values", "", {0.0, 1.0}, 1024,
                         "spectral albedo: values at ground.albedo_wavelengths_nm, linearly interpolated",
                         [](Scene& s) -> std::vector<double>& { return s.atmosphere.ground.albedo_values; }));
    // sun
    r.push_back(number_key("sun.elevation_deg", "degrees", {-90.0, 90.0}, "sun elevation above the horizon",
                           [](Scene& s) -> double& { return s.sun.elevation_deg; }));
    r.push_back(number_key("sun.azimuth_deg", "degrees", {-360.0, 360.0}, "sun azimuth, clockwise from north",
                           [](Scene& s) -> double& { return s.sun.azimuth_deg; }));
    r.push_back(choice_key(
        "sun.spectrum", {"solar", "flat"},
        "solar: measured extraterrestrial spectrum (ASTM G173-03) at sun.distance_au; "
        "flat: sun.spectral_irradiance at every wavelength",
        [](Scene& s, const std::string& v) {
          s.sun.spectrum = v == "flat" ? SunSpec::Spectrum::Flat : SunSpec::Spectrum::Solar;
        },
        [](const Scene& s) { return std::string(s.sun.spectrum == SunSpec::Spectrum::Flat ? "flat" : "solar"); }));
    r.push_back(number_key("sun.spectral_irradiance", "W m^-2 nm^-1", {0.0, 1e6, true},
                           "the flat spectrum's value (sun.spectrum = \"flat\")",
                           [](Scene& s) -> double& { return s.sun.spectral_irradiance_W_m2_nm; }));
    r.push_back(number_key("sun.distance_au", "au", {0.05, 100.0},
                           "planet-sun distance: scales the solar spectrum by (1 au / d)^2 and sets the disk's size "
                           "(Earth 0.983-1.017, Mars 1.38-1.67)",
                           [](Scene& s) -> double& { return s.sun.distance_au; }));
    r.push_back(bool_key("sun.disk", "draw the limb-darkened sun disk", [](Scene& s) -> bool& { return s.sun.disk; }));
    {
      KeyDef k;
      k.key = "sun.date_time";
      const std::string allowed =
          "\"\" or an ISO 8601 date-time with UTC offset, e.g. \"2026-06-21T20:30:00+02:00\" (quoted, or unquoted as a "
          "TOML date-time)";
      k.doc = "(" + allowed +
              ") when set, the sun's position and distance are computed for this time at "
              "location.latitude_deg / longitude_deg (NREL SPA)";
      k.set = [k, allowed](Scene& s, const toml::node& n, const std::string& origin) {
        if (const auto* when = n.as_date_time()) {  // a TOML offset date-time, unquoted
          s.sun.date_time = toml_date_time_text(when->get(), k.key, node_text(n), origin);
          return;
        }
        auto str = n.as_string();
        if (!str) throw InputError(k.key, node_text(n), allowed, origin);
        if (!str->get().empty()) {
          try {
            (void)parse_iso8601(str->get(), k.key);
          } catch (const InputError& e) {
            throw InputError(k.key, node_text(n), e.allowed(), origin);
          }
        }
        s.sun.date_time = str->get();
      };
      k.get = [](const Scene& s) {
        std::ostringstream o;
        o << toml::value<std::string>(s.sun.date_time);
        return o.str();
      };
      r.push_back(k);
    }
    r.push_back(bool_key("sun.refraction", "with sun.date_time: apparent elevation, refracted by the air",
                         [](Scene& s) -> bool& { return s.sun.refraction; }));
    r.push_back(number_key("location.latitude_deg", "degrees", {-90.0, 90.0}, "latitude of the reference point",
                           [](Scene& s) -> double& { return s.location.latitude_deg; }));
    r.push_back(number_key("location.longitude_deg", "degrees", {-180.0, 180.0},
                           "longitude of the reference point, east positive",
                           [](Scene& s) -> double& { return s.location.longitude_deg; }));
    // terrain
    r.push_back(choice_key(
        "terrain.model", names_of(terrain_models()),
        "none: the planet's sphere is the ground; ridge: a synthetic mountain ridge (terrain.ridge.*); file: "
        "heights from an elevation raster (terrain.file), around location.latitude_deg / longitude_deg; heightmap: "
        "heights from an image without georeferencing (terrain.file) at the scale terrain.heightmap.* states, "
        "centred on the reference point",
        [](Scene& s, const std::string& v) { s.terrain.model = value_named(terrain_models(), v, "terrain.model"); },
        [](const Scene& s) { return std::string(terrain_model_name(s.terrain.model)); }));
    {
      KeyDef k = text_key(
          "terrain.file",
          "model = file: a georeferenced elevation raster GDAL reads (GeoTIFF, ...), heights in metres "
          "above sea level; model = heightmap: an OpenEXR file (channel Y, Z or R, or its only channel) or "
          "another image GDAL reads (PNG, TIFF, ...; band 1), its top row north; a relative path is taken "
          "from the scene file's folder (elsewhere: from the current folder)",
          [](Scene& s) -> std::string& { return s.terrain.file; }, false);
      k.input_path = true;
      const auto written = k.get;
      k.get = [written](const Scene& s) { return s.terrain.file.empty() ? std::string() : written(s); };  // unset
      r.push_back(k);
    }
    r.push_back(
        optional_number_key("terrain.heightmap.pixel_m", "m", {1e-3, 1e5},
                            "heightmap: distance between the centres of neighbouring pixels on the ground (required)",
                            [](Scene& s) -> std::optional<double>& { return s.terrain.heightmap.pixel_m; }));
    r.push_back(number_key("terrain.heightmap.height_scale_m", "m", {-1e5, 1e5},
                           "heightmap: metres per unit of value (height = value x scale + offset); the value is "
                           "the code over 255 or 65535 for an 8- or 16-bit unsigned image (a PNG: 0 to 1), "
                           "as stored for EXR, float and signed images",
                           [](Scene& s) -> double& { return s.terrain.heightmap.height_scale_m; }));
    r.push_back(number_key("terrain.heightmap.height_offset_m", "m", {-1e4, 1e4},
                           "heightmap: metres added to every height (heights below 0 are raised to 0, the sphere)",
                           [](Scene& s) -> double& { return s.terrain.heightmap.height_offset_m; }));
    r.push_back(optional_number_key(
        "terrain.albedo", "", {0.0, 1.0},
        "Lambertian albedo of the terrain's surface (unset: the ground's, ground.albedo or ground.albedo_values); "
        "beyond the terrain's grid the ground is the sphere, with the ground's albedo",
        [](Scene& s) -> std::optional<double>& { return s.terrain.albedo; }));
    r.push_back(list_key("terrain.albedo_wavelengths_nm", "nm", {1.0, 1e5}, 1024,
                         "the terrain's spectral albedo: wavelengths (replaces terrain.albedo when not empty)",
                         [](Scene& s) -> std::vector<double>& { return s.terrain.albedo_wavelengths_nm; }));
    r.push_back(list_key("terrain.albedo_values", "", {0.0, 1.0}, 1024,
                         "the terrain's spectral albedo: values at terrain.albedo_wavelengths_nm, linearly "
                         "interpolated",
                         [](Scene& s) -> std::vector<double>& { return s.terrain.albedo_values; }));
    {
      KeyDef k = text_key(
          "terrain.albedo_map",
          "a factor in [0, 1] on the terrain's albedo at each point: model = file: a georeferenced raster GDAL "
          "reads (band 1, its scale and offset applied); model = heightmap: an image (EXR, or PNG and the others "
          "GDAL reads, 8/16-bit codes over 255/65535) spread over the height map's ground, top row north; a "
          "relative path as terrain.file's",
          [](Scene& s) -> std::string& { return s.terrain.albedo_map; }, false);
      k.input_path = true;
      const auto written = k.get;
      k.get = [written](const Scene& s) { return s.terrain.albedo_map.empty() ? std::string() : written(s); };  // unset
      r.push_back(k);
    }
    r.push_back(number_key("terrain.extent_m", "m", {100.0, 1e6},
                           "model = file, heightmap: half the side of the square read around the reference point "
                           "(a height map: no further than it reaches)",
                           [](Scene& s) -> double& { return s.terrain.extent_m; }));
    r.push_back(number_key("terrain.spacing_m", "m", {1.0, 1e5},
                           "spacing of the grid the terrain's heights are sampled on (bilinear between samples)",
                           [](Scene& s) -> double& { return s.terrain.spacing_m; }));
    r.push_back(number_key("terrain.ridge.height_m", "m", {0.0, 9000.0}, "ridge: height of its crest",
                           [](Scene& s) -> double& { return s.terrain.ridge.height_m; }));
    r.push_back(number_key("terrain.ridge.distance_m", "m", {0.0, 2e6},
                           "ridge: distance from the reference point to the crest",
                           [](Scene& s) -> double& { return s.terrain.ridge.distance_m; }));
    r.push_back(number_key("terrain.ridge.azimuth_deg", "degrees", {0.0, 360.0},
                           "ridge: direction from the reference point to the crest, clockwise from north (the crest "
                           "runs across it)",
                           [](Scene& s) -> double& { return s.terrain.ridge.azimuth_deg; }));
    r.push_back(number_key("terrain.ridge.half_width_m", "m", {1.0, 1e6},
                           "ridge: half the width of its foot (cross-section h cos^2(pi x / 2w))",
                           [](Scene& s) -> double& { return s.terrain.ridge.half_width_m; }));
    r.push_back(number_key("terrain.ridge.length_m", "m", {1.0, 2e6},
                           "ridge: length of the crest (more than twice the half width)",
                           [](Scene& s) -> double& { return s.terrain.ridge.length_m; }));
    r.push_back(number_key("terrain.ridge.notch_spacing_m", "m", {0.0, 1e6},
                           "ridge: distance between notches in the crest that let light shafts through (0: none)",
                           [](Scene& s) -> double& { return s.terrain.ridge.notch_spacing_m; }));
    r.push_back(number_key("terrain.ridge.notch_depth", "", {0.0, 1.0},
                           "ridge: depth of the notches as a share of the crest's height",
                           [](Scene& s) -> double& { return s.terrain.ridge.notch_depth; }));
    // camera
    r.push_back(choice_key(
        "camera.type", names_of(camera_types()), "projection",
        [](Scene& s, const std::string& v) { s.camera.type = value_named(camera_types(), v, "camera.type"); },
        [](const Scene& s) { return std::string(camera_type_name(s.camera.type)); }));
    r.push_back(integer_key("camera.width", 1, 65536, "image width in pixels",
                            [](Scene& s) -> int& { return s.camera.width; }));
    r.push_back(integer_key("camera.height", 1, 65536, "image height in pixels",
                            [](Scene& s) -> int& { return s.camera.height; }));
    r.push_back(vec3_key("camera.position_m", "m", kMaxLength, "camera position [east, north, height above sea level]",
                         [](Scene& s) -> Vec3& { return s.camera.position_m; }));
    r.push_back(optional_number_key("camera.above_ground_m", "m", {0.0, kMaxLength, true},
                                    "when set, the camera stands this high above the ground under it (the terrain's "
                                    "surface or the sphere), replacing camera.position_m's height",
                                    [](Scene& s) -> std::optional<double>& { return s.camera.above_ground_m; }));
    using Type = CameraSpec::Type;
    r.push_back(only_for(Type::Perspective, vec3_key("camera.look_at_m", "m", kMaxLength, "point the camera looks at",
                                                     [](Scene& s) -> Vec3& { return s.camera.look_at_m; })));
    r.push_back(only_for(Type::Perspective,
                         number_key("camera.fov_deg", "degrees", {0.0, 179.0, true}, "vertical field of view",
                                    [](Scene& s) -> double& { return s.camera.fov_deg; })));
    r.push_back(
        only_for(Type::Equirectangular, number_key("camera.min_elevation_deg", "degrees", {-90.0, 89.0},
                                                   "elevation of the bottom edge (-90: the whole sphere; 0: the upper "
                                                   "hemisphere only, as sky-dome textures are)",
                                                   [](Scene& s) -> double& { return s.camera.min_elevation_deg; })));
    r.push_back(only_for(
        Type::Equirectangular,
        choice_key(
            "camera.panorama_convention", names_of(panorama_conventions()),
            "skyspec (north at the left edge, east a quarter in), blender (Cycles' mapping with north on Blender's "
            "+Y: east at the centre) or openexr (OpenEXR's lat-long map, up +Y, north -Z); blender and openexr "
            "need min_elevation_deg = -90 (docs/other-tools.md)",
            [](Scene& s, const std::string& v) {
              s.camera.panorama_convention = value_named(panorama_conventions(), v, "camera.panorama_convention");
            },
            [](const Scene& s) { return std::string(panorama_convention_name(s.camera.panorama_convention)); })));
    // spectrum
    r.push_back(number_key("spectrum.min_nm", "nm", {1.0, 1e5}, "first wavelength",
                           [](Scene& s) -> double& { return s.spectrum.min_nm; }));
    r.push_back(number_key("spectrum.max_nm", "nm", {1.0, 1e5}, "last wavelength",
                           [](Scene& s) -> double& { return s.spectrum.max_nm; }));
    r.push_back(number_key("spectrum.step_nm", "nm", {1.0, 1e5}, "spacing of the wavelengths",
                           [](Scene& s) -> double& { return s.spectrum.step_nm; }));
    r.push_back(integer_key("spectrum.count", 0, WavelengthGrid::kMaxWavelengths,
                            "number of evenly spread wavelengths over min..max (0: use step_nm)",
                            [](Scene& s) -> int& { return s.spectrum.count; }));
    r.push_back(number_key("spectrum.bandwidth_nm", "nm", {0.0, WavelengthGrid::kMaxBandwidth_nm},
                           "each sample stands for this band around it: the solar spectrum and the ozone "
                           "cross-sections are averaged over lambda +- bandwidth/2 at every sample, whatever the "
                           "other samples are (0: taken at the sample wavelength)",
                           [](Scene& s) -> double& { return s.spectrum.bandwidth_nm; }));
    r.push_back(list_key("spectrum.wavelengths_nm", "nm", {1.0, 1e5}, WavelengthGrid::kMaxWavelengths,
                         "explicit wavelengths (replaces min/max/step when not empty)",
                         [](Scene& s) -> std::vector<double>& { return s.spectrum.wavelengths_nm; }));
    // render
    r.push_back(choice_key(
        "render.path", {"spectral", "rgb-fast"},
        "spectral: spectrum -> CIE XYZ -> RGB; rgb-fast: 3 wavelengths read directly as linear Rec.709",
        [](Scene& s, const std::string& v) {
          s.render.path = v == "rgb-fast" ? RenderSpec::Path::RgbFast : RenderSpec::Path::Spectral;
        },
        [](const Scene& s) {
          return std::string(s.render.path == RenderSpec::Path::RgbFast ? "rgb-fast" : "spectral");
        }));
    r.push_back(integer_key("render.view_segments", 1, 4096, "quadrature segments along each view ray",
                            [](Scene& s) -> int& { return s.render.view_segments; }));
    r.push_back(integer_key("render.table_altitude_samples", 8, 4096, "sun optical-depth table: altitudes",
                            [](Scene& s) -> int& { return s.render.table_altitude_samples; }));
    r.push_back(integer_key("render.table_zenith_samples", 8, 8192, "sun optical-depth table: zenith cosines",
                            [](Scene& s) -> int& { return s.render.table_zenith_samples; }));
    r.push_back(integer_key("render.threads", 0, 1024, "worker threads (0: all cores)",
                            [](Scene& s) -> int& { return s.render.threads; }));
    r.push_back(integer_key("render.scattering_orders", 1, 50,
                            "highest scattering order (1: single scattering; >= 2 adds precomputed orders)",
                            [](Scene& s) -> int& { return s.render.scattering_orders; }));
    r.push_back(integer_key("render.ms_altitude_samples", 4, 512, "multiple-scattering tables: altitudes",
                            [](Scene& s) -> int& { return s.render.ms_altitude_samples; }));
    r.push_back(integer_key("render.ms_sun_samples", 4, 1024, "multiple-scattering tables: sun zenith cosines",
                            [](Scene& s) -> int& { return s.render.ms_sun_samples; }));
    r.push_back(integer_key("render.ms_angular_degree", 0, 12,
                            "multiple-scattering tables: spherical-harmonic degree of the scattered light "
                            "(0: isotropic; 2: Rayleigh exact; more: the aerosol's forward scattering)",
                            [](Scene& s) -> int& { return s.render.ms_angular_degree; }));
    r.push_back(integer_key("render.ms_view_segments", 4, 1024,
                            "multiple-scattering tables: quadrature segments along each ray of order 2's table",
                            [](Scene& s) -> int& { return s.render.ms_view_segments; }));
    r.push_back(integer_key("render.ms_higher_order_segments", 4, 1024,
                            "multiple-scattering tables: quadrature segments along each ray of the tables of "
                            "orders 3 and up (their sources are smoother than order 2's)",
                            [](Scene& s) -> int& { return s.render.ms_higher_order_segments; }));
    r.push_back(integer_key("render.shower_passes", 0, 8,
                            "a rain shower (atmosphere.rain.extent = \"shower\"): passes that add the light its drops "
                            "scatter more than once, and the air about it and the ground below it its light, computed "
                            "for the camera (each about 5 s on 2 cores; 0: the drops scatter the clear sky's light "
                            "once, 1: twice, 2: three times, 3: four times, approximately; 6 and more change nothing)",
                            [](Scene& s) -> int& { return s.render.shower_passes; }));
    r.push_back(number_key("render.ms_forward_cone_deg", "degrees", {0.0, 90.0},
                           "multiple-scattering tables: a tabulated scattering matrix's forward peak within this "
                           "angle is cut off and travels with the unscattered light (delta-M; single scattering "
                           "keeps the uncut phase function; 0: nothing cut)",
                           [](Scene& s) -> double& { return s.render.ms_forward_cone_deg; }));
    r.push_back(choice_key(
        "render.ms_tables", {"exact", "interpolated"},
        "exact: the multiple-scattering tables built for this atmosphere; interpolated: blended, per wavelength, "
        "from the cached tables of atmospheres on a grid of Angstrom aerosol amounts and ozone columns (a dataset "
        "of many atmospheres shares their builds; docs/jobs.md measures what it errs; an atmosphere off the grid "
        "gets exact tables)",
        [](Scene& s, const std::string& v) {
          s.render.ms_tables = v == "interpolated" ? RenderSpec::Tables::Interpolated : RenderSpec::Tables::Exact;
        },
        [](const Scene& s) {
          return std::string(s.render.ms_tables == RenderSpec::Tables::Interpolated ? "interpolated" : "exact");
        }));
    r.push_back(bool_key("render.cache_tables",
                         "keep multiple-scattering tables (and a microphysical aerosol's optics) on disk "
                         "($SKYSPEC_CACHE_DIR, $XDG_CACHE_HOME/skyspec or ~/.cache/skyspec) and reuse them for the "
                         "same atmosphere",
                         [](Scene& s) -> bool& { return s.render.cache_tables; }));
    r.push_back(bool_key("render.sky_view_table",
                         "interpolate the image from a table of marched view directions where the camera is "
                         "inside the atmosphere (false: march a ray for every pixel)",
                         [](Scene& s) -> bool& { return s.render.sky_view_table; }));
    r.push_back(integer_key("render.sky_view_zenith_samples", 8, 4096,
                            "sky-view table: rows from the horizon to the zenith (half as many below it)",
                            [](Scene& s) -> int& { return s.render.sky_view_zenith_samples; }));
    r.push_back(integer_key("render.sky_view_azimuth_samples", 4, 4096,
                            "sky-view table: columns from towards the sun to away from it",
                            [](Scene& s) -> int& { return s.render.sky_view_azimuth_samples; }));
    r.push_back(integer_key("render.sky_view_higher_zenith_samples", 8, 4096,
                            "sky-view table: rows of the coarser table the higher orders' light is interpolated from "
                            "(at or above render.sky_view_zenith_samples: the table's own)",
                            [](Scene& s) -> int& { return s.render.sky_view_higher_zenith_samples; }));
    r.push_back(integer_key("render.sky_view_higher_azimuth_samples", 4, 4096,
                            "sky-view table: columns of that coarser table (at or above "
                            "render.sky_view_azimuth_samples: the table's own)",
                            [](Scene& s) -> int& { return s.render.sky_view_higher_azimuth_samples; }));
    // output
    r.push_back(text_key(
        "output.directory", "folder for the output files", [](Scene& s) -> std::string& { return s.output.directory; },
        false));
    r.push_back(text_key(
        "output.name", "base name of the output files (<name>.exr, <name>.png)",
        [](Scene& s) -> std::string& { return s.output.name; }, true));
    r.push_back(bool_key("output.exr", "write the spectral OpenEXR", [](Scene& s) -> bool& { return s.output.exr; }));
    r.push_back(bool_key("output.png", "write the sRGB PNG preview", [](Scene& s) -> bool& { return s.output.png; }));
    r.push_back(
        bool_key("output.polarisation",
                 "polarised sky: Stokes S1-S3 per wavelength in the spectral EXR beside S0, and "
                 "<name>-polarisation.exr with the luminance-weighted Y, DoLP and AoLP (vector transport for "
                 "the air, aerosols as unit scattering matrices; 1.8-3.5 times the render time, 4-5 times the EXR; "
                 "needs render.ms_angular_degree >= 2 with multiple scattering)",
                 [](Scene& s) -> bool& { return s.output.polarisation; }));
    r.push_back(bool_key("output.polarisation_png",
                         "with output.polarisation and output.png: also <name>-polarisation.png, the angle of linear "
                         "polarisation as hue (a colour wheel over 180 degrees) and its degree as brightness",
                         [](Scene& s) -> bool& { return s.output.polarisation_png; }));
    r.push_back(bool_key("output.surface",
                         "also <name>-surface.exr: per pixel Z, the distance in metres along its ray to the surface it "
                         "ends on (0 for the sky), and mask.terrain and mask.ground (1 where that surface is the "
                         "terrain or the planet's ground), for compositing",
                         [](Scene& s) -> bool& { return s.output.surface; }));
    r.push_back(choice_key(
        "output.exr_compression", {"piz", "zip", "zips", "rle", "none"},
        "lossless compression of the spectral EXR: piz (wavelet, smallest and fastest to write for sky "
        "images), zip (16 rows per block), zips (1 row), rle, none",
        [](Scene& s, const std::string& v) { s.output.exr_compression = v; },
        [](const Scene& s) { return s.output.exr_compression; }));
    r.push_back(choice_key(
        "output.exr_spectral_type", {"float", "half"},
        "pixel type of the spectral EXR's S0 channels: float (32 bits, exact) or half (16 bits: half the data, a "
        "relative error of at most 2^-11 from 6.1e-5 up, values above 65504 refused; R, G, B stay float)",
        [](Scene& s, const std::string& v) { s.output.exr_spectral_type = v; },
        [](const Scene& s) { return s.output.exr_spectral_type; }));
    {
      KeyDef k;
      k.key = "output.exposure_ev";
      const std::string allowed = "a number of stops from -64 to 64";
      k.doc = "(" + allowed + ") preview exposure: pixel values are multiplied by 2^EV (automatic when absent)";
      k.set = [k, allowed](Scene& s, const toml::node& n, const std::string& origin) {
        const double v = get_number(k, n, origin, allowed);
        if (!std::isfinite(v) || v < -64 || v > 64) throw InputError(k.key, node_text(n), allowed, origin);
        s.output.exposure_ev = v;
      };
      k.get = [](const Scene& s) { return s.output.exposure_ev ? exact_number(*s.output.exposure_ev) : std::string(); };
      r.push_back(k);
    }
    // irradiance
    r.push_back(
        bool_key("irradiance.broadband",
                 "irradiance outputs (skyspec irradiance, a job's irradiance tables, the render summary) "
                 "also give the broadband irradiance, 300-4000 nm, with the gases' absorption bands (water vapour "
                 "and the mixed gases, Bird & Riordan's band model): the light transport solved five more "
                 "times on 122 wavelengths (docs/jobs.md, \"Irradiance and pyranometers\")",
                 [](Scene& s) -> bool& { return s.irradiance.broadband; }));
    add_conditions(r);
    return r;
  }();
  return keys;
}

const KeyDef* find_key(const std::string& key) {
  for (const auto& k : registry())
    if (k.key == key) return &k;
  return nullptr;
}

[[noreturn]] void unknown_key(const std::string& key, const std::string& origin) {
  std::string best;
  size_t best_d = std::numeric_limits<size_t>::max();
  for (const auto& k : registry()) {
    // Compare with the full key and with its last component (a key in the wrong table).
    const size_t d = edit_distance(key, k.key);
    const std::string leaf = k.key.substr(k.key.rfind('.') + 1);
    const std::string key_leaf = key.substr(key.rfind('.') + 1);
    const size_t d2 = key_leaf == leaf ? 1 : d;
    if (std::min(d, d2) < best_d) {
      best_d = std::min(d, d2);
      best = k.key;
    }
  }
  std::string hint;
  if (best_d <= std::max<size_t>(3, key.size() / 3)) hint += " (did you mean \"" + best + "\"?)";
  hint += "; `skyspec render --help-keys` lists the known keys";
  throw InputError::unknown_key(key, hint, origin);
}

}  // namespace skyspec::scene_keys
