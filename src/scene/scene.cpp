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

#include "physics/date_time.hpp"
#include "physics/ozone.hpp"
#include "physics/solar_spectrum.hpp"
#include "physics/solar_position.hpp"
#include "base/embedded_data.hpp"
#include "skyspec/error.hpp"
#include "base/text_format.hpp"
#include "scene/toml_limits.hpp"
#include "skyspec/refractive_index.hpp"
#include "skyspec/units.hpp"

namespace skyspec {
namespace {

// ---------------------------------------------------------------------------------------------
// Value formatting

std::string node_text(const toml::node& n) {
  std::ostringstream s;
  if (auto str = n.as_string()) {
    s << '"' << str->get() << '"';
  } else if (auto arr = n.as_array()) {
    s << *arr;
  } else if (n.is_table()) {
    s << "(a table)";
  } else {
    n.visit([&](auto&& v) { s << v; });
  }
  return s.str();
}

std::string origin_of(const toml::node& n, const std::string& fallback) {
  const auto& src = n.source();
  if (src.begin.line == 0) return fallback;
  std::ostringstream s;
  s << (src.path ? *src.path : fallback) << ":" << src.begin.line << ":" << src.begin.column;
  return s.str();
}

std::string origin_of_key(const toml::key& k, const std::string& fallback) {
  const auto& src = k.source();
  if (src.begin.line == 0) return fallback;
  std::ostringstream s;
  s << (src.path ? *src.path : fallback) << ":" << src.begin.line << ":" << src.begin.column;
  return s.str();
}

// A number for scene_to_toml that reads back as exactly the stored value: the shortest of 10 to 17
// significant digits whose value times scale is stored_value (so a scene written into a file's
// header and loaded again is the same scene, bit for bit).
std::string exact_number(double stored_value, double scale = 1.0) {
  std::string text;
  for (int digits = 10; digits <= 17; ++digits) {
    std::ostringstream s;
    s << std::setprecision(digits) << stored_value / scale;
    text = s.str();
    if (std::strtod(text.c_str(), nullptr) * scale == stored_value) break;
  }
  return text;
}

// Levenshtein distance, for "did you mean".
size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

// ---------------------------------------------------------------------------------------------
// The key registry: one entry per scene key, with its unit, range, setter and getter.

struct KeyDef {
  std::string key;
  std::string doc;  // "(unit, range) help"
  std::function<void(Scene&, const toml::node&, const std::string& origin)> set;
  std::function<std::string(const Scene&)> get;  // TOML value text
  bool text = false;  // the value is a string (a flag's bare word is taken as one, even "nan" or "1")
};

double get_number(const KeyDef& k, const toml::node& n, const std::string& origin, const std::string& allowed) {
  if (auto i = n.as_integer()) return static_cast<double>(i->get());
  if (auto f = n.as_floating_point()) return f->get();
  throw InputError(k.key, node_text(n), allowed, origin);
}

struct Range {
  double lo, hi;
  bool lo_open = false;
  std::string describe(const std::string& unit) const {
    std::ostringstream s;
    s << "a number" << (unit.empty() ? "" : " in " + unit) << ", " << (lo_open ? "> " : ">= ") << format_number(lo)
      << " and <= " << format_number(hi);
    return s.str();
  }
  bool contains(double v) const { return std::isfinite(v) && (lo_open ? v > lo : v >= lo) && v <= hi; }
};

// scale: the stored value is the entered value times scale (e.g. ppm -> parts per volume).
KeyDef number_key(std::string key, std::string unit, Range range, std::string help,
                  std::function<double&(Scene&)> ref, double scale = 1.0) {
  KeyDef k;
  k.key = std::move(key);
  const std::string allowed = range.describe(unit);
  k.doc = "(" + allowed + ") " + help;
  k.set = [k, allowed, range, ref, scale](Scene& s, const toml::node& n, const std::string& origin) {
    const double v = get_number(k, n, origin, allowed);
    if (!range.contains(v)) throw InputError(k.key, node_text(n), allowed, origin);
    ref(s) = v * scale;
  };
  k.get = [ref, scale](const Scene& s) { return exact_number(ref(const_cast<Scene&>(s)), scale); };
  return k;
}

KeyDef integer_key(std::string key, long lo, long hi, std::string help, std::function<int&(Scene&)> ref) {
  KeyDef k;
  k.key = std::move(key);
  const std::string allowed = "a whole number from " + std::to_string(lo) + " to " + std::to_string(hi);
  k.doc = "(" + allowed + ") " + help;
  k.set = [k, allowed, lo, hi, ref](Scene& s, const toml::node& n, const std::string& origin) {
    auto i = n.as_integer();
    if (!i || i->get() < lo || i->get() > hi) throw InputError(k.key, node_text(n), allowed, origin);
    ref(s) = static_cast<int>(i->get());
  };
  k.get = [ref](const Scene& s) { return std::to_string(ref(const_cast<Scene&>(s))); };
  return k;
}

KeyDef bool_key(std::string key, std::string help, std::function<bool&(Scene&)> ref) {
  KeyDef k;
  k.key = std::move(key);
  k.doc = "(true or false) " + help;
  k.set = [k, ref](Scene& s, const toml::node& n, const std::string& origin) {
    auto b = n.as_boolean();
    if (!b) throw InputError(k.key, node_text(n), "true or false", origin);
    ref(s) = b->get();
  };
  k.get = [ref](const Scene& s) { return ref(const_cast<Scene&>(s)) ? std::string("true") : std::string("false"); };
  return k;
}

std::string join(const std::vector<std::string>& v, const std::string& sep) {
  std::string out;
  for (size_t i = 0; i < v.size(); ++i) out += (i ? sep : "") + v[i];
  return out;
}

// A string chosen from a list; conversion to the scene's type is done by the callbacks.
KeyDef choice_key(std::string key, std::vector<std::string> choices, std::string help,
                  std::function<void(Scene&, const std::string&)> set_value,
                  std::function<std::string(const Scene&)> get_value) {
  KeyDef k;
  k.key = std::move(key);
  k.text = true;
  const std::string allowed = "one of: " + join(choices, ", ");
  k.doc = "(" + allowed + ") " + help;
  k.set = [k, allowed, choices, set_value](Scene& s, const toml::node& n, const std::string& origin) {
    auto str = n.as_string();
    if (!str || std::find(choices.begin(), choices.end(), str->get()) == choices.end())
      throw InputError(k.key, node_text(n), allowed, origin);
    set_value(s, str->get());
  };
  k.get = [get_value](const Scene& s) { return "\"" + get_value(s) + "\""; };
  return k;
}

KeyDef text_key(std::string key, std::string help, std::function<std::string&(Scene&)> ref,
                bool file_name_only) {
  KeyDef k;
  k.key = std::move(key);
  k.text = true;
  const std::string allowed = file_name_only ? "a non-empty file name without '/' (letters, digits, '-', '_', '.')"
                                             : "a non-empty path";
  k.doc = "(" + allowed + ") " + help;
  k.set = [k, allowed, ref, file_name_only](Scene& s, const toml::node& n, const std::string& origin) {
    auto str = n.as_string();
    if (!str || str->get().empty()) throw InputError(k.key, node_text(n), allowed, origin);
    if (file_name_only) {
      const std::string& v = str->get();
      const bool ok = v != "." && v != ".." && std::all_of(v.begin(), v.end(), [](char c) {
                        return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
                      });
      if (!ok) throw InputError(k.key, node_text(n), allowed, origin);
    }
    ref(s) = str->get();
  };
  k.get = [ref](const Scene& s) {
    std::ostringstream o;
    o << toml::value<std::string>(ref(const_cast<Scene&>(s)));
    return o.str();
  };
  return k;
}

KeyDef vec3_key(std::string key, std::string unit, double bound, std::string help, std::function<Vec3&(Scene&)> ref) {
  KeyDef k;
  k.key = std::move(key);
  const std::string allowed = "an array of 3 numbers in " + unit + ", each within +-" + format_number(bound);
  k.doc = "(" + allowed + ") " + help;
  k.set = [k, allowed, bound, ref](Scene& s, const toml::node& n, const std::string& origin) {
    auto arr = n.as_array();
    if (!arr || arr->size() != 3) throw InputError(k.key, node_text(n), allowed, origin);
    Vec3 v;
    for (size_t i = 0; i < 3; ++i) {
      const double x = get_number(k, *arr->get(i), origin, allowed);
      if (!std::isfinite(x) || std::abs(x) > bound) throw InputError(k.key, node_text(n), allowed, origin);
      v[static_cast<int>(i)] = x;
    }
    ref(s) = v;
  };
  k.get = [ref](const Scene& s) {
    const Vec3& v = ref(const_cast<Scene&>(s));
    return "[" + exact_number(v[0]) + ", " + exact_number(v[1]) + ", " + exact_number(v[2]) + "]";
  };
  return k;
}

KeyDef list_key(std::string key, std::string unit, Range range, size_t max_count, std::string help,
                std::function<std::vector<double>&(Scene&)> ref) {
  KeyDef k;
  k.key = std::move(key);
  const std::string allowed = "an array of up to " + std::to_string(max_count) + " numbers, each " +
                              range.describe(unit).substr(std::string("a number").size() + 2);
  k.doc = "(" + allowed + ") " + help;
  k.set = [k, allowed, range, max_count, ref](Scene& s, const toml::node& n, const std::string& origin) {
    auto arr = n.as_array();
    if (!arr || arr->size() > max_count) throw InputError(k.key, node_text(n), allowed, origin);
    std::vector<double> v;
    for (size_t i = 0; i < arr->size(); ++i) {
      const double x = get_number(k, *arr->get(i), origin, allowed);
      if (!range.contains(x)) throw InputError(k.key, node_text(n), allowed, origin);
      v.push_back(x);
    }
    ref(s) = v;
  };
  k.get = [ref](const Scene& s) {
    const auto& v = ref(const_cast<Scene&>(s));
    std::string out = "[";
    for (size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + exact_number(v[i]);
    return out + "]";
  };
  return k;
}

// A TOML date-time (RFC 3339, unquoted in a scene file or after --set) as ISO 8601 text. It must
// carry its UTC offset: a local date-time, a date or a time alone names no instant.
std::string toml_date_time_text(const toml::date_time& t, const std::string& key, const std::string& value,
                                const std::string& origin) {
  if (!t.offset)
    throw InputError(key, value,
                     "a date-time with its UTC offset: add Z for UTC or the zone's offset such as +02:00 (a bare "
                     "local time is ambiguous)",
                     origin);
  DateTime d;
  d.year = t.date.year;
  d.month = t.date.month;
  d.day = t.date.day;
  d.hour = t.time.hour;
  d.minute = t.time.minute;
  d.second = t.time.second + t.time.nanosecond * 1e-9;
  d.utc_offset_hours = t.offset->minutes / 60.0;
  try {
    validate(d, key);
  } catch (const InputError& e) {
    throw InputError(key, value, e.allowed(), origin);
  }
  return to_iso8601(d);
}

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
            ref(s) = v == "us1976" ? ProfileKind::UsStandard1976
                                   : v == "constant" ? ProfileKind::Constant : ProfileKind::Exponential;
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
    r.push_back(profile_key("atmosphere.rayleigh.profile",
                            [](Scene& s) -> ProfileKind& { return s.atmosphere.rayleigh.profile; },
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
          s.atmosphere.rayleigh.derivation.formula = parse_refractive_index_formula(v, "atmosphere.rayleigh.refractive_index");
        },
        [](const Scene& s) { return to_string(s.atmosphere.rayleigh.derivation.formula); }));
    r.push_back(number_key("atmosphere.rayleigh.co2_ppm", "ppm", {0.0, 1e6},
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
    r.push_back(profile_key("atmosphere.mie.profile", [](Scene& s) -> ProfileKind& { return s.atmosphere.mie.profile; },
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
    r.push_back(list_key("atmosphere.mie.table_extinction_efficiency", "", {0.0, 1e6}, 1024,
                         "spectral aerosol tables: extinction efficiency Q (any scale)",
                         [](Scene& s) -> std::vector<double>& { return s.atmosphere.mie.table_extinction_efficiency; }));
    r.push_back(list_key("atmosphere.mie.table_single_scattering_albedo", "", {1e-6, 1.0}, 1024,
                         "spectral aerosol tables: single-scattering albedo",
                         [](Scene& s) -> std::vector<double>& { return s.atmosphere.mie.table_single_scattering_albedo; }));
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
    // ground
    r.push_back(number_key("ground.albedo", "", {0.0, 1.0},
                           "Lambertian albedo of the ground (0: black); unless a preset, file or flag sets a ground "
                           "albedo, a panorama that sees below the horizon (equirectangular, min_elevation_deg < 0) "
                           "gets " + format_number(kPanoramaGroundAlbedo) + " (pvlib's default ground albedo)",
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
      k.doc = "(" + allowed + ") when set, the sun's position and distance are computed for this time at "
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
    // camera
    r.push_back(choice_key(
        "camera.type", names_of(camera_types()), "projection",
        [](Scene& s, const std::string& v) { s.camera.type = value_named(camera_types(), v, "camera.type"); },
        [](const Scene& s) { return std::string(camera_type_name(s.camera.type)); }));
    r.push_back(integer_key("camera.width", 1, 65536, "image width in pixels",
                            [](Scene& s) -> int& { return s.camera.width; }));
    r.push_back(integer_key("camera.height", 1, 65536, "image height in pixels",
                            [](Scene& s) -> int& { return s.camera.height; }));
    r.push_back(vec3_key("camera.position_m", "m", kMaxLength,
                         "camera position [east, north, height above sea level]",
                         [](Scene& s) -> Vec3& { return s.camera.position_m; }));
    r.push_back(vec3_key("camera.look_at_m", "m", kMaxLength, "perspective: point the camera looks at",
                         [](Scene& s) -> Vec3& { return s.camera.look_at_m; }));
    r.push_back(number_key("camera.fov_deg", "degrees", {0.0, 179.0, true}, "perspective: vertical field of view",
                           [](Scene& s) -> double& { return s.camera.fov_deg; }));
    r.push_back(number_key("camera.min_elevation_deg", "degrees", {-90.0, 89.0},
                           "equirectangular: elevation of the bottom edge (-90: the whole sphere; 0: the upper "
                           "hemisphere only, as sky-dome textures are)",
                           [](Scene& s) -> double& { return s.camera.min_elevation_deg; }));
    r.push_back(choice_key(
        "camera.panorama_convention", names_of(panorama_conventions()),
        "equirectangular: skyspec (north at the left edge, east a quarter in), blender (Cycles' mapping with north "
        "on Blender's +Y: east at the centre) or openexr (OpenEXR's lat-long map, up +Y, north -Z); blender and "
        "openexr need min_elevation_deg = -90 (docs/other-tools.md)",
        [](Scene& s, const std::string& v) {
          s.camera.panorama_convention = value_named(panorama_conventions(), v, "camera.panorama_convention");
        },
        [](const Scene& s) { return std::string(panorama_convention_name(s.camera.panorama_convention)); }));
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
        [](const Scene& s) { return std::string(s.render.path == RenderSpec::Path::RgbFast ? "rgb-fast" : "spectral"); }));
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
    r.push_back(bool_key("render.cache_tables",
                         "keep multiple-scattering tables on disk ($SKYSPEC_CACHE_DIR, $XDG_CACHE_HOME/skyspec or "
                         "~/.cache/skyspec) and reuse them for the same atmosphere",
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
    // output
    r.push_back(text_key("output.directory", "folder for the output files",
                         [](Scene& s) -> std::string& { return s.output.directory; }, false));
    r.push_back(text_key("output.name", "base name of the output files (<name>.exr, <name>.png)",
                         [](Scene& s) -> std::string& { return s.output.name; }, true));
    r.push_back(bool_key("output.exr", "write the spectral OpenEXR", [](Scene& s) -> bool& { return s.output.exr; }));
    r.push_back(bool_key("output.png", "write the sRGB PNG preview", [](Scene& s) -> bool& { return s.output.png; }));
    r.push_back(bool_key("output.polarisation",
                         "polarised sky: Stokes S1-S3 per wavelength in the spectral EXR beside S0, and "
                         "<name>-polarisation.exr with the luminance-weighted Y, DoLP and AoLP (vector transport for "
                         "the air, aerosols as unit scattering matrices; 1.8-3.5 times the render time, 4-5 times the EXR; "
                         "needs render.ms_angular_degree >= 2 with multiple scattering)",
                         [](Scene& s) -> bool& { return s.output.polarisation; }));
    r.push_back(bool_key("output.polarisation_png",
                         "with output.polarisation and output.png: also <name>-polarisation.png, the angle of linear "
                         "polarisation as hue (a colour wheel over 180 degrees) and its degree as brightness",
                         [](Scene& s) -> bool& { return s.output.polarisation_png; }));
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

void apply_table(Scene& scene, const toml::table& tbl, const std::string& prefix, const std::string& fallback_origin,
                 std::set<std::string>& applied) {
  for (const auto& [k, node] : tbl) {
    const std::string key = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    if (auto sub = node.as_table()) {
      // A table is a group of keys, unless the registry has no key below it.
      bool any = false;
      for (const auto& def : registry())
        if (def.key.rfind(key + ".", 0) == 0) any = true;
      if (!any) unknown_key(key, origin_of_key(k, fallback_origin));
      apply_table(scene, *sub, key, fallback_origin, applied);
      continue;
    }
    const KeyDef* def = find_key(key);
    if (!def) unknown_key(key, origin_of_key(k, fallback_origin));
    def->set(scene, node, origin_of(node, fallback_origin));
    applied.insert(key);
  }
}

toml::table parse_toml(const std::string& text, const std::string& origin) {
  check_toml_limits(text, "scene file", origin);  // before the (recursive) parser sees it
  try {
    return toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    std::ostringstream s;
    s << origin << ":" << e.source().begin.line << ":" << e.source().begin.column << ": not valid TOML: "
      << e.description();
    throw InputError("scene file", origin, "valid TOML (" + std::string(e.description()) + ")",
                     origin + ":" + std::to_string(e.source().begin.line) + ":" +
                         std::to_string(e.source().begin.column));
  }
}

// The Blender and OpenEXR lat-long conventions map the whole image to the whole sphere.
void check_panorama(const CameraSpec& c) {
  if (c.panorama_convention == PanoramaConvention::Skyspec) return;
  const std::string name = panorama_convention_name(c.panorama_convention);
  if (c.min_elevation_deg != -90.0)
    throw InputError("camera.min_elevation_deg", format_number(c.min_elevation_deg),
                     "-90 with camera.panorama_convention = \"" + name +
                         "\" (its lat-long map covers the whole sphere; a partial panorama takes the skyspec convention)");
  if (c.panorama_convention == PanoramaConvention::OpenExr && (c.width < 2 || c.height < 2))
    throw InputError("camera.width x camera.height", std::to_string(c.width) + "x" + std::to_string(c.height),
                     "at least 2x2 pixels with camera.panorama_convention = \"openexr\" (its first and last pixel "
                     "centres are the poles and the seam)");
}

bool sees_below_horizon_as_panorama(const CameraSpec& c) {
  return c.type == CameraSpec::Type::Equirectangular && c.min_elevation_deg < 0.0;
}

bool ground_albedo_given(const std::set<std::string>& given) {
  for (const char* key : {"ground.albedo", "ground.albedo_wavelengths_nm", "ground.albedo_values"})
    if (given.count(key)) return true;
  return false;
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
                         (std::filesystem::is_directory(status) ? "a folder" : std::filesystem::is_fifo(status) ? "a FIFO" : "not a regular file") + ")");
  std::string text;
  {
    FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw InputError(kSceneFileSetting, "\"" + path + "\"", "a readable TOML scene file (" + std::string(std::strerror(errno)) + ")");
    char buf[65536];
    size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) {
      text.append(buf, n);
      if (text.size() > kMaxTomlBytes) {
        std::fclose(f);
        throw InputError(kSceneFileSetting, "\"" + path + "\"", "a scene file of at most " + std::to_string(kMaxTomlBytes >> 20) + " MiB");
      }
    }
    std::fclose(f);
  }
  apply_toml(text, path);
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
}

namespace {
// The wavelengths a spectral render can take: where every built-in table the scene uses is
// defined. Colour (XYZ, RGB, PNG) integrates over the grid's overlap with the CIE colour-matching
// functions (360-830 nm), so it sets no limit here.
struct SpectralLimit {
  double min_nm, max_nm;
  std::string reason;
};
// The refractive index of air bounds any derivation of air's Rayleigh coefficients.
std::optional<SpectralLimit> refractive_index_limit(const Scene& s) {
  if (s.atmosphere.rayleigh.source != RayleighSpec::Source::Derived ||
      s.atmosphere.rayleigh.derivation.gas != ScatteringGas::Air)
    return std::nullopt;
  const RefractiveIndexValidity v = validity(s.atmosphere.rayleigh.derivation.formula);
  return SpectralLimit{v.min_nm, v.max_nm, "the refractive index of air: " + v.reason};
}
std::vector<SpectralLimit> spectral_limits(const Scene& s) {
  std::vector<SpectralLimit> limits;
  if (const auto air = refractive_index_limit(s)) limits.push_back(*air);
  if (s.sun.spectrum == SunSpec::Spectrum::Solar) {
    const TabulatedSpectrum& sun = solar_irradiance_table();
    limits.push_back({sun.min_nm(), sun.max_nm(), "the extraterrestrial solar spectrum (ASTM G173-03, sun.spectrum = \"solar\")"});
  }
  const OzoneSpec& o3 = s.atmosphere.ozone;
  if (o3.enabled && o3.cross_section_m2.empty()) {
    const TabulatedSpectrum& table = ozone_cross_section_table();
    limits.push_back({table.min_nm(), table.max_nm(),
                      "the built-in ozone cross-sections (laboratory data at 233 K; ozone.enabled = true)"});
  }
  return limits;
}

void check_limits(const WavelengthGrid& grid, const std::vector<SpectralLimit>& limits, const std::string& what) {
  double lo = 0.0, hi = std::numeric_limits<double>::infinity();
  std::string lo_reason, hi_reason;
  for (const SpectralLimit& l : limits) {
    if (l.min_nm > lo) lo = l.min_nm, lo_reason = l.reason;
    if (l.max_nm < hi) hi = l.max_nm, hi_reason = l.reason;
  }
  if (grid.min_nm() >= lo && grid.max_nm() <= hi) return;
  if (lo_reason == hi_reason)
    throw InputError("spectrum", grid.describe(),
                     "wavelengths from " + format_number(lo) + " to " + format_number(hi) + " nm" + what + ": " + lo_reason);
  throw InputError("spectrum", grid.describe(),
                   "wavelengths from " + format_number(lo) + " nm (" + lo_reason + ") to " + format_number(hi) + " nm (" +
                       hi_reason + ")" + what);
}

void check_refractive_index_range(const Scene& s, const WavelengthGrid& grid) {
  if (const auto air = refractive_index_limit(s)) check_limits(grid, {*air}, "");
}
}  // namespace

void check_spectral_range(const Scene& s, const WavelengthGrid& grid) {
  if (grid.size() < 2)
    throw InputError("spectrum", grid.describe(), "at least 2 wavelengths when render.path = \"spectral\"");
  check_limits(grid, spectral_limits(s), " when render.path = \"spectral\"");
}

Scene SceneLoader::finish(SceneUse use) const {
  Scene s = scene_;
  const double R = s.atmosphere.planet_radius_m;
  // Camera: not inside the planet.
  const Vec3 world = Vec3(s.camera.position_m.x(), s.camera.position_m.y(), R + s.camera.position_m.z());
  if (world.norm() < R)
    throw InputError("camera.position_m",
                     "[" + format_number(s.camera.position_m.x()) + ", " + format_number(s.camera.position_m.y()) + ", " +
                         format_number(s.camera.position_m.z()) + "]",
                     "a position on or above the ground (this one is " + format_number(R - world.norm()) + " m below it)");
  if (s.camera.type == CameraSpec::Type::Perspective && (s.camera.look_at_m - s.camera.position_m).norm() < 1e-6)
    throw InputError("camera.look_at_m", "the camera position", "a point different from camera.position_m");
  if (static_cast<double>(s.camera.width) * s.camera.height > 1.0e9)
    throw InputError("camera.width x camera.height", std::to_string(s.camera.width) + "x" + std::to_string(s.camera.height),
                     "at most 1e9 pixels");
  if (s.camera.type == CameraSpec::Type::Equirectangular) check_panorama(s.camera);
  if (sees_below_horizon_as_panorama(s.camera) && !ground_albedo_given(given_)) s.atmosphere.ground.albedo = kPanoramaGroundAlbedo;
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
        throw InputError(key, std::to_string(size) + " values",
                         "one value per entry of atmosphere.mie.table_wavelengths_nm (" + std::to_string(n_table) + ")");
    for (size_t i = 1; i < n_table; ++i)
      if (!(mie.table_wavelengths_nm[i] > mie.table_wavelengths_nm[i - 1]))
        throw InputError("atmosphere.mie.table_wavelengths_nm", format_number(mie.table_wavelengths_nm[i]),
                         "strictly increasing wavelengths");
  }
  const auto& gr = s.atmosphere.ground;
  if (gr.albedo_wavelengths_nm.size() != gr.albedo_values.size())
    throw InputError("ground.albedo_values", std::to_string(gr.albedo_values.size()) + " values",
                     "one value per entry of ground.albedo_wavelengths_nm (" +
                         std::to_string(gr.albedo_wavelengths_nm.size()) + ")");
  for (size_t i = 1; i < gr.albedo_wavelengths_nm.size(); ++i)
    if (!(gr.albedo_wavelengths_nm[i] > gr.albedo_wavelengths_nm[i - 1]))
      throw InputError("ground.albedo_wavelengths_nm", format_number(gr.albedo_wavelengths_nm[i]),
                       "strictly increasing wavelengths");
  if (s.output.polarisation_png && !s.output.polarisation)
    throw InputError("output.polarisation_png", "true", "false unless output.polarisation = true (it draws the polarisation)");
  if (s.output.polarisation && s.render.scattering_orders >= 2 && s.render.ms_angular_degree < 2)
    throw InputError("render.ms_angular_degree", std::to_string(s.render.ms_angular_degree),
                     "2 or more with output.polarisation = true and multiple scattering (the polarisation of light "
                     "scattered more than once comes from its field's quadrupole; the draft quality's 0 has none)");
  // Grid and colour path.
  const WavelengthGrid grid = make_wavelength_grid(s);
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

std::string scene_to_toml(const Scene& scene, SceneTomlKeys keys) {
  const Scene& s = scene;
  std::map<std::string, std::vector<std::pair<std::string, std::string>>> tables;
  std::vector<std::string> order;
  for (const auto& k : registry()) {
    if (keys == SceneTomlKeys::Recorded &&
        (k.key == "output.directory" || k.key == "output.name" || k.key == "render.threads"))
      continue;
    const std::string value = k.get(s);
    if (value.empty()) continue;
    const auto dot = k.key.rfind('.');
    const std::string table = k.key.substr(0, dot), leaf = k.key.substr(dot + 1);
    if (!tables.count(table)) order.push_back(table);
    tables[table].push_back({leaf, value});
  }
  std::ostringstream out;
  for (const auto& t : order) {
    out << "[" << t << "]\n";
    for (const auto& [leaf, value] : tables[t]) out << leaf << " = " << value << "\n";
    out << "\n";
  }
  return out.str();
}

std::vector<std::pair<std::string, std::string>> scene_key_help() {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& k : registry()) out.push_back({k.key, k.doc});
  return out;
}

namespace {
// A key's documentation is "(allowed values) meaning": split at the parenthesis that closes the first.
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

}  // namespace

std::string scene_keys_markdown() {
  const Scene defaults = default_scene();
  std::ostringstream out;
  out << "# Scene keys\n\n"
      << "Generated from the key registry (src/scene/scene.cpp) by `skyspec render --help-keys=markdown`;\n"
      << "do not edit by hand. A scene file (TOML) or `--set KEY=VALUE` sets these; the default is the\n"
      << "built-in default scene (data/scenes/default.toml, equal to `Scene{}`). Values outside the allowed\n"
      << "range are refused with a message naming the key.\n\n"
      << "| key | default | allowed | meaning |\n|---|---|---|---|\n";
  for (const auto& k : registry()) {
    const auto [allowed, meaning] = split_doc(k.doc);
    std::string value = k.get(defaults);
    if (value.empty()) value = "(none)";
    out << "| `" << k.key << "` | " << markdown_cell(value) << " | " << markdown_cell(allowed) << " | "
        << markdown_cell(meaning) << " |\n";
  }
  return out.str();
}

Scene default_scene() { return SceneLoader("default").finish(); }

}  // namespace skyspec
