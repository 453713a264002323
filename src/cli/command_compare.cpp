// `skyspec compare`: the RGB-fast sky against the spectral one (or two existing EXRs), with a
// report, a Delta E map, a side-by-side preview and optionally a sweep over sun elevations.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "base/atomic_file.hpp"
#include "commands.hpp"
#include "display_options.hpp"
#include "progress.hpp"
#include "report/comparison_report.hpp"
#include "scene_options.hpp"
#include "skyspec/error.hpp"
#include "skyspec/sky_comparison.hpp"

namespace skyspec::cli {
namespace {

std::vector<KeyFlag> compare_flags() {
  std::vector<KeyFlag> flags = camera_flags(true);
  append_flags(flags, sun_flags());
  append_flags(flags, {
                          {"--view-segments", "render.view_segments", "quadrature segments per view ray", {}, false},
                          {"--threads", "render.threads", "worker threads (0: all cores)", {}, false},
                      });
  return flags;
}

struct CompareOptions {
  SceneOptions scene{"default", {}, {}, compare_flags()};
  std::vector<std::string> exrs;
  std::string out = "skyspec-compare", name = "compare", sweep;
  RegionSettings regions;
  double delta_e_max = 10.0;
  bool keep_sun_disk = false, quiet = false;
  DisplayOptions display;
};

/// "START:STOP:STEP" (inclusive) or "a,b,c": sun elevations in degrees, each within [-90, 90].
std::vector<double> parse_sweep(const std::string& text) {
  const auto fail = [&]() {
    return InputError("--sweep", "\"" + text + "\"",
                      "START:STOP:STEP (e.g. -6:90:3) or a list (e.g. -6,-3,0,2,5,10,30,60,90) of elevations "
                      "from -90 to 90 degrees, at most 1000");
  };
  const auto number = [&](const std::string& s) {
    std::istringstream in(s);
    in.imbue(std::locale::classic());
    double v = 0;
    if (!(in >> v) || !in.eof() || !std::isfinite(v)) throw fail();
    return v;
  };
  std::vector<double> values;
  if (text.find(':') != std::string::npos) {
    std::vector<std::string> parts;
    std::string part;
    std::istringstream in(text);
    while (std::getline(in, part, ':')) parts.push_back(part);
    if (parts.size() != 3) throw fail();
    const double a = number(parts[0]), b = number(parts[1]), step = number(parts[2]);
    if (!(step > 0) || b < a || (b - a) / step > 1000) throw fail();
    // Counted, not "while a + i * step <= b": a step below the spacing of doubles near a (e.g.
    // 90:90:1e-300) leaves a + i * step == a for ever (tests/fuzz/regressions/cli/).
    const int count = static_cast<int>(std::floor((b - a) / step + 1e-9)) + 1;
    for (int i = 0; i < count; ++i) values.push_back(std::min(a + i * step, b));
  } else {
    std::string part;
    std::istringstream in(text);
    while (std::getline(in, part, ',')) values.push_back(number(part));
  }
  if (values.empty() || values.size() > 1000) throw fail();
  for (double v : values)
    if (v < -90 || v > 90) throw fail();
  return values;
}

std::string command_line(const CompareOptions& o) {
  std::string cmd = "skyspec compare";
  const auto arg = [&](const std::string& flag, const std::string& value) {
    const bool quote = value.find_first_of(" ,()&") != std::string::npos;
    cmd += " " + flag + (value.empty() ? "" : " " + (quote ? "\"" + value + "\"" : value));
  };
  if (o.exrs.empty()) {
    if (o.scene.preset != "default") arg("--preset", o.scene.preset);
    if (!o.scene.scene_file.empty()) arg("--scene", o.scene.scene_file);
    for (const auto& f : o.scene.flags)
      if (f.value) arg(f.flag, *f.value);
    for (const auto& s : o.scene.sets) arg("--set", s);
    if (!o.sweep.empty()) arg("--sweep", o.sweep);
    if (o.keep_sun_disk) arg("--keep-sun-disk", "");
  } else {
    for (const auto& e : o.exrs) cmd += " " + e;
  }
  const RegionSettings defaults;
  if (o.regions.near_sun_deg != defaults.near_sun_deg) arg("--near-sun-deg", std::to_string(o.regions.near_sun_deg));
  if (o.regions.horizon_deg != defaults.horizon_deg) arg("--horizon-deg", std::to_string(o.regions.horizon_deg));
  if (o.regions.zenith_deg != defaults.zenith_deg) arg("--zenith-deg", std::to_string(o.regions.zenith_deg));
  if (!o.display.display.empty()) arg("--display", o.display.display);
  if (!o.display.view.empty()) arg("--view", o.display.view);
  if (!o.display.look.empty()) arg("--look", o.display.look);
  arg("--out", o.out);
  if (o.name != "compare") arg("--name", o.name);
  return cmd;
}

std::string scene_summary(const Scene& s, const std::string& origin) {
  char text[256];
  const char* camera = camera_type_name(s.camera.type);
  std::snprintf(text, sizeof text, "%s, %s %d x %d, sun elevation %.4g deg, azimuth %.4g deg, %d scattering order%s",
                origin.c_str(), camera, s.camera.width, s.camera.height, s.sun.elevation_deg, s.sun.azimuth_deg,
                s.render.scattering_orders, s.render.scattering_orders == 1 ? "" : "s");
  return text;
}

void check_regions(const RegionSettings& r) {
  const auto check = [](double v, const char* flag) {
    if (!std::isfinite(v) || v < 0 || v > 90)
      throw InputError(flag, std::to_string(v), "an angle from 0 to 90 degrees");
  };
  check(r.near_sun_deg, "--near-sun-deg");
  check(r.horizon_deg, "--horizon-deg");
  check(r.zenith_deg, "--zenith-deg");
}

// The outputs besides <name>.json and <name>.md.
constexpr const char* kDeltaEMapSuffix = "-delta-e.png";
constexpr const char* kSideBySideSuffix = "-side-by-side.png";
constexpr const char* kSweepPlotSuffix = "-sweep.svg";

int run_compare(const CompareOptions& o) {
  if (list_displays_if_asked(o.display)) return kExitOk;
  check_regions(o.regions);
  if (!(o.delta_e_max > 0) || !std::isfinite(o.delta_e_max))
    throw InputError("--delta-e-max", std::to_string(o.delta_e_max), "a positive number");
  if (o.name.empty() || o.name.find('/') != std::string::npos)
    throw InputError("--name", "\"" + o.name + "\"", "a file name without '/'");
  if (!o.exrs.empty() && o.exrs.size() != 2)
    throw InputError("EXR files", std::to_string(o.exrs.size()) + " given", "none (render the scene twice) or two");
  if (!o.exrs.empty() && !o.sweep.empty())
    throw InputError("--sweep", o.sweep, "only when rendering a scene, not with two EXR files");
  const std::vector<double> elevations = o.sweep.empty() ? std::vector<double>{} : parse_sweep(o.sweep);
  const DisplayPipeline pipeline(display_settings(o.display));  // names checked before any work
  ensure_writable_directory(o.out, "--out");
  {  // before anything is rendered: no output may replace an input
    std::vector<NamedInput> inputs = scene_input_files(o.scene);
    for (const auto& exr : o.exrs) inputs.push_back({"EXR", exr});
    for (const char* suffix : {kDeltaEMapSuffix, kSideBySideSuffix, kSweepPlotSuffix, ".json", ".md"})
      refuse_output_replacing_input(std::filesystem::path(o.out) / (o.name + suffix), "--out / --name", inputs);
  }

  ComparisonRun run;
  run.command = command_line(o);
  run.regions = o.regions;
  run.delta_e_max = o.delta_e_max;
  SkyImage reference, test;
  Scene scene;
  ProgressBar bar("rendering", o.quiet);
  if (!o.exrs.empty()) {
    Scene scene_b;
    reference = read_sky_image(o.exrs[0], &scene);
    test = read_sky_image(o.exrs[1], &scene_b);
    if (reference.path != "spectral" && test.path == "spectral") {
      std::swap(reference, test);
      std::swap(scene, scene_b);
    }
    const auto& a = scene.camera;
    const auto& b = scene_b.camera;
    if (a.type != b.type || a.width != b.width || a.height != b.height || a.position_m != b.position_m ||
        scene.sun.elevation_deg != scene_b.sun.elevation_deg || scene.sun.azimuth_deg != scene_b.sun.azimuth_deg)
      throw InputError("EXR files", o.exrs[0] + " and " + o.exrs[1], "two renders of the same camera and sun");
    run.scene_summary = scene_summary(scene, "from " + o.exrs[0] + " and " + o.exrs[1]);
  } else {
    scene = load_scene(o.scene);
    if (!o.keep_sun_disk) {
      scene.sun.disk = false;
      run.notes.push_back(
          "The sun's disk is not drawn (sun.disk = false; --keep-sun-disk draws it): the comparison is "
          "about the sky, including the aureole.");
    }
    const bool scene_is_fast = scene.render.path == RenderSpec::Path::RgbFast;
    std::string note;
    const Scene spectral = scene_is_fast ? spectral_twin(scene, &note) : scene;
    const Scene fast = scene_is_fast ? scene : rgb_fast_twin(scene);
    if (!note.empty()) run.notes.push_back(note);
    run.notes.push_back(scene_is_fast
                            ? "The scene is RGB-fast; its spectral twin has the same atmosphere, sun and camera on "
                              "380-780 nm in 10 nm steps."
                            : "The scene is spectral; its RGB-fast twin has the same atmosphere, sun and camera on "
                              "440, 550 and 680 nm.");
    const std::string origin =
        o.scene.scene_file.empty() ? "preset " + o.scene.preset : o.scene.scene_file + " over preset " + o.scene.preset;
    run.scene_summary = scene_summary(scene, origin);
    const int renders = 2 * (1 + static_cast<int>(elevations.size()));
    int finished = 0;
    const auto progress = [&](int done, int total) { bar.update(finished * total + done, renders * total); };
    reference = render_sky_image(spectral, progress);
    ++finished;
    test = render_sky_image(fast, progress);
    ++finished;
    for (double elevation : elevations) {
      Scene a = spectral, b = fast;
      a.sun.elevation_deg = b.sun.elevation_deg = elevation;
      const SkyImage ra = render_sky_image(a, progress);
      ++finished;
      const SkyImage rb = render_sky_image(b, progress);
      ++finished;
      const SkyComparison c = compare_skies(ra, rb, pixel_geometry(a, o.regions));
      run.sweep.push_back({elevation, c.all, c.regions});
    }
  }
  bar.finish();
  run.sun_elevation_deg = scene.sun.elevation_deg;
  run.reference_label = reference.label;
  run.test_label = test.label;
  run.comparison = compare_skies(reference, test, pixel_geometry(scene, o.regions));

  const std::filesystem::path dir(o.out);
  run.delta_e_map_file = o.name + kDeltaEMapSuffix;
  run.side_by_side_file = o.name + kSideBySideSuffix;
  if (!run.sweep.empty()) run.sweep_plot_file = o.name + kSweepPlotSuffix;
  std::vector<std::filesystem::path> written;
  try {
    const auto keep = [&](const std::filesystem::path& p) {
      written.push_back(p);
      return p;
    };
    write_delta_e_map(keep(dir / run.delta_e_map_file), run.comparison, run.delta_e_max);
    write_side_by_side(keep(dir / run.side_by_side_file), run.comparison, pipeline, "SPECTRAL", "RGB-FAST");
    if (!run.sweep.empty()) write_text_file(keep(dir / run.sweep_plot_file), sweep_plot_svg(run.sweep));
    write_text_file(keep(dir / (o.name + ".json")), comparison_json(run));
    write_text_file(keep(dir / (o.name + ".md")), comparison_markdown(run));
  } catch (...) {
    std::error_code ec;
    for (const auto& p : written) std::filesystem::remove(p, ec);
    throw;
  }
  if (!o.quiet) {
    const auto& d = run.comparison.all.delta_e;
    std::printf(
        "Delta E 2000 (%zu sky pixels, sun %.4g deg): mean %.2f, median %.2f, p95 %.2f, max %.2f; "
        "above 1: %.1f %%, 2: %.1f %%, 5: %.1f %%\n",
        d.pixels, run.sun_elevation_deg, d.mean, d.median, d.p95, d.max, 100 * d.share_above_1, 100 * d.share_above_2,
        100 * d.share_above_5);
    for (const auto& p : written) std::cout << "wrote " << p.string() << "\n";
  }
  return kExitOk;
}

}  // namespace

Command add_compare_command(CLI::App& app) {
  auto opts = std::make_shared<CompareOptions>();
  auto* compare =
      app.add_subcommand("compare", "Compare the RGB-fast sky with the spectral one: Delta E report, map, plot");
  compare->footer(
      "Examples:\n"
      "  skyspec compare --width 128 --height 128                     # default scene vs its RGB-fast twin\n"
      "  skyspec compare --preset seed --sun-elevation 2              # the seed tutorial's sky vs its spectral twin\n"
      "  skyspec compare --preset seed --width 96 --height 96 --sweep -6:90:3\n"
      "  skyspec compare spectral.exr rgb-fast.exr                    # two existing renders of one camera and sun\n"
      "Outputs in --out: NAME.md, NAME.json, NAME-delta-e.png, NAME-side-by-side.png, NAME-sweep.svg (with --sweep).\n"
      "The rules (common white: the sun; common exposure: the spectral image's automatic exposure) are in the report.");
  add_scene_options(*compare, opts->scene);
  add_quality_option(*compare, opts->scene);
  compare->add_option("EXR", opts->exrs, "two skyspec EXRs instead of a scene: the spectral one is the reference");
  compare->add_option("--out", opts->out, "output folder (created if missing)")->capture_default_str();
  compare->add_option("--name", opts->name, "base name of the outputs")->capture_default_str();
  compare->add_option("--sweep", opts->sweep, "also compare over sun elevations: START:STOP:STEP or a,b,c (degrees)");
  compare
      ->add_option("--near-sun-deg", opts->regions.near_sun_deg, "region 'near the sun': angular distance below this")
      ->capture_default_str();
  compare->add_option("--horizon-deg", opts->regions.horizon_deg, "region 'horizon band': elevation below this")
      ->capture_default_str();
  compare->add_option("--zenith-deg", opts->regions.zenith_deg, "region 'zenith': zenith angle below this")
      ->capture_default_str();
  compare->add_option("--delta-e-max", opts->delta_e_max, "top of the Delta E map's colour bar")->capture_default_str();
  compare->add_flag("--keep-sun-disk", opts->keep_sun_disk, "draw the sun's disk (default: off, the sky is compared)");
  compare->add_flag("-q,--quiet", opts->quiet, "no progress bar and no summary");
  add_display_options(*compare, opts->display, DisplayOptionSet{false, false});
  return {compare, [opts] { return run_compare(*opts); },
          [opts] {  // run_compare's checks, without rendering or reading EXRs (Command::validate)
            if (opts->display.list) return void(OcioConfig(display_settings(opts->display).config));
            check_regions(opts->regions);
            if (!opts->sweep.empty()) parse_sweep(opts->sweep);
            DisplayPipeline{display_settings(opts->display)};
            if (opts->exrs.empty()) load_scene(opts->scene);
          }};
}

}  // namespace skyspec::cli
