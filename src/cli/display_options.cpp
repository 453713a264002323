#include "display_options.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "skyspec/error.hpp"

namespace skyspec::cli {

void add_display_options(CLI::App& app, DisplayOptions& o, DisplayOptionSet which) {
  const std::string group = "Display pipeline (OpenColorIO)";
  app.add_option("--ocio", o.ocio, "OpenColorIO config file (default: $OCIO, else skyspec's built-in config)")
      ->group(group);
  app.add_option("--display", o.display, "display: sRGB (default), \"Display P3\", \"Rec.1886 Rec.709\", Rec.2100-PQ")
      ->group(group);
  app.add_option("--view", o.view, "view, e.g. Un-tone-mapped (default), \"ACES 1.0 - SDR Video\"")->group(group);
  app.add_option("--look", o.look,
                 "look: an OCIO look (reinhard) or a skyspec look (reinhard-extended, "
                 "reinhard-luminance, uncharted2-filmic, aces-approx)")
      ->group(group);
  app.add_option("--look-white", o.look_white,
                 "reinhard-extended/-luminance: the exposed value that maps to 1 "
                 "(default: the image's largest luminance)")
      ->group(group);
  if (which.camera) {
    app.add_option("--iso", o.iso, "camera exposure: ISO speed (default 100)")->group(group);
    app.add_option("--shutter", o.shutter, "camera exposure: shutter time in s, e.g. 1/250")->group(group);
    app.add_option("--f-number", o.f_number, "camera exposure: f-number, e.g. 8")->group(group);
  }
  app.add_option("--png-bits", o.png_bits, "PNG bits per channel: 8 or 16")->capture_default_str()->group(group);
  if (which.exr_space)
    app.add_option("--exr-space", o.exr_space,
                   "also write a scene-linear RGB EXR in ACEScg, ACES2065-1 or \"Linear Rec.709\"")
        ->group(group);
  app.add_flag("--list-displays", o.list, "list the config's displays, views and looks, then exit")->group(group);
}

double parse_shutter_s(const std::string& text) {
  const auto fail = [&]() {
    return InputError("--shutter", "\"" + text + "\"", "a time in seconds, e.g. 1/250 or 0.004");
  };
  const auto number = [&](const std::string& s) {
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(v) || v <= 0.0) throw fail();
    return v;
  };
  const auto slash = text.find('/');
  if (slash == std::string::npos) return number(text);
  return number(text.substr(0, slash)) / number(text.substr(slash + 1));
}

DisplaySettings display_settings(const DisplayOptions& o, bool exposure_flag_given) {
  DisplaySettings s;
  if (!o.ocio.empty()) {
    s.config = {o.ocio, "--ocio"};
  } else if (const char* env = std::getenv("OCIO"); env && *env) {
    s.config = {env, "OCIO environment variable"};
  }
  s.display = o.display;
  s.view = o.view;
  s.look = o.look;
  s.look_white = o.look_white;
  s.png_bit_depth = o.png_bits;
  s.exr_space = o.exr_space;
  const bool camera = o.iso || o.shutter || o.f_number;
  if (camera) {
    if (exposure_flag_given)
      throw InputError("--exposure", "a manual exposure",
                       "no --iso, --shutter or --f-number with it (a manual and a camera exposure exclude each other)");
    if (!o.shutter || !o.f_number)
      throw InputError(o.shutter ? "--f-number" : "--shutter", "(not given)",
                       "a value: a camera exposure needs --shutter and --f-number (--iso defaults to 100)");
    s.exposure.mode = ExposureSettings::Mode::Camera;
    s.exposure.shutter_s = parse_shutter_s(*o.shutter);
    s.exposure.f_number = *o.f_number;
    s.exposure.iso = o.iso.value_or(100.0);
  }
  return s;
}

namespace {
// The built-in config as a file for other tools: where `cmake --install` puts it, relative to the
// installed program (<prefix>/bin/skyspec -> <prefix>/share/skyspec/ocio/config.ocio); empty when
// this program has no such file beside it (a build tree).
std::filesystem::path installed_builtin_config() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  const std::filesystem::path config = exe.parent_path().parent_path() / "share" / "skyspec" / "ocio" / "config.ocio";
  return std::filesystem::is_regular_file(config, ec) ? config : std::filesystem::path();
}
}  // namespace

bool list_displays_if_asked(const DisplayOptions& o) {
  if (!o.list) return false;
  const DisplaySettings s = display_settings(o);
  const OcioConfig config(s.config);
  std::cout << describe_displays_and_looks(config);
  if (config.is_builtin()) {
    const std::filesystem::path file = installed_builtin_config();
    std::cout << "\nThe built-in config as a file, for other tools (oiiotool --colorconfig, ociocheck --iconfig): "
              << (file.empty() ? std::string("data/ocio/config.ocio in skyspec's sources; `cmake --install` puts it in "
                                             "<prefix>/share/skyspec/ocio/config.ocio")
                               : file.string())
              << "\n";
  }
  return true;
}

}  // namespace skyspec::cli
