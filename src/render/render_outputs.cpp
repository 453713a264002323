// Rendering into memory and into files: the image with what it shows (directions, sun, the
// exposure's meter reading), the exposure chosen for the preview, the files' headers, and the
// files themselves (spectral EXR streamed band by band, PNG, working-space EXR), each atomic.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include "base/atomic_file.hpp"
#include "base/output_lock.hpp"
#include "colour/display_pipeline.hpp"
#include "colour/exposure.hpp"
#include "colour/polarisation_colour.hpp"
#include "io/png_image.hpp"
#include "io/rgb_exr.hpp"
#include "io/spectral_exr.hpp"
#include "physics/unmodelled_absorption.hpp"
#include "render/render_budget.hpp"
#include "render/scene_provenance.hpp"
#include "render/surface_pass.hpp"
#include "skyspec/colour.hpp"
#include "skyspec/error.hpp"
#include "skyspec/render.hpp"
#include "skyspec/units.hpp"
#include "skyspec/version.hpp"

namespace skyspec {

namespace {

/// The automatic exposure, metered before rendering so that the EXR header can record it: the
/// sky's radiance (without the sun's disk) at the pixels metering_pixels() picks (exposure.hpp).
double meter_before_rendering(const SkyRenderer& r) {
  const auto camera = make_camera(r.scene());
  const auto pixels = metering_pixels(r.width(), r.height());
  std::vector<double> luminance(pixels.size(), 0.0);  // 0 (ignored by the meter): outside the image circle
  tbb::task_arena arena(r.threads());
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, pixels.size(), 256), [&](const tbb::blocked_range<size_t>& range) {
      for (size_t i = range.begin(); i != range.end(); ++i) {
        Vec3 dir;
        if (!camera->direction(pixels[i].first + 0.5, pixels[i].second + 0.5, dir)) continue;
        const Rgb rgb = r.radiance_rgb(dir);
        luminance[i] = rec709_luminance(rgb.data());
      }
    });
  });
  return key_exposure_scale(luminance);
}

// The exposure of the preview: the display settings', unless the scene fixes output.exposure_ev
// (a manual exposure) while the settings say automatic; automatic exposure meters the sky first.
struct ChosenExposure {
  ExposureSettings settings;
  ResolvedExposure resolved;
};
ChosenExposure choose_exposure(const Scene& scene, const DisplaySettings& display,
                               const std::function<double()>& meter) {
  ChosenExposure c{display.exposure, {}};
  if (c.settings.mode == ExposureSettings::Mode::Automatic && scene.output.exposure_ev) {
    c.settings.mode = ExposureSettings::Mode::Manual;
    c.settings.ev = *scene.output.exposure_ev;
  }
  const bool automatic = c.settings.mode == ExposureSettings::Mode::Automatic;
  c.resolved = resolve_exposure(c.settings, automatic ? meter() : 1.0);
  return c;
}

// The header attributes every output file carries: skyspec:version, skyspec:scene, skyspec:data
// (provenance.hpp), then what this render chose.
std::map<std::string, std::string> render_provenance(const Scene& scene, const ResolvedExposure& exposure,
                                                     bool builtin_ocio_config) {
  std::map<std::string, std::string> provenance = provenance_attributes(scene, builtin_ocio_config);
  provenance["skyspec:renderPath"] = scene.render.path == RenderSpec::Path::RgbFast ? "rgb-fast" : "spectral";
  provenance["skyspec:wavelengths"] = make_wavelength_grid(scene).describe();
  if (scene.render.path == RenderSpec::Path::Spectral)
    provenance["skyspec:notModelled"] = unmodelled_absorption_note(make_wavelength_grid(scene));
  provenance["skyspec:exposure"] = exposure.description;
  return provenance;
}

// The spectral EXR's header: the provenance, the exposure's scale as a number (a double
// attribute), what the channels hold, and envmap for a whole-sphere panorama.
SpectralExrMetadata spectral_exr_metadata(const Scene& scene, const std::map<std::string, std::string>& provenance,
                                          double exposure_scale, const Rgb& sun_rgb, int threads) {
  SpectralExrMetadata meta;
  meta.strings = provenance;
  meta.doubles[kExposureScaleAttribute] = exposure_scale;
  meta.vectors[kSunRgbAttribute] = {sun_rgb[0], sun_rgb[1], sun_rgb[2]};
  meta.compression = scene.output.exr_compression;
  meta.threads = threads;
  meta.latlong_envmap = is_latlong_envmap(scene.camera);
  meta.half_spectral = scene.output.exr_spectral_type == "half";
  meta.polarised = scene.output.polarisation;
  meta.strings["skyspec:units"] =
      scene.render.path == RenderSpec::Path::RgbFast
          ? "RGB-fast path: S0 channels and R,G,B in the sun's units (spectral_irradiance x sr^-1); "
            "R,G,B are the 680, 550, 440 nm values read as linear Rec.709"
          : "S0 channels: spectral radiance, W m^-2 sr^-1 nm^-1; R,G,B: linear Rec.709 (D65) with "
            "Y = luminance in cd m^-2";
  if (scene.output.polarisation)
    meta.strings["skyspec:polarisation"] =
        "S1, S2, S3 per wavelength in the units of S0: the Stokes vector in each pixel's frame, e1 = the image's x "
        "axis "
        "carried onto the sky (perpendicular to the pixel's ray), e2 = k x e1 with k the light's direction (towards "
        "the "
        "camera); S1 > 0 polarised along e1, S2 > 0 along e1 + e2; S3 = 0. Vector transport for the air; particles "
        "polarise the sun's light by their scattering matrix (analytic aerosols: a unit matrix) and scatter light "
        "scattered before as unit matrices; the ground depolarises (docs/polarisation.md)";
  return meta;
}

std::string describe(const PixelBounds& b) {
  return std::to_string(b.x0) + "," + std::to_string(b.x1) + "," + std::to_string(b.y0) + "," + std::to_string(b.y1);
}

// Renders the image in bands of whole line blocks of the EXR's codec, each band rendered and
// compressed on one thread while the other threads do the same with the next bands, and written
// to the file in order as soon as it and the bands before it are done (tbb::parallel_pipeline):
// compression, most of a render's time, is spread over the cores with the rows, and no thread
// waits for another to write. With render.threads = 1 everything runs on the calling thread, so
// that the render uses one core, as asked (the writer's flush to the disk runs on a helper thread
// that only waits: exr_streams.hpp). A band is about 4 MiB of values (at most 64 rows, at least one
// line block: 32 rows for PIZ, 16 for ZIP, one otherwise); two per thread are under way at most,
// fewer when they are large (an 8192-pixel-wide PIZ band is 91 MB). The whole image's linear RGB is
// kept in `rgb` when it is not empty (for the PNG and the working-space EXR). A polarised render
// also keeps, when `stokes_y` is not empty, the luminance-weighted S0, S1, S2 of every pixel
// ([y][x][3]: the spectrum_to_rgb of each component's spectrum, then Rec.709 luminance; both steps
// are linear in the spectrum) for the DoLP / AoLP images.
void render_bands(const SkyRenderer& r, SpectralExrWriter* exr, std::vector<float>& rgb, std::vector<float>& stokes_y,
                  const ProgressFn& progress, const PixelBounds& window) {
  const int x0 = window.x0, w = window.x1 - window.x0, y_first = window.y0, y_end = window.y1, n = r.grid().size();
  const int h = y_end - y_first;
  // Polarised: S0-S3 per wavelength (render_window_stokes), as the EXR takes them.
  const bool polarised = r.scene().output.polarisation;
  const int values = polarised ? 4 * n : n;
  const size_t row_bytes = static_cast<size_t>(w) * static_cast<size_t>(values + 3) * sizeof(float);
  const int band = render_band_rows(w, values, exr ? exr->rows_per_block() : 1, h);
  const size_t band_bytes = static_cast<size_t>(band) * row_bytes;
  const int threads = r.threads();
  const auto in_flight =
      static_cast<size_t>(std::clamp<size_t>((size_t{256} << 20) / band_bytes, 1, 2 * static_cast<size_t>(threads)));

  // The bands' values, reused: one per band being rendered. Left uninitialised: the renderer
  // writes every value, and its threads touch the pages first.
  struct Buffers {
    std::unique_ptr<float[]> spectral, rgb;
  };
  std::mutex free_mutex;
  std::vector<std::unique_ptr<Buffers>> free_buffers;
  const auto take = [&] {
    {
      std::lock_guard<std::mutex> lock(free_mutex);
      if (!free_buffers.empty()) {
        auto b = std::move(free_buffers.back());
        free_buffers.pop_back();
        return b;
      }
    }
    auto b = std::make_unique<Buffers>();
    b->spectral.reset(new float[static_cast<size_t>(band) * w * values]);
    b->rgb.reset(new float[static_cast<size_t>(band) * w * 3]);
    return b;
  };
  const auto give_back = [&](std::unique_ptr<Buffers> b) {
    std::lock_guard<std::mutex> lock(free_mutex);
    free_buffers.push_back(std::move(b));
  };

  // The bands, from their renderer to the file: the pipeline passes their numbers, and each band's
  // encoded bytes live here until written, so that a stopped pipeline (a write error, a
  // cancellation) leaves nothing behind that this function does not free.
  struct Band {
    int y = 0, rows = 0;  // rows of the window
    SpectralExrWriter::EncodedRows encoded;
  };
  std::vector<Band> bands(static_cast<size_t>((h + band - 1) / band));
  for (size_t i = 0; i < bands.size(); ++i) {
    bands[i].y = static_cast<int>(i) * band;
    bands[i].rows = std::min(band, h - bands[i].y);
  }
  size_t next_band = 0;
  int rows_done = 0;
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_pipeline(
        in_flight,
        tbb::make_filter<void, size_t>(tbb::filter_mode::serial_in_order, [&](tbb::flow_control& control) -> size_t {
          if (next_band == bands.size()) control.stop();
          return next_band < bands.size() ? next_band++ : 0;
        }) & tbb::make_filter<size_t, size_t>(tbb::filter_mode::parallel, [&](size_t i) {
          Band& b = bands[i];
          std::unique_ptr<Buffers> buffers = take();
          float* spectral = buffers->spectral.get();
          float* band_rgb = buffers->rgb.get();
          if (polarised)
            r.render_window_stokes(x0, x0 + w, y_first + b.y, b.rows, spectral, band_rgb);
          else
            r.render_window(x0, x0 + w, y_first + b.y, b.rows, spectral, band_rgb);
          const size_t pixels = static_cast<size_t>(b.rows) * w;
          if (!rgb.empty()) std::copy(band_rgb, band_rgb + pixels * 3, rgb.begin() + static_cast<long>(b.y) * w * 3);
          if (polarised && !stokes_y.empty())
            for (size_t p = 0; p < pixels; ++p) {
              const float* v = spectral + p * static_cast<size_t>(values);
              float* out = stokes_y.data() + (static_cast<size_t>(b.y) * w + p) * 3;
              for (int c = 0; c < 3; ++c)
                out[c] = static_cast<float>(
                    rec709_luminance(r.spectrum_to_rgb(Eigen::Map<const Spectrum>(v + c * n, n)).data()));
            }
          if (exr) b.encoded = exr->encode_rows(b.y, b.rows, spectral, band_rgb);
          give_back(std::move(buffers));
          return i;
        }) & tbb::make_filter<size_t, void>(tbb::filter_mode::serial_in_order, [&](size_t i) {
          if (exr) exr->write_encoded(std::move(bands[i].encoded));
          rows_done += bands[i].rows;
          if (progress) progress(rows_done, h);
        }));
  });
}

// The text chunks of the PNG preview.
std::vector<std::pair<std::string, std::string>> preview_png_text(
    const DisplayPipeline& pipeline, const ResolvedExposure& exposure,
    const std::map<std::string, std::string>& provenance) {
  return {{"Software", std::string("skyspec ") + version_string()},
          {"skyspec:display", pipeline.describe()},
          {"skyspec:exposure", exposure.description},
          {kVersionAttribute, provenance.at(kVersionAttribute)},
          {kSceneAttribute, provenance.at(kSceneAttribute)},
          {kDataAttribute, provenance.at(kDataAttribute)}};
}

void write_preview_png(const std::filesystem::path& path, int width, int height, const DisplayPipeline& pipeline,
                       const DisplaySettings& display, const std::vector<float>& rgb, const ResolvedExposure& exposure,
                       const std::map<std::string, std::string>& provenance) {
  write_png_display(path, width, height, pipeline.encode(rgb, exposure.scale), display.png_bit_depth,
                    pipeline.png_tag(), preview_png_text(pipeline, exposure, provenance));
}

void write_working_space_exr(const std::filesystem::path& path, const Scene& scene, const DisplayPipeline& pipeline,
                             const WorkingSpace& space, const std::vector<float>& rgb, const ExposureSettings& exposure,
                             double exposure_scale, std::map<std::string, std::string> strings) {
  strings["skyspec:workingSpace"] = space.name + " (scene-linear, converted by " + pipeline.config().describe() + ")";
  strings["skyspec:units"] = working_space_units(space, scene.render.path == RenderSpec::Path::RgbFast);
  std::map<std::string, float> floats;
  if (exposure.mode == ExposureSettings::Mode::Camera) {  // OpenEXR's standard camera attributes
    floats["expTime"] = static_cast<float>(exposure.shutter_s);
    floats["aperture"] = static_cast<float>(exposure.f_number);
    floats["isoSpeed"] = static_cast<float>(exposure.iso);
  }
  write_rgb_exr(path, scene.camera.width, scene.camera.height, to_working_space(pipeline.config(), rgb, space),
                space.chromaticities, strings, floats, {{kExposureScaleAttribute, exposure_scale}},
                is_latlong_envmap(scene.camera));
}

// The luminance-weighted polarisation as float images: Y (S0's luminance), DoLP and AoLP (degrees,
// from the pixel's e1 towards e2; spectral EXR's frame).
void write_polarisation_exr(const std::filesystem::path& path, const Scene& scene, const std::vector<float>& stokes_y,
                            std::map<std::string, std::string> strings) {
  std::vector<float> values(stokes_y.size());
  for (size_t p = 0; p < stokes_y.size() / 3; ++p) {
    const float* s = &stokes_y[3 * p];
    const LinearPolarisation lp = linear_polarisation(s[0], s[1], s[2]);
    values[3 * p] = s[0];
    values[3 * p + 1] = static_cast<float>(lp.degree);
    values[3 * p + 2] = static_cast<float>(lp.angle_deg);
  }
  strings["skyspec:units"] =
      "Y: luminance of S0 (cd m^-2 on the spectral path); DoLP: degree of linear polarisation of the "
      "luminance-weighted "
      "Stokes vector (0 where Y = 0); AoLP: its angle in degrees, (-90, 90], from e1 (the image's x axis carried onto "
      "the sky) towards e2 = k x e1 (the spectral EXR's frames; docs/polarisation.md)";
  write_float_channels_exr(path, scene.camera.width, scene.camera.height, {"Y", "DoLP", "AoLP"}, values, strings,
                           is_latlong_envmap(scene.camera));
}

// The polarisation as a picture (polarisation_colour.hpp): sRGB code values and the text chunks.
std::vector<float> polarisation_code_values(const std::vector<float>& stokes_y) {
  std::vector<float> code(stokes_y.size());
  for (size_t p = 0; p < stokes_y.size() / 3; ++p) {
    const std::array<float, 3> c =
        polarisation_colour(linear_polarisation(stokes_y[3 * p], stokes_y[3 * p + 1], stokes_y[3 * p + 2]));
    std::copy(c.begin(), c.end(), code.begin() + static_cast<long>(3 * p));
  }
  return code;
}

std::vector<std::pair<std::string, std::string>> polarisation_png_text(
    const std::map<std::string, std::string>& provenance) {
  return {{"Software", std::string("skyspec ") + version_string()},
          {"skyspec:polarisation",
           "hue: angle of linear polarisation of the luminance-weighted Stokes vector, once round the "
           "colour wheel over 180 degrees (red at +-90, yellow -60, green -30, cyan 0, blue 30, "
           "magenta 60 degrees from e1 towards e2); brightness: its degree (black 0, full 1)"},
          {kVersionAttribute, provenance.at(kVersionAttribute)},
          {kSceneAttribute, provenance.at(kSceneAttribute)}};
}

// The polarisation as a picture, 8-bit sRGB.
void write_polarisation_png(const std::filesystem::path& path, const Scene& scene, const std::vector<float>& stokes_y,
                            const std::map<std::string, std::string>& provenance) {
  write_png_display(path, scene.camera.width, scene.camera.height, polarisation_code_values(stokes_y), 8,
                    PngColourTag::Srgb, polarisation_png_text(provenance));
}

// What a rendered image hands to the files written after it (every output but the streamed
// spectral EXR).
struct FinishedImage {
  const Scene& scene;
  const DisplaySettings& display;
  const DisplayPipeline* pipeline;     ///< set when an output that needs one is asked for
  const std::vector<float>& rgb;       ///< [y][x][c] linear Rec.709, when a pipeline is set
  const std::vector<float>& stokes_y;  ///< [y][x][S0, S1, S2] luminance-weighted, when polarised
  const ChosenExposure& exposure;
  const std::map<std::string, std::string>& provenance;
};

// The outputs of a render, one row each: the one list that render_output_paths, render_scene_to_files
// (what to write, in which order, what to remove when another fails), RenderOutputs::files (the
// job records) and the render budget (planned_outputs, planned_output_bytes) read. A new output is
// one row here (and its field in RenderOutputs, render.hpp).
struct FileOutput {
  const char* id;
  /// Asked for by the scene and the display settings (`tile`: a tile of the image is rendered).
  bool (*wanted)(const Scene& scene, const DisplaySettings& display, bool tile);
  /// Its file name in output.directory.
  std::string (*file_name)(const Scene& scene, const DisplaySettings& display);
  std::filesystem::path RenderOutputs::*field;
  bool needs_pipeline;          ///< encodes the image's RGB through the display pipeline
  bool needs_stokes_luminance;  ///< reads the luminance-weighted Stokes vectors
  /// Writes the file (atomically); null for the spectral EXR, streamed while the image renders.
  void (*write)(const FinishedImage& image, const std::filesystem::path& path);
  /// An upper bound of its size for the render budget (render_budget.hpp).
  std::uint64_t (*bytes)(const RenderPlan& plan);
};

const std::vector<FileOutput>& file_outputs() {
  static const std::vector<FileOutput> outputs = {
      {"spectral_exr", [](const Scene& s, const DisplaySettings&, bool) { return s.output.exr; },
       [](const Scene& s, const DisplaySettings&) { return s.output.name + ".exr"; }, &RenderOutputs::exr, false, false,
       nullptr,
       [](const RenderPlan& p) { return spectral_exr_bytes(p.width, p.height, p.wavelengths * p.stokes_components); }},
      {"png", [](const Scene& s, const DisplaySettings&, bool) { return s.output.png; },
       [](const Scene& s, const DisplaySettings&) { return s.output.name + ".png"; }, &RenderOutputs::png, true, false,
       [](const FinishedImage& i, const std::filesystem::path& path) {
         write_preview_png(path, i.scene.camera.width, i.scene.camera.height, *i.pipeline, i.display, i.rgb,
                           i.exposure.resolved, i.provenance);
       },
       [](const RenderPlan& p) { return png_bytes(p.width, p.height, p.png_bit_depth); }},
      {"working_exr", [](const Scene&, const DisplaySettings& d, bool) { return !d.exr_space.empty(); },
       [](const Scene& s, const DisplaySettings& d) {
         return s.output.name + "-" + find_working_space(d.exr_space).file_suffix + ".exr";
       },
       &RenderOutputs::working_exr, true, false,
       [](const FinishedImage& i, const std::filesystem::path& path) {
         write_working_space_exr(path, i.scene, *i.pipeline, find_working_space(i.display.exr_space), i.rgb,
                                 i.exposure.settings, i.exposure.resolved.scale, i.provenance);
       },
       [](const RenderPlan& p) { return rgb_exr_bytes(p.width, p.height); }},
      {"polarisation_exr",
       [](const Scene& s, const DisplaySettings&, bool tile) { return s.output.polarisation && s.output.exr && !tile; },
       [](const Scene& s, const DisplaySettings&) { return s.output.name + "-polarisation.exr"; },
       &RenderOutputs::polarisation_exr, false, true,
       [](const FinishedImage& i, const std::filesystem::path& path) {
         write_polarisation_exr(path, i.scene, i.stokes_y, i.provenance);
       },
       [](const RenderPlan& p) { return rgb_exr_bytes(p.width, p.height); }},  // Y, DoLP, AoLP
      {"polarisation_png",
       [](const Scene& s, const DisplaySettings&, bool) {
         return s.output.polarisation && s.output.polarisation_png && s.output.png;
       },
       [](const Scene& s, const DisplaySettings&) { return s.output.name + "-polarisation.png"; },
       &RenderOutputs::polarisation_png, false, true,
       [](const FinishedImage& i, const std::filesystem::path& path) {
         write_polarisation_png(path, i.scene, i.stokes_y, i.provenance);
       },
       [](const RenderPlan& p) { return png_bytes(p.width, p.height, 8); }},
      {"surface_exr", [](const Scene& s, const DisplaySettings&, bool tile) { return s.output.surface && !tile; },
       [](const Scene& s, const DisplaySettings&) { return s.output.name + "-surface.exr"; },
       &RenderOutputs::surface_exr, false, false,
       [](const FinishedImage& i, const std::filesystem::path& path) {
         std::map<std::string, std::string> strings = i.provenance;
         strings["skyspec:units"] =
             "Z: distance in metres from the camera along the pixel's central ray to the first surface it meets "
             "(0 where it meets none); mask.terrain, mask.ground: 1 where that surface is the terrain or the "
             "planet's ground, else 0";
         write_float_channels_exr(path, i.scene.camera.width, i.scene.camera.height, surface_channel_names(),
                                  surface_channels(i.scene), strings, is_latlong_envmap(i.scene.camera));
       },
       [](const RenderPlan& p) { return rgb_exr_bytes(p.width, p.height); }},  // Z and two masks
  };
  return outputs;
}

}  // namespace

namespace {
size_t pixel_index(const SpectralImageBuffer& image, int x, int y) {
  if (x < 0 || y < 0 || x >= image.width || y >= image.height)
    throw Error("pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is outside the " +
                std::to_string(image.width) + " x " + std::to_string(image.height) + " image");
  return static_cast<size_t>(y) * static_cast<size_t>(image.width) + static_cast<size_t>(x);
}
}  // namespace

const float* SpectralImageBuffer::spectrum(int x, int y) const {
  return spectral.data() + pixel_index(*this, x, y) * wavelengths_nm.size();
}

Rgb SpectralImageBuffer::pixel_rgb(int x, int y) const {
  const float* c = rgb.data() + pixel_index(*this, x, y) * 3;
  return Rgb(c[0], c[1], c[2]);
}

Vec3 SpectralImageBuffer::direction(int x, int y) const {
  const double* d = directions.data() + pixel_index(*this, x, y) * 3;
  return Vec3(d[0], d[1], d[2]);
}

SpectralImageBuffer render_to_memory(const Scene& scene, const ProgressFn& progress) {
  SkyRenderer r(scene);
  SpectralImageBuffer img;
  img.width = r.width();
  img.height = r.height();
  img.wavelengths_nm = r.grid().nanometres();
  const size_t n = static_cast<size_t>(r.grid().size());
  const size_t pixels = static_cast<size_t>(img.width) * static_cast<size_t>(img.height);
  img.spectral.resize(pixels * n);
  img.rgb.resize(pixels * 3);
  const int band = 16;
  const bool polarised = scene.output.polarisation;
  std::vector<float> stokes;  // a band's S0-S3 (polarised)
  if (polarised) img.stokes.resize(pixels * 3 * n);
  for (int y = 0; y < img.height; y += band) {
    const int rows = std::min(band, img.height - y);
    float* rgb = img.rgb.data() + static_cast<size_t>(y) * img.width * 3;
    if (!polarised) {
      r.render_rows(y, rows, img.spectral.data() + static_cast<size_t>(y) * img.width * n, rgb);
    } else {
      const size_t band_pixels = static_cast<size_t>(rows) * img.width, first = static_cast<size_t>(y) * img.width;
      stokes.resize(band_pixels * 4 * n);
      r.render_window_stokes(0, img.width, y, rows, stokes.data(), rgb);
      for (size_t p = 0; p < band_pixels; ++p) {
        const float* v = stokes.data() + p * 4 * n;
        std::copy(v, v + n, img.spectral.begin() + static_cast<long>((first + p) * n));
        std::copy(v + n, v + 4 * n, img.stokes.begin() + static_cast<long>((first + p) * 3 * n));
      }
    }
    if (progress) progress(y + rows, img.height);
  }
  // What the pixels show.
  img.scene = r.scene();
  img.directions.assign(pixels * 3, 0.0);
  const auto camera = make_camera(r.scene());
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      Vec3 d;
      if (camera->direction(x + 0.5, y + 0.5, d))
        std::copy(d.data(), d.data() + 3,
                  img.directions.begin() + static_cast<long>((static_cast<size_t>(y) * img.width + x) * 3));
    }
  img.sun_direction = r.sun_direction();
  img.sun_rgb = r.spectrum_to_rgb(r.sun_irradiance());
  img.metered_exposure_scale = meter_before_rendering(r);
  return img;
}

namespace {
// The exposure a write of an image in memory records and applies.
ChosenExposure exposure_of(const SpectralImageBuffer& image, const DisplaySettings& display) {
  return choose_exposure(image.scene, display, [&image] { return image.metered_exposure_scale; });
}

void check_image_buffer(const SpectralImageBuffer& image, const std::filesystem::path& path) {
  const size_t pixels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
  if (image.width != image.scene.camera.width || image.height != image.scene.camera.height ||
      image.rgb.size() != pixels * 3 || image.spectral.size() != pixels * image.wavelengths_nm.size() ||
      image.stokes.size() != (image.scene.output.polarisation ? 3 * image.spectral.size() : 0))
    throw Error("'" + path.string() +
                "': the image in memory is not one render_to_memory made (its size, "
                "channels and scene disagree)");
  // The EXR writer checks every value it writes; a display encoding would turn a NaN into a code value.
  for (size_t i = 0; i < image.rgb.size(); ++i)
    if (!std::isfinite(image.rgb[i]))
      throw Error("'" + path.string() + "': the image's R, G, B have a non-finite value at x = " +
                  std::to_string(i / 3 % static_cast<size_t>(image.width)) +
                  ", y = " + std::to_string(i / 3 / static_cast<size_t>(image.width)) + "; nothing was written");
}
}  // namespace

PreviewExposure preview_exposure(const SpectralImageBuffer& image) {
  return preview_exposure(image, DisplaySettings{});
}

PreviewExposure preview_exposure(const SpectralImageBuffer& image, const DisplaySettings& display) {
  const ResolvedExposure e = exposure_of(image, display).resolved;
  return {e.scale, e.description};
}

void write_spectral_exr(const SpectralImageBuffer& image, const std::filesystem::path& path) {
  write_spectral_exr(image, path, DisplaySettings{});
}

void write_spectral_exr(const SpectralImageBuffer& image, const std::filesystem::path& path,
                        const DisplaySettings& display) {
  check_image_buffer(image, path);
  const ChosenExposure exposure = exposure_of(image, display);
  const auto provenance = render_provenance(image.scene, exposure.resolved, false);
  SpectralExrWriter exr(path, image.width, image.height, image.wavelengths_nm,
                        spectral_exr_metadata(image.scene, provenance, exposure.resolved.scale, image.sun_rgb,
                                              image.scene.render.threads));
  if (image.scene.output.polarisation) {  // S0 then S1-S3 per pixel, as the writer takes them
    const size_t n = image.wavelengths_nm.size(), pixels = static_cast<size_t>(image.width) * image.height;
    std::vector<float> all(pixels * 4 * n);
    for (size_t p = 0; p < pixels; ++p) {
      std::copy_n(image.spectral.data() + p * n, n, all.data() + p * 4 * n);
      std::copy_n(image.stokes.data() + p * 3 * n, 3 * n, all.data() + p * 4 * n + n);
    }
    exr.write_rows(image.height, all.data(), image.rgb.data());
  } else {
    exr.write_rows(image.height, image.spectral.data(), image.rgb.data());
  }
  exr.finish();
}

double write_display_png(const SpectralImageBuffer& image, const std::filesystem::path& path) {
  return write_display_png(image, path, DisplaySettings{});
}

double write_display_png(const SpectralImageBuffer& image, const std::filesystem::path& path,
                         const DisplaySettings& display) {
  check_image_buffer(image, path);
  const DisplayPipeline pipeline(display);
  const ChosenExposure exposure = exposure_of(image, display);
  const auto provenance = render_provenance(image.scene, exposure.resolved, pipeline.config().is_builtin());
  write_preview_png(path, image.width, image.height, pipeline, display, image.rgb, exposure.resolved, provenance);
  return exposure.resolved.scale;
}

std::string display_png_bytes(const SpectralImageBuffer& image, const DisplaySettings& display,
                              PngCompression compression) {
  check_image_buffer(image, "(in memory)");
  const DisplayPipeline pipeline(display);
  const ChosenExposure exposure = exposure_of(image, display);
  const auto provenance = render_provenance(image.scene, exposure.resolved, pipeline.config().is_builtin());
  return png_display_in_memory(image.width, image.height, pipeline.encode(image.rgb, exposure.resolved.scale),
                               display.png_bit_depth, pipeline.png_tag(),
                               preview_png_text(pipeline, exposure.resolved, provenance), compression);
}

std::string polarisation_png_bytes(const SpectralImageBuffer& image, PngCompression compression) {
  check_image_buffer(image, "(in memory)");
  if (!image.scene.output.polarisation)
    throw InputError("output.polarisation", "false", "true for a picture of the polarisation");
  // The luminance of each Stokes component's spectrum, as render_bands takes it for the files
  // (SkyRenderer::spectrum_to_rgb, then Rec.709 luminance): one weight per wavelength.
  const WavelengthGrid grid = make_wavelength_grid(image.scene);
  const size_t n = image.wavelengths_nm.size(), pixels = static_cast<size_t>(image.width) * image.height;
  Eigen::VectorXd luminance = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n));
  const double* y_of_rgb = kRec709LuminanceWeights;
  if (image.scene.render.path == RenderSpec::Path::RgbFast) {
    const int index[3] = {grid.index_of(680), grid.index_of(550), grid.index_of(440)};
    for (int c = 0; c < 3; ++c) luminance[index[c]] += y_of_rgb[c];
  } else {
    const SpectrumToXyz xyz(grid, constants::kMaxLuminousEfficacy_lm_per_W);
    luminance = (Eigen::RowVector3d(y_of_rgb[0], y_of_rgb[1], y_of_rgb[2]) * xyz_to_linear_rec709() * xyz.weights())
                    .transpose();
  }
  std::vector<float> stokes_y(pixels * 3);
  for (size_t p = 0; p < pixels; ++p) {
    const float* components[3] = {image.spectral.data() + p * n, image.stokes.data() + p * 3 * n,
                                  image.stokes.data() + p * 3 * n + n};
    for (int c = 0; c < 3; ++c) {
      double sum = 0.0;
      for (size_t k = 0; k < n; ++k) sum += luminance[static_cast<Eigen::Index>(k)] * components[c][k];
      stokes_y[3 * p + static_cast<size_t>(c)] = static_cast<float>(sum);
    }
  }
  const ChosenExposure exposure = exposure_of(image, DisplaySettings{});
  const auto provenance = render_provenance(image.scene, exposure.resolved, true);
  return png_display_in_memory(image.width, image.height, polarisation_code_values(stokes_y), 8, PngColourTag::Srgb,
                               polarisation_png_text(provenance), compression);
}

RenderOutputs render_output_paths(const Scene& scene, const DisplaySettings& display) {
  if (!scene.output.exr && !scene.output.png && display.exr_space.empty())
    throw InputError("output.exr and output.png", "false", "at least one output to be true");
  RenderOutputs out;
  const std::filesystem::path dir(scene.output.directory);
  for (const FileOutput& o : file_outputs())
    if (o.wanted(scene, display, false)) out.*o.field = dir / o.file_name(scene, display);
  return out;
}

std::vector<std::string> planned_outputs(const Scene& scene, const DisplaySettings& display, bool tile) {
  std::vector<std::string> ids;
  for (const FileOutput& o : file_outputs())
    if (o.wanted(scene, display, tile)) ids.emplace_back(o.id);
  return ids;
}

std::uint64_t planned_output_bytes(const RenderPlan& plan) {
  std::uint64_t bytes = 0;
  for (const FileOutput& o : file_outputs())
    if (plan.writes(o.id)) bytes += o.bytes(plan);
  return bytes;
}

std::vector<std::filesystem::path> RenderOutputs::files() const {
  std::vector<std::filesystem::path> paths;
  for (const FileOutput& o : file_outputs())
    if (!(this->*o.field).empty()) paths.push_back(this->*o.field);
  return paths;
}

RenderOutputs render_scene_to_files(const Scene& scene, const ProgressFn& progress) {
  return render_scene_to_files(scene, DisplaySettings{}, progress);
}

RenderOutputs render_scene_to_files(const Scene& scene, const DisplaySettings& display, const ProgressFn& progress,
                                    const PreparedFn& prepared, const std::optional<PixelBounds>& tile) {
  using Clock = std::chrono::steady_clock;
  const auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  const auto t_start = Clock::now();
  // 1. The outputs asked for, and the display pipeline's names, are checked before rendering.
  ensure_writable_directory(scene.output.directory, "output.directory");
  const RenderOutputs paths = render_output_paths(scene, display);
  const OutputLock lock(scene.output.directory, scene.output.name, "output.name");  // one writer per name
  // Holding the name's lock: the temporaries of its files that a killed run left (SIGKILL, power)
  // are removed, where the process in their name no longer runs.
  remove_stale_temporaries(scene.output.directory, scene.output.name + ".");
  remove_stale_temporaries(scene.output.directory, scene.output.name + "-");
  RenderOutputs out;
  const bool working_exr = !display.exr_space.empty();
  // The files written after the image, in the list's order.
  std::vector<const FileOutput*> after;
  for (const FileOutput& o : file_outputs())
    if (o.write && o.wanted(scene, display, tile.has_value())) after.push_back(&o);
  const auto any = [&after](bool FileOutput::*need) {
    return std::any_of(after.begin(), after.end(), [need](const FileOutput* o) { return o->*need; });
  };
  const PixelBounds window = tile.value_or(PixelBounds{0, scene.camera.width, 0, scene.camera.height});
  if (tile) {
    check_pixel_bounds(*tile, scene.camera, "pixel bounds");
    if (scene.output.png || working_exr || !scene.output.exr)
      throw InputError(
          "pixel bounds", describe(*tile),
          "a tile that writes only its spectral EXR (output.exr = true, output.png = false, no working-space "
          "EXR): merge the tiles (skyspec merge), then make the PNG with skyspec convert");
  }
  std::optional<DisplayPipeline> pipeline;
  if (any(&FileOutput::needs_pipeline)) pipeline.emplace(display);

  // 2. Tables, then the caller's veto (the render budget), then the exposure.
  SkyRenderer r(scene);
  out.tables_seconds = since(t_start);
  if (prepared) prepared(r);
  const auto t_image = Clock::now();
  const ChosenExposure exposure = choose_exposure(scene, display, [&r] { return meter_before_rendering(r); });
  out.preview_scale = exposure.resolved.scale;
  out.preview_ev = exposure.resolved.ev;
  out.exposure = exposure.resolved.description;
  const auto provenance = render_provenance(scene, exposure.resolved, pipeline && pipeline->config().is_builtin());

  // 3. The image, streamed into the spectral EXR band by band.
  std::unique_ptr<SpectralExrWriter> exr;
  if (scene.output.exr) {
    SpectralExrMetadata meta = spectral_exr_metadata(scene, provenance, exposure.resolved.scale,
                                                     r.spectrum_to_rgb(r.sun_irradiance()), r.threads());
    if (tile) meta.data_window = std::array<int, 4>{tile->x0, tile->x1, tile->y0, tile->y1};
    exr = std::make_unique<SpectralExrWriter>(out.exr = paths.exr, r.width(), r.height(), r.grid().nanometres(), meta);
  }
  std::vector<float> rgb, stokes_y;
  if (pipeline) rgb.resize(static_cast<size_t>(r.width()) * r.height() * 3);
  if (any(&FileOutput::needs_stokes_luminance)) stokes_y.resize(static_cast<size_t>(r.width()) * r.height() * 3);
  render_bands(r, exr.get(), rgb, stokes_y, progress, window);
  out.image_seconds = since(t_image);

  // 4. The files completed, all or nothing. Completing the EXR (its offset table, fsync, rename)
  // waits mostly for the disk: when other files follow, it runs beside their encoding.
  const auto t_output = Clock::now();
  std::future<void> committing;
  if (exr && !after.empty())
    committing = std::async(std::launch::async, [&exr] { exr->finish(); });
  else if (exr)
    exr->finish();
  bool exr_done = exr && !committing.valid();
  std::vector<std::filesystem::path> done;  // the files after the image that this render completed
  try {
    const FinishedImage image{scene, display, pipeline ? &*pipeline : nullptr, rgb, stokes_y, exposure, provenance};
    for (const FileOutput* o : after) {
      const std::filesystem::path& path = out.*o->field = paths.*o->field;
      o->write(image, path);
      done.push_back(path);
    }
    if (scene.output.png) out.display = pipeline->describe();
    if (committing.valid()) {
      committing.get();  // rethrows the EXR's error
      exr_done = true;
    }
  } catch (...) {
    // Do not leave the files of a render whose outputs did not all arrive. The EXR's completion
    // is waited for first (it uses `exr`); only files this render completed are removed (a failed
    // write leaves an earlier file of that name as it was).
    if (committing.valid()) {
      try {
        committing.get();
        exr_done = true;
      } catch (...) {  // the first error is the one reported
      }
    }
    std::error_code ec;
    if (exr_done) std::filesystem::remove(out.exr, ec);
    for (const auto& path : done) std::filesystem::remove(path, ec);
    throw;
  }
  out.output_seconds = since(t_output);
  out.seconds = since(t_start);
  return out;
}

}  // namespace skyspec
