#include "skyspec/render.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <mutex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include "base/cancellation.hpp"
#include "base/recent_values.hpp"
#include "physics/sun_disk.hpp"
#include "render/scene_tables.hpp"
#include "render/sun_irradiance.hpp"
#include "render/table_family.hpp"
#include "scene/scene_terrain.hpp"
#include "skyspec/colour.hpp"
#include "skyspec/error.hpp"
#include "skyspec/units.hpp"
#include "transport/multiple_scattering.hpp"
#include "transport/regional_orders.hpp"
#include "transport/scattering_tables_cache.hpp"
#include "transport/single_scattering.hpp"
#include "transport/sky_view_table.hpp"

namespace skyspec {

namespace {
// render.threads, or all cores for 0.
int thread_count(const Scene& s) {
  return s.render.threads > 0 ? s.render.threads : tbb::this_task_arena::max_concurrency();
}

// The sun angles the sun table must serve: with single scattering every look-up is on a ray from
// the camera, so only the band of sun angles met in the air the camera sees (a few degrees either
// side of the sun's angle at the camera, for a camera on the ground); building the scattering
// orders needs every angle.
SunColumnTable::MuBand sun_band(const Scene& s, const AtmosphereModel& atmosphere) {
  if (s.render.scattering_orders >= 2) return SunColumnTable::MuBand{};
  return SunColumnTable::band_seen_from(atmosphere, make_camera(s)->origin_m(), sun_direction(s));
}

// The scattering-order tables for orders 2 .. render.scattering_orders.
std::shared_ptr<const ScatteringOrders> build_orders(const Scene& s, const SingleScattering& integrator) {
  if (s.render.ms_tables == RenderSpec::Tables::Interpolated) {
    std::string why_not;
    if (auto blended = interpolated_scattering_orders(s, integrator.atmosphere(), &why_not)) return blended;
    // Once per reason and process (a job's worker renders many such skies).
    static std::mutex mutex;
    static std::set<std::string> said;
    const std::lock_guard<std::mutex> lock(mutex);
    if (said.insert(why_not).second)
      std::cerr << "skyspec: warning: render.ms_tables = \"interpolated\": " << why_not
                << "; the tables are built for this atmosphere instead\n";
  }
  return scattering_orders_for(integrator, sun_table_resolution(s), multiple_scattering_settings(s),
                               s.render.cache_tables);
}

// The sky-view tables kept besides the newest: at most this many, of at most this many bytes; a
// table larger than that is not kept at all (its render holds it while it needs it).
constexpr size_t kKeptSkyViewTables = 3;
constexpr size_t kKeptSkyViewBytes = size_t{192} << 20;

// The sky-view table of a render. Its entries depend on the air and the tables' settings (all of
// which the scattering-order tables' key names), the integrator's segments, what the table holds,
// its resolution, the camera's radius and the sun's zenith angle there (SkyViewTable marches in
// its own frame): renders that agree on those share them, such as the viewer's frames while the
// camera turns or the sun moves in azimuth. The newest tables are kept (kKeptSkyViewTables more),
// sharing their entries with the renders that use them.
std::unique_ptr<SkyViewTable> sky_view_table_for(const Scene& s, const AtmosphereModel& atmosphere,
                                                 const SingleScattering& integrator, const ScatteringSources& sources,
                                                 const Vec3& origin_m, const Vec3& sun_dir, SkyViewResolution res,
                                                 int threads) {
  std::ostringstream key;
  key << scattering_tables_key(atmosphere, sun_table_resolution(s), multiple_scattering_settings(s)).inputs
      << "view_segments " << s.render.view_segments << "\nhigher " << (sources.higher != nullptr) << " polarisation "
      << sources.polarisation << " single " << sources.single << "\nrows " << res.sky_rows << ' ' << res.ground_rows
      << ' ' << res.azimuths << ' ' << res.ground_side << ' ' << res.higher_sky_rows << ' ' << res.higher_azimuths
      << std::hexfloat << "\nradius " << origin_m.norm();
  const Vec3 sun = SkyViewTable::own_frame_sun(origin_m, sun_dir);
  key << " sun " << sun[0] << ' ' << sun[1] << ' ' << sun[2];
  static RecentValues<SkyViewTable> kept(kKeptSkyViewTables, kKeptSkyViewBytes,
                                         [](const SkyViewTable& t) { return t.bytes(); });
  const auto table = kept.get(key.str(), [&] {
    return std::make_shared<const SkyViewTable>(integrator, sources, origin_m, sun_dir, res, threads);
  });
  return std::make_unique<SkyViewTable>(table->reoriented(origin_m, sun_dir));
}
}  // namespace

struct SkyRenderer::Impl {
  Scene scene;
  WavelengthGrid grid;
  AtmosphereModel atmosphere;
  std::shared_ptr<const SunColumnTable> table;  // shared with other renders of the same air
  TableSunColumns sun_columns;
  SingleScattering integrator;
  std::shared_ptr<const ScatteringOrders> orders;  // null for single scattering
  std::shared_ptr<const Terrain> terrain;          // null without terrain
  ScatteringSources sources;                       // with the terrain: what marched rays see
  // A medium confined to a region: the light it scatters twice, for this camera (null: none).
  std::unique_ptr<RegionalSecondOrder> regional;
  std::unique_ptr<Camera> camera;
  std::unique_ptr<SkyViewTable> sky_view;  // null: every pixel is marched
  double sky_view_seconds = 0.0;           // its build time
  double build_seconds = 0.0;              // the constructor's wall time
  Vec3 sun_dir;
  Spectrum sun_irradiance;
  double sun_radius_rad;
  Spectrum to_rgb[3];            // spectrum -> linear Rec.709: R, G, B are the dot products with these rows
  int rgb_index[3] = {0, 0, 0};  // RGB-fast: indices of 680, 550, 440 nm
  bool rgb_fast;
  int threads;

  // Adds the limb-darkened sun disk to the radiance of pixel (px, py) (top-left corner), whose
  // centre looks along dir. The disk is far smaller than most pixels, so the pixel's area is
  // sampled on an 8 x 8 grid and the disk's radiance averaged over it; the attenuation along the
  // line of sight is taken at the pixel's centre. `right`: the direction of pixel (px + 1, py) if the
  // caller has it (null: asked of the camera).
  void add_sun_disk(int px, int py, const Vec3& dir, const Vec3* right, float* radiance, Spectrum& disk,
                    Spectrum& trans) const {
    Vec3 neighbour;
    if (right)
      neighbour = *right;
    else if (!camera->direction(px + 1.5, py + 0.5, neighbour) && !camera->direction(px - 0.5, py + 0.5, neighbour))
      return;
    // Most pixels are far from the sun, which their chords show without an arc cosine: an angle a
    // with chord c = 2 sin(a / 2) has c <= a <= (pi / 2) c, so a chord to the sun longer than
    // sun_radius + 1.5 (pi / 2) (the chord to the neighbour) fails the test below too.
    if ((dir - sun_dir).norm() > sun_radius_rad + 0.75 * kPi * (neighbour - dir).norm()) return;
    const double pixel_rad = std::acos(std::clamp(neighbour.dot(dir), -1.0, 1.0));
    const double to_sun = std::acos(std::clamp(dir.dot(sun_dir), -1.0, 1.0));
    if (to_sun > sun_radius_rad + 1.5 * pixel_rad) return;
    const int n = 8;
    Spectrum& sample = trans;  // reused below for the transmittance
    disk.setZero();
    bool any = false;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        Vec3 d;
        if (!camera->direction(px + (i + 0.5) / n, py + (j + 0.5) / n, d)) continue;
        const double x = std::acos(std::clamp(d.dot(sun_dir), -1.0, 1.0)) / sun_radius_rad;
        if (x >= 1.0) continue;
        disk_radiance_per_irradiance(grid, sun_radius_rad, x, sample);
        disk += sample;
        any = true;
      }
    if (!any) return;
    if (terrain_hides(dir)) return;  // behind a mountain
    integrator.transmittance_to_space(camera->origin_m(), dir, trans);
    Eigen::Map<Spectrum>(radiance, grid.size()) += disk * (1.0f / (n * n)) * trans * sun_irradiance;
  }

  // Whether the terrain is in front of the camera along dir.
  bool terrain_hides(const Vec3& dir) const {
    return terrain && std::isfinite(terrain->intersect(camera->origin_m(), dir, 0.0, 2.0 * atmosphere.top_radius_m()));
  }

  // Whether the terrain or its shadow touches the ray along dir, and where (Terrain::
  // affected_stretch); elsewhere the sky-view table (built without terrain) serves it.
  bool terrain_touches(const Vec3& dir, Interval& stretch) const {
    return terrain &&
           terrain->affected_stretch(camera->origin_m(), dir, 0.0, 2.0 * atmosphere.top_radius_m(), sun_dir, stretch);
  }
  bool table_serves(const Vec3& dir) const {
    Interval stretch;
    return !terrain_touches(dir, stretch);
  }

  // The parts of a direction the terrain's shadow touches but the terrain does not hide: the
  // sky-view table's (built without terrain), less the light of order 1 the shadows take away,
  // which is the integrator's order 1 without the terrain less the same with it (the same
  // quadrature wherever no shadow falls on the ray, so the difference is exactly that of the
  // shadowed pieces and of a shadowed ground). The higher orders are the table's where the ray
  // ends in the sky, or on the ground without the terrain's shadow on it (single_scattering.hpp).
  // False where the ray meets the terrain or ends on the ground over its grid with the terrain's own
  // albedo, where it ends on the ground past the terrain's shadow
  // with higher orders (the sky the terrain hides from its points: SkylineCut in
  // single_scattering.cpp), or where the table does not hold the direction: then it is marched.
  // `stretch`: terrain_touches()'s.
  bool table_less_shadows(const Vec3& dir, const Interval& stretch, ScatteringWorkspace& ws,
                          RadianceParts& parts) const {
    const Vec3& o = camera->origin_m();
    const double ground = sphere_entry_distance(o, dir, atmosphere.planet_radius_m());
    const double end = std::min(stretch.t1_m, ground);
    if (std::isfinite(terrain->intersect(o, dir, stretch.t0_m, end))) return false;
    // The ground over the terrain's grid reflects with the terrain's albedo, which the table does not know.
    if (std::isfinite(ground) && terrain->has_own_albedo() && terrain->covers(o + ground * dir)) return false;
    if (!sky_view->lookup(dir, parts)) return false;
    // No terrain shadow on the ray (its visibility probed as the integrator probes it): the table's
    // parts are the answer (the two marches below would be equal).
    thread_local std::vector<Interval> lit;
    lit.clear();
    terrain->sunlit_parts(o, dir, stretch.t0_m, end, sun_dir, lit);
    double covered = 0.0;
    for (const Interval& i : lit) covered += i.t1_m - i.t0_m;
    if (covered >= (end - stretch.t0_m) * (1.0 - 1e-12)) return true;
    if (sources.higher && std::isfinite(ground)) return false;
    thread_local RadianceParts open, shaded;
    ScatteringSources single;  // order 1: the sun's light scattered once, and off the ground
    integrator.radiance_parts(o, dir, sun_dir, single, ws, open);
    single.terrain = terrain.get();
    integrator.radiance_parts(o, dir, sun_dir, single, ws, shaded);
    for (size_t j = 0; j < parts.scattered.size(); ++j)
      parts.scattered[j] = (parts.scattered[j] - (open.scattered[j] - shaded.scattered[j])).max(0.0f);
    parts.phase_free = (parts.phase_free - (open.phase_free - shaded.phase_free)).max(0.0f);
    return true;
  }

  // The sky's radiance along dir (unit) without the sun's disk: interpolated from the sky-view
  // table where there is one for that direction (less the terrain's shadows, table_less_shadows),
  // marched otherwise (render_rows does the same for chunks of pixels).
  void sky_radiance(const Vec3& dir, ScatteringWorkspace& ws, Spectrum& out) const {
    Interval stretch;
    const bool touched = terrain_touches(dir, stretch);
    if (sky_view && !touched && sky_view->lookup(dir, ws.parts))
      integrator.combine(ws.parts, dir.dot(sun_dir), sun_irradiance, ws, out);
    else if (sky_view && touched && table_less_shadows(dir, stretch, ws, ws.parts))
      integrator.combine(ws.parts, dir.dot(sun_dir), sun_irradiance, ws, out);
    else
      integrator.radiance(camera->origin_m(), dir, sun_dir, sun_irradiance, sources, ws, out);
  }

  // Whether any pixel of the image looks below the geometric horizon (a fisheye of the sky does
  // not, so the sky-view table can leave out that side): from the camera's closed form where it
  // has one (a bound: at worst the table's ground side is built for nothing), else pixel by pixel.
  bool image_sees_below_horizon() const {
    const Vec3 up = camera->origin_m().normalized();
    const double r = camera->origin_m().norm(), R = atmosphere.planet_radius_m();
    const double below = -std::sqrt(std::max(0.0, (r - R) * (r + R))) / r;  // cos of the horizon's zenith angle
    if (const std::optional<double> lowest = camera->lowest_cosine_to(up)) return *lowest <= below + 1e-9;
    const int w = camera->width(), h = camera->height();
    tbb::task_arena arena(threads);
    return arena.execute([&] {
      return tbb::parallel_reduce(
          tbb::blocked_range<int>(0, h), false,
          [&](const tbb::blocked_range<int>& rows, bool seen) {
            Vec3 d;
            for (int y = rows.begin(); y != rows.end() && !seen; ++y)
              for (int x = 0; x < w && !seen; ++x)
                seen = camera->direction(x + 0.5, y + 0.5, d) && d.dot(up) <= below + 1e-9;
            return seen;
          },
          [](bool a, bool b) { return a || b; });
    });
  }

  explicit Impl(const Scene& s)
      : scene(s),
        grid(make_wavelength_grid(s)),
        atmosphere(s.atmosphere, grid, s.render.cache_tables),
        table(SunColumnTable::shared(atmosphere, sun_table_resolution(s), sun_band(s, atmosphere))),
        sun_columns(*table),
        integrator(atmosphere, sun_columns, IntegratorSettings{s.render.view_segments}),
        orders(s.render.scattering_orders >= 2 ? build_orders(s, integrator) : nullptr),
        terrain(scene_terrain(s)),
        sources{true, orders.get()},
        camera(make_camera(s)),
        sun_dir(skyspec::sun_direction(s)),
        sun_irradiance(scene_sun_irradiance(s, grid)),
        sun_radius_rad(skyspec::sun_angular_radius_rad(s.sun.distance_au)),
        rgb_fast(s.render.path == RenderSpec::Path::RgbFast),
        threads(thread_count(s)) {
    sources.terrain = terrain.get();
    if (orders && atmosphere.has_regional_media() && s.render.shower_passes > 0) {
      RegionalSecondOrder::Grid passes;
      passes.passes = s.render.shower_passes;
      regional =
          std::make_unique<RegionalSecondOrder>(integrator, sources, camera->origin_m(), sun_dir, passes, threads);
      sources.regional = regional.get();
    }
    if (s.render.sky_view_table && SkyViewTable::applicable(atmosphere, camera->origin_m())) {
      const int rows = s.render.sky_view_zenith_samples;
      const bool below = image_sees_below_horizon();
      const auto start = std::chrono::steady_clock::now();
      try {
        ScatteringSources table_sources = sources;
        table_sources.polarisation = s.output.polarisation;  // then it holds Q and U too
        table_sources.terrain = nullptr;  // directions the terrain touches: table_less_shadows or marched
        sky_view = sky_view_table_for(
            s, atmosphere, integrator, table_sources, camera->origin_m(), sun_dir,
            SkyViewResolution{rows, std::max(2, rows / 2), s.render.sky_view_azimuth_samples, below,
                              s.render.sky_view_higher_zenith_samples, s.render.sky_view_higher_azimuth_samples},
            threads);
      } catch (const Cancelled&) {
        throw;
      } catch (const Error&) {
        sky_view.reset();  // a geometry the table cannot resolve (rows that coincide): march every pixel
      }
      sky_view_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    if (rgb_fast) {
      rgb_index[0] = grid.index_of(680);
      rgb_index[1] = grid.index_of(550);
      rgb_index[2] = grid.index_of(440);
    } else {
      const SpectrumToXyz xyz(grid, constants::kMaxLuminousEfficacy_lm_per_W);
      const Eigen::MatrixXf m = (xyz_to_linear_rec709() * xyz.weights()).cast<float>();
      for (int c = 0; c < 3; ++c) to_rgb[c] = m.row(c).transpose().array();
    }
  }
};

SkyRenderer::SkyRenderer(const Scene& scene) {
  // The tables (sun columns, scattering orders, sky view) are built in parallel too: within
  // render.threads, like the image.
  const auto start = std::chrono::steady_clock::now();
  tbb::task_arena arena(thread_count(scene));
  arena.execute([&] { impl_ = std::make_unique<Impl>(scene); });
  impl_->build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
SkyRenderer::~SkyRenderer() = default;
const Scene& SkyRenderer::scene() const { return impl_->scene; }
const WavelengthGrid& SkyRenderer::grid() const { return impl_->grid; }
int SkyRenderer::width() const { return impl_->camera->width(); }
int SkyRenderer::height() const { return impl_->camera->height(); }
int SkyRenderer::threads() const { return impl_->threads; }

const Spectrum& SkyRenderer::sun_irradiance() const { return impl_->sun_irradiance; }
const Vec3& SkyRenderer::sun_direction() const { return impl_->sun_dir; }
const Vec3& SkyRenderer::camera_origin_m() const { return impl_->camera->origin_m(); }
double SkyRenderer::sun_angular_radius_rad() const { return impl_->sun_radius_rad; }
double SkyRenderer::sky_view_table_seconds() const { return impl_->sky_view_seconds; }
double SkyRenderer::build_seconds() const { return impl_->build_seconds; }

Spectrum SkyRenderer::transmittance(const Vec3& dir) const {
  const auto& m = *impl_;
  Spectrum t(m.grid.size());
  const Vec3 d = dir.normalized();
  if (m.terrain_hides(d))
    t.setZero();
  else
    m.integrator.transmittance_to_space(m.camera->origin_m(), d, t);
  return t;
}

Rgb SkyRenderer::spectrum_to_rgb(const Eigen::Ref<const Spectrum>& spectrum) const {
  const auto& m = *impl_;
  if (spectrum.size() != m.grid.size())
    throw Error("spectrum_to_rgb: " + std::to_string(spectrum.size()) + " values for a grid of " +
                std::to_string(m.grid.size()) + " wavelengths");
  Rgb rgb;
  for (int c = 0; c < 3; ++c) rgb[c] = m.rgb_fast ? spectrum[m.rgb_index[c]] : (m.to_rgb[c] * spectrum).sum();
  return rgb;
}

Spectrum SkyRenderer::radiance(const Vec3& dir) const {
  const auto& m = *impl_;
  const int n = m.grid.size();
  // Scratch kept per thread: callers (the exposure meter, tests) ask for many directions.
  thread_local std::optional<ScatteringWorkspace> ws;
  if (!ws || ws->view_tau.size() != n) ws.emplace(n);
  Spectrum out(n);
  m.sky_radiance(dir.normalized(), *ws, out);  // the sky as the image shows it
  return out;
}

Rgb SkyRenderer::radiance_rgb(const Vec3& dir) const { return spectrum_to_rgb(radiance(dir)); }

void SkyRenderer::stokes(const Vec3& dir, const Vec3& e1, Spectrum& i, Spectrum& q, Spectrum& u) const {
  const auto& m = *impl_;
  const int n = m.grid.size();
  thread_local std::optional<ScatteringWorkspace> ws;
  if (!ws || ws->view_tau.size() != n) ws.emplace(n);
  const Vec3 d = dir.normalized();
  // Integrated along the ray, not interpolated from the sky-view table (as the image's pixels are):
  // the probe of `skyspec reference --stokes --compare`.
  RadianceParts parts(n);
  ScatteringSources sources = m.sources;
  sources.polarisation = true;
  m.integrator.radiance_parts(m.camera->origin_m(), d, m.sun_dir, sources, *ws, parts);
  m.integrator.stokes(parts, d, m.sun_dir, e1.normalized(), m.sun_irradiance, *ws, i, q, u);
}

void SkyRenderer::aerial_rows(int y0, int rows, const float* distance_m, float* transmittance, float* inscatter) const {
  const auto& m = *impl_;
  const int w = m.camera->width(), n = m.grid.size();
  struct Scratch {
    ScatteringWorkspace ws;
    Spectrum radiance, trans;
    explicit Scratch(int k) : ws(k), radiance(k), trans(k) {}
  };
  tbb::enumerable_thread_specific<Scratch> scratch([n] { return Scratch(n); });
  tbb::task_arena arena(m.threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, rows * w, 64), [&](const tbb::blocked_range<int>& r) {
      Scratch& sc = scratch.local();
      for (int idx = r.begin(); idx != r.end(); ++idx) {
        const int row = idx / w, x = idx % w;
        float* t_px = transmittance + static_cast<size_t>(idx) * n;
        float* l_px = inscatter + static_cast<size_t>(idx) * n;
        Vec3 dir;
        if (!m.camera->direction(x + 0.5, y0 + row + 0.5, dir)) {
          std::fill(t_px, t_px + n, 1.0f);
          std::fill(l_px, l_px + n, 0.0f);
          continue;
        }
        ScatteringSources src = m.sources;
        src.max_distance_m = std::isfinite(distance_m[idx]) ? static_cast<double>(distance_m[idx])
                                                            : std::numeric_limits<double>::infinity();
        src.transmittance = &sc.trans;
        m.integrator.radiance(m.camera->origin_m(), dir, m.sun_dir, m.sun_irradiance, src, sc.ws, sc.radiance);
        std::copy(sc.trans.data(), sc.trans.data() + n, t_px);
        std::copy(sc.radiance.data(), sc.radiance.data() + n, l_px);
      }
    });
  });
}

Vec3 stokes_frame_axis_of_pixel(const Camera& camera, double x, double y, const Vec3& dir) {
  // Image x as a direction on the sky: the pixel's neighbours a quarter pixel either side (one side
  // at the edge of a fisheye's circle), made perpendicular to the pixel's ray.
  Vec3 right, left;
  const bool has_right = camera.direction(x + 0.25, y, right), has_left = camera.direction(x - 0.25, y, left);
  Vec3 t = has_right && has_left ? Vec3(right - left)
           : has_right           ? Vec3(right - dir)
           : has_left            ? Vec3(dir - left)
                                 : Vec3::Zero();
  t -= t.dot(dir) * dir;
  if (t.norm() > 1e-12) return t.normalized();
  // No image x at this point (not met by skyspec's cameras at pixel centres): any perpendicular.
  t = dir.cross(std::abs(dir.z()) < 0.9 ? Vec3(0, 0, 1) : Vec3(1, 0, 0));
  return t.normalized();
}

Vec3 SkyRenderer::stokes_frame_axis_of_pixel(double x, double y, const Vec3& dir) const {
  return skyspec::stokes_frame_axis_of_pixel(*impl_->camera, x, y, dir);
}

void SkyRenderer::render_window_stokes(int x0, int x1, int y0, int rows, float* stokes, float* rgb) const {
  const auto& m = *impl_;
  if (!m.scene.output.polarisation)
    throw Error("render_window_stokes: the scene does not ask for polarisation (output.polarisation = false)");
  if (!(0 <= x0 && x0 < x1 && x1 <= width() && 0 <= y0 && rows > 0 && y0 + rows <= height()))
    throw Error("render_window_stokes: columns " + std::to_string(x0) + ".." + std::to_string(x1) + ", rows " +
                std::to_string(y0) + ".." + std::to_string(y0 + rows) + " are not inside the " +
                std::to_string(width()) + " x " + std::to_string(height()) + " image");
  const int w = x1 - x0, n = m.grid.size();
  const size_t stride = 4 * static_cast<size_t>(n);
  // Each pixel's parts from the sky-view table (built with Q and U for a polarised scene) where it
  // covers the direction, else integrated along its ray with the polarised sources; then its
  // Stokes vector in its own frame.
  struct Scratch {
    ScatteringWorkspace ws;
    RadianceParts parts;
    Spectrum i, q, u, disk, trans;
    explicit Scratch(int k) : ws(k), parts(k), i(k), q(k), u(k), disk(k), trans(k) {}
  };
  tbb::enumerable_thread_specific<Scratch> scratch([n] { return Scratch(n); });
  std::atomic<bool> non_finite{false};
  ScatteringSources sources = m.sources;
  sources.polarisation = true;
  tbb::task_arena arena(m.threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, rows * w, 16), [&](const tbb::blocked_range<int>& r) {
      Scratch& sc = scratch.local();
      throw_if_cancelled();
      for (int idx = r.begin(); idx != r.end(); ++idx) {
        const int x = x0 + idx % w, y = y0 + idx / w;
        float* px = stokes + static_cast<size_t>(idx) * stride;
        Vec3 dir;
        if (!m.camera->direction(x + 0.5, y + 0.5, dir)) {
          std::fill(px, px + stride, 0.0f);
        } else {
          const Vec3 e1 = stokes_frame_axis_of_pixel(x + 0.5, y + 0.5, dir);
          if (!(m.sky_view && m.table_serves(dir) && m.sky_view->lookup_polarised(dir, sc.parts)))
            m.integrator.radiance_parts(m.camera->origin_m(), dir, m.sun_dir, sources, sc.ws, sc.parts);
          m.integrator.stokes(sc.parts, dir, m.sun_dir, e1, m.sun_irradiance, sc.ws, sc.i, sc.q, sc.u);
          std::copy(sc.i.data(), sc.i.data() + n, px);
          std::copy(sc.q.data(), sc.q.data() + n, px + n);
          std::copy(sc.u.data(), sc.u.data() + n, px + 2 * n);
          std::fill(px + 3 * n, px + 4 * n, 0.0f);  // V: zero for these scattering matrices
          if (m.scene.sun.disk) m.add_sun_disk(x, y, dir, nullptr, px, sc.disk, sc.trans);  // unpolarised
        }
        const Rgb c = spectrum_to_rgb(Eigen::Map<const Spectrum>(px, n));
        std::copy(c.data(), c.data() + 3, rgb + static_cast<size_t>(idx) * 3);
        if (!c.allFinite() || !Eigen::Map<const Eigen::ArrayXf>(px, static_cast<Eigen::Index>(stride)).allFinite())
          non_finite.store(true, std::memory_order_relaxed);
      }
    });
  });
  if (non_finite.load())
    throw Error("internal error: a non-finite Stokes or RGB value was computed; no file was written");
}

void SkyRenderer::render_rows(int y0, int rows, float* spectral, float* rgb) const {
  render_window(0, width(), y0, rows, spectral, rgb);
}

void SkyRenderer::render_window(int x0, int x1, int y0, int rows, float* spectral, float* rgb) const {
  const auto& m = *impl_;
  if (!(0 <= x0 && x0 < x1 && x1 <= width() && 0 <= y0 && rows > 0 && y0 + rows <= height()))
    throw Error("render_window: columns " + std::to_string(x0) + ".." + std::to_string(x1) + ", rows " +
                std::to_string(y0) + ".." + std::to_string(y0 + rows) + " are not inside the " +
                std::to_string(width()) + " x " + std::to_string(height()) + " image");
  const int w = x1 - x0, n = m.grid.size();  // w: the window's width; idx counts its pixels
  // Pixels go through in chunks: a chunk's directions are looked up in the sky-view table
  // together (SkyViewTable::lookup_many computes their angles in one vectorised loop); what the
  // table does not cover is marched, as sky_radiance() does for one direction.
  constexpr int kChunk = 64;
  struct Scratch {
    ScatteringWorkspace ws;
    Spectrum radiance, disk, trans;
    Vec3 dirs[kChunk];
    int pixel[kChunk];  // the chunk's pixels that have a direction
    bool found[kChunk];
    bool touched[kChunk] = {};  // the terrain or its shadow touches it (terrain_touches) ...
    Interval stretch[kChunk];   // ... there
    double mu[kChunk];          // their cosines to the sun
    float* out[kChunk];         // where their radiances go
    std::vector<float> parts;   // their sky-view parts, SkyViewTable::parts() x n floats each
    Scratch(int k, int parts_per_direction)
        : ws(k), radiance(k), disk(k), trans(k), parts(static_cast<size_t>(parts_per_direction * kChunk * k)) {}
  };
  const int parts_per_direction = m.sky_view ? m.sky_view->parts() : 0;
  tbb::enumerable_thread_specific<Scratch> scratch(
      [n, parts_per_direction] { return Scratch(n, parts_per_direction); });
  std::atomic<bool> non_finite{false};
  tbb::task_arena arena(m.threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, rows * w, kChunk), [&](const tbb::blocked_range<int>& r) {
      Scratch& sc = scratch.local();
      for (int c0 = r.begin(); c0 < r.end(); c0 += kChunk) {
        throw_if_cancelled();  // every 64 pixels: a request stops the image within a second
        const int c1 = std::min(r.end(), c0 + kChunk);
        int count = 0;
        for (int idx = c0; idx < c1; ++idx) {
          const int row = idx / w, x = x0 + idx % w;
          if (m.camera->direction(x + 0.5, y0 + row + 0.5, sc.dirs[count]))
            sc.pixel[count++] = idx;
          else
            std::fill(spectral + static_cast<size_t>(idx) * n, spectral + static_cast<size_t>(idx + 1) * n, 0.0f);
        }
        if (m.sky_view) {
          m.sky_view->lookup_many(count, sc.dirs, sc.parts.data(), sc.found);
          for (int k = 0; k < count; ++k) {
            sc.touched[k] = sc.found[k] && m.terrain_touches(sc.dirs[k], sc.stretch[k]);
            sc.found[k] = sc.found[k] && !sc.touched[k];  // those are done one by one below
          }
          for (int k = 0; k < count; ++k) {
            sc.mu[k] = sc.dirs[k].dot(m.sun_dir);
            sc.out[k] = spectral + static_cast<size_t>(sc.pixel[k]) * n;
          }
          m.integrator.combine_many(count, sc.parts.data(), sc.mu, sc.found, m.sun_irradiance, sc.out, sc.ws);
        }
        for (int k = 0; k < count; ++k) {
          const Vec3& dir = sc.dirs[k];
          const int idx = sc.pixel[k];
          float* px = spectral + static_cast<size_t>(idx) * n;
          if (!(m.sky_view && sc.found[k])) {
            if (m.sky_view && sc.touched[k] && m.table_less_shadows(dir, sc.stretch[k], sc.ws, sc.ws.parts))
              m.integrator.combine(sc.ws.parts, dir.dot(m.sun_dir), m.sun_irradiance, sc.ws, sc.radiance);
            else
              m.integrator.radiance(m.camera->origin_m(), dir, m.sun_dir, m.sun_irradiance, m.sources, sc.ws,
                                    sc.radiance);
            std::copy(sc.radiance.data(), sc.radiance.data() + n, px);
          }
          if (m.scene.sun.disk) {
            // The next pixel of the chunk is the one to the right unless this one ends its row.
            const bool right = k + 1 < count && sc.pixel[k + 1] == idx + 1 && (idx + 1) % w != 0;
            m.add_sun_disk(x0 + idx % w, y0 + idx / w, dir, right ? &sc.dirs[k + 1] : nullptr, px, sc.disk, sc.trans);
          }
        }
        for (int idx = c0; idx < c1; ++idx) {
          const float* px = spectral + static_cast<size_t>(idx) * n;
          float* px_rgb = rgb + static_cast<size_t>(idx) * 3;
          const Rgb c = spectrum_to_rgb(Eigen::Map<const Spectrum>(px, n));
          std::copy(c.data(), c.data() + 3, px_rgb);
          // Checked here, while the pixel is in cache, rather than in a pass over the band.
          if (!std::isfinite(px_rgb[0]) || !std::isfinite(px_rgb[1]) || !std::isfinite(px_rgb[2]) ||
              !Eigen::Map<const Spectrum>(px, n).allFinite())
            non_finite.store(true, std::memory_order_relaxed);
        }
      }
    });
  });
  if (non_finite.load())
    throw Error("internal error: a non-finite radiance or RGB value was computed; no file was written");
}

}  // namespace skyspec
