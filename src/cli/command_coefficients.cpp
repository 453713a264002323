// `skyspec coefficients`: the derivation report of a scene's atmosphere (every step from the
// refractive index to the optical depth, checked against published tables) as Markdown, CSV, JSON
// or a self-contained HTML page with plots.

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "base/atomic_file.hpp"
#include "commands.hpp"
#include "progress.hpp"
#include "scene_options.hpp"
#include "skyspec/coefficient_report.hpp"
#include "skyspec/error.hpp"
#include "skyspec/scene.hpp"

namespace skyspec::cli {
namespace {

struct CoefficientOptions {
  SceneOptions scene;
  std::string altitudes = "0";
  std::optional<std::string> pressure, temperature;
  double latitude_deg = 45.0;
  std::optional<std::string> format;
  std::string out;
  bool quiet = false;
};

std::vector<KeyFlag> coefficient_flags() {
  std::vector<KeyFlag> flags = spectrum_flags();
  flags.push_back(
      {"--refractive-index", "atmosphere.rayleigh.refractive_index", "peck-reeder, edlen or ciddor", {}, false});
  flags.push_back({"--co2-ppm", "atmosphere.rayleigh.co2_ppm", "CO2 content, ppm", {}, false});
  return flags;
}

/// A number followed by a unit, e.g. "250hPa", "250 hPa", "-56.5C". Returns false when the text is
/// not a number followed by a known unit (case-sensitive, as SI writes them).
struct UnitFactor {
  const char* unit;
  double scale, offset;  ///< SI value = number * scale + offset
};

bool parse_with_unit(const std::string& text, const std::vector<UnitFactor>& units, double& si) {
  size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    return false;
  }
  std::string unit = text.substr(used);
  while (!unit.empty() && std::isspace(static_cast<unsigned char>(unit.front()))) unit.erase(unit.begin());
  for (const auto& u : units)
    if (unit == u.unit) {
      si = v * u.scale + u.offset;
      return std::isfinite(si);
    }
  return false;
}

double parse_pressure_Pa(const std::string& text) {
  static const std::vector<UnitFactor> units = {{"Pa", 1.0, 0.0},     {"hPa", 100.0, 0.0}, {"kPa", 1000.0, 0.0},
                                                {"mbar", 100.0, 0.0}, {"bar", 1.0e5, 0.0}, {"atm", 101325.0, 0.0}};
  double p = 0.0;
  if (!parse_with_unit(text, units, p))
    throw InputError("--pressure", "\"" + text + "\"",
                     "a pressure with its unit, e.g. 250hPa, 25000Pa or 1atm (Pa, hPa, kPa, mbar, bar, atm)");
  if (p <= 0.0 || p > 1e8) throw InputError("--pressure", "\"" + text + "\"", "a pressure above 0 and up to 1e8 Pa");
  return p;
}

double parse_temperature_K(const std::string& text) {
  static const std::vector<UnitFactor> units = {{"K", 1.0, 0.0}, {"C", 1.0, 273.15}, {"degC", 1.0, 273.15}};
  double t = 0.0;
  if (!parse_with_unit(text, units, t))
    throw InputError("--temperature", "\"" + text + "\"",
                     "a temperature with its unit, e.g. 220K or -53.15C (K, C, degC)");
  if (t <= 0.0 || t > 1e4)
    throw InputError("--temperature", "\"" + text + "\"", "a temperature above 0 K and up to 10000 K");
  return t;
}

std::vector<double> parse_altitudes_m(const std::string& text, double top_m) {
  std::vector<double> out;
  std::stringstream in(text);
  std::string item;
  const std::string allowed =
      "comma-separated altitudes in metres from 0 up to (not including) the top of the "
      "atmosphere (atmosphere.top_altitude_m = " +
      std::to_string(static_cast<long long>(top_m)) + ")";
  while (std::getline(in, item, ',')) {
    size_t used = 0;
    double z = 0.0;
    try {
      z = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    while (used < item.size() && std::isspace(static_cast<unsigned char>(item[used]))) ++used;
    if (used == 0 || used != item.size() || !std::isfinite(z) || z < 0.0 || z >= top_m)
      throw InputError("--altitudes", "\"" + item + "\"", allowed);
    out.push_back(z);
  }
  if (out.empty()) throw InputError("--altitudes", "\"" + text + "\"", allowed);
  return out;
}

ReportFormat choose_format(const CoefficientOptions& o) {
  if (o.format) return parse_report_format(*o.format, "--format");
  const std::string ext = std::filesystem::path(o.out).extension().string();
  if (ext == ".csv") return ReportFormat::Csv;
  if (ext == ".json") return ReportFormat::Json;
  if (ext == ".html" || ext == ".htm") return ReportFormat::Html;
  return ReportFormat::Markdown;
}

std::string describe_origin(const CoefficientOptions& o) {
  std::string s = "preset " + o.scene.preset;
  if (!o.scene.scene_file.empty()) s += ", scene file " + o.scene.scene_file;
  for (const auto& f : o.scene.flags)
    if (f.value) s += ", " + f.flag + " " + *f.value;
  for (const auto& set : o.scene.sets) s += ", --set " + set;
  return s;
}

int run_coefficients(const CoefficientOptions& o) {
  const ReportFormat format = choose_format(o);
  if (o.pressure.has_value() != o.temperature.has_value())
    throw InputError(o.pressure ? "--temperature" : "--pressure", "(missing)",
                     "--pressure and --temperature together (e.g. --pressure 250hPa --temperature 220K)");
  if (!std::isfinite(o.latitude_deg) || o.latitude_deg < -90.0 || o.latitude_deg > 90.0)
    throw InputError("--latitude", std::to_string(o.latitude_deg), "-90 to 90 degrees");
  const Scene scene = load_scene(o.scene, {}, SceneUse::Atmosphere);

  CoefficientReportRequest req;
  req.atmosphere = scene.atmosphere;
  req.wavelengths_nm = make_wavelength_grid(scene).nanometres();
  req.altitudes_m = parse_altitudes_m(o.altitudes, scene.atmosphere.top_altitude_m);
  if (o.pressure) req.conditions = AirConditions{parse_pressure_Pa(*o.pressure), parse_temperature_K(*o.temperature)};
  req.latitude_deg = o.latitude_deg;
  req.origin = describe_origin(o);

  // Check the destination before the work, so that a bad --out fails fast and leaves nothing.
  std::filesystem::path out_path;
  if (!o.out.empty()) {
    out_path = o.out;
    const auto parent = out_path.has_parent_path() ? out_path.parent_path() : std::filesystem::path(".");
    ensure_writable_directory(parent, "--out");
  }
  // A microphysical aerosol's optics (Lorenz-Mie at every wavelength) can take a minute: the bar
  // shows them.
  std::string text;
  {
    ProgressBar bar("coefficients", o.quiet);
    bar.watch_preparation();
    text = format_report(make_coefficient_report(req), format);
    bar.finish();
  }
  if (o.out.empty()) {
    std::cout << text;
    return kExitOk;
  }
  write_file_atomically(out_path, text);
  return kExitOk;
}

}  // namespace

Command add_coefficients_command(CLI::App& app) {
  auto opts = std::make_shared<CoefficientOptions>();
  opts->scene.flags = coefficient_flags();
  auto* cmd = app.add_subcommand(
      "coefficients",
      "Report how the scattering coefficients are derived, per wavelength, checked against published tables");
  cmd->footer(
      "Examples:\n"
      "  skyspec coefficients                                   # default scene, Markdown on stdout\n"
      "  skyspec coefficients --pressure 250hPa --temperature 220K --format json --out cold.json\n"
      "  skyspec coefficients --altitudes 0,1500,5000 --out report.html\n"
      "  skyspec coefficients --preset seed                     # the seed's typed-in constants vs the derivation\n"
      "  skyspec coefficients --wavelengths 440,550,680 --refractive-index ciddor --co2-ppm 360\n"
      "The atmosphere comes from the same presets, scene files and --set keys as `skyspec render`.\n"
      "--format defaults to the --out file's extension (.md, .csv, .json, .html), else md.");
  add_scene_options(*cmd, opts->scene);
  cmd->add_option("--altitudes", opts->altitudes,
                  "altitudes (m above sea level, comma-separated) for beta(z) and the optical depth to the top")
      ->capture_default_str();
  cmd->add_option("--pressure", opts->pressure, "also report air at this pressure, with unit: 250hPa, 25000Pa, 1atm");
  cmd->add_option("--temperature", opts->temperature, "... and this temperature, with unit: 220K, -53.15C");
  cmd->add_option("--latitude", opts->latitude_deg, "latitude for gravity in hydrostatic columns, degrees")
      ->capture_default_str();
  cmd->add_option("--format", opts->format, "md, csv, json or html");
  cmd->add_option("--out", opts->out, "output file (written atomically); default: standard output");
  cmd->add_flag("-q,--quiet", opts->quiet, "no progress bar");
  return {cmd, [opts] { return run_coefficients(*opts); },
          [opts] {  // run_coefficients' checks, without computing the report (Command::validate)
            choose_format(*opts);
            const Scene scene = load_scene(opts->scene, {}, SceneUse::Atmosphere);
            parse_altitudes_m(opts->altitudes, scene.atmosphere.top_altitude_m);
            if (opts->pressure) parse_pressure_Pa(*opts->pressure);
            if (opts->temperature) parse_temperature_K(*opts->temperature);
          }};
}

}  // namespace skyspec::cli
