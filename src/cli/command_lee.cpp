// `skyspec lee-diagram`: the colour of light scattered by water drops against scattering angle and
// drop radius (skyspec/lee_diagram.hpp), as a spectral EXR and a PNG.

#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "display_options.hpp"
#include "progress.hpp"
#include "skyspec/lee_diagram.hpp"

namespace skyspec::cli {
namespace {

struct LeeOptions {
  LeeDiagramSettings settings;
  std::string out = "skyspec-out", name = "lee";
  bool no_png = false, quiet = false;
  DisplayOptions display;
};

int run_lee(const LeeOptions& o) {
  if (list_displays_if_asked(o.display)) return kExitOk;
  const LeeDiagramSettings s = o.settings;
  check_lee_diagram_settings(s);
  const DisplaySettings display = display_settings(o.display);
  DisplayPipeline{display};  // the display's names, before the computation
  ProgressBar bar("lee diagram", o.quiet);
  const LeeDiagram diagram = compute_lee_diagram(s, [&bar](int done, int total) { bar.update(done, total); });
  bar.finish();
  const LeeDiagramFiles files = write_lee_diagram(diagram, o.out, o.name, display, !o.no_png);
  if (!o.quiet) {
    std::cout << "wrote " << files.exr.string() << "\n";
    if (!files.png.empty())
      std::cout << "wrote " << files.png.string() << " (each row scaled to its brightest pixel)\n";
    std::cout << diagram.width << " x " << diagram.height << " pixels: scattering angle " << s.angle_min_deg << "-"
              << s.angle_max_deg << " deg, drop radius " << s.radius_max_um << "-" << s.radius_min_um << " um, "
              << diagram.wavelengths_nm.size() << " wavelengths\n";
  }
  return kExitOk;
}

}  // namespace

Command add_lee_command(CLI::App& app) {
  auto opts = std::make_shared<LeeOptions>();
  auto* lee = app.add_subcommand(
      "lee-diagram", "The colour of sunlight scattered by water drops against scattering angle and drop radius");
  lee->footer(
      "Each row is one drop radius (largest at the top), each column a scattering angle; the EXR holds\n"
      "E_sun(lambda) P_11, the radiance per unit scattering optical depth of the drops (Lorenz-Mie theory).\n"
      "Examples:\n"
      "  skyspec lee-diagram                          # primary and secondary bows, 10 um - 1 mm\n"
      "  skyspec lee-diagram --angle-min 170 --angle-max 180 --radius-min-um 2 --radius-max-um 50   # glories\n"
      "  skyspec lee-diagram --polarisation --name lee-polarised");
  LeeDiagramSettings& s = opts->settings;
  lee->add_option("--radius-min-um", s.radius_min_um, "smallest drop radius, um (bottom row)")->capture_default_str();
  lee->add_option("--radius-max-um", s.radius_max_um, "largest drop radius, um (top row)")->capture_default_str();
  lee->add_option("--angle-min", s.angle_min_deg, "smallest scattering angle, degrees (left)")->capture_default_str();
  lee->add_option("--angle-max", s.angle_max_deg, "largest scattering angle, degrees (right)")->capture_default_str();
  lee->add_option("--width", s.width, "columns")->capture_default_str();
  lee->add_option("--height", s.height, "rows")->capture_default_str();
  lee->add_option("--lambda-min", s.lambda_min_nm, "shortest wavelength, nm")->capture_default_str();
  lee->add_option("--lambda-max", s.lambda_max_nm, "longest wavelength, nm")->capture_default_str();
  lee->add_option("--lambda-step", s.lambda_step_nm, "wavelength step, nm")->capture_default_str();
  lee->add_option("--water-temperature", s.water_temperature_C, "water temperature, degC")->capture_default_str();
  lee->add_option("--angle-samples", s.angle_subsamples, "scattering angles averaged per column")
      ->capture_default_str();
  lee->add_flag("--polarisation", s.polarisation, "also write S1 (Q: positive perpendicular to the scattering plane)");
  lee->add_option("--out", opts->out, "output folder")->capture_default_str();
  lee->add_option("--name", opts->name, "base name of the files")->capture_default_str();
  lee->add_flag("--no-png", opts->no_png, "write the EXR only");
  lee->add_flag("-q,--quiet", opts->quiet, "no progress bar, no summary");
  add_display_options(*lee, opts->display, DisplayOptionSet{false, false});
  return {lee, [opts] { return run_lee(*opts); },
          [opts] {  // run_lee's checks, without computing or writing
            if (opts->display.list) return void(OcioConfig(display_settings(opts->display).config));
            check_lee_diagram_settings(opts->settings);
            DisplayPipeline{display_settings(opts->display)};
          }};
}

}  // namespace skyspec::cli
