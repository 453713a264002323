// `skyspec irradiance`: direct and diffuse irradiance and illuminance on a horizontal surface at
// the camera, for the scene's sun or a list of sun elevations.

#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "base/atomic_file.hpp"
#include "commands.hpp"
#include "progress.hpp"
#include "render/irradiance.hpp"
#include "scene_options.hpp"
#include "skyspec/error.hpp"
#include "skyspec/render.hpp"
#include "text_output.hpp"

namespace skyspec::cli {
namespace {

struct IrradianceOptions {
  SceneOptions scene;
  std::string elevations;  // comma-separated degrees
  std::string format = "md";
  std::string out;
  bool quiet = false;
};

std::vector<double> parse_elevations(const std::string& text) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0' || !(x >= -90.0 && x <= 90.0))
      throw InputError("--sun-elevations", "\"" + item + "\"",
                       "comma-separated angles in degrees, each from -90 to 90");
    v.push_back(x);
  }
  if (v.empty()) throw InputError("--sun-elevations", "\"\"", "at least one angle in degrees");
  return v;
}

int run(IrradianceOptions& o) {
  if (o.format != "md" && o.format != "csv") throw InputError("--format", "\"" + o.format + "\"", "one of: md, csv");
  const Scene base = load_scene(o.scene, [](SceneLoader& l) {
    // Only the camera position matters; a 1x1 image keeps the set-up cheap.
    l.apply_override("camera.width", "1", "irradiance");
    l.apply_override("camera.height", "1", "irradiance");
  });
  const std::vector<double> elevations =
      o.elevations.empty() ? std::vector<double>{base.sun.elevation_deg} : parse_elevations(o.elevations);
  // The first elevation builds the scattering-order tables (and the broadband runs' tables), which
  // the bar shows; then the elevations done. The scene's refusals come before any work.
  ProgressBar bar("irradiance", o.quiet);
  bar.watch_preparation();
  const std::vector<IrradianceReport> reports =
      irradiance_reports(base, elevations, [&](int done, int total) { bar.update(done, total); });
  bar.finish();
  std::ostringstream text;
  const bool broadband = base.irradiance.broadband;
  if (o.format == "md") {
    text << "| sun elevation (deg) | direct normal (W/m2) | direct normal (lx) | direct horizontal (lx) | "
            "diffuse horizontal (W/m2) | diffuse horizontal (lx) | global horizontal (lx) | global CCT (K) | "
            "diffuse CCT (K) |"
         << (broadband ? " broadband global horizontal (W/m2) |\n" : "\n")
         << "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |" << (broadband ? " ---: |\n" : "\n");
  } else {  // the band the W/m2 columns integrate over, then every number of the list
    text << "sun_elevation_deg,band_min_nm,band_max_nm";
    for (const IrradianceQuantity& q : irradiance_quantities())
      if (!q.spectral() && (broadband || !q.of_broadband)) text << "," << q.key;
    text << ",global_cct_K,global_duv,diffuse_cct_K,diffuse_duv\n";
  }
  // A CCT as text: empty (CSV) or "-" (Markdown) where the light has none.
  const auto cct_text = [&](const std::optional<ColourTemperature>& c, bool with_duv) {
    if (!c) return std::string(o.format == "md" ? "-" : (with_duv ? "," : ""));
    char buf[64];
    if (with_duv)
      std::snprintf(buf, sizeof buf, "%.1f,%.5f", c->cct_K, c->duv);
    else
      std::snprintf(buf, sizeof buf, "%.0f", c->cct_K);
    return std::string(buf);
  };
  for (size_t k = 0; k < elevations.size(); ++k) {
    const double el = elevations[k];
    const IrradianceReport& rep = reports[k];
    char line[512];
    const bool md = o.format == "md";
    if (md)
      std::snprintf(line, sizeof line, "| %g | %.1f | %.0f | %.0f | %.1f | %.0f | %.0f | ", el, rep.direct_normal_W_m2,
                    rep.direct_normal_lux, rep.direct_horizontal_lux, rep.diffuse_horizontal_W_m2,
                    rep.diffuse_horizontal_lux, rep.global_horizontal_lux());
    else
      std::snprintf(line, sizeof line, "%g,%g,%g,", el, rep.band_min_nm(), rep.band_max_nm());
    text << line;
    if (!md)
      for (const IrradianceQuantity& q : irradiance_quantities()) {
        if (q.spectral() || !q.present_in(rep)) continue;
        std::snprintf(line, sizeof line, "%.*f,", q.decimals, q.value(rep));
        text << line;
      }
    text << cct_text(rep.global_horizontal_cct, !md) << (md ? " | " : ",") << cct_text(rep.diffuse_horizontal_cct, !md);
    if (md && rep.broadband) {
      std::snprintf(line, sizeof line, " | %.1f", rep.broadband->global_horizontal_W_m2());
      text << line;
    }
    text << (md ? " |\n" : "\n");
  }
  if (o.format == "md")
    text << "\nDirect normal and diffuse horizontal W/m2 over " << make_wavelength_grid(base).min_nm() << "-"
         << make_wavelength_grid(base).max_nm()
         << " nm; lux = 683 lm/W x y-bar-weighted integral; CCT: correlated colour temperature (CIE 015, nearest "
            "Planckian chromaticity in the CIE 1960 UCS diagram; - where the light has none)."
         << (broadband ? " Broadband global horizontal: 300-4000 nm with the gases' absorption bands "
                         "(irradiance.broadband; docs/jobs.md, \"Irradiance and pyranometers\")."
                       : "")
         << "\n";
  print_or_write(text.str(), o.out);
  return kExitOk;
}

}  // namespace

Command add_irradiance_command(CLI::App& app) {
  auto o = std::make_shared<IrradianceOptions>();
  auto* cmd = app.add_subcommand("irradiance",
                                 "Direct and diffuse irradiance (W/m2), illuminance (lux) and colour temperature on a "
                                 "horizontal surface at the camera");
  cmd->footer(
      "Example:\n"
      "  skyspec irradiance --sun-elevations 5,10,20,30,45,60,90\n"
      "The scene's camera position is the measuring point; the sky includes every scattering order the\n"
      "scene asks for (render.scattering_orders) and its ground albedo.");
  o->scene.flags = spectrum_flags();
  o->scene.flags.push_back({"--position", "camera.position_m", "measuring point east,north,height in m", {}, true});
  o->scene.flags.push_back({"--sun-azimuth", "sun.azimuth_deg", "sun azimuth, degrees", {}, false});
  add_scene_options(*cmd, o->scene);
  add_quality_option(*cmd, o->scene);
  cmd->add_option("--sun-elevations", o->elevations,
                  "comma-separated sun elevations in degrees (default: the scene's)");
  cmd->add_option("--format", o->format, "md (Markdown table) or csv")->capture_default_str();
  cmd->add_option("--out", o->out, "write to this file instead of standard output");
  cmd->add_flag("-q,--quiet", o->quiet, "no progress bar");
  return {cmd, [o] { return run(*o); },
          [o] {  // run's checks, without computing (Command::validate)
            load_scene(o->scene, [](SceneLoader& l) { l.apply_override("camera.width", "1", "irradiance"); });
            if (!o->elevations.empty()) parse_elevations(o->elevations);
          }};
}

}  // namespace skyspec::cli
