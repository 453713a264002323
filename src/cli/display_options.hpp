// Command-line options of the display pipeline, shared by render, convert and compare: the OCIO
// config (--ocio, else the OCIO environment variable, else skyspec's built-in config), display,
// view, look, camera exposure, PNG bit depth and the working-space EXR.
#pragma once

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

#include "colour/display_pipeline.hpp"

namespace skyspec::cli {

struct DisplayOptions {
  std::string ocio, display, view, look, exr_space;
  std::optional<double> look_white;
  std::optional<double> iso, f_number;
  std::optional<std::string> shutter;
  int png_bits = 8;
  bool list = false;
};

struct DisplayOptionSet {
  bool exr_space = true;  ///< offer --exr-space
  bool camera = true;     ///< offer --iso, --shutter, --f-number
};

void add_display_options(CLI::App& app, DisplayOptions& o, DisplayOptionSet which = {});

/// The settings the options ask for. A camera exposure needs --shutter and --f-number (--iso
/// defaults to 100); `exposure_flag_given` says whether a manual --exposure was also given, which
/// is an error together with camera flags.
DisplaySettings display_settings(const DisplayOptions& o, bool exposure_flag_given = false);

/// "1/250", "0.004" or "4ms"-free plain seconds: the shutter time in seconds (InputError naming
/// --shutter otherwise).
double parse_shutter_s(const std::string& text);

/// With --list-displays: prints the config's displays, views and looks and returns true.
bool list_displays_if_asked(const DisplayOptions& o);

}  // namespace skyspec::cli
