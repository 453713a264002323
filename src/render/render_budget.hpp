// What a render will cost before it starts: the bytes it writes, the memory it holds and the time
// it takes, against the free disk, the available memory and a day. Absurd but legal requests (an
// EXR bigger than the disk, a render of several days) are refused up front, unless forced.
//
// Sizes are upper bounds from the image size (uncompressed pixel data plus room for the headers);
// memory follows what render_scene_to_files keeps (a whole-image float RGB buffer for the PNG and
// the working-space EXR, a band of spectral rows per thread, the EXR encoders' buffers); the time is measured,
// not guessed: radiance() is timed on a sample of the camera's own pixels and extrapolated to the
// image, the frames and the threads.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "skyspec/render.hpp"  // kForceSetting

namespace skyspec {

class SkyRenderer;
struct Scene;
struct ScatteringTablesKey;
struct DisplaySettings;
struct RenderPlan;

/// Upper bound of a spectral EXR's size: width x height x (wavelengths + 3 RGB channels) floats,
/// the scan-line offset table and 64 KiB for the header.
std::uint64_t spectral_exr_bytes(int width, int height, int wavelengths);
/// Upper bound of an RGB float EXR's size (the working-space EXR).
std::uint64_t rgb_exr_bytes(int width, int height);
/// Upper bound of a PNG's size: 3 samples of bit_depth bits per pixel, a filter byte per row
/// (stored without compression) and 64 KiB for the chunks.
std::uint64_t png_bytes(int width, int height, int bit_depth);

/// A size for messages, in SI units: "41 GB", "720 kB", "12 bytes".
std::string format_bytes(std::uint64_t bytes);
/// "0.8 s", "12 min", "3.5 h", "3.2 days".
std::string format_duration(double seconds);

/// The outputs list's part of a plan (render_outputs.cpp, one row per file a render can write):
/// the ids of the files a render of `scene` with `display` writes (`tile`: a tile of the image),
/// and the bytes of one frame's files of a plan, each row's own upper bound.
std::vector<std::string> planned_outputs(const Scene& scene, const DisplaySettings& display, bool tile);
std::uint64_t planned_output_bytes(const RenderPlan& plan);

/// The rows of a band of render_scene_to_files's image (render_outputs.cpp): whole line blocks
/// of `block_rows` (the spectral EXR's codec's, 1 without the file) of about 4 MiB of values
/// (`values_per_pixel` floats and R, G, B per pixel), at most 64 rows unless one block is taller,
/// at most the image's `height`.
int render_band_rows(int width, int values_per_pixel, int block_rows, int height);

/// What a request asks for: image size, grid, outputs and how many frames.
struct RenderPlan {
  int width = 0, height = 0, wavelengths = 0, view_segments = 0, threads = 1;
  int frames = 1;
  /// The files of one frame, by their id in the outputs list: "spectral_exr", "png",
  /// "working_exr", "polarisation_exr", "polarisation_png", "surface_exr".
  std::vector<std::string> outputs;
  bool writes(const std::string& id) const;
  void drop(const std::string& id);
  /// 4 for a polarised render (S0-S3 per wavelength, output.polarisation; its Y/DoLP/AoLP EXR too), else 1.
  int stokes_components = 1;
  int png_bit_depth = 8;
  /// The spectral EXR's line block (spectral_exr_block_rows of output.exr_compression).
  int exr_block_rows = 32;
  std::filesystem::path directory;
  /// What a caller writes and holds besides what render_scene_to_files does (aerial perspective
  /// writes several spectral EXRs and keeps whole spectral images): added to output_bytes() once
  /// per frame, and to peak_memory_bytes() per pixel. 0 for render and timelapse.
  std::uint64_t extra_output_bytes = 0;
  double extra_bytes_per_pixel = 0.0;
  /// The multiple-scattering tables held while rendering (ScatteringOrders::table_bytes; with
  /// interpolated tables also the grid's and the blend, render/table_family.hpp).
  std::uint64_t table_bytes = 0;

  /// The plan of render_scene_to_files for a scene: its size, grid, outputs and directory;
  /// threads as the renderer will use them (render.threads, at most the cores available).
  /// `tile`: the plan of a tile (render --pixel-bounds; the caller sets its width and height).
  static RenderPlan for_scene(const Scene& scene, const DisplaySettings& display, int frames = 1, bool tile = false);
  /// The same with the default display settings (8-bit PNG, no working-space EXR).
  static RenderPlan for_scene(const Scene& scene, int frames = 1);
  /// All files of all frames.
  std::uint64_t output_bytes() const;
  /// Peak memory of one frame.
  std::uint64_t peak_memory_bytes() const;
  /// "41 wavelengths, 64 view segments, 16384x8192, 2 threads[, 300 frames]".
  std::string settings() const;
};

/// The estimate of one request and what the machine has.
struct RenderEstimate {
  RenderPlan plan;
  std::uint64_t output_bytes = 0, peak_memory_bytes = 0;
  std::optional<std::uint64_t> disk_available_bytes;    ///< unknown: not checked
  std::optional<std::uint64_t> memory_available_bytes;  ///< unknown: not checked
  std::optional<double> seconds;                        ///< wall time of the image; unknown until measured
  std::optional<double> table_seconds;                  ///< wall time of tables not yet built, if estimated
  std::uint64_t table_cache_bytes = 0;                  ///< what the disk cache gains by them
  /// "outputs up to 46 MB (74 GB free), peak memory about 6 MB (22 GB available), about 2.1 s of
  /// rendering[, tables about 40 s[ and 56 MB in the table cache]]" (the tables: everything before
  /// the first pixel).
  std::string describe() const;
  /// One sentence per limit exceeded: output > free disk, memory > MemAvailable, time > 24 h.
  std::vector<std::string> problems() const;
};

/// Sizes and memory of the plan against the disk of plan.directory and /proc/meminfo.
RenderEstimate estimate_render(const RenderPlan& plan);

/// Seconds to render the plan's pixels (all frames) with the renderer, from CPU time measured on
/// it: render_rows on one or two of the image's rows, scaled to width x height x frames / threads.
/// When a row would take over a second even so, the cost of radiance() (every pixel marched),
/// timed on up to 64 pixels spread over the image, is scaled instead. With a spectral EXR, the
/// cost of compressing a rendered row into one (encoded in memory) is added; with a PNG, the cost
/// of the display pipeline and libpng's compression on 16 rows (in memory, serial as in the render).
/// Building the renderer is not included (estimate_table_seconds). The sample is a row or two, so the estimate costs a
/// small fraction of a render; with many wavelengths most of it is the compression of the sample
/// (docs/performance.md).
double measure_render_seconds(const SkyRenderer& renderer, const RenderPlan& plan);

/// The scene as `render --dry-run` builds it, so that nothing expensive is computed: the higher
/// orders from the smallest tables allowed (4 x 4 entries of order 2, not cached) and a sky-view
/// table of at most 32 x 32 entries. The cost of a pixel or a sky-view entry measured on its
/// renderer is that of the render's (a look-up in tables of the same degree and wavelengths).
Scene scene_for_estimate(const Scene& scene);
/// Seconds to build the scene's scattering-order tables (render.scattering_orders >= 2), or those
/// of the grid's atmospheres it interpolates (scenes_of_tables), 0 for tables cached (in this
/// process or on disk): ScatteringOrders::estimate_build_seconds, which builds and times 16
/// entries of one order. Builds the scene's sun table to do so.
double estimate_scattering_orders_seconds(const Scene& scene);
/// The size of the cache file of the scene's scattering-order tables, named by `key`.
std::uint64_t scattering_tables_file_bytes(const Scene& scene, const ScatteringTablesKey& key);
/// Bytes the disk cache gains when the scene's scattering-order tables are built: their files (the
/// grid's, scenes_of_tables, for interpolated tables), or 0 when they are cached, single
/// scattering is asked for or render.cache_tables is false.
std::uint64_t estimate_table_cache_bytes(const Scene& scene);
/// Seconds to build what every frame builds anew, measured on `estimate_renderer` (built from
/// scene_for_estimate(scene)): its own construction (the atmosphere on the grid, the sun's
/// optical-depth table, a small sky-view table) and the rest of the scene's sky-view table, its
/// build time scaled by the ratio of the table sizes (the sky-view table depends on the sun).
double estimate_frame_table_seconds(const Scene& scene, const SkyRenderer& estimate_renderer);
/// Seconds to build every table of `scene`: estimate_frame_table_seconds and the scattering
/// orders (estimate_scattering_orders_seconds; 0 when cached).
double estimate_table_seconds(const Scene& scene, const SkyRenderer& estimate_renderer);

/// Throws InputError::refused naming every limit exceeded, the estimate and `force_flag`.
void refuse_if_over_budget(const RenderEstimate& estimate, const std::string& force_flag = kForceSetting);

/// Before a renderer is built: refuse_if_over_budget with the estimate of the scene's
/// scattering-order tables added (estimate_scattering_orders_seconds), so that tables that would
/// take more than a day are refused before they start.
void refuse_if_tables_over_budget(const Scene& scene, RenderEstimate estimate,
                                  const std::string& force_flag = kForceSetting);

/// MemAvailable of /proc/meminfo, if readable.
std::optional<std::uint64_t> available_memory_bytes();
/// Free bytes for an unprivileged writer on the file system of `dir` (or of its nearest existing
/// parent, when dir does not exist yet), if known.
std::optional<std::uint64_t> available_disk_bytes(const std::filesystem::path& dir);

}  // namespace skyspec
