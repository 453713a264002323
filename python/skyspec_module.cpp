// The `skyspec` Python module: the coefficient derivation (NumPy arrays), the report in every
// format, the U.S. Standard Atmosphere 1976 and rendering into NumPy arrays. A thin layer over the
// C++ library: scenes are loaded by the same SceneLoader as the CLI, so presets, scene files and
// key overrides are validated the same way, and errors name the key (ValueError for bad input,
// OSError for files).
#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <Eigen/Core>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <functional>
#include <future>
#include <iomanip>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "skyspec/aerial_perspective.hpp"
#include "skyspec/aerosol_components.hpp"
#include "skyspec/camera.hpp"
#include "skyspec/cancellation.hpp"
#include "skyspec/coefficient_report.hpp"
#include "skyspec/colour.hpp"
#include "skyspec/display.hpp"
#include "skyspec/error.hpp"
#include "skyspec/irradiance.hpp"
#include "skyspec/lee_diagram.hpp"
#include "skyspec/lorenz_mie.hpp"
#include "skyspec/monte_carlo_reference.hpp"
#include "skyspec/preparation_progress.hpp"
#include "skyspec/rayleigh.hpp"
#include "skyspec/refractive_index.hpp"
#include "skyspec/render.hpp"
#include "skyspec/scene.hpp"
#include "skyspec/standard_atmosphere.hpp"
#include "skyspec/timelapse.hpp"
#include "skyspec/units.hpp"
#include "skyspec/version.hpp"
#include "skyspec/water.hpp"

namespace py = pybind11;
using namespace skyspec;

namespace {

// Numbers in messages, as the library writes them (ten significant digits).
std::string format_number(double v) {
  std::ostringstream s;
  s << std::setprecision(10) << v;
  return s.str();
}

constexpr double kPpvPerPpm = 1.0e-6;

// ---- long calls: Ctrl-C and progress --------------------------------------------------------
//
// A long call (render, aerial_perspective, monte_carlo) runs on a thread of its own while the
// calling thread waits without the GIL, waking every 50 ms to run Python's signal handlers and the
// progress callback. Python runs its Ctrl-C handler only between bytecodes of the main thread, so
// a call that held the main thread until it returned would hear Ctrl-C only at its end. On
// KeyboardInterrupt (or an exception from the callback) the wait asks the library to cancel
// (skyspec/cancellation.hpp), waits for the worker to stop (within a second: every long loop
// polls), and raises it. The request is process-wide: it stops every call under way, and is forgotten
// when the last of them has ended.

constexpr auto kPollInterval = std::chrono::milliseconds(50);

std::mutex g_calls_mutex;
int g_calls_under_way = 0;

class CallUnderWay {
 public:
  CallUnderWay() {
    const std::lock_guard<std::mutex> lock(g_calls_mutex);
    if (g_calls_under_way++ == 0) {
      clear_cancellation_request();
      reset_preparation_progress();
    }
  }
  ~CallUnderWay() {
    const std::lock_guard<std::mutex> lock(g_calls_mutex);
    if (--g_calls_under_way == 0) clear_cancellation_request();
  }
  CallUnderWay(const CallUnderWay&) = delete;
  CallUnderWay& operator=(const CallUnderWay&) = delete;
};

// Written by the worker (any thread), read by the waiting Python thread.
struct ProgressCounter {
  std::atomic<long long> done{0}, total{0};
  ProgressFn rows() {
    return [this](int d, int t) {
      total.store(t, std::memory_order_relaxed);
      done.store(d, std::memory_order_relaxed);
    };
  }
};

// progress=: None (nothing), a callable progress(done, total), or True: a bar with an ETA on
// sys.stderr when it is a terminal or a notebook's output (nothing otherwise), redrawn at most every
// half second.
class ProgressReport {
 public:
  ProgressReport(py::object progress, std::string label)
      : progress_(std::move(progress)), label_(std::move(label)), start_(std::chrono::steady_clock::now()) {
    if (progress_.is_none() || (py::isinstance<py::bool_>(progress_) && !progress_.cast<bool>())) {
      kind_ = Kind::None;
    } else if (py::isinstance<py::bool_>(progress_)) {
      // A bar where someone watches: a terminal, or a Jupyter kernel's output; not in a pipe or log.
      const auto err = py::module_::import("sys").attr("stderr");
      const bool terminal = !err.is_none() && py::hasattr(err, "isatty") && err.attr("isatty")().cast<bool>();
      const bool notebook = py::module_::import("sys").attr("modules").contains("ipykernel");
      kind_ = terminal || notebook ? Kind::Bar : Kind::None;
    } else if (PyCallable_Check(progress_.ptr())) {
      kind_ = Kind::Callback;
    } else {
      throw InputError("progress", py::repr(progress_).cast<std::string>(),
                       "None, True (a bar on stderr) or a callable progress(done, total)");
    }
  }

  // With the GIL. Calls the callback when the counts changed; the bar also while nothing has come
  // yet (the tables are being built), saying how long it has waited.
  void update(long long done, long long total, bool last = false) {
    if (kind_ == Kind::None) return;
    const bool changed = done != done_ || total != total_;
    done_ = done, total_ = total;
    if (kind_ == Kind::Callback) {
      if (changed && total > 0) progress_(done, total);
      return;
    }
    const auto now = std::chrono::steady_clock::now();
    if (!last && now - drawn_ < std::chrono::milliseconds(500)) return;
    drawn_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    char line[160];
    if (total <= 0) {
      const PreparationProgress p = preparation_progress();
      if (p.planned > 0) {
        const double f = p.fraction();
        if (p.phase != phase_) building_ = now, phase_ = p.phase;  // each phase's own ETA
        const double built = std::chrono::duration<double>(now - building_).count();
        std::string bar(static_cast<size_t>(f * 30.0), '#');
        bar.resize(30, '.');
        if (f > 0.0)
          std::snprintf(line, sizeof line, "\rskyspec %s: %s [%s] %3.0f%%, ETA %.0f s  ", label_.c_str(), p.what,
                        bar.c_str(), 100.0 * f, built / f - built);
        else
          std::snprintf(line, sizeof line, "\rskyspec %s: %s [%s] %3.0f%%  ", label_.c_str(), p.what, bar.c_str(),
                        100.0 * f);
      } else {
        std::snprintf(line, sizeof line, "\rskyspec %s: preparing, %.0f s", label_.c_str(), elapsed);
      }
    } else {
      const double f = static_cast<double>(done) / static_cast<double>(total);
      const int filled = static_cast<int>(f * 30.0);
      std::string bar(static_cast<size_t>(filled), '#');
      bar.resize(30, '.');
      if (f >= 1.0 || f <= 0.0)
        std::snprintf(line, sizeof line, "\rskyspec %s: [%s] %3.0f%%, %.0f s          ", label_.c_str(), bar.c_str(),
                      100.0 * f, elapsed);
      else
        std::snprintf(line, sizeof line, "\rskyspec %s: [%s] %3.0f%%, ETA %.0f s     ", label_.c_str(), bar.c_str(),
                      100.0 * f, elapsed * (1.0 - f) / f);
    }
    write(line);
  }

  // With the GIL, after a call that returned: the last values, and the bar's line ended.
  void finish() {
    if (kind_ == Kind::Bar) {
      update(done_, total_, true);
      write("\n");
    }
  }

  // With the GIL, after a call that failed or was stopped: the bar's line ended, if one was drawn.
  void abandon() noexcept {
    if (kind_ != Kind::Bar || drawn_ == std::chrono::steady_clock::time_point{}) return;
    try {
      write("\n");
    } catch (...) {  // keep the call's own error
      PyErr_Clear();
    }
  }

 private:
  enum class Kind { None, Callback, Bar };
  void write(const char* text) {
    const auto err = py::module_::import("sys").attr("stderr");
    if (err.is_none()) return;
    err.attr("write")(text);
    err.attr("flush")();
  }
  py::object progress_;
  std::string label_;
  Kind kind_ = Kind::None;
  long long done_ = -1, total_ = -1;
  std::chrono::steady_clock::time_point start_, drawn_{}, building_{};
  long long phase_ = -1;
};

// Runs work(counter) on a thread of its own (see above); called with the GIL held. Its result, or
// its exception; KeyboardInterrupt on Ctrl-C.
template <class Work>
auto run_interruptible(Work&& work, const py::object& progress, const std::string& label) {
  ProgressReport report(progress, label);
  ProgressCounter counter;
  const CallUnderWay under_way;
  auto future = std::async(std::launch::async, [&work, &counter] { return work(counter); });
  const auto stop = [&] {  // after a Python error: the worker asked to stop, and waited for
    request_cancellation(0);
    {
      py::gil_scoped_release release;
      future.wait();
    }
    report.abandon();
  };
  for (;;) {
    {
      py::gil_scoped_release release;
      if (future.wait_for(kPollInterval) == std::future_status::ready) break;
    }
    if (PyErr_CheckSignals() != 0) {
      py::error_already_set interrupted;  // takes the KeyboardInterrupt (or another handler's error)
      stop();
      throw interrupted;
    }
    try {
      report.update(counter.done.load(std::memory_order_relaxed), counter.total.load(std::memory_order_relaxed));
    } catch (...) {  // the callback raised
      const auto raised = std::current_exception();
      stop();
      std::rethrow_exception(raised);
    }
  }
  try {
    auto result = future.get();  // rethrows the worker's exception
    report.update(counter.done.load(std::memory_order_relaxed), counter.total.load(std::memory_order_relaxed));
    report.finish();
    return result;
  } catch (...) {
    report.abandon();
    throw;
  }
}

// ---- scenes from Python arguments -----------------------------------------------------------

/// A Python value as TOML value text: bool, int, float, str, or a sequence of them.
std::string toml_value(const py::handle& v, const std::string& key) {
  if (py::isinstance<py::bool_>(v) || py::isinstance(v, py::module_::import("numpy").attr("bool_")))
    return v.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(v)) return toml_quoted(v.cast<std::string>());
  if (py::isinstance<py::int_>(v)) return py::str(v).cast<std::string>();
  // Integers of any kind (NumPy's int64, uint8, ...: they have __index__), written as integers.
  if (!py::isinstance<py::array>(v) && PyIndex_Check(v.ptr())) {
    PyObject* as_int = PyNumber_Index(v.ptr());
    if (!as_int) throw py::error_already_set();
    return py::str(py::reinterpret_steal<py::object>(as_int)).cast<std::string>();
  }
  const bool is_sequence =
      py::isinstance<py::sequence>(v) || (py::isinstance<py::array>(v) && py::hasattr(v, "__len__"));
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

// `last`, when given, applies what the call itself decides (aerial_perspective: the image's size).
Scene load_scene(const std::string& preset, const std::optional<std::filesystem::path>& scene_file,
                 const std::optional<std::string>& scene_toml, const std::optional<py::dict>& overrides,
                 const std::function<void(SceneLoader&)>& last = {}) {
  SceneLoader loader(preset);
  if (scene_file) loader.apply_file(scene_file->string());
  if (scene_toml) loader.apply_toml(*scene_toml, "scene_toml");
  if (overrides) apply_overrides(loader, *overrides, "");
  if (last) last(loader);
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
                              const std::optional<std::filesystem::path>& scene_file,
                              const std::optional<std::string>& scene_toml, const std::optional<py::dict>& overrides,
                              const py::object& altitudes, std::optional<double> pressure_Pa,
                              std::optional<double> temperature_K, double latitude_deg,
                              const std::optional<std::string>& refractive_index, std::optional<double> co2_ppm) {
  Scene scene = load_scene(preset, scene_file, scene_toml, overrides);
  if (refractive_index)
    scene.atmosphere.rayleigh.derivation.formula =
        parse_refractive_index_formula(*refractive_index, "refractive_index");
  if (co2_ppm) {
    if (!(*co2_ppm >= 0.0 && *co2_ppm <= 1e6)) throw InputError("co2_ppm", std::to_string(*co2_ppm), "0 to 1e6 ppm");
    scene.atmosphere.rayleigh.derivation.co2_ppv = *co2_ppm * kPpvPerPpm;
  }
  if (pressure_Pa.has_value() != temperature_K.has_value())
    throw InputError(pressure_Pa ? "temperature_K" : "pressure_Pa", "None",
                     "both pressure_Pa and temperature_K, or neither");
  CoefficientReportRequest req;
  req.atmosphere = scene.atmosphere;
  req.wavelengths_nm =
      wavelengths.is_none() ? make_wavelength_grid(scene).nanometres() : numbers_arg(wavelengths, "wavelengths_nm");
  req.altitudes_m = numbers_arg(altitudes, "altitudes_m");
  if (pressure_Pa) req.conditions = AirConditions{*pressure_Pa, *temperature_K};
  req.latitude_deg = latitude_deg;
  req.origin = "Python: preset " + preset + (scene_file ? ", scene file " + scene_file->string() : std::string()) +
               (scene_toml ? ", scene_toml" : "") + (overrides ? ", overrides" : "");
  return make_coefficient_report(req);
}

py::dict derive(const py::object& wavelengths_nm, const std::string& preset,
                const std::optional<std::filesystem::path>& scene_file, const std::optional<std::string>& scene_toml,
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
  d["rayleigh_scattering_per_m"] = array2(
      r.levels, n, [](const ReportLevel& l) -> const auto& { return l.rayleigh_scattering_per_m; });
  d["rayleigh_optical_depth"] = array2(
      r.levels, n, [](const ReportLevel& l) -> const auto& { return l.rayleigh_optical_depth; });
  d["mie_scattering_per_m"] = array2(
      r.levels, n, [](const ReportLevel& l) -> const auto& { return l.mie_scattering_per_m; });
  d["mie_extinction_per_m"] = array2(
      r.levels, n, [](const ReportLevel& l) -> const auto& { return l.mie_extinction_per_m; });
  d["mie_optical_depth"] = array2(
      r.levels, n, [](const ReportLevel& l) -> const auto& { return l.mie_optical_depth; });
  d["ozone_absorption_per_m"] = array2(
      r.levels, n, [](const ReportLevel& l) -> const auto& { return l.ozone_absorption_per_m; });
  d["ozone_optical_depth"] = array2(
      r.levels, n, [](const ReportLevel& l) -> const auto& { return l.ozone_optical_depth; });
  for (size_t k = 0; k < r.media.size(); ++k) {
    const std::string& name = r.media[k].name;
    d[py::str(name + "_scattering_per_m")] = array2(
        r.levels, n, [k](const ReportLevel& l) -> const auto& { return l.media[k].scattering_per_m; });
    d[py::str(name + "_extinction_per_m")] = array2(
        r.levels, n, [k](const ReportLevel& l) -> const auto& { return l.media[k].extinction_per_m; });
    d[py::str(name + "_optical_depth")] = array2(
        r.levels, n, [k](const ReportLevel& l) -> const auto& { return l.media[k].optical_depth; });
  }
  d["total_optical_depth"] = array2(
      r.levels, n, [](const ReportLevel& l) -> const auto& { return l.total_optical_depth; });
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

// ---- spheres: Lorenz-Mie, water, the Lee diagram ----------------------------------------------

py::dict lorenz_mie_py(std::complex<double> m, double x, const py::object& angles_deg) {
  const MieSeries series = lorenz_mie(m, x);
  const MieEfficiencies q = mie_efficiencies(series);
  py::dict d;
  d["qext"] = q.extinction;
  d["qsca"] = q.scattering;
  d["qabs"] = q.absorption();
  d["qback"] = q.backscatter;
  d["g"] = q.asymmetry;
  d["terms"] = series.terms();
  if (angles_deg.is_none()) return d;
  const auto angles = numbers_array(angles_deg, "angles_deg");
  std::vector<double> mu(static_cast<size_t>(angles.size()));
  for (py::ssize_t i = 0; i < angles.size(); ++i) {
    const double a = angles.data()[i];
    if (!(a >= 0.0 && a <= 180.0))
      throw InputError("angles_deg", std::to_string(a), "scattering angles from 0 to 180 degrees");
    mu[static_cast<size_t>(i)] = std::cos(a * kPi / 180.0);
  }
  const std::vector<MieAmplitudes> amp = mie_amplitudes(series, mu);
  const auto shape = angles.request().shape;
  py::array_t<std::complex<double>> s1(shape), s2(shape);
  py::array_t<double> s11(shape), s12(shape), s33(shape), s34(shape);
  for (size_t i = 0; i < amp.size(); ++i) {
    const SphereScatteringMatrix f = sphere_scattering_matrix(amp[i]);
    s1.mutable_data()[i] = amp[i].s1;
    s2.mutable_data()[i] = amp[i].s2;
    s11.mutable_data()[i] = f.s11;
    s12.mutable_data()[i] = f.s12;
    s33.mutable_data()[i] = f.s33;
    s34.mutable_data()[i] = f.s34;
  }
  d["s1"] = s1;
  d["s2"] = s2;
  d["s11"] = s11;
  d["s12"] = s12;
  d["s33"] = s33;
  d["s34"] = s34;
  return d;
}

py::array_t<double> water_index_py(const py::object& wavelengths_nm, double temperature_C) {
  const auto nm = numbers_array(wavelengths_nm, "wavelengths_nm");
  if (!(temperature_C >= 0.0 && temperature_C <= 100.0))
    throw InputError("temperature_C", std::to_string(temperature_C),
                     "0-100 degC (liquid water at atmospheric pressure)");
  const double t = temperature_C + 273.15, density = liquid_water_density_kg_per_m3(t);
  py::array_t<double> n(nm.request().shape);
  for (py::ssize_t i = 0; i < nm.size(); ++i) n.mutable_data()[i] = water_refractive_index(t, density, nm.data()[i]);
  return n;
}

// OPAC components by Lorenz-Mie (skyspec/aerosol_components.hpp): the mixture's coefficients per
// wavelength and its normalised scattering matrix, angles ascending from 0 to 180 degrees.
py::dict aerosol_optics_py(const py::object& wavelengths_nm, const py::dict& components, double humidity,
                           const py::object& progress) {
  const auto nm = numbers_array(wavelengths_nm, "wavelengths_nm");
  const WavelengthGrid grid = WavelengthGrid::from_list(std::vector<double>(nm.data(), nm.data() + nm.size()));
  if (!(humidity >= 0.0 && humidity <= 99.0))
    throw InputError("relative_humidity_percent", py::repr(py::float_(humidity)).cast<std::string>(),
                     "a relative humidity in percent, >= 0 and <= 99 (OPAC's range)");
  AerosolMixture mix;
  mix.relative_humidity_percent = humidity;
  const auto& names = aerosol_component_names();
  std::string allowed;
  for (const char* n : names) allowed += (allowed.empty() ? "" : ", ") + std::string(n);
  for (const auto& [key, value] : components) {
    const std::string name = py::str(key);
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end()) throw InputError("components", "\"" + name + "\"", "OPAC's component names: " + allowed);
    double n = std::numeric_limits<double>::quiet_NaN();     // not a number: refused below
    if (PyObject* as_float = PyNumber_Float(value.ptr())) {  // int, float, NumPy scalars
      n = PyFloat_AsDouble(as_float);
      Py_DECREF(as_float);
    } else {
      PyErr_Clear();
    }
    if (!(n >= 0.0 && n <= 1e7))
      throw InputError("components[\"" + name + "\"]", py::repr(value).cast<std::string>(),
                       "a number concentration in particles per cm^3, >= 0 and <= 1e7");
    mix.number_per_cm3[static_cast<size_t>(it - names.begin())] = n;
  }
  // The mixture's own checks name its scene keys; here they are arguments, checked first.
  if (std::none_of(mix.number_per_cm3.begin(), mix.number_per_cm3.end(), [](double n) { return n > 0.0; }))
    throw InputError("components", py::repr(components).cast<std::string>(),
                     "at least one component with a number concentration > 0 (particles per cm^3)");
  const AerosolMixtureOptics o = run_interruptible(
      [&](ProgressCounter&) { return aerosol_mixture_optics(mix, grid, "components"); }, progress, "aerosol_optics");
  const TabulatedScatteringMatrix& t = *o.matrix;
  const py::ssize_t n = grid.size(), m = static_cast<py::ssize_t>(t.mu().size());
  py::array_t<double> ext(n), sca(n), ssa(n), g(n), angles(m), p11({n, m}), p12({n, m}), p33({n, m}), p34({n, m});
  for (py::ssize_t i = 0; i < n; ++i) {
    ext.mutable_data()[i] = o.extinction_per_m[i];
    sca.mutable_data()[i] = o.scattering_per_m[i];
    ssa.mutable_data()[i] = o.extinction_per_m[i] > 0.0 ? o.scattering_per_m[i] / o.extinction_per_m[i] : 0.0;
    g.mutable_data()[i] = t.asymmetry(static_cast<int>(i));
    for (py::ssize_t k = 0; k < m; ++k) {
      const size_t node = static_cast<size_t>(m - 1 - k);  // the table's cosines ascend: angles descend
      const size_t row = static_cast<size_t>(i), at = static_cast<size_t>(i * m + k);
      p11.mutable_data()[at] = t.a1()[row][node];
      p12.mutable_data()[at] = t.b1()[row][node];
      p33.mutable_data()[at] = t.a3()[row][node];
      p34.mutable_data()[at] = t.b2()[row][node];
      if (i == 0) angles.mutable_data()[k] = std::acos(t.mu()[node]) * 180.0 / kPi;
    }
  }
  py::dict d;
  d["wavelengths_nm"] = py::array_t<double>(n, grid.nanometres().data());
  d["extinction_per_m"] = ext;
  d["scattering_per_m"] = sca;
  d["single_scattering_albedo"] = ssa;
  d["asymmetry"] = g;
  d["angles_deg"] = angles;
  d["p11"] = p11;
  d["p12"] = p12;
  d["p33"] = p33;
  d["p34"] = p34;
  return d;
}

py::dict lee_diagram_py(const LeeDiagramSettings& settings, const py::object& progress) {
  check_lee_diagram_settings(settings);
  const auto diagram = std::make_shared<LeeDiagram>(
      run_interruptible([&settings](ProgressCounter& counter) { return compute_lee_diagram(settings, counter.rows()); },
                        progress, "lee_diagram"));
  const py::ssize_t h = diagram->height, w = diagram->width,
                    n = static_cast<py::ssize_t>(diagram->wavelengths_nm.size());
  // The arrays share the diagram's memory, which a capsule keeps alive.
  const py::capsule owner(new std::shared_ptr<LeeDiagram>(diagram),
                          [](void* p) { delete static_cast<std::shared_ptr<LeeDiagram>*>(p); });
  py::dict d;
  d["radiance"] = py::array_t<float>({h, w, n}, diagram->spectral.data(), owner);
  if (!diagram->stokes.empty())
    d["q"] =
        py::array_t<float>({h, w, py::ssize_t{3}, n}, diagram->stokes.data(),
                           owner)[py::make_tuple(py::ellipsis(), 0, py::slice(py::none(), py::none(), py::none()))];
  d["wavelengths_nm"] = py::array_t<double>(n, diagram->wavelengths_nm.data());
  d["angles_deg"] = py::array_t<double>(w, diagram->angles_deg.data());
  d["radii_um"] = py::array_t<double>(h, diagram->radii_um.data());
  return d;
}

// ---- rendering ------------------------------------------------------------------------------

// A render in memory with what it shows. The NumPy arrays spectral, rgb, directions and
// wavelengths_nm are views of the C++ buffer (each keeps it alive), so write_exr / write_png write
// what the arrays hold.
struct RenderResult {
  std::shared_ptr<SpectralImageBuffer> image;
  py::array_t<float> xyz;
};

template <class T>
py::array_t<T> view_of(const std::shared_ptr<SpectralImageBuffer>& image, std::vector<py::ssize_t> shape, T* data,
                       bool writeable = true) {
  auto* keep = new std::shared_ptr<SpectralImageBuffer>(image);
  py::capsule owner(keep, [](void* p) { delete static_cast<std::shared_ptr<SpectralImageBuffer>*>(p); });
  py::array_t<T> a(std::move(shape), data, owner);
  if (!writeable) a.attr("flags").attr("writeable") = false;  // what the render is, not its values
  return a;
}

// CIE XYZ of every pixel: from the spectrum (spectral path), or from linear Rec.709 (RGB-fast).
py::array_t<float> xyz_of(const SpectralImageBuffer& img) {
  const auto h = static_cast<py::ssize_t>(img.height), w = static_cast<py::ssize_t>(img.width);
  const auto nl = static_cast<py::ssize_t>(img.wavelengths_nm.size());
  py::array_t<float> xyz({h, w, py::ssize_t{3}});
  float* out = xyz.mutable_data();
  const size_t pixels = static_cast<size_t>(h * w);
  if (img.scene.render.path == RenderSpec::Path::Spectral) {
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
  return xyz;
}

RenderResult render(const std::string& preset, const std::optional<std::filesystem::path>& scene_file,
                    const std::optional<std::string>& scene_toml, const std::optional<py::dict>& overrides,
                    const py::object& progress) {
  const Scene scene = load_scene(preset, scene_file, scene_toml, overrides);
  auto image = std::make_shared<SpectralImageBuffer>(run_interruptible(
      [&scene](ProgressCounter& counter) { return render_to_memory(scene, counter.rows()); }, progress, "render"));
  return {image, xyz_of(*image)};
}

// A time-lapse (skyspec/timelapse.hpp): the frames' files in `out` (output.directory), named after
// `name` (output.name).
py::dict timelapse_py(const std::string& start, const std::string& end, double step_minutes, const std::string& preset,
                      const std::optional<std::filesystem::path>& scene_file,
                      const std::optional<std::string>& scene_toml, const std::optional<py::dict>& overrides,
                      const std::optional<std::filesystem::path>& out, const std::optional<std::string>& name,
                      const std::optional<std::string>& frames, bool resume, bool force, const py::object& progress) {
  const Scene scene = load_scene(preset, scene_file, scene_toml, overrides, [&](SceneLoader& loader) {
    if (out) loader.apply_override("output.directory", toml_quoted(out->string()), "out");
    if (name) loader.apply_override("output.name", toml_quoted(*name), "name");
  });
  TimelapseSettings settings;
  settings.start = start;
  settings.end = end;
  settings.step_minutes = step_minutes;
  settings.frames = frames.value_or("");
  settings.resume = resume;
  settings.force = force;
  const TimelapseResult r =
      run_interruptible([&](ProgressCounter& counter) { return render_timelapse(scene, settings, counter.rows()); },
                        progress, "time-lapse");
  py::dict d;
  d["frames"] = r.frames;
  d["first"] = r.first;
  d["last"] = r.last;
  d["written"] = r.written;
  d["kept"] = r.kept;
  d["failed"] = r.failed;
  d["replaced"] = r.replaced;
  d["failures"] = r.failures;
  d["exposure_ev"] = r.exposure_ev;
  d["exposure"] = r.exposure;
  py::list files;
  for (const auto& f : r.files) files.append(f.string());
  d["files"] = files;
  d["manifest"] = r.manifest.string();
  return d;
}

// Aerial perspective for a depth pass given as an (h, w) array: the camera's size is the array's.
py::dict aerial_perspective_py(const py::array_t<float, py::array::c_style | py::array::forcecast>& depth,
                               const std::string& depth_is, const std::string& preset,
                               const std::optional<std::filesystem::path>& scene_file,
                               const std::optional<std::string>& scene_toml, const std::optional<py::dict>& overrides,
                               const py::object& progress) {
  if (depth.ndim() != 2 || depth.shape(0) < 1 || depth.shape(1) < 1)
    throw InputError("depth", "an array of " + std::to_string(depth.ndim()) + " dimensions",
                     "a 2-D (height, width) array");
  if (depth_is != "distance" && depth_is != "z")
    throw InputError("depth_is", "\"" + depth_is + "\"", "one of: distance (along each ray), z (along the view axis)");
  const auto h = depth.shape(0), w = depth.shape(1);
  const Scene scene = load_scene(preset, scene_file, scene_toml, overrides, [w, h](SceneLoader& loader) {
    loader.apply_override("camera.width", std::to_string(w), "depth's width");
    loader.apply_override("camera.height", std::to_string(h), "depth's height");
  });
  std::vector<float> values(depth.data(), depth.data() + depth.size());
  if (depth_is == "z") values = ray_distances_from_z(scene, values, "depth");
  const AerialPerspectiveImage ap = run_interruptible(
      [&scene, &values](ProgressCounter& counter) {
        return aerial_perspective(scene, values, counter.rows(), {}, "depth");
      },
      progress, "aerial perspective");
  const auto n = static_cast<py::ssize_t>(ap.wavelengths_nm.size());
  auto array3 = [&](const std::vector<float>& v, py::ssize_t depth_n) {
    py::array_t<float> a({h, w, depth_n});
    std::copy(v.begin(), v.end(), a.mutable_data());
    return a;
  };
  py::dict out;
  out["wavelengths_nm"] = py::array_t<double>(n, ap.wavelengths_nm.data());
  out["transmittance"] = array3(ap.transmittance, n);
  out["inscatter"] = array3(ap.inscatter, n);
  out["transmittance_rgb"] = array3(ap.transmittance_rgb, 3);
  out["inscatter_rgb"] = array3(ap.inscatter_rgb, 3);
  out["scene_toml"] = scene_to_toml(scene, SceneTomlKeys::Recorded);
  return out;
}

// skyspec.irradiance: camera_irradiance's list as arrays over the sun elevations.
py::dict irradiance_py(const std::string& preset, const std::optional<std::filesystem::path>& scene_file,
                       const std::optional<std::string>& scene_toml, const std::optional<py::dict>& overrides,
                       const py::object& sun_elevations, const py::object& progress) {
  const Scene scene = load_scene(preset, scene_file, scene_toml, overrides);
  std::vector<double> elevations;
  if (!sun_elevations.is_none()) {
    elevations = numbers_arg(sun_elevations, "sun_elevations");
    if (elevations.empty()) throw InputError("sun_elevations", "[]", "at least one angle in degrees");
    for (double el : elevations)
      if (!(el >= -90.0 && el <= 90.0))
        throw InputError("sun_elevations", format_number(el), "angles in degrees from -90 to 90");
  }
  const std::vector<CameraIrradiance> list = run_interruptible(
      [&scene, &elevations](ProgressCounter& counter) { return camera_irradiance(scene, elevations, counter.rows()); },
      progress, "irradiance");
  const auto k = static_cast<py::ssize_t>(list.size());
  const auto n = static_cast<py::ssize_t>(list.front().wavelengths_nm.size());
  py::dict out;
  out["wavelength_nm"] = array1(list.front().wavelengths_nm);
  py::array_t<double> elevation(k);
  for (py::ssize_t a = 0; a < k; ++a) elevation.mutable_at(a) = list[static_cast<size_t>(a)].sun_elevation_deg;
  out["sun_elevation_deg"] = elevation;
  for (size_t q = 0; q < list.front().values.size(); ++q) {  // every entry has the same names
    py::array_t<double> v(k);
    for (py::ssize_t a = 0; a < k; ++a) v.mutable_at(a) = list[static_cast<size_t>(a)].values[q].second;
    out[py::str(list.front().values[q].first)] = v;
  }
  for (size_t q = 0; q < list.front().spectra.size(); ++q) {
    py::array_t<double> v({k, n});
    for (py::ssize_t a = 0; a < k; ++a)
      for (py::ssize_t i = 0; i < n; ++i)
        v.mutable_at(a, i) = list[static_cast<size_t>(a)].spectra[q].second[static_cast<size_t>(i)];
    out[py::str(list.front().spectra[q].first)] = v;
  }
  // Colour temperatures: None where the light has none.
  const auto column = [&](std::optional<double> CameraIrradiance::*member) {
    py::list values;
    for (const CameraIrradiance& c : list) values.append((c.*member) ? py::cast(*(c.*member)) : py::none());
    return values;
  };
  out["global_cct_K"] = column(&CameraIrradiance::global_cct_K);
  out["global_duv"] = column(&CameraIrradiance::global_duv);
  out["diffuse_cct_K"] = column(&CameraIrradiance::diffuse_cct_K);
  out["diffuse_duv"] = column(&CameraIrradiance::diffuse_duv);
  return out;
}

// The Monte Carlo reference at probes given as (azimuth, elevation) pairs (default: the standard ones).
py::dict monte_carlo(const std::string& preset, const std::optional<std::filesystem::path>& scene_file,
                     const std::optional<std::string>& scene_toml, const std::optional<py::dict>& overrides,
                     const py::object& probes, long long paths, unsigned long long seed, int orders, bool irradiance,
                     bool stokes, double sun_peak_share, const py::object& progress) {
  const Scene scene = load_scene(preset, scene_file, scene_toml, overrides);
  std::vector<ReferenceProbe> list;
  if (probes.is_none()) {
    list = standard_reference_probes(scene);
  } else {
    for (const auto& item : py::iter(probes)) {
      const auto pair = numbers_arg(py::reinterpret_borrow<py::object>(item), "probes");
      if (pair.size() != 2 || !std::isfinite(pair[0]) || !(pair[1] >= -90.0 && pair[1] <= 90.0))
        throw InputError("probes", py::repr(item).cast<std::string>(),
                         "(azimuth_deg, elevation_deg) pairs, elevation -90 to 90");
      list.push_back({format_number(pair[0]) + "," + format_number(pair[1]), pair[0], pair[1]});
    }
  }
  ReferenceSettings settings;
  settings.paths = paths;
  settings.seed = seed;
  settings.max_orders = orders;
  settings.sun_peak_share = sun_peak_share;
  settings.diffuse_irradiance = irradiance;
  settings.stokes = stokes;
  const ReferenceResult r = run_interruptible(
      [&scene, &list, &settings](ProgressCounter& counter) {
        return monte_carlo_reference(scene, list, settings, counter.rows());
      },
      progress, "Monte Carlo");
  const auto k = static_cast<py::ssize_t>(r.probes.size()), n = static_cast<py::ssize_t>(r.wavelengths_nm.size());
  py::array_t<double> radiance({k, n}), error({k, n}), az(k), el(k);
  for (py::ssize_t a = 0; a < k; ++a) {
    az.mutable_at(a) = r.probes[static_cast<size_t>(a)].azimuth_deg;
    el.mutable_at(a) = r.probes[static_cast<size_t>(a)].elevation_deg;
    for (py::ssize_t i = 0; i < n; ++i) {
      radiance.mutable_at(a, i) = r.radiance[static_cast<size_t>(a)][static_cast<size_t>(i)];
      error.mutable_at(a, i) = r.radiance_standard_error[static_cast<size_t>(a)][static_cast<size_t>(i)];
    }
  }
  py::list labels;
  for (const auto& p : r.probes) labels.append(p.label);
  py::dict out;
  out["wavelength_nm"] = array1(r.wavelengths_nm);
  out["labels"] = labels;
  out["azimuth_deg"] = az;
  out["elevation_deg"] = el;
  out["radiance"] = radiance;
  out["standard_error"] = error;
  if (irradiance) {
    out["diffuse_horizontal"] = array1(r.diffuse_horizontal);
    out["diffuse_horizontal_standard_error"] = array1(r.diffuse_horizontal_standard_error);
  }
  if (stokes) {
    py::array_t<double> sv({k, n, py::ssize_t{4}}), se({k, n, py::ssize_t{4}});
    for (py::ssize_t a = 0; a < k; ++a)
      for (py::ssize_t i = 0; i < n; ++i)
        for (py::ssize_t c = 0; c < 4; ++c) {
          sv.mutable_at(a, i, c) = r.stokes[static_cast<size_t>(a)][static_cast<size_t>(i)][static_cast<size_t>(c)];
          se.mutable_at(a, i, c) =
              r.stokes_standard_error[static_cast<size_t>(a)][static_cast<size_t>(i)][static_cast<size_t>(c)];
        }
    out["stokes"] = sv;
    out["stokes_standard_error"] = se;
  }
  out["paths"] = paths;
  out["seed"] = seed;
  out["orders"] = orders;
  out["seconds"] = r.seconds;
  return out;
}

// The pixel whose view direction is nearest (azimuth, elevation): (row, column).
std::pair<int, int> nearest_pixel(const SpectralImageBuffer& img, double azimuth_deg, double elevation_deg) {
  if (!std::isfinite(azimuth_deg))
    throw InputError("azimuth_deg", format_number(azimuth_deg), "a finite number of degrees");
  if (!(elevation_deg >= -90.0 && elevation_deg <= 90.0))
    throw InputError("elevation_deg", format_number(elevation_deg), "-90 to 90 degrees");
  const Vec3 want = direction_from_angles(azimuth_deg, elevation_deg);
  double best = -2.0;
  std::pair<int, int> at{-1, -1};
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const double* d = &img.directions[(static_cast<size_t>(y) * img.width + x) * 3];
      if (d[0] == 0.0 && d[1] == 0.0 && d[2] == 0.0) continue;  // no direction there
      const double c = d[0] * want.x() + d[1] * want.y() + d[2] * want.z();
      if (c > best) {
        best = c;
        at = {y, x};
      }
    }
  if (at.first < 0)
    throw InputError("azimuth_deg, elevation_deg", "any direction", "an image with pixels that look somewhere");
  return at;
}

// Python's words for the library's neutral setting ids (skyspec/display.hpp, skyspec/scene.hpp):
// the keyword arguments that carry them. Scene keys are the same everywhere.
const std::vector<std::pair<std::string, std::string>>& python_spellings() {
  namespace d = display_setting;
  static const std::vector<std::pair<std::string, std::string>> table = {
      {d::kOcio, "ocio"},
      {d::kDisplay, "display"},
      {d::kView, "view"},
      {d::kLook, "look"},
      {d::kPngBits, "bits"},
      {d::kExposureEv, "exposure_ev"},
      {kSceneFileSetting, "scene_file"},
      {lee_setting::kRadiusMin, "radius_min_um"},
      {lee_setting::kRadiusMax, "radius_max_um"},
      {lee_setting::kAngleMin, "angle_min_deg"},
      {lee_setting::kAngleMax, "angle_max_deg"},
      {lee_setting::kWidth, "width"},
      {lee_setting::kHeight, "height"},
      {lee_setting::kLambdaMin, "lambda_min_nm"},
      {lee_setting::kLambdaMax, "lambda_max_nm"},
      {lee_setting::kLambdaStep, "lambda_step_nm"},
      {lee_setting::kTemperature, "water_temperature_C"},
      {lee_setting::kSubsamples, "angle_samples"},
      {timelapse_setting::kStart, "start"},
      {timelapse_setting::kEnd, "end"},
      {timelapse_setting::kStepMinutes, "step_minutes"},
      {timelapse_setting::kFrames, "frames"},
      {kForceSetting, "force"},
  };
  return table;
}

DisplaySettings display_settings(const std::optional<std::string>& display, const std::optional<std::string>& view,
                                 const std::optional<std::string>& look, int bits,
                                 const std::optional<double>& exposure_ev, const std::optional<std::string>& ocio) {
  DisplaySettings d;
  if (ocio) d.config = {*ocio, "ocio"};
  if (display) d.display = *display;
  if (view) d.view = *view;
  if (look) d.look = *look;
  d.png_bit_depth = bits;
  if (exposure_ev) {
    if (!std::isfinite(*exposure_ev))
      throw InputError("exposure_ev", format_number(*exposure_ev), "a finite number of stops");
    d.exposure.mode = ExposureSettings::Mode::Manual;
    d.exposure.ev = *exposure_ev;
  }
  return d;
}

void bind_render_result(py::module_& m) {
  py::class_<RenderResult>(m, "RenderResult",
                           R"(A sky rendered into memory, with what it shows (skyspec.render() makes it).

Arrays (row 0 is the top of the image, as in the EXR; h x w pixels, n wavelengths):
  spectral        float32 (h, w, n): spectral radiance, W m^-2 sr^-1 nm^-1 (absolute with sun.spectrum =
                  "solar"; with "flat", in units of sun.spectral_irradiance; RGB-fast path: the 3 values)
  wavelengths_nm  float64 (n)
  xyz             float32 (h, w, 3): CIE 1931 XYZ, Y in cd m^-2 (RGB-fast path: from its linear Rec.709)
  rgb             float32 (h, w, 3): linear Rec.709 (D65), the EXR's R, G, B
  directions      float64 (h, w, 3): unit view direction through each pixel's centre, east-north-up at the
                  scene's reference point (x east, y north, z up); (0, 0, 0) where the camera has none
  valid           bool (h, w): the pixel has a direction (False outside a fisheye's circle)
  stokes          float32 (h, w, n, 4): [S0, S1, S2, S3] per wavelength with output.polarisation (else None),
                  in each pixel's frame: e1 = stokes_e1 (float64 (h, w, 3)), e2 = k x e1, k = -direction
spectral and rgb are writable views of the result (write_exr/write_png write what they hold); directions and
wavelengths_nm are read-only views.)")
      .def_property_readonly(
          "spectral",
          [](const RenderResult& r) {
            auto& i = *r.image;
            return view_of<float>(r.image, {i.height, i.width, static_cast<py::ssize_t>(i.wavelengths_nm.size())},
                                  i.spectral.data());
          },
          "float32 (h, w, n): spectral radiance, W m^-2 sr^-1 nm^-1")
      .def_property_readonly(
          "stokes",
          [](const RenderResult& r) -> py::object {
            // A copy: S0 is spectral, S1-S3 are kept apart in the image.
            const auto& i = *r.image;
            if (i.stokes.empty()) return py::none();
            const size_t n = i.wavelengths_nm.size(),
                         pixels = static_cast<size_t>(i.width) * static_cast<size_t>(i.height);
            py::array_t<float> out({static_cast<py::ssize_t>(i.height), static_cast<py::ssize_t>(i.width),
                                    static_cast<py::ssize_t>(n), py::ssize_t{4}});
            float* o = out.mutable_data();
            for (size_t p = 0; p < pixels; ++p)
              for (size_t k = 0; k < n; ++k) {
                float* v = o + (p * n + k) * 4;
                v[0] = i.spectral[p * n + k];
                for (size_t c = 0; c < 3; ++c) v[c + 1] = i.stokes[(p * 3 + c) * n + k];
              }
            return out;
          },
          "float32 (h, w, n, 4): the Stokes vector [S0, S1, S2, S3] per pixel and wavelength (S0 = spectral) in\n"
          "each pixel's frame (stokes_e1), with output.polarisation; None otherwise")
      .def_property_readonly(
          "stokes_e1",
          [](const RenderResult& r) -> py::object {
            const auto& i = *r.image;
            if (i.stokes.empty()) return py::none();
            const auto camera = make_camera(i.scene);
            py::array_t<double> out(
                {static_cast<py::ssize_t>(i.height), static_cast<py::ssize_t>(i.width), py::ssize_t{3}});
            double* o = out.mutable_data();
            for (int y = 0; y < i.height; ++y)
              for (int x = 0; x < i.width; ++x) {
                Vec3 d, e1 = Vec3::Zero();
                if (camera->direction(x + 0.5, y + 0.5, d))
                  e1 = stokes_frame_axis_of_pixel(*camera, x + 0.5, y + 0.5, d);
                std::copy(e1.data(), e1.data() + 3, o + (static_cast<size_t>(y) * i.width + x) * 3);
              }
            return out;
          },
          "float64 (h, w, 3): e1 of each pixel's Stokes frame, east-north-up (the image's x axis on the sky; e2 =\n"
          "k x e1 with k = -direction, the light's direction); (0, 0, 0) where no direction; None without polarisation")
      .def_property_readonly(
          "wavelengths_nm",
          [](const RenderResult& r) {
            return view_of<double>(r.image, {static_cast<py::ssize_t>(r.image->wavelengths_nm.size())},
                                   r.image->wavelengths_nm.data(), false);
          },
          "float64 (n,): the wavelengths, nm")
      .def_readonly("xyz", &RenderResult::xyz, "float32 (h, w, 3): CIE 1931 XYZ, Y in cd m^-2")
      .def_property_readonly(
          "rgb",
          [](const RenderResult& r) {
            return view_of<float>(r.image, {r.image->height, r.image->width, 3}, r.image->rgb.data());
          },
          "float32 (h, w, 3): linear Rec.709 (D65), the EXR's R, G, B")
      .def_property_readonly(
          "directions",
          [](const RenderResult& r) {
            return view_of<double>(r.image, {r.image->height, r.image->width, 3}, r.image->directions.data(), false);
          },
          "float64 (h, w, 3): unit view direction of each pixel's centre, east-north-up; (0, 0, 0) where none")
      .def_property_readonly(
          "valid",
          [](const RenderResult& r) {
            const auto& i = *r.image;
            py::array_t<bool> valid({static_cast<py::ssize_t>(i.height), static_cast<py::ssize_t>(i.width)});
            bool* out = valid.mutable_data();
            for (size_t p = 0; p < static_cast<size_t>(i.width) * static_cast<size_t>(i.height); ++p)
              out[p] = i.directions[p * 3] != 0.0 || i.directions[p * 3 + 1] != 0.0 || i.directions[p * 3 + 2] != 0.0;
            return valid;
          },
          "bool (h, w): whether the pixel has a view direction")
      .def_property_readonly(
          "width", [](const RenderResult& r) { return r.image->width; }, "pixels")
      .def_property_readonly(
          "height", [](const RenderResult& r) { return r.image->height; }, "pixels")
      .def_property_readonly(
          "sun_direction",
          [](const RenderResult& r) {
            const Vec3& s = r.image->sun_direction;
            return array1({s.x(), s.y(), s.z()});
          },
          "float64 (3,): unit vector towards the sun's centre, east-north-up (the frame of directions)")
      .def_property_readonly(
          "sun_azimuth_deg", [](const RenderResult& r) { return r.image->scene.sun.azimuth_deg; },
          "the sun's azimuth, degrees clockwise from north (computed for sun.date_time when set)")
      .def_property_readonly(
          "sun_elevation_deg", [](const RenderResult& r) { return r.image->scene.sun.elevation_deg; },
          "the sun's elevation above the horizon, degrees")
      .def_property_readonly(
          "exposure_scale", [](const RenderResult& r) { return preview_exposure(*r.image).scale; },
          "the factor the preview applies to rgb (the EXR's skyspec:exposureScale): output.exposure_ev when\n"
          "the scene sets it, else the automatic one (log-average luminance -> 0.18)")
      .def_property_readonly(
          "exposure_ev", [](const RenderResult& r) { return std::log2(preview_exposure(*r.image).scale); },
          "log2(exposure_scale)")
      .def_property_readonly(
          "exposure", [](const RenderResult& r) { return preview_exposure(*r.image).description; },
          "how the exposure was chosen, in words (the EXR's skyspec:exposure)")
      .def_property_readonly(
          "scene_toml", [](const RenderResult& r) { return scene_to_toml(r.image->scene); },
          "the effective scene as TOML, every key (the EXR's skyspec:scene; render(scene_toml=...) again\n"
          "gives the same image)")
      .def_property_readonly(
          "scene",
          [](const RenderResult& r) {
            return py::module_::import("tomllib").attr("loads")(scene_to_toml(r.image->scene));
          },
          "the effective scene as a nested dict (scene_toml read with tomllib)")
      .def(
          "pixel",
          [](const RenderResult& r, double azimuth_deg, double elevation_deg) {
            return nearest_pixel(*r.image, azimuth_deg, elevation_deg);
          },
          py::arg("azimuth_deg"), py::arg("elevation_deg"),
          "(row, column) of the pixel whose view direction is nearest to (azimuth clockwise from north, elevation),\n"
          "degrees")
      .def(
          "spectrum_at",
          [](const RenderResult& r, double azimuth_deg, double elevation_deg) {
            const auto [y, x] = nearest_pixel(*r.image, azimuth_deg, elevation_deg);
            const size_t n = r.image->wavelengths_nm.size();
            const float* s = &r.image->spectral[(static_cast<size_t>(y) * r.image->width + x) * n];
            return array1(std::vector<double>(s, s + n));
          },
          py::arg("azimuth_deg"), py::arg("elevation_deg"),
          "float64 (n,): the spectral radiance of the pixel nearest that direction (see pixel()), W m^-2 sr^-1 nm^-1")
      .def(
          "write_exr",
          [](const RenderResult& r, const std::filesystem::path& path) {
            py::gil_scoped_release release;
            write_spectral_exr(*r.image, path);
          },
          py::arg("path"),
          "Write the spectral EXR, as `skyspec render` writes it for this scene (channels, values, header: scene,\n"
          "exposure, units, envmap), atomically. OSError if it cannot be written.")
      .def(
          "write_png",
          [](const RenderResult& r, const std::filesystem::path& path, const std::optional<std::string>& display,
             const std::optional<std::string>& view, const std::optional<std::string>& look, int bits,
             const std::optional<double>& exposure_ev, const std::optional<std::string>& ocio) {
            const DisplaySettings settings = display_settings(display, view, look, bits, exposure_ev, ocio);
            py::gil_scoped_release release;
            return write_display_png(*r.image, path, settings);
          },
          py::arg("path"), py::kw_only(), py::arg("display") = py::none(), py::arg("view") = py::none(),
          py::arg("look") = py::none(), py::arg("bits") = 8, py::arg("exposure_ev") = py::none(),
          py::arg("ocio") = py::none(),
          "Write the image through an OpenColorIO display and view as a PNG, as `skyspec render` writes its preview\n"
          "(default: skyspec's config, sRGB, Un-tone-mapped, 8 bits, the recorded exposure; exposure_ev: a manual\n"
          "one; ocio: another config file), atomically. Returns the exposure's scale. ValueError names a bad\n"
          "display, view, look or bit depth.")
      .def("__repr__", [](const RenderResult& r) {
        const auto& i = *r.image;
        return "<skyspec.RenderResult " + std::to_string(i.width) + "x" + std::to_string(i.height) + ", " +
               std::to_string(i.wavelengths_nm.size()) + " wavelengths, sun azimuth " +
               format_number(i.scene.sun.azimuth_deg) + " elevation " + format_number(i.scene.sun.elevation_deg) + ">";
      });
}

}  // namespace

// The long calls' common paragraph.
#define PROGRESS_DOC                                                                                       \
  "\nprogress: None, True (a bar with an ETA on stderr, in a terminal or a notebook) or a callable\n"      \
  "progress(done, total), called from this thread as the work advances (rows of the image, estimates of\n" \
  "the Monte Carlo); an exception it raises stops the call. Ctrl-C (KeyboardInterrupt) stops the call\n"   \
  "within about a second, also while the scattering tables are built."

PYBIND11_MODULE(skyspec, m) {
  m.doc() =
      "skyspec: a spectral, physically based sky simulator.\n\n"
      "derive(...)                 Rayleigh/aerosol/ozone coefficients per wavelength as NumPy arrays\n"
      "coefficient_report(...)     the same as a Markdown, CSV, JSON or HTML report (text)\n"
      "published_comparisons()     skyspec against Bodhaine et al. 1999, Bucholtz 1995 and the seed constants\n"
      "us_standard_atmosphere(z)   temperature, pressure, number density of the U.S. Standard Atmosphere 1976\n"
      "rayleigh_cross_section(...) sigma(lambda) in m^2\n"
      "lorenz_mie(m, x, ...)       one sphere by Lorenz-Mie theory: efficiencies, g, S1, S2, scattering matrix\n"
      "water_refractive_index(nm)  IAPWS R9-97\n"
      "lee_diagram(...)            water drops' light against scattering angle and radius (NumPy arrays)\n"
      "render(...)                 a spectral sky image with its directions, sun, exposure and scene (RenderResult)\n"
      "scene_toml(...), preset_names(), scene_keys()\n"
      "run_job(job, ...)           a job file (sites x times x parameters) on a Dask cluster\n\n"
      "Scenes: a preset ('default' or 'seed'), then an optional scene file or TOML text, then overrides, a dict\n"
      "of scene keys, e.g. {'camera.width': 64, 'sun.elevation_deg': 5} or {'sun': {'elevation_deg': 5}}\n"
      "(the keys of `skyspec render --help-keys`). Bad input raises ValueError naming the key.";
  m.attr("__version__") = version_string();

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Cancelled& e) {  // another thread's Ctrl-C stopped this call too
      PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
    } catch (const InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.respelled(python_spellings()).what());
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
      [](const std::string& preset, const std::optional<std::filesystem::path>& scene_file,
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
  the top of the atmosphere); with fog, ice or rain in the atmosphere also <name>_scattering_per_m,
  <name>_extinction_per_m and <name>_optical_depth for each ((k, n), in the total). With pressure_Pa
  and temperature_K also: conditions_number_density_per_m3,
  conditions_refractivity, conditions_rayleigh_scattering_per_m (sigma N) and
  conditions_rayleigh_optical_depth_above (hydrostatic column above that pressure level).
Also the strings refractive_index, rayleigh_source and the float co2_ppm.

Example: skyspec.derive(pressure_Pa=25000, temperature_K=220)["conditions_rayleigh_scattering_per_m"])";
  m.def("derive", &derive, py::arg("wavelengths_nm") = py::none(), py::kw_only(), py::arg("preset") = "default",
        py::arg("scene_file") = py::none(), py::arg("scene_toml") = py::none(), py::arg("overrides") = py::none(),
        py::arg("altitudes_m") = 0.0, py::arg("pressure_Pa") = py::none(), py::arg("temperature_K") = py::none(),
        py::arg("latitude_deg") = 45.0, py::arg("refractive_index") = py::none(), py::arg("co2_ppm") = py::none(),
        derive_doc);

  m.def(
      "coefficient_report",
      [](const std::string& format, const py::object& wavelengths_nm, const std::string& preset,
         const std::optional<std::filesystem::path>& scene_file, const std::optional<std::string>& scene_toml,
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
      py::arg("altitudes_m") = 0.0, py::arg("pressure_Pa") = py::none(), py::arg("temperature_K") = py::none(),
      py::arg("latitude_deg") = 45.0, py::arg("refractive_index") = py::none(), py::arg("co2_ppm") = py::none(),
      "The coefficient derivation report as text: format 'md', 'csv', 'json' or 'html' (the output of\n"
      "`skyspec coefficients`); the other arguments are those of derive().");

  m.def("published_comparisons", &comparisons,
        "skyspec's derivation against published values, at the published conditions: a list of dicts with id,\n"
        "title, quantity, conditions, source, method, wavelength_nm, published, skyspec, difference_percent\n"
        "(arrays), max_abs_difference_percent and a plain-language explanation.");

  m.def("lorenz_mie", &lorenz_mie_py, py::arg("m"), py::arg("x"), py::kw_only(), py::arg("angles_deg") = py::none(),
        "One homogeneous sphere by Lorenz-Mie theory (Wiscombe's algorithm): m the relative refractive index\n"
        "(complex, imaginary part >= 0 absorbs), x = 2 pi r n_medium / lambda (1e-3 to 2e4). A dict of qext, qsca,\n"
        "qabs, qback (4 |S1(180)|^2 / x^2), g and terms; with angles_deg (scattering angles, degrees), also the\n"
        "amplitudes s1, s2 (Bohren & Huffman's convention) and the scattering matrix s11, s12, s33, s34, shaped\n"
        "like angles_deg.");
  m.def("aerosol_optics", &aerosol_optics_py, py::arg("wavelengths_nm"), py::kw_only(), py::arg("components"),
        py::arg("relative_humidity_percent") = 70.0, py::arg("progress") = py::none(),
        "An aerosol from its microphysics, as atmosphere.mie.model = \"opac\" computes it: OPAC's components\n"
        "(Hess, Koepke & Schult 1998) by Lorenz-Mie theory over their size distributions. components: OPAC's name\n"
        "-> particles per cm^3 (inso, waso, soot, ssam, sscm, minm, miam, micm, mitr, suso); wavelengths 250-2500 nm\n"
        "(sorted ascending in the result). Returns wavelengths_nm, extinction_per_m, scattering_per_m,\n"
        "single_scattering_albedo, asymmetry (per wavelength), angles_deg (0-180, ascending) and the normalised\n"
        "scattering matrix p11 (the phase function, sr^-1, integral 1 over the sphere), p12, p33, p34\n"
        "([wavelength, angle]; linear in cos(angle) between the angles).");
  m.def("water_refractive_index", &water_index_py, py::arg("wavelengths_nm"), py::kw_only(),
        py::arg("temperature_C") = 10.0,
        "The refractive index of liquid water (IAPWS R9-97; its density at 1 atm from Kell 1975), 200-1100 nm,\n"
        "0-100 degC; shaped like wavelengths_nm.");
  m.def(
      "lee_diagram",
      [](double radius_min_um, double radius_max_um, double angle_min_deg, double angle_max_deg, int width, int height,
         double lambda_min_nm, double lambda_max_nm, double lambda_step_nm, double water_temperature_C,
         int angle_samples, bool polarisation, const py::object& progress) {
        LeeDiagramSettings s;
        s.radius_min_um = radius_min_um;
        s.radius_max_um = radius_max_um;
        s.angle_min_deg = angle_min_deg;
        s.angle_max_deg = angle_max_deg;
        s.width = width;
        s.height = height;
        s.lambda_min_nm = lambda_min_nm;
        s.lambda_max_nm = lambda_max_nm;
        s.lambda_step_nm = lambda_step_nm;
        s.water_temperature_C = water_temperature_C;
        s.angle_subsamples = angle_samples;
        s.polarisation = polarisation;
        return lee_diagram_py(s, progress);
      },
      py::kw_only(), py::arg("radius_min_um") = 10.0, py::arg("radius_max_um") = 1000.0,
      py::arg("angle_min_deg") = 125.0, py::arg("angle_max_deg") = 145.0, py::arg("width") = 400,
      py::arg("height") = 100, py::arg("lambda_min_nm") = 380.0, py::arg("lambda_max_nm") = 780.0,
      py::arg("lambda_step_nm") = 10.0, py::arg("water_temperature_C") = 10.0, py::arg("angle_samples") = 4,
      py::arg("polarisation") = false, py::arg("progress") = py::none(),
      "The Lee diagram (`skyspec lee-diagram`): E_sun(lambda) P_11 of water drops, W m^-2 sr^-1 nm^-1 per unit\n"
      "scattering optical depth, as a dict of radiance (height, width, wavelengths; row 0 the largest radius),\n"
      "wavelengths_nm, angles_deg (column centres), radii_um (row centres) and, with polarisation, q (the same\n"
      "shape: positive when polarised perpendicular to the scattering plane). progress: True for a bar, or a\n"
      "callable (rows done, rows). Ctrl-C stops it.");
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
        if (co2_ppm && !(*co2_ppm >= 0.0 && *co2_ppm <= 1e6))
          throw InputError("co2_ppm", format_number(*co2_ppm), "0 to 1e6 ppm");
        const RefractiveIndexValidity valid = validity(in.formula);
        const auto nm = numbers_array(wavelengths_nm, "wavelengths_nm");
        py::array_t<double> s(nm.request().shape);  // shaped like the wavelengths (a scalar: shape ())
        for (py::ssize_t i = 0; i < nm.size(); ++i) {
          const double l = nm.data()[i];
          // The refractive index formula's range, as in the coefficient report.
          if (!std::isfinite(l) || l < valid.min_nm || l > valid.max_nm)
            throw InputError("wavelengths_nm", format_number(l),
                             "wavelengths from " + format_number(valid.min_nm) + " to " + format_number(valid.max_nm) +
                                 " nm, " + valid.reason);
          s.mutable_data()[i] = rayleigh_cross_section_m2(l, in);
        }
        return s;
      },
      py::arg("wavelengths_nm"), py::arg("refractive_index") = "peck-reeder", py::arg("co2_ppm") = py::none(),
      "Rayleigh cross-section of dry air per molecule, m^2 (Bodhaine et al. 1999 eq. 2), at each wavelength (nm;\n"
      "a number or a list/array of any shape, 230-1690 nm: the refractive index formula's range; the result has\n"
      "the wavelengths' shape), with co2_ppm of CO2 (default: the "
      "scenes' 420 ppm; Bodhaine's\n"
      "tables are at 360).");

  bind_render_result(m);
  m.def("render", &render, py::arg("preset") = "default", py::kw_only(), py::arg("scene_file") = py::none(),
        py::arg("scene_toml") = py::none(), py::arg("overrides") = py::none(), py::arg("progress") = py::none(),
        R"(Render a scene into memory; returns a RenderResult (no files are written until you ask).

The result holds the image (spectral, wavelengths_nm, xyz, rgb), where each pixel looks (directions,
valid, pixel(), spectrum_at()), the sun (sun_direction, sun_azimuth_deg, sun_elevation_deg), the exposure
(exposure_scale, exposure_ev, exposure) and the effective scene (scene_toml, scene), and writes the files
`skyspec render` would (write_exr(), write_png()). Example:
  img = skyspec.render(overrides={"camera.width": 64, "camera.height": 64, "sun.elevation_deg": 10})
  img.spectrum_at(azimuth_deg=0, elevation_deg=45); img.write_exr("sky.exr")
)" PROGRESS_DOC);

  m.def("aerial_perspective", &aerial_perspective_py, py::arg("depth"), py::kw_only(), py::arg("depth_is") = "distance",
        py::arg("preset") = "default", py::arg("scene_file") = py::none(), py::arg("scene_toml") = py::none(),
        py::arg("overrides") = py::none(), py::arg("progress") = py::none(),
        R"(Aerial perspective (`skyspec aerial`) for a depth pass: depth is a (height, width) array of distances in
metres along each pixel's ray (depth_is="z": along the camera's view axis); infinity is sky. The scene's camera
(camera.type, position, look_at, fov) must be the one the depth was rendered with; its size is the array's.
Returns a dict: wavelengths_nm (n), transmittance and inscatter (float32 (h, w, n); inscatter in
W m^-2 sr^-1 nm^-1), transmittance_rgb and inscatter_rgb (float32 (h, w, 3), linear Rec.709) and scene_toml.
A surface image I becomes I * transmittance + inscatter (per wavelength, or per channel with the RGB pair).
)" PROGRESS_DOC);

  m.def("timelapse", &timelapse_py, py::arg("start"), py::arg("end"), py::arg("step_minutes"), py::kw_only(),
        py::arg("preset") = "default", py::arg("scene_file") = py::none(), py::arg("scene_toml") = py::none(),
        py::arg("overrides") = py::none(), py::arg("out") = py::none(), py::arg("name") = py::none(),
        py::arg("frames") = py::none(), py::arg("resume") = false, py::arg("force") = false,
        py::arg("progress") = py::none(),
        R"(A time-lapse (`skyspec timelapse`): one image per step_minutes from start to end (ISO 8601 with a UTC
offset) at the scene's location (location.latitude_deg, location.longitude_deg), the sun placed by the NREL
algorithm, one exposure for every frame (output.exposure_ev, or metered once on the frame with the highest
sun). Files: <name>_0000.exr/.png ... in `out` (default: the scene's output.directory and output.name), each
with a record <name>_0000.json, and manifest.jsonl. frames="A-B" renders only those (inclusive, 0-based);
resume=True keeps the frames an earlier run finished (record, scene and files checked); force=True skips the
render budget's refusals. Returns a dict: frames, first, last, written, kept, failed, replaced, failures,
exposure_ev, exposure, files, manifest.
)" PROGRESS_DOC);

  m.def("irradiance", &irradiance_py, py::arg("preset") = "default", py::kw_only(), py::arg("scene_file") = py::none(),
        py::arg("scene_toml") = py::none(), py::arg("overrides") = py::none(), py::arg("sun_elevations") = py::none(),
        py::arg("progress") = py::none(),
        R"(The irradiance at the scene's camera (`skyspec irradiance`; docs/jobs.md, "Irradiance and pyranometers"):
the direct beam (the sun's transmittance) and the diffuse light (the sky's radiance over the upper hemisphere,
every scattering order the scene asks for) on a horizontal surface, for each of sun_elevations (degrees; default:
the scene's), the sun at the scene's azimuth. Spectral scenes only.
Returns a dict: wavelength_nm (n), sun_elevation_deg (k); the numbers (k), named as the irradiance tables'
columns: direct_normal_W_m2, direct_horizontal_W_m2, diffuse_horizontal_W_m2, global_horizontal_W_m2 (over
wavelength_nm's range), the same in lux (*_lux), and with overrides {"irradiance.broadband": True} also
broadband_*_W_m2 (300-4000 nm with the gases' absorption bands, what a pyranometer measures); the spectra
(k, n; W m^-2 nm^-1): global_horizontal_W_m2_nm, diffuse_horizontal_W_m2_nm, direct_normal_W_m2_nm; and lists
(k) global_cct_K, global_duv, diffuse_cct_K, diffuse_duv (CIE 015; None where the light has none).
)" PROGRESS_DOC);

  m.def("monte_carlo", &monte_carlo, py::arg("preset") = "default", py::kw_only(), py::arg("scene_file") = py::none(),
        py::arg("scene_toml") = py::none(), py::arg("overrides") = py::none(), py::arg("probes") = py::none(),
        py::arg("paths") = 100000, py::arg("seed") = 1, py::arg("orders") = 0, py::arg("irradiance") = false,
        py::arg("stokes") = false, py::arg("sun_peak_share") = 0.0, py::arg("progress") = py::none(),
        R"(The Monte Carlo reference of a scene (`skyspec reference`): sky radiance with every scattering order
at the camera's position, by backward path tracing independent of the renderer (docs/validation.md).

probes: (azimuth_deg, elevation_deg) pairs (default: zenith, 45 deg up towards the sun, 1 deg above the
horizon towards, across and away from it); paths per probe and wavelength; seed; orders: 0 for all,
1 for single scattering; irradiance: also the diffuse horizontal irradiance; stokes: also the Stokes
vectors (vector transport, as many paths again); sun_peak_share: the share (0 to 0.5) of scatterings
whose direction is drawn about the sun (unbiased; for forward-peaked media such as fog).
Returns a dict: wavelength_nm (n), labels, azimuth_deg, elevation_deg (k), radiance and standard_error
((k, n), W m^-2 sr^-1 nm^-1), with irradiance diffuse_horizontal and its standard error (n,
W m^-2 nm^-1), with stokes `stokes` and `stokes_standard_error` ((k, n, 4): I, Q, U, V in the frame of
the vertical through the line of sight, Q > 0 polarised in that plane, U > 0 at 45 deg from it towards
the observer's left; at the zenith from north), and paths, seed, orders, seconds. The same seed gives the same values on any machine
and number of threads.
)" PROGRESS_DOC);

  // Jobs run on Dask through the pure-Python driver beside this module (skyspec_jobs.py).
  m.def(
      "run_job",
      [](const py::object& job, const py::object& out, const py::object& scheduler, const py::object& workers,
         int threads, const py::object& skyspec, bool quiet) {
        return py::module_::import("skyspec_jobs")
            .attr("run_job")(job, py::arg("out") = out, py::arg("scheduler") = scheduler, py::arg("workers") = workers,
                             py::arg("threads") = threads, py::arg("skyspec") = skyspec, py::arg("quiet") = quiet);
      },
      py::arg("job"), py::kw_only(), py::arg("out") = py::none(), py::arg("scheduler") = py::none(),
      py::arg("workers") = py::none(), py::arg("threads") = 1, py::arg("skyspec") = py::none(),
      py::arg("quiet") = false,
      R"(Run a job file (docs/jobs.md) on Dask: a LocalCluster of `workers` processes by default, or the cluster
of `scheduler` ("tcp://host:8786"). Each chunk of tasks runs `skyspec job run --tasks` in a child
process (`skyspec`: the program, default $SKYSPEC_CLI, the build tree, the interpreter's bin folder or PATH) with `threads`
render threads; finished tasks are kept, so running it again runs only what is missing. Returns a
summary dict (tasks, ok, failed, missing, output); raises skyspec_jobs.JobFailed when tasks failed or did not run.)");
}
