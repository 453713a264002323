#include "skyspec/render.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "skyspec/atomic_file.hpp"
#include "skyspec/colour.hpp"
#include "skyspec/error.hpp"
#include "skyspec/png_image.hpp"
#include "skyspec/multiple_scattering.hpp"
#include "skyspec/single_scattering.hpp"
#include "skyspec/spectral_exr.hpp"
#include "skyspec/units.hpp"
#include "skyspec/version.hpp"

namespace skyspec {

std::unique_ptr<Camera> make_camera(const Scene& scene) {
  const double R = scene.atmosphere.planet_radius_m;
  auto world = [R](const Vec3& p) { return Vec3(p.x(), p.y(), R + p.z()); };
  const auto& c = scene.camera;
  switch (c.type) {
    case CameraSpec::Type::Fisheye:
      return std::make_unique<FisheyeCamera>(c.width, c.height, world(c.position_m));
    case CameraSpec::Type::Perspective:
      return std::make_unique<PerspectiveCamera>(c.width, c.height, world(c.position_m), world(c.look_at_m), c.fov_deg);
    case CameraSpec::Type::Equirectangular:
      return std::make_unique<EquirectangularCamera>(c.width, c.height, world(c.position_m));
  }
  return nullptr;
}

namespace {
std::unique_ptr<ScatteringOrders> build_orders(const Scene& s, const SingleScattering& integrator) {
  MultipleScatteringSettings ms;
  ms.orders = s.render.scattering_orders;
  ms.altitude_samples = s.render.ms_altitude_samples;
  ms.sun_samples = s.render.ms_sun_samples;
  return std::make_unique<ScatteringOrders>(integrator, ms);
}
}  // namespace

struct SkyRenderer::Impl {
  Scene scene;
  WavelengthGrid grid;
  AtmosphereModel atmosphere;
  SunColumnTable table;
  TableSunColumns sun_columns;
  SingleScattering integrator;
  std::unique_ptr<ScatteringOrders> orders;  // null for single scattering
  ScatteringSources sources;
  std::unique_ptr<Camera> camera;
  Vec3 sun_dir;
  Spectrum sun_irradiance;
  Eigen::Matrix<float, 3, Eigen::Dynamic> to_rgb;  // spectrum -> linear Rec.709
  int rgb_index[3] = {0, 0, 0};                     // RGB-fast: indices of 680, 550, 440 nm
  bool rgb_fast;
  int threads;

  explicit Impl(const Scene& s)
      : scene(s),
        grid(make_wavelength_grid(s)),
        atmosphere(s.atmosphere, grid),
        table(atmosphere, SunColumnTable::Resolution{s.render.table_altitude_samples, s.render.table_zenith_samples, 128}),
        sun_columns(table),
        integrator(atmosphere, sun_columns, IntegratorSettings{s.render.view_segments}),
        orders(s.render.scattering_orders >= 2 ? build_orders(s, integrator) : nullptr),
        sources{true, orders.get()},
        camera(make_camera(s)),
        sun_dir(sun_direction(s)),
        sun_irradiance(Spectrum::Constant(grid.size(), static_cast<float>(s.sun.spectral_irradiance_W_m2_nm))),
        rgb_fast(s.render.path == RenderSpec::Path::RgbFast),
        threads(s.render.threads > 0 ? s.render.threads : tbb::this_task_arena::max_concurrency()) {
    if (rgb_fast) {
      rgb_index[0] = grid.index_of(680);
      rgb_index[1] = grid.index_of(550);
      rgb_index[2] = grid.index_of(440);
    } else {
      const SpectrumToXyz xyz(grid, constants::kMaxLuminousEfficacy_lm_per_W);
      to_rgb = (xyz_to_linear_rec709() * xyz.weights()).cast<float>();
    }
  }
};

SkyRenderer::SkyRenderer(const Scene& scene) : impl_(std::make_unique<Impl>(scene)) {}
SkyRenderer::~SkyRenderer() = default;
const Scene& SkyRenderer::scene() const { return impl_->scene; }
const WavelengthGrid& SkyRenderer::grid() const { return impl_->grid; }
int SkyRenderer::width() const { return impl_->camera->width(); }
int SkyRenderer::height() const { return impl_->camera->height(); }

void SkyRenderer::spectrum_to_rgb(const float* spectrum, float rgb[3]) const {
  const auto& m = *impl_;
  if (m.rgb_fast) {
    for (int c = 0; c < 3; ++c) rgb[c] = spectrum[m.rgb_index[c]];
    return;
  }
  const Eigen::Map<const Eigen::VectorXf> s(spectrum, m.grid.size());
  const Eigen::Vector3f v = m.to_rgb * s;
  for (int c = 0; c < 3; ++c) rgb[c] = v[c];
}

void SkyRenderer::radiance(const Vec3& dir, float* spectrum) const {
  const auto& m = *impl_;
  ScatteringWorkspace ws(m.grid.size());
  Spectrum out(m.grid.size());
  m.integrator.radiance(m.camera->origin_m(), dir.normalized(), m.sun_dir, m.sun_irradiance, m.sources, ws, out);
  std::copy(out.data(), out.data() + out.size(), spectrum);
}

void SkyRenderer::radiance_rgb(const Vec3& dir, float rgb[3]) const {
  std::vector<float> s(static_cast<size_t>(impl_->grid.size()));
  radiance(dir, s.data());
  spectrum_to_rgb(s.data(), rgb);
}

void SkyRenderer::render_rows(int y0, int rows, float* spectral, float* rgb) const {
  const auto& m = *impl_;
  const int w = m.camera->width(), n = m.grid.size();
  tbb::enumerable_thread_specific<std::pair<ScatteringWorkspace, Spectrum>> scratch(
      [n] { return std::make_pair(ScatteringWorkspace(n), Spectrum(n)); });
  tbb::task_arena arena(m.threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, rows * w, 64), [&](const tbb::blocked_range<int>& r) {
      auto& [ws, radiance] = scratch.local();
      for (int idx = r.begin(); idx != r.end(); ++idx) {
        const int row = idx / w, x = idx % w;
        Vec3 dir;
        float* px = spectral + static_cast<size_t>(idx) * n;
        if (m.camera->direction(x + 0.5, y0 + row + 0.5, dir)) {
          m.integrator.radiance(m.camera->origin_m(), dir, m.sun_dir, m.sun_irradiance, m.sources, ws, radiance);
          std::copy(radiance.data(), radiance.data() + n, px);
        } else {
          std::fill(px, px + n, 0.0f);
        }
        spectrum_to_rgb(px, rgb + static_cast<size_t>(idx) * 3);
      }
    });
  });
}

SpectralImageBuffer render_to_memory(const Scene& scene, const ProgressFn& progress) {
  SkyRenderer r(scene);
  SpectralImageBuffer img;
  img.width = r.width();
  img.height = r.height();
  img.wavelengths_nm = r.grid().nanometres();
  const size_t n = static_cast<size_t>(r.grid().size());
  img.spectral.resize(static_cast<size_t>(img.width) * img.height * n);
  img.rgb.resize(static_cast<size_t>(img.width) * img.height * 3);
  const int band = 16;
  for (int y = 0; y < img.height; y += band) {
    const int rows = std::min(band, img.height - y);
    r.render_rows(y, rows, img.spectral.data() + static_cast<size_t>(y) * img.width * n,
                  img.rgb.data() + static_cast<size_t>(y) * img.width * 3);
    if (progress) progress(y + rows, img.height);
  }
  return img;
}

double auto_exposure_scale(const std::vector<float>& linear_rgb) {
  std::vector<double> y;
  y.reserve(linear_rgb.size() / 3);
  for (size_t i = 0; i + 2 < linear_rgb.size(); i += 3) {
    const double v = 0.2126 * linear_rgb[i] + 0.7152 * linear_rgb[i + 1] + 0.0722 * linear_rgb[i + 2];
    if (v > 0.0) y.push_back(v);
  }
  if (y.empty()) return 1.0;
  // Only pixels within a factor 100 of the 90th percentile count, so that dark ground or the
  // night side does not drag the exposure of the sky up.
  std::vector<double> sorted = y;
  const size_t k = sorted.size() * 9 / 10;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(k), sorted.end());
  const double floor = 0.01 * sorted[k];
  double sum_log = 0.0;
  size_t count = 0;
  for (double v : y)
    if (v >= floor) {
      sum_log += std::log(v);
      ++count;
    }
  return 0.18 / std::exp(sum_log / static_cast<double>(count));
}

namespace {
void check_finite(const float* p, size_t n, const char* what) {
  for (size_t i = 0; i < n; ++i)
    if (!std::isfinite(p[i]))
      throw Error(std::string("internal error: a non-finite ") + what + " value was computed; no file was written");
}
}  // namespace

RenderOutputs render_scene_to_files(const Scene& scene, const ProgressFn& progress) {
  const auto t_start = std::chrono::steady_clock::now();
  ensure_writable_directory(scene.output.directory, "output.directory");
  const std::filesystem::path dir(scene.output.directory);
  RenderOutputs out;
  if (!scene.output.exr && !scene.output.png)
    throw InputError("output.exr and output.png", "false", "at least one output to be true");

  SkyRenderer r(scene);
  const int w = r.width(), h = r.height(), n = r.grid().size();
  const bool rgb_fast = scene.render.path == RenderSpec::Path::RgbFast;

  std::unique_ptr<SpectralExrWriter> exr;
  if (scene.output.exr) {
    SpectralExrMetadata meta;
    meta.strings["skyspec:version"] = version_string();
    meta.strings["skyspec:scene"] = scene_to_toml(scene);
    meta.strings["skyspec:renderPath"] = rgb_fast ? "rgb-fast" : "spectral";
    meta.strings["skyspec:wavelengths"] = r.grid().describe();
    meta.strings["skyspec:units"] =
        rgb_fast ? "RGB-fast path: S0 channels and R,G,B in the sun's units (spectral_irradiance x sr^-1); "
                   "R,G,B are the 680, 550, 440 nm values read as linear Rec.709"
                 : "S0 channels: spectral radiance, W m^-2 sr^-1 nm^-1; R,G,B: linear Rec.709 (D65) with "
                   "Y = luminance in cd m^-2";
    out.exr = dir / (scene.output.name + ".exr");
    exr = std::make_unique<SpectralExrWriter>(out.exr, w, h, r.grid().nanometres(), meta);
  }

  const int band = 32;  // two ZIP line blocks per write, compressed in parallel
  std::vector<float> spectral(static_cast<size_t>(band) * w * n), band_rgb(static_cast<size_t>(band) * w * 3);
  std::vector<float> rgb;  // whole preview image, for the automatic exposure
  if (scene.output.png) rgb.resize(static_cast<size_t>(w) * h * 3);
  for (int y = 0; y < h; y += band) {
    const int rows = std::min(band, h - y);
    r.render_rows(y, rows, spectral.data(), band_rgb.data());
    check_finite(spectral.data(), static_cast<size_t>(rows) * w * n, "radiance");
    check_finite(band_rgb.data(), static_cast<size_t>(rows) * w * 3, "RGB");
    if (exr) exr->write_rows(rows, spectral.data(), band_rgb.data());
    if (!rgb.empty())
      std::copy(band_rgb.begin(), band_rgb.begin() + static_cast<long>(rows) * w * 3,
                rgb.begin() + static_cast<long>(y) * w * 3);
    if (progress) progress(y + rows, h);
  }

  out.preview_scale = scene.output.exposure_ev ? std::exp2(*scene.output.exposure_ev) : auto_exposure_scale(rgb);
  out.preview_ev = std::log2(out.preview_scale);
  if (exr) exr->finish();
  if (scene.output.png) {
    out.png = dir / (scene.output.name + ".png");
    try {
      write_png_srgb8(out.png, w, h, rgb, out.preview_scale);
    } catch (...) {
      // All or nothing: do not leave the EXR of a render whose outputs did not all arrive.
      std::error_code ec;
      if (!out.exr.empty()) std::filesystem::remove(out.exr, ec);
      throw;
    }
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  return out;
}

}  // namespace skyspec
