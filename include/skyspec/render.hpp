// Rendering a scene: cameras x single scattering -> spectral image -> files.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "skyspec/camera.hpp"
#include "skyspec/scene.hpp"
#include "skyspec/spectrum.hpp"

namespace skyspec {

/// Called after each band of rows with (rows done, rows in total).
using ProgressFn = std::function<void(int rows_done, int rows_total)>;

/// The camera a scene describes (world-space, planet-centred).
std::unique_ptr<Camera> make_camera(const Scene& scene);

/// Everything needed to render one scene, built once: atmosphere on the grid, the sun's column
/// table, the integrator, the camera, and the colour conversion.
class SkyRenderer {
 public:
  explicit SkyRenderer(const Scene& scene);
  ~SkyRenderer();
  const Scene& scene() const;
  const WavelengthGrid& grid() const;
  int width() const;
  int height() const;

  /// Renders rows [y0, y0 + rows): spectral radiance ([row][x][lambda]) and linear Rec.709
  /// preview RGB ([row][x][c]); uses all threads allowed by render.threads. Results do not depend
  /// on the number of threads.
  void render_rows(int y0, int rows, float* spectral, float* rgb) const;

  /// Spectral radiance (grid size floats) seen from the scene's camera position looking along
  /// the world-space unit direction dir, and the same as linear Rec.709.
  void radiance(const Vec3& dir, float* spectrum) const;
  void radiance_rgb(const Vec3& dir, float rgb[3]) const;

  /// Linear Rec.709 from a spectrum: through CIE XYZ (spectral path, Y in cd m^-2 for radiance in
  /// W m^-2 sr^-1 nm^-1) or directly from the 680/550/440 nm values (RGB-fast path).
  void spectrum_to_rgb(const float* spectrum, float rgb[3]) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// A whole image in memory (tests, Python, small renders).
struct SpectralImageBuffer {
  int width = 0, height = 0;
  std::vector<double> wavelengths_nm;
  std::vector<float> spectral;  ///< [y][x][lambda]
  std::vector<float> rgb;       ///< [y][x][c]
};
SpectralImageBuffer render_to_memory(const Scene& scene, const ProgressFn& progress = {});

struct RenderOutputs {
  std::filesystem::path exr, png;  ///< empty when not written
  double preview_scale = 1.0;      ///< factor applied to linear RGB before sRGB encoding
  double preview_ev = 0.0;         ///< log2(preview_scale)
  double seconds = 0.0;
};

/// Renders the scene and writes its outputs (spectral EXR streamed in bands, PNG preview), each
/// atomically: on any error no output file is left behind.
RenderOutputs render_scene_to_files(const Scene& scene, const ProgressFn& progress = {});

/// The automatic preview exposure: the scale that maps the log-average luminance to 0.18
/// (Reinhard et al. 2002's key value), over the pixels no darker than 1/100 of the 90th
/// percentile (so dark ground does not count), from linear RGB ([n][3]).
double auto_exposure_scale(const std::vector<float>& linear_rgb);

}  // namespace skyspec
