// `skyspec convert`: an existing skyspec EXR through the display pipeline, without rendering.

#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "commands.hpp"
#include "display_options.hpp"
#include "render/display_conversion.hpp"
#include "skyspec/error.hpp"

namespace skyspec::cli {
namespace {

struct ConvertOptions {
  std::string input, out, name;
  std::optional<double> exposure_ev;
  bool no_png = false, quiet = false;
  DisplayOptions display;
};

int run_convert(const ConvertOptions& o) {
  if (list_displays_if_asked(o.display)) return kExitOk;
  if (o.input.empty()) throw InputError("INPUT", "(missing)", "a skyspec EXR to convert, e.g. skyspec-out/sky.exr");
  const std::filesystem::path input(o.input);
  const std::filesystem::path dir =
      o.out.empty() ? (input.has_parent_path() ? input.parent_path() : ".") : std::filesystem::path(o.out);
  const std::string name = o.name.empty() ? input.stem().string() : o.name;
  const auto out = convert_exr_for_display(input, dir, name, display_settings(o.display, o.exposure_ev.has_value()),
                                           o.exposure_ev, !o.no_png);
  if (!o.quiet) {
    if (!out.png.empty()) std::cout << "wrote " << out.png.string() << "\n";
    if (!out.working_exr.empty()) std::cout << "wrote " << out.working_exr.string() << "\n";
    if (!out.png.empty()) std::cout << "display: " << out.display << "\n";
    std::cout << "exposure: " << out.exposure.description << "\n";
  }
  return kExitOk;
}

}  // namespace

Command add_convert_command(CLI::App& app) {
  auto opts = std::make_shared<ConvertOptions>();
  auto* convert =
      app.add_subcommand("convert", "Apply the display pipeline to an existing skyspec EXR (no re-rendering)");
  convert->footer(
      "Examples:\n"
      "  skyspec convert skyspec-out/sky.exr --display \"Display P3\" --name sky-p3\n"
      "  skyspec convert skyspec-out/sky.exr --view \"ACES 1.0 - SDR Video\" --name sky-aces\n"
      "  skyspec convert skyspec-out/sky.exr --display Rec.2100-PQ --view \"ACES 1.1 - HDR Video (1000 nits & Rec.2020 "
      "lim)\" --png-bits 16 --name sky-pq\n"
      "  skyspec convert skyspec-out/sky.exr --no-png --exr-space ACEScg   # -> sky-acescg.exr\n"
      "The exposure recorded by `skyspec render` is used unless --exposure or a camera exposure is given.");
  convert->add_option("INPUT", opts->input, "a skyspec EXR (its R, G, B: linear Rec.709)");
  convert->add_option("--out", opts->out, "output folder (default: the input's folder)");
  convert->add_option("--name", opts->name, "base name of the outputs (default: the input's name)");
  convert->add_option("--exposure", opts->exposure_ev, "exposure in EV: scale 2^EV (default: the recorded one)");
  convert->add_flag("--no-png", opts->no_png, "write no PNG (with --exr-space)");
  convert->add_flag("-q,--quiet", opts->quiet, "no summary");
  add_display_options(*convert, opts->display);
  return {convert, [opts] { return run_convert(*opts); },
          [opts] {  // run_convert's checks, without reading the EXR (Command::validate)
            if (opts->display.list) return void(OcioConfig(display_settings(opts->display).config));
            DisplayPipeline{display_settings(opts->display, opts->exposure_ev.has_value())};
          }};
}

}  // namespace skyspec::cli
