// `skyspec render`: a scene (preset + file + flags) to a spectral EXR and a PNG preview.

#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/atomic_file.hpp"
#include "commands.hpp"
#include "display_options.hpp"
#include "progress.hpp"
#include "render/broadband_irradiance.hpp"
#include "render/irradiance.hpp"
#include "render/render_budget.hpp"
#include "scene_options.hpp"
#include "skyspec/error.hpp"
#include "skyspec/render.hpp"
#include "skyspec/scene.hpp"

namespace skyspec::cli {
namespace {

std::vector<KeyFlag> render_flags() {
  std::vector<KeyFlag> flags = output_flags();
  append_flags(flags, camera_flags(true));
  append_flags(flags, sun_flags());
  append_flags(flags, spectrum_flags());
  append_flags(flags,
               {
                   {"--path", "render.path", "spectral or rgb-fast", {}, false},
                   {"--view-segments", "render.view_segments", "quadrature segments per view ray", {}, false},
                   {"--threads", "render.threads", "worker threads (0: all cores)", {}, false},
                   {"--exposure", "output.exposure_ev", "preview exposure in EV (default: automatic)", {}, false},
               });
  return flags;
}

struct RenderOptions {
  SceneOptions scene{"default", {}, {}, render_flags()};
  DisplayOptions display;
  bool no_exr = false, no_png = false, quiet = false, print_scene = false;
  std::string help_keys;  ///< "", "text" or "markdown"
  bool force = false, dry_run = false;
  std::string pixel_bounds;  ///< --pixel-bounds x0,x1,y0,y1: a tile
};

Scene load_scene(const RenderOptions& o) {
  return cli::load_scene(o.scene, [&](SceneLoader& loader) {
    if (o.no_exr) loader.apply_override("output.exr", "false", "--no-exr");
    if (o.no_png) loader.apply_override("output.png", "false", "--no-png");
    // A tile writes its spectral EXR alone: the PNG comes from the merged file (skyspec convert).
    if (!o.pixel_bounds.empty()) loader.apply_override("output.png", "false", "--pixel-bounds");
  });
}

// --pixel-bounds, checked against the scene's image.
std::optional<PixelBounds> tile_of(const RenderOptions& o, const Scene& scene) {
  if (o.pixel_bounds.empty()) return std::nullopt;
  const PixelBounds b = parse_pixel_bounds(o.pixel_bounds, "--pixel-bounds");
  check_pixel_bounds(b, scene.camera, "--pixel-bounds");
  return b;
}

bool exposure_flag_given(const RenderOptions& o) {
  for (const auto& f : o.scene.flags)
    if (f.flag == "--exposure") return f.value.has_value();
  return false;
}

// Absolute photometry of the render for the summary: the sky's luminance at the zenith and the
// illuminance the sun and the sky put on a horizontal surface at the camera, from the renderer
// that makes the image (its tables are built once: a few thousand rays or table look-ups).
std::string photometry_line(const SkyRenderer& r) {
  const Rgb rgb = r.radiance_rgb(r.camera_origin_m().normalized());
  const double zenith_cd_m2 = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
  const IrradianceReport e = irradiance_at_camera(r, 16, 32);
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "luminance at the zenith %.4g cd/m2; at the camera, horizontal: direct %.4g lx, diffuse %.4g lx",
                zenith_cd_m2, e.direct_horizontal_lux, e.diffuse_horizontal_lux);
  std::string line = buf;
  // With irradiance.broadband, what a pyranometer at the camera would read (five more runs).
  if (r.scene().irradiance.broadband) {
    const BroadbandIrradiance bb = broadband_irradiance(r.scene(), 16, 32);
    std::snprintf(buf, sizeof buf, "; broadband (300-4000 nm, the gases' bands) global horizontal %.1f W/m2",
                  bb.global_horizontal_W_m2());
    line += buf;
  }
  return line;
}

int run_render(RenderOptions& o) {
  if (list_displays_if_asked(o.display)) return kExitOk;
  if (o.help_keys == "markdown") {
    std::cout << scene_keys_markdown();
    return kExitOk;
  }
  if (!o.help_keys.empty()) {
    for (const auto& [key, doc] : scene_key_help()) std::cout << key << "  " << doc << "\n";
    return kExitOk;
  }
  const Scene scene = load_scene(o);
  if (o.print_scene) {
    std::cout << scene_to_toml(scene);
    return kExitOk;
  }
  const DisplaySettings display = display_settings(o.display, exposure_flag_given(o));
  for (const auto& path : render_output_paths(scene, display).files())
    refuse_output_replacing_input(path, "--out / --name", scene_input_files(o.scene));
  // Absurd requests are refused up front (render_budget.hpp): the sizes and the memory before the
  // renderer is built, the time once it is (measured on it, inside render_scene_to_files).
  const std::optional<PixelBounds> tile = tile_of(o, scene);
  // A tile writes its spectral EXR alone, and the surface file cannot be merged from tiles.
  if (tile && scene.output.surface)
    throw InputError("output.surface", "true",
                     "false with --pixel-bounds (a tile writes its spectral EXR alone; render the surface file "
                     "without --pixel-bounds: it is geometry only)");
  RenderPlan plan = RenderPlan::for_scene(scene, display, 1, tile.has_value());
  if (tile) plan.width = tile->x1 - tile->x0, plan.height = tile->y1 - tile->y0;
  // Its errors first; a folder created here is removed again if the render is refused or fails.
  std::optional<OutputFolderGuard> folder;
  if (!o.dry_run) folder.emplace(scene.output.directory, "output.directory");
  RenderEstimate estimate = estimate_render(plan);
  if (!o.force) refuse_if_over_budget(estimate);
  std::string photometry;
  const auto measure = [&](const SkyRenderer& r) {  // once the tables are built
    const auto tables = estimate.table_seconds;
    estimate.table_seconds.reset();  // built: only the image's time counts now
    estimate.seconds = measure_render_seconds(r, plan);
    if (!o.force) refuse_if_over_budget(estimate);
    estimate.table_seconds = tables;  // for the summary: what the tables were estimated to take
  };
  // The summary's broadband irradiance (irradiance.broadband) solves five more scenes, each with
  // scattering-order tables of its own.
  const auto broadband_tables = [&scene](double& seconds, std::uint64_t& bytes) {
    if (!scene.irradiance.broadband || scene.render.path != RenderSpec::Path::Spectral) return;
    for (const Scene& run : broadband_run_scenes(scene)) {
      seconds += estimate_scattering_orders_seconds(run);
      bytes += estimate_table_cache_bytes(run);
    }
  };
  if (o.dry_run) {  // nothing expensive: a light renderer, and the tables it leaves out estimated
    const SkyRenderer light(scene_for_estimate(scene));
    double seconds = estimate_table_seconds(scene, light);
    std::uint64_t bytes = estimate_table_cache_bytes(scene);
    broadband_tables(seconds, bytes);
    estimate.table_seconds = seconds;
    estimate.table_cache_bytes = bytes;
    estimate.seconds = measure_render_seconds(light, plan);
    if (!o.force) refuse_if_over_budget(estimate);
    std::cout << "estimate: " << estimate.describe() << " (" << plan.settings() << ")\n";
    return kExitOk;
  }
  // The bar shows the preparation from here: the estimate below computes a microphysical aerosol's
  // optics (it names the tables by them), which can take a minute.
  ProgressBar bar("rendering", o.quiet);
  bar.watch_preparation();
  // The scattering-order tables can take hours at extreme settings: refused before they are built.
  // (The summary then quotes that estimate when they were built, beside the time they took.)
  double orders = estimate_scattering_orders_seconds(scene);
  std::uint64_t unused_bytes = 0;
  broadband_tables(orders, unused_bytes);
  if (orders > 0.0) estimate.table_seconds = orders;
  if (!o.force) refuse_if_over_budget(estimate);
  const auto prepared = [&](const SkyRenderer& r) {
    measure(r);
    if (!o.quiet && scene.render.path == RenderSpec::Path::Spectral && r.grid().size() >= 2)
      photometry = photometry_line(r);
  };
  const auto out = render_scene_to_files(
      scene, display, [&](int done, int total) { bar.update(done, total); }, prepared, tile);
  bar.finish();
  if (!o.quiet) {
    if (!out.exr.empty()) std::cout << "wrote " << out.exr.string() << "\n";
    if (!out.png.empty())
      std::cout << "wrote " << out.png.string() << " (preview exposure " << out.preview_ev << " EV)\n";
    if (!out.working_exr.empty()) std::cout << "wrote " << out.working_exr.string() << "\n";
    if (!out.polarisation_exr.empty()) std::cout << "wrote " << out.polarisation_exr.string() << "\n";
    if (!out.polarisation_png.empty()) std::cout << "wrote " << out.polarisation_png.string() << "\n";
    if (!out.surface_exr.empty()) std::cout << "wrote " << out.surface_exr.string() << "\n";
    if (!out.png.empty()) std::cout << "display: " << out.display << "\n";
    std::cout << "exposure: " << out.exposure << "\n";
    std::cout << "estimate: " << estimate.describe() << "\n";
    if (tile)
      std::printf("tile: columns %d-%d, rows %d-%d of the %dx%d image (merge the tiles with skyspec merge)\n", tile->x0,
                  tile->x1 - 1, tile->y0, tile->y1 - 1, scene.camera.width, scene.camera.height);
    std::printf("rendered %dx%d, %s, in %.2f s (tables %.3f s, image %.3f s, completing the files %.3f s)\n",
                plan.width, plan.height, make_wavelength_grid(scene).describe().c_str(), out.seconds,
                out.tables_seconds, out.image_seconds, out.output_seconds);
    if (!photometry.empty()) std::cout << photometry << "\n";
  }
  return kExitOk;
}

}  // namespace

Command add_render_command(CLI::App& app) {
  auto opts = std::make_shared<RenderOptions>();
  auto* render = app.add_subcommand("render", "Render a sky to a spectral OpenEXR and a PNG preview");
  render->footer(
      "Examples:\n"
      "  skyspec render                                  # built-in default scene -> skyspec-out/sky.exr, sky.png\n"
      "  skyspec render --sun-elevation 5 --out dusk     # low sun\n"
      "  skyspec render --preset seed                    # the seed tutorial's RGB-fast sky\n"
      "  skyspec render --quality draft                  # quick look (also: lean, default, high, reference)\n"
      "  skyspec render --scene my.toml --set atmosphere.mie.g=0.8\n"
      "  skyspec render --camera equirectangular --width 1024 --height 512\n"
      "  skyspec render --camera equirectangular --width 4096 --height 2048 --panorama-convention blender \\\n"
      "                 --exr-space \"Linear Rec.709\"     # an HDRI for Blender (docs/other-tools.md)\n"
      "  skyspec render --display \"Display P3\"            # the PNG for a Display P3 screen\n"
      "  skyspec render --display Rec.2100-PQ --view \"ACES 1.1 - HDR Video (1000 nits & Rec.2020 lim)\" --png-bits "
      "16\n"
      "  skyspec render --shutter 1/250 --f-number 8 --iso 100   # physical camera exposure\n"
      "  skyspec render --list-displays                  # displays, views and looks of the OCIO config\n"
      "  skyspec render --from skyspec-out/sky.exr --out again   # the scene recorded in an EXR, rendered again\n"
      "Scene files are TOML; data/scenes/default.toml documents every key, --help-keys lists units and ranges.");
  add_scene_options(*render, opts->scene);
  add_quality_option(*render, opts->scene);
  add_from_option(*render, opts->scene);
  render->add_flag("--no-exr", opts->no_exr, "do not write the spectral EXR");
  render->add_flag("--no-png", opts->no_png, "do not write the PNG preview");
  render->add_flag("-q,--quiet", opts->quiet, "no progress bar and no summary");
  render
      ->add_flag("--help-keys{text}", opts->help_keys,
                 "list every scene key with its unit and range, then exit; --help-keys=markdown prints the "
                 "table of docs/scene-keys.md")
      ->check(CLI::IsMember({"text", "markdown"}));
  render->add_flag("--print-scene", opts->print_scene, "print the effective scene as TOML, then exit");
  render->add_flag("--force", opts->force,
                   "render even if the outputs exceed the free disk, the memory needed exceeds what is available "
                   "or the estimated time exceeds 24 hours");
  render->add_option("--pixel-bounds", opts->pixel_bounds,
                     "x0,x1,y0,y1: render only columns x0..x1-1 and rows y0..y1-1 (pbrt's order) into a tile EXR "
                     "(no PNG); skyspec merge assembles the tiles into the whole image's EXR, byte for byte");
  render->add_flag("--dry-run", opts->dry_run,
                   "estimate the outputs' size, the memory and the time (refusing as a render would), print the "
                   "estimate and exit");
  add_display_options(*render, opts->display);
  return {render, [opts] { return run_render(*opts); },
          [opts] {  // run_render's checks, up to the rendering (Command::validate)
            if (opts->display.list) return void(OcioConfig(display_settings(opts->display).config));
            if (!opts->help_keys.empty()) return;
            const Scene scene = load_scene(*opts);
            if (opts->print_scene) return void(scene_to_toml(scene));
            tile_of(*opts, scene);
            const DisplaySettings display = display_settings(opts->display, exposure_flag_given(*opts));
            if (scene.output.png || !display.exr_space.empty()) DisplayPipeline{display};
          }};
}

}  // namespace skyspec::cli
