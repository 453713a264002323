// The `skyspec` Python module: the coefficient derivation (NumPy arrays), the report in every
// format, the U.S. Standard Atmosphere 1976 and rendering into NumPy arrays. A thin layer over the
// C++ library: scenes are loaded by the same SceneLoader as the CLI, so presets, scene files and
// key overrides are validated the same way, and errors name the key (ValueError for bad input,
// OSError for files).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <Eigen/Core>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "base/text_format.hpp"
#include "skyspec/coefficient_report.hpp"
#include "skyspec/colour.hpp"
#include "skyspec/error.hpp"
#include "skyspec/rayleigh.hpp"
#include "skyspec/refractive_index.hpp"
#include "skyspec/render.hpp"
#include "skyspec/scene.hpp"
#include "skyspec/standard_atmosphere.hpp"
#include "skyspec/units.hpp"
#include "skyspec/version.hpp"

namespace py = pybind11;
using namespace skyspec;

namespace {

constexpr double kPpvPerPpm = 1.0e-6;

// ---- scenes from Python arguments -----------------------------------------------------------

std::string toml_string(const std::string& s) {
  std::string out = "\"";
  for (char ch : s) {
    switch (ch) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default: out += ch;
    }
  }
  return out + "\"";
}

/// A Python value as TOML value text: bool, int, float, str, or a sequence of them.
std::string toml_value(const py::handle& v, const std::string& key) {
  if (py::isinstance<py::bool_>(v)) return v.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(v)) return toml_string(v.cast<std::string>());
  if (py::isinstance<py::int_>(v)) return py::str(v).cast<std::string>();
  const bool is_sequence = py::isinstance<py::sequence>(v) || (py::isinstance<py::array>(v) && py::hasattr(v, "__len__"));
  if (!is_sequence && py::hasattr(v, "__float__")) {  // float, NumPy scalars
    PyObject* as_float = PyNumber_Float(v.ptr());
    if (!as_float) throw py::error_already_set();
    const double d = py::reinterpret_steal<py::object>(as_float).cast<double>();
    return py::repr(py::float_(d)).cast<std::string>();
  }
  if (is_sequence) {
    std::string out = "[";
    bool first = true;
    for (const auto& item : py::iter(v)) {
      out += (first ? "" : ", ") + toml_value(item, key);
      first = false;
    }
    return out + "]";
  }
  throw InputError(key, py::repr(v).cast<std::string>(), "a bool, number, string or list of them");
}

/// Applies overrides {"sun.elevation_deg": 10} or nested {"sun": {"elevation_deg": 10}}.
void apply_overrides(SceneLoader& loader, const py::dict& overrides, const std::string& prefix) {
  for (const auto& [k, v] : overrides) {
    const std::string key = prefix + py::str(k).cast<std::string>();
    if (py::isinstance<py::dict>(v)) {
      apply_overrides(loader, py::reinterpret_borrow<py::dict>(v), key + ".");
      continue;
    }
    loader.apply_override(key, toml_value(v, key), "overrides[\"" + key + "\"]");
  }
}

Scene load_scene(const std::string& preset, const std::optional<std::string>& scene_file,
                 const std::optional<std::string>& scene_toml, const std::optional<py::dict>& overrides) {
  SceneLoader loader(preset);
  if (scene_file) loader.apply_file(*scene_file);
  if (scene_toml) loader.apply_toml(*scene_toml, "scene_toml");
  if (overrides) apply_overrides(loader, *overrides, "");
  return loader.finish();
}

// ---- NumPy helpers --------------------------------------------------------------------------

py::array_t<double> array1(const std::vector<double>& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

template <class Get>
py::array_t<double> array2(const std::vector<ReportLevel>& levels, size_t n, Get get) {
  py::array_t<double> a({static_cast<py::ssize_t>(levels.size()), static_cast<py::ssize_t>(n)});
  auto m = a.mutable_unchecked<2>();
  for (size_t k = 0; k < levels.size(); ++k) {
    const std::vector<double>& row = get(levels[k]);
    for (size_t i = 0; i < n; ++i) m(static_cast<py::ssize_t>(k), static_cast<py::ssize_t>(i)) = row[i];
  }
  return a;
}

// A number or a list / array of numbers as a NumPy array of doubles (a scalar: shape ()). None
// and what is not numbers are a ValueError naming the argument (numpy's cast would make None a
// NaN).
py::array_t<double, py::array::c_style> numbers_array(const py::object& value, const std::string& name) {
  const std::string allowed = "a number or a list/array of numbers";
  if (value.is_none()) throw InputError(name, "None", allowed);
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!a) {
    PyErr_Clear();
    throw InputError(name, py::str(value).cast<std::string>(), allowed);
  }
  return a;
}

// The same as a list: one wavelength or altitude is naturally a scalar.
std::vector<double> numbers_arg(const py::object& value, const std::string& name) {
  const auto a = numbers_array(value, name);
  return std::vector<double>(a.data(), a.data() + a.size());
}

CoefficientReport make_report(const py::object& wavelengths, const std::string& preset,
                              const std::optional<std::string>& scene_file,
                              const std::optional<std::string>& scene_toml, const std::optional<py::dict>& overrides,
                              const py::object& altitudes, std::optional<double> pressure_Pa,
                              std::optional<double> temperature_K, double latitude_deg,
                              const std::optional<std::string>& refractive_index, std::optional<double> co2_ppm) {
  Scene scene = load_scene(preset, scene_file, scene_toml, overrides);
  if (refractive_index)
    scene.atmosphere.rayleigh.derivation.formula = parse_refractive_index_formula(*refractive_index, "refractive_index");
  if (co2_ppm) {
    if (!(*co2_ppm >= 0.0 && *co2_ppm <= 1e6)) throw InputError("co2_ppm", std::to_string(*co2_ppm), "0 to 1e6 ppm");
    scene.atmosphere.rayleigh.derivation.co2_ppv = *co2_ppm * kPpvPerPpm;
  }
  if (pressure_Pa.has_value() != temperature_K.has_value())
    throw InputError(pressure_Pa ? "temperature_K" : "pressure_Pa", "None",
                     "both pressure_Pa and temperature_K, or neither");
  CoefficientReportRequest req;
  req.atmosphere = scene.atmosphere;
  req.wavelengths_nm = wavelengths.is_none() ? make_wavelength_grid(scene).nanometres() : numbers_arg(wavelengths, "wavelengths_nm");
  req.altitudes_m = numbers_arg(altitudes, "altitudes_m");
  if (pressure_Pa) req.conditions = AirConditions{*pressure_Pa, *temperature_K};
  req.latitude_deg = latitude_deg;
  req.origin = "Python: preset " + preset + (scene_file ? ", scene file " + *scene_file : std::string()) +
               (scene_toml ? ", scene_toml" : "") + (overrides ? ", overrides" : "");
  return make_coefficient_report(req);
}

py::dict derive(const py::object& wavelengths_nm, const std::string& preset,
                const std::optional<std::string>& scene_file, const std::optional<std::string>& scene_toml,
                const std::optional<py::dict>& overrides, const py::object& altitudes_m,
                std::optional<double> pressure_Pa, std::optional<double> temperature_K, double latitude_deg,
                const std::optional<std::string>& refractive_index, std::optional<double> co2_ppm) {
  const CoefficientReport r = make_report(wavelengths_nm, preset, scene_file, scene_toml, overrides, altitudes_m,
                                          pressure_Pa, temperature_K, latitude_deg, refractive_index, co2_ppm);
  const size_t n = r.wavelengths_nm.size();
  py::dict d;
  d["wavelength_nm"] = array1(r.wavelengths_nm);
  const DerivationColumns columns = derivation_columns(r);
  d["gas"] = to_string(r.gas);
  d["refractive_index"] = to_string(r.formula);
  d["co2_ppm"] = r.co2_ppv / kPpvPerPpm;
  d["rayleigh_source"] = r.rayleigh_derived ? "derived" : "fixed";
  d["refractivity_formula_co2"] = array1(columns.refractivity_ref);
  d["refractivity"] = array1(columns.refractivity);
  d["king_factor_air"] = array1(columns.king_factor_air);
  d["king_factor_n2"] = array1(columns.king_factor_n2);
  d["king_factor_o2"] = array1(columns.king_factor_o2);
  d["cross_section_m2"] = array1(columns.cross_section_m2);
  std::vector<double> alts, dens;
  for (const auto& l : r.levels) {
    alts.push_back(l.altitude_m);
    dens.push_back(l.rayleigh_number_density_per_m3);
  }
  d["altitude_m"] = array1(alts);
  d["number_density_per_m3"] = array1(dens);
  d["rayleigh_scattering_per_m"] = array2(r.levels, n, [](const ReportLevel& l) -> const auto& { return l.rayleigh_scattering_per_m; });
  d["rayleigh_optical_depth"] = array2(r.levels, n, [](const ReportLevel& l) -> const auto& { return l.rayleigh_optical_depth; });
  d["mie_scattering_per_m"] = array2(r.levels, n, [](const ReportLevel& l) -> const auto& { return l.mie_scattering_per_m; });
  d["mie_extinction_per_m"] = array2(r.levels, n, [](const ReportLevel& l) -> const auto& { return l.mie_extinction_per_m; });
  d["mie_optical_depth"] = array2(r.levels, n, [](const ReportLevel& l) -> const auto& { return l.mie_optical_depth; });
  d["ozone_absorption_per_m"] = array2(r.levels, n, [](const ReportLevel& l) -> const auto& { return l.ozone_absorption_per_m; });
  d["ozone_optical_depth"] = array2(r.levels, n, [](const ReportLevel& l) -> const auto& { return l.ozone_optical_depth; });
  d["total_optical_depth"] = array2(r.levels, n, [](const ReportLevel& l) -> const auto& { return l.total_optical_depth; });
  if (r.conditions) {
    const auto& c = *r.conditions;
    d["conditions_pressure_Pa"] = c.air.pressure_Pa;
    d["conditions_temperature_K"] = c.air.temperature_K;
    d["conditions_number_density_per_m3"] = c.number_density_per_m3;
    d["conditions_refractivity"] = array1(c.refractivity);
    d["conditions_rayleigh_scattering_per_m"] = array1(c.rayleigh_scattering_per_m);
    d["conditions_rayleigh_optical_depth_above"] = array1(c.rayleigh_optical_depth_above);
  }
  return d;
}

py::list comparisons() {
  py::list out;
  for (const auto& c : published_comparisons()) {
    py::dict d;
    d["id"] = c.id;
    d["title"] = c.title;
    d["quantity"] = c.quantity;
    d["conditions"] = c.conditions;
    d["source"] = c.source;
    d["method"] = c.method;
    std::vector<double> l, p, s, diff;
    for (const auto& row : c.rows) {
      l.push_back(row.wavelength_nm);
      p.push_back(row.published);
      s.push_back(row.skyspec);
      diff.push_back(row.difference_percent);
    }
    d["wavelength_nm"] = array1(l);
    d["published"] = array1(p);
    d["skyspec"] = array1(s);
    d["difference_percent"] = array1(diff);
    d["max_abs_difference_percent"] = c.max_abs_difference_percent;
    d["explanation"] = c.explanation;
    out.append(d);
  }
  return out;
}

py::dict standard_atmosphere(const py::object& altitude) {
  const auto altitude_m = numbers_array(altitude, "altitude_m");
  py::array_t<double> t(altitude_m.request().shape), p(altitude_m.request().shape), n(altitude_m.request().shape);
  const double* z = altitude_m.data();
  for (py::ssize_t i = 0; i < altitude_m.size(); ++i) {
    const AtmosphereState s = us_standard_atmosphere_1976(z[i]);
    t.mutable_data()[i] = s.temperature_K;
    p.mutable_data()[i] = s.pressure_Pa;
    n.mutable_data()[i] = s.number_density_per_m3;
  }
  py::dict d;
  d["temperature_K"] = t;
  d["pressure_Pa"] = p;
  d["number_density_per_m3"] = n;
  return d;
}

py::object render(const std::string& preset, const std::optional<std::string>& scene_file,
                  const std::optional<std::string>& scene_toml, const std::optional<py::dict>& overrides) {
  const Scene scene = load_scene(preset, scene_file, scene_toml, overrides);
  SpectralImageBuffer img;
  {
    py::gil_scoped_release release;
    img = render_to_memory(scene);
  }
  const auto h = static_cast<py::ssize_t>(img.height), w = static_cast<py::ssize_t>(img.width);
  const auto nl = static_cast<py::ssize_t>(img.wavelengths_nm.size());
  py::array_t<float> spectral({h, w, nl}), rgb({h, w, py::ssize_t{3}}), xyz({h, w, py::ssize_t{3}});
  std::copy(img.spectral.begin(), img.spectral.end(), spectral.mutable_data());
  std::copy(img.rgb.begin(), img.rgb.end(), rgb.mutable_data());
  float* out = xyz.mutable_data();
  const size_t pixels = static_cast<size_t>(h * w);
  if (scene.render.path == RenderSpec::Path::Spectral) {
    const SpectrumToXyz to_xyz(WavelengthGrid::from_list(img.wavelengths_nm), constants::kMaxLuminousEfficacy_lm_per_W);
    const auto& W = to_xyz.weights();
    for (size_t p = 0; p < pixels; ++p) {
      const Eigen::Map<const Eigen::VectorXf> s(img.spectral.data() + p * static_cast<size_t>(nl), nl);
      const Eigen::Vector3d v = W * s.cast<double>();
      for (int c = 0; c < 3; ++c) out[p * 3 + static_cast<size_t>(c)] = static_cast<float>(v[c]);
    }
  } else {
    const Eigen::Matrix3d M = linear_rec709_to_xyz();
    for (size_t p = 0; p < pixels; ++p) {
      const Eigen::Vector3d c(img.rgb[p * 3], img.rgb[p * 3 + 1], img.rgb[p * 3 + 2]);
      const Eigen::Vector3d v = M * c;
      for (int k = 0; k < 3; ++k) out[p * 3 + static_cast<size_t>(k)] = static_cast<float>(v[k]);
    }
  }
  static py::object result_type = py::module_::import("collections")
                                       .attr("namedtuple")("RenderResult", py::make_tuple("spectral", "wavelengths_nm", "xyz", "rgb"));
  return result_type(spectral, array1(img.wavelengths_nm), xyz, rgb);
}

}  // namespace

PYBIND11_MODULE(skyspec, m) {
  m.doc() =
      "skyspec: a spectral, physically based sky simulator.\n\n"
      "derive(...)                 Rayleigh/aerosol/ozone coefficients per wavelength as NumPy arrays\n"
      "coefficient_report(...)     the same as a Markdown, CSV, JSON or HTML report (text)\n"
      "published_comparisons()     skyspec against Bodhaine et al. 1999, Bucholtz 1995 and the seed constants\n"
      "us_standard_atmosphere(z)   temperature, pressure, number density of the U.S. Standard Atmosphere 1976\n"
      "rayleigh_cross_section(...) sigma(lambda) in m^2\n"
      "render(...)                 a spectral sky image: (spectral HxWxN float32, wavelengths_nm, xyz, rgb)\n"
      "scene_toml(...), preset_names(), scene_keys()\n\n"
      "Scenes: a preset ('default' or 'seed'), then an optional scene file or TOML text, then overrides, a dict\n"
      "of scene keys, e.g. {'camera.width': 64, 'sun.elevation_deg': 5} or {'sun': {'elevation_deg': 5}}\n"
      "(the keys of `skyspec render --help-keys`). Bad input raises ValueError naming the key.";
  m.attr("__version__") = version_string();

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const IoError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    } catch (const Error& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());
    }
  });

  m.def("preset_names", &preset_names, "Names of the built-in scene presets.");
  m.def(
      "scene_keys",
      [] {
        py::dict keys;
        for (const auto& [key, doc] : scene_key_help()) keys[py::str(key)] = doc;
        return keys;
      },
      "Every scene key that overrides= accepts, with its unit, allowed range and meaning (the same\n"
      "registry as scene files, `skyspec render --set` and docs/scene-keys.md).");

  m.def(
      "scene_toml",
      [](const std::string& preset, const std::optional<std::string>& scene_file,
         const std::optional<std::string>& scene_toml, const std::optional<py::dict>& overrides) {
        return skyspec::scene_to_toml(load_scene(preset, scene_file, scene_toml, overrides));
      },
      py::arg("preset") = "default", py::kw_only(), py::arg("scene_file") = py::none(),
      py::arg("scene_toml") = py::none(), py::arg("overrides") = py::none(),
      "The effective scene (preset, then scene_file, then scene_toml, then overrides) as TOML text, every key.");

  const char* derive_doc = R"(Derive the scattering coefficients of a scene's atmosphere, per wavelength.

Arguments (all optional):
  wavelengths_nm    a wavelength or a list/array of them, nm (default: the scene's spectrum)
  preset, scene_file, scene_toml, overrides   the atmosphere, as for render()
  altitudes_m       an altitude or a list/array (m above sea level) for beta(z) and tau(z -> top); default 0
  pressure_Pa, temperature_K   an extra state of the air, e.g. 25000, 220: N = P / (k T)
  latitude_deg      gravity for the hydrostatic column above that pressure level (default 45)
  refractive_index  'peck-reeder', 'edlen' or 'ciddor' (default: the scene's)
  co2_ppm           CO2 in ppm (default: the scene's)

Returns a dict of NumPy arrays, for n wavelengths and k altitudes (shapes (n,), (k,) or (k, n)):
  wavelength_nm (n); refractivity_formula_co2, refractivity (n_s - 1 at the formula's own and at the
  requested CO2); king_factor_air, king_factor_n2, king_factor_o2; cross_section_m2 (sigma, m^2);
  altitude_m (k); number_density_per_m3 (k); rayleigh_scattering_per_m, rayleigh_optical_depth,
  mie_scattering_per_m, mie_extinction_per_m, mie_optical_depth, ozone_absorption_per_m,
  ozone_optical_depth, total_optical_depth ((k, n): a row per altitude; optical depths are vertical, from the altitude to
  the top of the atmosphere). With pressure_Pa and temperature_K also: conditions_number_density_per_m3,
  conditions_refractivity, conditions_rayleigh_scattering_per_m (sigma N) and
  conditions_rayleigh_optical_depth_above (hydrostatic column above that pressure level).
Also the strings refractive_index, rayleigh_source and the float co2_ppm.

Example: skyspec.derive(pressure_Pa=25000, temperature_K=220)["conditions_rayleigh_scattering_per_m"])";
  m.def("derive", &derive, py::arg("wavelengths_nm") = py::none(), py::kw_only(), py::arg("preset") = "default",
        py::arg("scene_file") = py::none(), py::arg("scene_toml") = py::none(), py::arg("overrides") = py::none(),
        py::arg("altitudes_m") = 0.0, py::arg("pressure_Pa") = py::none(),
        py::arg("temperature_K") = py::none(), py::arg("latitude_deg") = 45.0, py::arg("refractive_index") = py::none(),
        py::arg("co2_ppm") = py::none(), derive_doc);

  m.def(
      "coefficient_report",
      [](const std::string& format, const py::object& wavelengths_nm, const std::string& preset,
         const std::optional<std::string>& scene_file, const std::optional<std::string>& scene_toml,
         const std::optional<py::dict>& overrides, const py::object& altitudes_m, std::optional<double> pressure_Pa,
         std::optional<double> temperature_K, double latitude_deg, const std::optional<std::string>& refractive_index,
         std::optional<double> co2_ppm) {
        const ReportFormat f = parse_report_format(format, "format");
        return format_report(make_report(wavelengths_nm, preset, scene_file, scene_toml, overrides, altitudes_m,
                                         pressure_Pa, temperature_K, latitude_deg, refractive_index, co2_ppm),
                             f);
      },
      py::arg("format") = "md", py::kw_only(), py::arg("wavelengths_nm") = py::none(), py::arg("preset") = "default",
      py::arg("scene_file") = py::none(), py::arg("scene_toml") = py::none(), py::arg("overrides") = py::none(),
      py::arg("altitudes_m") = 0.0, py::arg("pressure_Pa") = py::none(),
      py::arg("temperature_K") = py::none(), py::arg("latitude_deg") = 45.0, py::arg("refractive_index") = py::none(),
      py::arg("co2_ppm") = py::none(),
      "The coefficient derivation report as text: format 'md', 'csv', 'json' or 'html' (the output of\n"
      "`skyspec coefficients`); the other arguments are those of derive().");

  m.def("published_comparisons", &comparisons,
        "skyspec's derivation against published values, at the published conditions: a list of dicts with id,\n"
        "title, quantity, conditions, source, method, wavelength_nm, published, skyspec, difference_percent\n"
        "(arrays), max_abs_difference_percent and a plain-language explanation.");

  m.def("us_standard_atmosphere", &standard_atmosphere, py::arg("altitude_m"),
        "U.S. Standard Atmosphere 1976 at geometric altitudes (m, scalar or array, -5 km to 100 km): a dict of\n"
        "arrays temperature_K, pressure_Pa and number_density_per_m3 (= P / (k T)), shaped like altitude_m.");

  m.def(
      "rayleigh_cross_section",
      [](const py::object& wavelengths_nm, const std::string& refractive_index, std::optional<double> co2_ppm) {
        RayleighDerivationInput in;
        in.formula = parse_refractive_index_formula(refractive_index, "refractive_index");
        // One CO2 default everywhere: the scenes' (420 ppm, present-day air).
        in.co2_ppv = co2_ppm ? *co2_ppm * kPpvPerPpm : default_scene().atmosphere.rayleigh.derivation.co2_ppv;
        if (co2_ppm && !(*co2_ppm >= 0.0 && *co2_ppm <= 1e6)) throw InputError("co2_ppm", format_number(*co2_ppm), "0 to 1e6 ppm");
        std::vector<double> s;
        for (double l : numbers_arg(wavelengths_nm, "wavelengths_nm")) {
          // The range every other skyspec wavelength takes (scene spectrum.*, the coefficient report).
          if (!std::isfinite(l) || l < 360.0 || l > 830.0)
            throw InputError("wavelengths_nm", format_number(l), "wavelengths within 360-830 nm");
          s.push_back(rayleigh_cross_section_m2(l, in));
        }
        return array1(s);
      },
      py::arg("wavelengths_nm"), py::arg("refractive_index") = "peck-reeder", py::arg("co2_ppm") = py::none(),
      "Rayleigh cross-section of dry air per molecule, m^2 (Bodhaine et al. 1999 eq. 2), at each wavelength (nm;\n"
      "a number or a list/array, 360-830 nm), with co2_ppm of CO2 (default: the scenes' 420 ppm; Bodhaine's\n"
      "tables are at 360).");

  m.def("render", &render, py::arg("preset") = "default", py::kw_only(), py::arg("scene_file") = py::none(),
        py::arg("scene_toml") = py::none(), py::arg("overrides") = py::none(),
        R"(Render a scene into memory (no files are written).

Returns a named tuple (spectral, wavelengths_nm, xyz, rgb):
  spectral        float32 array (height, width, n): spectral radiance, W m^-2 sr^-1 nm^-1 (absolute with
                  sun.spectrum = "solar"; with "flat", in units of sun.spectral_irradiance;
                  RGB-fast path: the 3 values read as linear RGB)
  wavelengths_nm  float64 array (n)
  xyz             float32 (height, width, 3): CIE 1931 XYZ, Y in cd m^-2 (spectral path: integrated
                  from the spectrum; RGB-fast path: converted from its linear Rec.709 values)
  rgb             float32 (height, width, 3): linear Rec.709 (D65), as in the EXR's R, G, B
Row 0 is the top of the image, as in the EXR. Example:
  img = skyspec.render(overrides={"camera.width": 64, "camera.height": 64, "sun.elevation_deg": 10}))");
}
