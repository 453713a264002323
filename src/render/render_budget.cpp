#include "render/render_budget.hpp"

#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>
#include <system_error>

#include "colour/display_pipeline.hpp"
#include "io/png_image.hpp"
#include "io/spectral_exr.hpp"
#include "render/scene_tables.hpp"
#include "render/table_family.hpp"
#include "skyspec/camera.hpp"
#include "skyspec/display.hpp"
#include "skyspec/error.hpp"
#include "skyspec/render.hpp"
#include "skyspec/scene.hpp"
#include "transport/scattering_tables_cache.hpp"

namespace skyspec {
namespace {

constexpr std::uint64_t kHeaderRoom = 64 * 1024;  // headers: the scene, the data tables, ...
constexpr double kMaxSeconds = 24.0 * 3600.0;

std::uint64_t pixels(int width, int height) {
  return static_cast<std::uint64_t>(std::max(width, 0)) * static_cast<std::uint64_t>(std::max(height, 0));
}

std::string printf_text(const char* format, double value, const char* unit) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, format, value, unit);
  return buffer;
}

// CPU time of the calling thread or of the whole process, seconds (0 if the clock is not available).
double cpu_seconds(clockid_t clock) {
  timespec t{};
  if (clock_gettime(clock, &t) != 0) return 0.0;
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
double thread_cpu_seconds() { return cpu_seconds(CLOCK_THREAD_CPUTIME_ID); }
double process_cpu_seconds() { return cpu_seconds(CLOCK_PROCESS_CPUTIME_ID); }

}  // namespace

std::uint64_t spectral_exr_bytes(int width, int height, int wavelengths) {
  return pixels(width, height) * static_cast<std::uint64_t>(wavelengths + 3) * 4 +
         static_cast<std::uint64_t>(std::max(height, 0)) * 8 + kHeaderRoom;
}

std::uint64_t rgb_exr_bytes(int width, int height) { return spectral_exr_bytes(width, height, 0); }

std::uint64_t png_bytes(int width, int height, int bit_depth) {
  return pixels(width, height) * 3 * static_cast<std::uint64_t>(bit_depth / 8) +
         static_cast<std::uint64_t>(std::max(height, 0)) + kHeaderRoom;
}

std::string format_bytes(std::uint64_t bytes) {
  const double b = static_cast<double>(bytes);
  if (b < 1e3) return std::to_string(bytes) + " bytes";
  const char* units[] = {"kB", "MB", "GB", "TB", "PB"};
  double v = b / 1e3;
  int u = 0;
  while (v >= 999.5 && u < 4) v /= 1e3, ++u;
  return printf_text(v < 9.95 ? "%.1f %s" : "%.0f %s", v, units[u]);
}

std::string format_duration(double seconds) {
  if (seconds < 60.0) return printf_text(seconds < 9.95 ? "%.1f %s" : "%.0f %s", seconds, "s");
  if (seconds < 3600.0) return printf_text("%.0f %s", seconds / 60.0, "min");
  if (seconds < 48 * 3600.0) return printf_text("%.1f %s", seconds / 3600.0, "h");
  return printf_text("%.1f %s", seconds / 86400.0, "days");
}

RenderPlan RenderPlan::for_scene(const Scene& scene, int frames) { return for_scene(scene, DisplaySettings{}, frames); }

bool RenderPlan::writes(const std::string& id) const {
  return std::find(outputs.begin(), outputs.end(), id) != outputs.end();
}

void RenderPlan::drop(const std::string& id) {
  outputs.erase(std::remove(outputs.begin(), outputs.end(), id), outputs.end());
}

RenderPlan RenderPlan::for_scene(const Scene& scene, const DisplaySettings& display, int frames, bool tile) {
  RenderPlan p;
  p.width = scene.camera.width;
  p.height = scene.camera.height;
  p.wavelengths = make_wavelength_grid(scene).size();
  p.view_segments = scene.render.view_segments;
  const int cores = std::max(1, tbb::this_task_arena::max_concurrency());
  p.threads = scene.render.threads > 0 ? std::min(scene.render.threads, cores) : cores;
  p.frames = frames;
  p.outputs = planned_outputs(scene, display, tile);
  p.stokes_components = scene.output.polarisation ? 4 : 1;
  p.png_bit_depth = display.png_bit_depth;
  p.exr_block_rows = spectral_exr_block_rows(scene.output.exr_compression);
  p.directory = scene.output.directory;
  if (scene.render.scattering_orders >= 2) {
    const MultipleScatteringSettings ms = multiple_scattering_settings(scene);
    p.table_bytes = ScatteringOrders::table_bytes(ms, p.wavelengths);
    // Interpolated tables: the grid's, as read from the cache, held while they are blended (and
    // kept after, for the next sky), and the blend itself, besides a build's.
    if (scene.render.ms_tables == RenderSpec::Tables::Interpolated)
      if (const std::optional<TableFamily> family = table_family(scene))
        p.table_bytes += (family->members().size() + 1) * ScatteringOrders::cache_bytes(ms, p.wavelengths);
  }
  return p;
}

std::uint64_t RenderPlan::output_bytes() const {
  return (planned_output_bytes(*this) + extra_output_bytes) * static_cast<std::uint64_t>(std::max(frames, 1));
}

int render_band_rows(int width, int values_per_pixel, int block_rows, int height) {
  const std::uint64_t row_bytes = static_cast<std::uint64_t>(std::max(width, 1)) *
                                  (static_cast<std::uint64_t>(std::max(values_per_pixel, 0)) + 3) * 4;
  const int block = std::max(block_rows, 1);
  const int blocks = std::max(
      1, std::min(64 / block,
                  static_cast<int>(std::min<std::uint64_t>((std::uint64_t{4} << 20) / row_bytes, 1 << 20)) / block));
  return std::max(1, std::min(block * blocks, std::max(height, 1)));
}

std::uint64_t RenderPlan::peak_memory_bytes() const {
  const std::uint64_t px = pixels(width, height), n = static_cast<std::uint64_t>(std::max(wavelengths, 0));
  // render_scene_to_files renders and encodes a band per thread at a time (render_bands): each
  // thread holds its band's values and, with a spectral EXR, its encoder's three buffers of the
  // band's size (the values in the file's layout, compressed, the codec's scratch), and up to two
  // bands per thread wait, encoded, to be written in order.
  const int values = static_cast<int>(n) * std::max(stokes_components, 1);
  const bool spectral_exr = writes("spectral_exr"), png = writes("png"), working_exr = writes("working_exr");
  const std::uint64_t row_bytes =
      static_cast<std::uint64_t>(std::max(width, 1)) * (static_cast<std::uint64_t>(values) + 3) * 4;
  const std::uint64_t band =
      static_cast<std::uint64_t>(render_band_rows(width, values, spectral_exr ? exr_block_rows : 1, height)) *
      row_bytes;
  const std::uint64_t workers = static_cast<std::uint64_t>(std::max(threads, 1));
  std::uint64_t bytes = workers * band + table_bytes;
  // The spectral EXR's encoders; per pixel, the measured slopes of peak memory rounded up
  // (docs/reliability.md, "Memory estimates"): for a PNG, the whole-image RGB, the copy the
  // display pipeline encodes, its output, the PNG's samples and the allocator's pages around
  // them. With both, the larger part is the peak (the same measurements).
  const std::uint64_t exr_part = spectral_exr ? 5 * workers * band : 0;
  std::uint64_t display_part = 0;
  if (png || working_exr) {
    const std::uint64_t png_part = png ? px * 70 + px * 3 * static_cast<std::uint64_t>(png_bit_depth / 8 - 1) : 0;
    const std::uint64_t working_part = working_exr ? px * 70 : 0;
    display_part = std::max(png_part, working_part);
  }
  bytes += std::max(exr_part, display_part);
  return bytes + static_cast<std::uint64_t>(std::ceil(static_cast<double>(px) * extra_bytes_per_pixel));
}

std::string RenderPlan::settings() const {
  std::ostringstream s;
  s << wavelengths << " wavelength" << (wavelengths == 1 ? "" : "s") << ", " << view_segments << " view segment"
    << (view_segments == 1 ? "" : "s") << ", " << width << "x" << height << ", " << threads << " thread"
    << (threads == 1 ? "" : "s");
  if (frames > 1) s << ", " << frames << " frames";
  return s.str();
}

std::string RenderEstimate::describe() const {
  std::string text = "outputs up to " + format_bytes(output_bytes);
  if (disk_available_bytes) text += " (" + format_bytes(*disk_available_bytes) + " free)";
  text += ", peak memory about " + format_bytes(peak_memory_bytes);
  if (memory_available_bytes) text += " (" + format_bytes(*memory_available_bytes) + " available)";
  if (seconds) text += ", about " + format_duration(*seconds) + " of rendering";
  if (table_seconds) text += ", tables about " + format_duration(*table_seconds);
  if (table_seconds && table_cache_bytes > 0) text += " and " + format_bytes(table_cache_bytes) + " in the table cache";
  return text;
}

std::vector<std::string> RenderEstimate::problems() const {
  std::vector<std::string> out;
  if (disk_available_bytes && output_bytes > *disk_available_bytes) {
    std::string what = "up to " + format_bytes(output_bytes);
    if (plan.frames > 1)
      what += " (" + std::to_string(plan.frames) + " frames of up to " +
              format_bytes(output_bytes / static_cast<std::uint64_t>(plan.frames)) + ")";
    else if (plan.writes("spectral_exr"))
      what += " (a " + format_bytes(spectral_exr_bytes(plan.width, plan.height, plan.wavelengths)) + " EXR)";
    out.push_back("would write " + what + " but " + plan.directory.string() + " has " +
                  format_bytes(*disk_available_bytes) + " free");
  }
  if (memory_available_bytes && peak_memory_bytes > *memory_available_bytes)
    out.push_back("would need about " + format_bytes(peak_memory_bytes) + " of memory but " +
                  format_bytes(*memory_available_bytes) + " is available");
  const double tables = table_seconds.value_or(0.0);
  if (tables > kMaxSeconds)
    out.push_back("would spend about " + format_duration(tables) + " building its tables at these settings (" +
                  std::to_string(plan.wavelengths) +
                  " wavelengths); use fewer scattering orders, smaller tables "
                  "(render.ms_altitude_samples, render.ms_sun_samples, render.sky_view_*) or fewer wavelengths");
  else if (seconds && *seconds + tables > kMaxSeconds)
    out.push_back("would take about " + format_duration(*seconds + tables) + " at these settings (" + plan.settings() +
                  "); use a smaller image, fewer wavelengths or fewer view segments");
  return out;
}

RenderEstimate estimate_render(const RenderPlan& plan) {
  RenderEstimate e;
  e.plan = plan;
  e.output_bytes = plan.output_bytes();
  e.peak_memory_bytes = plan.peak_memory_bytes();
  e.disk_available_bytes = available_disk_bytes(plan.directory);
  e.memory_available_bytes = available_memory_bytes();
  return e;
}

Scene scene_for_estimate(const Scene& scene) {
  Scene light = scene;
  // The higher orders from the smallest tables allowed (4 x 4 entries of order 2, built in a few
  // milliseconds and never cached): a look-up costs what it costs in the real tables (the same
  // degree, wavelengths and polarisation), so the sky-view table's entries and the marched pixels
  // are timed with it.
  light.render.scattering_orders = std::min(scene.render.scattering_orders, 2);
  light.render.ms_altitude_samples = 4;
  light.render.ms_sun_samples = 4;
  light.render.cache_tables = false;
  light.render.sky_view_zenith_samples = std::min(scene.render.sky_view_zenith_samples, 32);
  light.render.sky_view_azimuth_samples = std::min(scene.render.sky_view_azimuth_samples, 32);
  // The higher orders' coarser table shrunk in the same proportion, so that both of the table's
  // marches (its own rays without the higher orders, the coarse ones with them) scale alike.
  const auto shrunk = [](int higher, int own, int light_own, int least) {
    return higher >= own ? light_own : std::clamp(higher * light_own / own, least, light_own);
  };
  light.render.sky_view_higher_zenith_samples =
      shrunk(scene.render.sky_view_higher_zenith_samples, scene.render.sky_view_zenith_samples,
             light.render.sky_view_zenith_samples, 8);
  light.render.sky_view_higher_azimuth_samples =
      shrunk(scene.render.sky_view_higher_azimuth_samples, scene.render.sky_view_azimuth_samples,
             light.render.sky_view_azimuth_samples, 4);
  return light;
}

double estimate_scattering_orders_seconds(const Scene& scene) {
  // The tables the render builds: its own, or the grid's it interpolates (table_family.hpp), which
  // share their settings and wavelengths, hence their cost: one is timed.
  std::vector<Scene> builds;
  for (Scene& s : scenes_of_tables(scene))
    if (!scattering_orders_cached(scattering_tables_key(s), s.render.cache_tables)) builds.push_back(std::move(s));
  if (builds.empty()) return 0.0;
  const Scene& first = builds.front();
  tbb::task_arena arena(first.render.threads > 0 ? first.render.threads : tbb::this_task_arena::max_concurrency());
  return static_cast<double>(builds.size()) * arena.execute([&] {
    const AtmosphereModel atmosphere(first.atmosphere, make_wavelength_grid(first), first.render.cache_tables);
    const auto table = SunColumnTable::shared(atmosphere, sun_table_resolution(first), SunColumnTable::MuBand{});
    const TableSunColumns columns(*table);
    const SingleScattering integrator(atmosphere, columns, IntegratorSettings{first.render.view_segments});
    return ScatteringOrders::estimate_build_seconds(integrator, multiple_scattering_settings(first));
  });
}

std::uint64_t scattering_tables_file_bytes(const Scene& scene, const ScatteringTablesKey& key) {
  return ScatteringOrders::cache_bytes(multiple_scattering_settings(scene), make_wavelength_grid(scene).size()) +
         key.inputs.size();
}

std::uint64_t estimate_table_cache_bytes(const Scene& scene) {
  if (scene.render.scattering_orders < 2 || !scene.render.cache_tables || table_cache_directory().empty()) return 0;
  std::uint64_t bytes = 0;
  for (const Scene& s : scenes_of_tables(scene)) {
    const auto key = scattering_tables_key(s);
    if (!scattering_orders_cached(key, true)) bytes += scattering_tables_file_bytes(s, key);
  }
  return bytes;
}

double estimate_frame_table_seconds(const Scene& scene, const SkyRenderer& estimate_renderer) {
  const Scene& light = estimate_renderer.scene();
  const double full = static_cast<double>(scene.render.sky_view_zenith_samples) * scene.render.sky_view_azimuth_samples;
  const double built =
      static_cast<double>(light.render.sky_view_zenith_samples) * light.render.sky_view_azimuth_samples;
  const double rest_of_sky_view = estimate_renderer.sky_view_table_seconds() * std::max(0.0, full / built - 1.0);
  return estimate_renderer.build_seconds() + rest_of_sky_view;
}

double estimate_table_seconds(const Scene& scene, const SkyRenderer& estimate_renderer) {
  return estimate_scattering_orders_seconds(scene) + estimate_frame_table_seconds(scene, estimate_renderer);
}

// The EXR's share of the estimate is timed on this many pixels of a row at most: each render
// pays for the sample before its image.
constexpr int kWriteSampleWidth = 128;

double measure_render_seconds(const SkyRenderer& renderer, const RenderPlan& plan) {
  const int w = renderer.width(), h = renderer.height();
  const double threads = std::max(plan.threads, 1);
  const double work = static_cast<double>(pixels(w, h)) * std::max(plan.frames, 1);
  // First a bound: radiance() does a pixel's work without the sun's disk (a sky-view table lookup
  // where the renderer has one, a march of the view ray otherwise), timed on a few pixels spread
  // over the image by the R2 low-discrepancy sequence (Roberts 2018). CPU time of the thread: what the work costs,
  // whatever else the machine is doing.
  const auto camera = make_camera(renderer.scene());
  // A polarised render's pixels come from the sky-view table as well where there is one (the
  // bound times the look-up); without one each is a polarised march, which the bound then times.
  const bool polarised = renderer.scene().output.polarisation;
  const bool polarised_march = polarised && renderer.sky_view_table_seconds() == 0.0;
  Spectrum spectrum, q, u;
  const double a1 = 0.7548776662466927, a2 = 0.5698402909980532;
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = thread_cpu_seconds();
  long samples = 0;
  for (;;) {
    const double k = static_cast<double>(samples + 1);
    Vec3 dir;
    const double x = std::fmod(0.5 + a1 * k, 1.0) * w, y = std::fmod(0.5 + a2 * k, 1.0) * h;
    if (camera->direction(x, y, dir)) {
      if (polarised_march)
        renderer.stokes(dir, renderer.stokes_frame_axis_of_pixel(x, y, dir), spectrum, q, u);
      else
        spectrum = renderer.radiance(dir);
    }
    ++samples;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (samples >= 64 || elapsed >= 0.1) break;
  }
  const double marched = (thread_cpu_seconds() - cpu_start) / static_cast<double>(samples);
  // Then, when a row costs at most about a second even if every pixel were marched, the real work:
  // render_rows on the middle row and, when that was quick, a row a quarter down, timed by the
  // process's CPU time (all of render_rows's threads).
  if (marched * w / threads > 1.0) return marched * work / threads;
  const size_t values = static_cast<size_t>(renderer.grid().size()) * (polarised ? 4 : 1);
  std::vector<float> spectral(static_cast<size_t>(w) * values), rgb(static_cast<size_t>(w) * 3);
  double cpu = 0.0;
  long rendered = 0;
  for (const int y : {h / 2, h / 4}) {
    const double before = process_cpu_seconds();
    if (polarised)
      renderer.render_window_stokes(0, w, y, 1, spectral.data(), rgb.data());
    else
      renderer.render_rows(y, 1, spectral.data(), rgb.data());
    cpu += process_cpu_seconds() - before;
    rendered += w;
    if (cpu > 0.05 || h < 4) break;
  }
  // And writing: the middle of the last row rendered (at most kWriteSampleWidth pixels), repeated
  // over a line block of the scene's compression (at least 16 rows), encoded as a spectral EXR into
  // nothing (SpectralExrWriter::Discarding); its cost per pixel is the image's.
  double write = 0.0;
  if (plan.writes("spectral_exr")) {
    const int rows = std::max(16, spectral_exr_block_rows(renderer.scene().output.exr_compression));
    const int sw = std::min(w, kWriteSampleWidth), x0 = (w - sw) / 2;
    const size_t row_values = static_cast<size_t>(sw) * values;
    std::vector<float> band_spectral(row_values * rows), band_rgb(static_cast<size_t>(sw) * 3 * rows);
    for (int r = 0; r < rows; ++r) {
      std::copy(spectral.begin() + static_cast<long>(x0 * values),
                spectral.begin() + static_cast<long>((x0 + sw) * values),
                band_spectral.begin() + static_cast<long>(r * row_values));
      std::copy(rgb.begin() + x0 * 3, rgb.begin() + (x0 + sw) * 3, band_rgb.begin() + r * sw * 3);
    }
    SpectralExrMetadata meta;
    meta.compression = renderer.scene().output.exr_compression;
    meta.polarised = polarised;
    // Encoded on this thread (as a render encodes each band on the thread that rendered it): this
    // thread's CPU time, without other threads' waiting for work. Whole line blocks, and timed the
    // second time in the same writer: a render's encoders keep their buffers from band to band,
    // and the first band's page faults for them, or a part of a block, cost more per row
    // (docs/reliability.md, "Time estimates").
    meta.threads = 1;
    SpectralExrWriter writer(SpectralExrWriter::Discarding{}, sw, 2 * rows, renderer.grid().nanometres(), meta);
    writer.write_rows(rows, band_spectral.data(), band_rgb.data());
    const double before = thread_cpu_seconds();
    writer.write_rows(rows, band_spectral.data(), band_rgb.data());
    write = (thread_cpu_seconds() - before) / rows * w / sw;  // a whole row's
  }
  // And the PNG, which the render makes on one thread once the image is done: the row through the
  // display pipeline (skyspec's config, its default display and view, at the plan's bit depth) and
  // libpng's compression, into memory, as 16 rows each shifted along by a few pixels (identical rows
  // would compress to nothing under libpng's "Up" filter), exposed to a mean of 0.18.
  double png = 0.0;
  if (plan.writes("png")) {
    const int rows = 16;
    double mean = 0.0;
    for (size_t i = 1; i < rgb.size(); i += 3) mean += rgb[i];
    mean /= std::max(w, 1);
    std::vector<float> band(rgb.size() * rows);
    for (int r = 0; r < rows; ++r)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c)
          band[(static_cast<size_t>(r) * w + x) * 3 + c] = rgb[static_cast<size_t>((x + 7 * r) % w) * 3 + c];
    DisplaySettings settings;
    settings.png_bit_depth = plan.png_bit_depth;
    const DisplayPipeline pipeline(settings);
    const double before = thread_cpu_seconds();
    const auto codes = pipeline.encode(std::move(band), mean > 0.0 && std::isfinite(mean) ? 0.18 / mean : 1.0);
    encoded_png_display_bytes(w, rows, codes, plan.png_bit_depth, pipeline.png_tag());
    png = (thread_cpu_seconds() - before) / (static_cast<double>(rows) * w);
  }
  return (cpu / static_cast<double>(rendered) + write / w) * work / threads + png * work;
}

void refuse_if_over_budget(const RenderEstimate& estimate, const std::string& force_flag) {
  const std::vector<std::string> problems = estimate.problems();
  if (problems.empty()) return;
  std::string message = "this render";
  for (size_t i = 0; i < problems.size(); ++i) message += (i ? ", and " : " ") + problems[i];
  message += " (use " + force_flag + " to render anyway)";
  throw InputError::refused(force_flag, message);
}

void refuse_if_tables_over_budget(const Scene& scene, RenderEstimate estimate, const std::string& force_flag) {
  if (scene.render.scattering_orders < 2) return;
  estimate.table_seconds = estimate_scattering_orders_seconds(scene);
  refuse_if_over_budget(estimate, force_flag);
}

std::optional<std::uint64_t> available_memory_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  std::uint64_t value = 0;
  std::string unit;
  while (in >> key >> value) {
    std::getline(in, unit);
    if (key == "MemAvailable:") return value * (unit.find("kB") != std::string::npos ? 1024 : 1);
  }
  return std::nullopt;
}

std::optional<std::uint64_t> available_disk_bytes(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::path p = std::filesystem::absolute(dir.empty() ? std::filesystem::path(".") : dir, ec);
  if (ec) return std::nullopt;
  while (!std::filesystem::exists(p, ec)) {
    if (!p.has_parent_path() || p.parent_path() == p) return std::nullopt;
    p = p.parent_path();
  }
  const auto info = std::filesystem::space(p, ec);
  if (ec) return std::nullopt;
  return static_cast<std::uint64_t>(info.available);
}

}  // namespace skyspec
