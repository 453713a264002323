#include "transport/sky_view_table.hpp"

#include <algorithm>
#include <cmath>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "base/cancellation.hpp"
#include "base/fast_atan2.hpp"
#include "skyspec/atmosphere.hpp"
#include "skyspec/error.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

namespace {
// Rays are never cast exactly along the horizon, where a ray grazes the ground and which side of
// it the ray falls on is decided by rounding: the row at the horizon is cast this far from it.
constexpr double kHorizonOffsetRad = 1e-6;

// The first step of a look-up's mix: the rows around it (n_rows of them, from rows_at, a row of
// `azimuths` entries apart) weighted by row_w, for the two columns c0 and c0 + 1 at once (their
// entries are contiguous, as are the parts of an entry: one loop over the 2 x entry floats of a
// row), into acc. kEntry > 0: the entry's floats known at compile time, so that the loops unroll.
template <int kEntry>
void mix_rows(const float* rows_at, int azimuths, const double* row_w, int n_rows, size_t entry_run,
              float* __restrict acc) {
  const size_t entry = kEntry > 0 ? static_cast<size_t>(kEntry) : entry_run;
  const size_t stride = static_cast<size_t>(azimuths) * entry;
  if (n_rows == 4) {  // one pass over the four rows
    const float v0 = static_cast<float>(row_w[0]), v1 = static_cast<float>(row_w[1]);
    const float v2 = static_cast<float>(row_w[2]), v3 = static_cast<float>(row_w[3]);
    const float* __restrict e0 = rows_at;
    const float* __restrict e1 = e0 + stride;
    const float* __restrict e2 = e1 + stride;
    const float* __restrict e3 = e2 + stride;
    for (size_t k = 0; k < 2 * entry; ++k) acc[k] = v0 * e0[k] + v1 * e1[k] + v2 * e2[k] + v3 * e3[k];
  } else {
    const float v = static_cast<float>(row_w[0]);
    for (size_t k = 0; k < 2 * entry; ++k) acc[k] = v * rows_at[k];
    for (int i = 1; i < n_rows; ++i) {
      const float vi = static_cast<float>(row_w[i]);
      const float* __restrict e = rows_at + static_cast<size_t>(i) * stride;
      for (size_t k = 0; k < 2 * entry; ++k) acc[k] += vi * e[k];
    }
  }
}

// The second step: the two columns of acc weighted by w0 and w1 into parts[0 .. n_parts - 1], n
// wavelengths each (kN > 0: n known at compile time). n_parts per entry: the radiance's (one per
// scattering medium and the phase-free part; clamped at 0: a cubic may undershoot where a part
// falls steeply to 0, the planet's shadow, and light is not negative), or the polarised two (Q,
// U: signed, not clamped).
template <int kN>
void mix_columns(const float* __restrict acc, float w0, float w1, int n_run, int n_parts, bool clamp,
                 float* const* parts) {
  const int n = kN > 0 ? kN : n_run;
  const size_t entry = static_cast<size_t>(n_parts) * static_cast<size_t>(n);
  for (int p = 0; p < n_parts; ++p) {
    const float* __restrict a = acc + static_cast<size_t>(p) * n;
    const float* __restrict b = a + entry;
    float* __restrict o = parts[p];
    if (clamp)
      for (int l = 0; l < n; ++l) o[l] = std::max(0.0f, w0 * a[l] + w1 * b[l]);
    else
      for (int l = 0; l < n; ++l) o[l] = w0 * a[l] + w1 * b[l];
  }
}

// Room for a look-up's rows mixed (2 entries): on the stack for up to 42 wavelengths (2 x 3 x 42
// floats), per thread beyond (one buffer per thread: at most one MixBuffer alive per thread, as
// mix_entries and lookup_many use them).
class MixBuffer {
 public:
  explicit MixBuffer(size_t entry) {
    thread_local std::vector<float> heap;
    if (2 * entry > kStackFloats) heap.resize(2 * entry);
    data_ = 2 * entry > kStackFloats ? heap.data() : stack_;
  }
  float* data() { return data_; }

 private:
  static constexpr size_t kStackFloats = 256;
  alignas(32) float stack_[kStackFloats];
  float* data_;
};

// Both steps. kN > 0: the wavelength count known at compile time (the RGB-fast path's 3).
template <int kN>
void mix_entries(const float* rows_at, int azimuths, const double* row_w, int n_rows, float w0, float w1, int n_run,
                 int n_parts, bool clamp, float* const* parts) {
  const int n = kN > 0 ? kN : n_run;
  const size_t entry = static_cast<size_t>(n_parts) * static_cast<size_t>(n);
  MixBuffer acc(entry);
  if (kN > 0 && n_parts == 3)
    mix_rows<3 * kN>(rows_at, azimuths, row_w, n_rows, entry, acc.data());
  else
    mix_rows<0>(rows_at, azimuths, row_w, n_rows, entry, acc.data());
  mix_columns<kN>(acc.data(), w0, w1, n, n_parts, clamp, parts);
}
constexpr int kPolarisedParts = 2;

}  // namespace

bool SkyViewTable::applicable(const AtmosphereModel& atm, const Vec3& origin_m) {
  const double r = origin_m.norm();
  return r >= atm.planet_radius_m() && r < atm.top_radius_m() && !atm.has_regional_media();
}

// Placement of the rows. Sky side: by the square root of the angle above the horizon, so they
// crowd where the sky brightens towards the horizon. Ground side: by the mean of two coordinates,
// the angle below the horizon and the distance to the ground (Bruneton and Neyret's
// parameterisation, from the horizon at distance rho = sqrt(r^2 - R^2) to the nadir at r - R):
// the air in front of the ground adds light in proportion to that distance, and as a function of
// angle the distance falls by orders of magnitude just below the horizon of a camera near the
// ground; the angle keeps the rows from thinning out towards the nadir.
[[gnu::always_inline]] inline double SkyViewTable::placement_of(bool sky_side, double theta) const {
  const double th = horizon_zenith_rad_;
  if (sky_side) return std::sqrt(std::clamp((th - theta) / th, 0.0, 1.0));
  const double angle = std::clamp((theta - th) / (kPi - th), 0.0, 1.0);
  if (rho_m_ <= 0.0) return angle;
  return 0.5 * (angle + (rho_m_ - ground_distance(theta)) / (rho_m_ - (r_m_ - R_m_)));
}

// Interpolation variable between rows: the placement coordinate on the sky side; the distance to
// the ground on the ground side (in which the light of the air in front of it is nearly linear).
double SkyViewTable::key_of(bool sky_side, double theta) const {
  if (sky_side || rho_m_ <= 0.0) return placement_of(sky_side, theta);
  return ground_distance(theta);
}

// Distance along a ray of zenith angle theta (below the horizon) to the ground: the nearer root of
// d^2 + 2 r mu d + r^2 - R^2 = 0, as (r^2 - R^2) / (far root), without cancellation.
double SkyViewTable::ground_distance(double theta) const {
  const double mu = std::cos(theta);
  const double disc = std::max(0.0, r_m_ * r_m_ * mu * mu - rho_m_ * rho_m_);
  const double far = -r_m_ * mu + std::sqrt(disc);
  return far > 0.0 ? std::min(rho_m_, rho_m_ * rho_m_ / far) : rho_m_;
}

// The zenith angle of placement coordinate u in [0, 1] (by bisection: placement_of is
// increasing away from the horizon).
double SkyViewTable::zenith_of(bool sky_side, double u) const {
  const double th = horizon_zenith_rad_;
  double lo = 0.0, hi = 1.0;  // fraction of the way from the horizon to the pole
  for (int i = 0; i < 64; ++i) {
    const double mid = 0.5 * (lo + hi);
    const double theta = sky_side ? th * (1.0 - mid) : th + mid * (kPi - th);
    (placement_of(sky_side, theta) < u ? lo : hi) = mid;
  }
  const double f = 0.5 * (lo + hi);
  return sky_side ? th * (1.0 - f) : th + f * (kPi - th);
}

// The first row of each side is cast just off the horizon, where a ray grazes the ground and
// rounding would decide which side it falls on: above it, by at most 1e-6 rad and a hundredth
// of the way to the next row; below it, where the distance to the ground is 1 - 1e-6 of the
// horizon's (so that its key differs from the next row's however the distance falls with angle).
double SkyViewTable::first_row_zenith(bool sky_side, int rows) const {
  const double th = horizon_zenith_rad_;
  if (sky_side) {
    const double spacing = th / ((rows - 1.0) * (rows - 1.0));  // to the next row (placement 1/(rows-1))
    return th - std::min(kHorizonOffsetRad, 0.01 * spacing);
  }
  if (rho_m_ <= 0.0) return th + std::min(kHorizonOffsetRad, 0.01 * (kPi - th) / ((rows - 1.0) * (rows - 1.0)));
  const double d = rho_m_ * (1.0 - 1e-6);
  return std::acos(std::clamp(-(rho_m_ * rho_m_ + d * d) / (2.0 * r_m_ * d), -1.0, 1.0));
}

Vec3 SkyViewTable::direction(bool sky_side, int row, int column) const {
  const double theta = (sky_side ? sky_theta_ : ground_theta_)[static_cast<size_t>(row)];
  const double phi = kPi * column / (res_.azimuths - 1);
  return std::sin(theta) * (std::cos(phi) * toward_sun_ + std::sin(phi) * across_) + std::cos(theta) * up_;
}

Vec3 SkyViewTable::own_frame_sun(const Vec3& origin_m, const Vec3& sun_dir) {
  const double cos_zenith = std::clamp(sun_dir.dot(origin_m.normalized()), -1.0, 1.0);
  return Vec3(std::sqrt((1.0 - cos_zenith) * (1.0 + cos_zenith)), 0.0, cos_zenith);
}

void SkyViewTable::set_frame(const Vec3& origin_m, const Vec3& sun_dir) {
  up_ = origin_m.normalized();
  // The sun's azimuth; for a sun at the zenith (or nadir) every azimuth is the same.
  Vec3 horizontal = sun_dir - sun_dir.dot(up_) * up_;
  if (horizontal.norm() < 1e-12) horizontal = up_.unitOrthogonal();
  toward_sun_ = horizontal.normalized();
  across_ = up_.cross(toward_sun_);
}

size_t SkyViewTable::bytes() const {
  return sizeof(float) * (entries_->sky.size() + entries_->ground.size() + entries_->polarised_sky.size() +
                          entries_->polarised_ground.size());
}

SkyViewTable SkyViewTable::reoriented(const Vec3& origin_m, const Vec3& sun_dir) const {
  if (origin_m.norm() != r_m_ || own_frame_sun(origin_m, sun_dir) != own_sun_)
    throw Error("sky-view table: reoriented for another camera radius or sun zenith angle than it was marched for");
  SkyViewTable t = *this;
  t.set_frame(origin_m, sun_dir);
  return t;
}

SkyViewTable::SkyViewTable(const SingleScattering& integrator, const ScatteringSources& sources, const Vec3& origin_m,
                           const Vec3& sun_dir, SkyViewResolution resolution, int threads)
    : res_(resolution), n_(integrator.atmosphere().grid().size()) {
  const AtmosphereModel& atm = integrator.atmosphere();
  if (!applicable(atm, origin_m))
    throw Error(atm.has_regional_media() ? "sky-view table: a medium is confined to a region"
                                         : "sky-view table: the camera is not inside the atmosphere");
  if (res_.sky_rows < 2 || res_.ground_rows < 2 || res_.azimuths < 2)
    throw Error("sky-view table: at least 2 rows and 2 azimuths on each side");
  // The rays are marched in the table's own frame (the camera on the z axis, the sun in the x-z
  // plane); look-ups use the camera's (set_frame, at the end).
  own_sun_ = own_frame_sun(origin_m, sun_dir);
  const Vec3 own_origin(0.0, 0.0, origin_m.norm());
  set_frame(own_origin, own_sun_);
  // The geometric horizon: sin of its depression below the horizontal is sqrt(r^2 - R^2) / r,
  // written without the cancellation of 1 - (R/r)^2 for a camera near the ground.
  r_m_ = origin_m.norm();
  R_m_ = atm.planet_radius_m();
  rho_m_ = std::sqrt((r_m_ - R_m_) * (r_m_ + R_m_));
  horizon_zenith_rad_ = 0.5 * kPi + std::asin(rho_m_ / r_m_);
  for (bool sky_side : {true, false}) {
    const int rows = sky_side ? res_.sky_rows : res_.ground_rows;
    std::vector<double>& theta = sky_side ? sky_theta_ : ground_theta_;
    std::vector<double>& key = sky_side ? sky_key_ : ground_key_;
    for (int i = 0; i < rows; ++i) {
      theta.push_back(i == 0 ? first_row_zenith(sky_side, rows)
                             : zenith_of(sky_side, static_cast<double>(i) / (rows - 1)));
      key.push_back(key_of(sky_side, theta.back()));
      if (i > 0 && key[static_cast<size_t>(i)] == key[static_cast<size_t>(i - 1)])
        throw Error("sky-view table: rows " + std::to_string(i - 1) + " and " + std::to_string(i) +
                    " coincide (too many rows for this geometry)");
    }
  }

  // 1 / prod_{j != i} (x_i - x_j) for the Lagrange weights of the rows lookup() takes around each
  // row pair (r0, r0 + 1): r0 - 1 .. r0 + 2, fewer at the table's ends.
  for (bool sky_side : {true, false}) {
    const std::vector<double>& key = sky_side ? sky_key_ : ground_key_;
    std::vector<double>& inv = sky_side ? sky_inv_den_ : ground_inv_den_;
    const int rows = static_cast<int>(key.size());
    inv.assign(4 * key.size(), 0.0);
    for (int r0 = 0; r0 + 1 < rows; ++r0) {
      const int first = std::max(0, r0 - 1), count = std::min(rows - 1, r0 + 2) - first + 1;
      for (int i = 0; i < count; ++i) {
        double den = 1.0;
        for (int j = 0; j < count; ++j)
          if (j != i) den *= key[static_cast<size_t>(first + i)] - key[static_cast<size_t>(first + j)];
        inv[4 * static_cast<size_t>(r0) + i] = 1.0 / den;
      }
    }
  }

  parts_ = integrator.scatterer_count() + 1;
  const size_t stride = static_cast<size_t>(res_.azimuths) * parts_ * static_cast<size_t>(n_);
  entries_->sky = ZeroedFloats(static_cast<size_t>(res_.sky_rows) * stride);
  if (res_.ground_side) entries_->ground = ZeroedFloats(static_cast<size_t>(res_.ground_rows) * stride);
  polarised_ = sources.polarisation;
  const size_t polarised_stride = static_cast<size_t>(res_.azimuths) * kPolarisedParts * static_cast<size_t>(n_);
  if (polarised_) {
    entries_->polarised_sky = ZeroedFloats(static_cast<size_t>(res_.sky_rows) * polarised_stride);
    if (res_.ground_side)
      entries_->polarised_ground = ZeroedFloats(static_cast<size_t>(res_.ground_rows) * polarised_stride);
  }
  ScatteringSources src = sources;
  src.transmittance = nullptr;
  src.max_distance_m = std::numeric_limits<double>::infinity();
  src.terrain = nullptr;  // it would break the symmetry the own frame relies on (renders march its pixels)
  // The higher orders on a coarser table: this one's rays marched without their light, which is
  // added afterwards from a coarse table of it alone (its rays marched without the light scattered
  // once: ScatteringSources::single; the same nodes, which the higher-order source places).
  const bool coarse_higher = src.higher && src.higher_light && res_.higher_sky_rows > 0 && res_.higher_azimuths > 0 &&
                             (res_.higher_sky_rows < res_.sky_rows || res_.higher_azimuths < res_.azimuths);
  std::unique_ptr<SkyViewTable> higher_only;
  if (coarse_higher) {
    SkyViewResolution coarse = res_;
    coarse.sky_rows = std::min(res_.higher_sky_rows, res_.sky_rows);
    coarse.ground_rows = std::max(2, coarse.sky_rows / 2);
    coarse.azimuths = std::min(res_.higher_azimuths, res_.azimuths);
    coarse.higher_sky_rows = coarse.higher_azimuths = 0;
    ScatteringSources higher = src;
    higher.single = false;
    higher_only = std::make_unique<SkyViewTable>(integrator, higher, own_origin, own_sun_, coarse, threads);
    src.higher_light = false;
  }
  // A row at a time: its rays share their zenith angle, so the integrator computes their nodes
  // once (SingleScattering::radiance_parts_same_zenith).
  struct RowScratch {
    ScatteringWorkspace ws;
    std::vector<Vec3> dirs;
    std::vector<RadianceParts> parts;
    RowScratch(int wavelengths, int azimuths, int scatterers)
        : ws(wavelengths),
          dirs(static_cast<size_t>(azimuths)),
          parts(static_cast<size_t>(azimuths), RadianceParts(wavelengths, scatterers)) {}
  };
  const int n = n_, m = res_.azimuths, scatterers = parts_ - 1;
  tbb::enumerable_thread_specific<RowScratch> scratch([n, m, scatterers] { return RowScratch(n, m, scatterers); });
  const int total_rows = res_.sky_rows + (res_.ground_side ? res_.ground_rows : 0);
  tbb::task_arena arena(std::max(1, threads));
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, total_rows, 1), [&](const tbb::blocked_range<int>& range) {
      RowScratch& sc = scratch.local();
      for (int row_all = range.begin(); row_all != range.end(); ++row_all) {
        throw_if_cancelled();  // a row of the table: a request stops it within a second
        const bool sky_side = row_all < res_.sky_rows;
        const int row = sky_side ? row_all : row_all - res_.sky_rows;
        for (int column = 0; column < m; ++column)
          sc.dirs[static_cast<size_t>(column)] = direction(sky_side, row, column);
        integrator.radiance_parts_same_zenith(own_origin, sc.dirs.data(), m, own_sun_, src, sc.ws, sc.parts.data());
        for (int column = 0; column < m; ++column) {
          const RadianceParts& p = sc.parts[static_cast<size_t>(column)];
          float* entry = (sky_side ? entries_->sky : entries_->ground).data() + row * stride +
                         static_cast<size_t>(column) * parts_ * static_cast<size_t>(n);
          for (int s = 0; s < scatterers; ++s)
            std::copy(p.scattered[static_cast<size_t>(s)].data(), p.scattered[static_cast<size_t>(s)].data() + n,
                      entry + static_cast<size_t>(s) * n);
          std::copy(p.phase_free.data(), p.phase_free.data() + n, entry + static_cast<size_t>(scatterers) * n);
          if (polarised_) {  // Q and U of the higher orders in the ray's polarisation_frame
            float* q = (sky_side ? entries_->polarised_sky : entries_->polarised_ground).data() +
                       row * polarised_stride + static_cast<size_t>(column) * kPolarisedParts * static_cast<size_t>(n);
            std::copy(p.polarised_q.data(), p.polarised_q.data() + n, q);
            std::copy(p.polarised_u.data(), p.polarised_u.data() + n, q + n);
          }
        }
      }
    });
  });
  if (coarse_higher) add_coarse_higher_orders(*higher_only, threads);
  set_frame(origin_m, sun_dir);
}

// Each entry's phase-free part gains the higher orders' light of the coarse table (interpolated at
// its direction as a look-up would), and its polarisation is theirs.
void SkyViewTable::add_coarse_higher_orders(const SkyViewTable& higher, int threads) {
  const int n = n_, m = res_.azimuths, scatterers = parts_ - 1;
  const size_t stride = static_cast<size_t>(m) * parts_ * static_cast<size_t>(n);
  const size_t polarised_stride = static_cast<size_t>(m) * kPolarisedParts * static_cast<size_t>(n);
  const int total_rows = res_.sky_rows + (res_.ground_side ? res_.ground_rows : 0);
  tbb::task_arena arena(std::max(1, threads));
  arena.execute([&] {
    tbb::parallel_for(0, total_rows, [&](int row_all) {
      const bool sky_side = row_all < res_.sky_rows;
      const int row = sky_side ? row_all : row_all - res_.sky_rows;
      RadianceParts a(n, scatterers);
      for (int column = 0; column < m; ++column) {
        const Vec3 d = direction(sky_side, row, column);
        if (!higher.lookup(d, a)) continue;
        float* entry = (sky_side ? entries_->sky : entries_->ground).data() + row * stride +
                       static_cast<size_t>(column) * parts_ * static_cast<size_t>(n) +
                       static_cast<size_t>(scatterers) * n;
        for (int l = 0; l < n; ++l) entry[l] += a.phase_free[l];
        if (polarised_ && higher.lookup_polarised(d, a)) {
          float* q = (sky_side ? entries_->polarised_sky : entries_->polarised_ground).data() + row * polarised_stride +
                     static_cast<size_t>(column) * kPolarisedParts * static_cast<size_t>(n);
          std::copy(a.polarised_q.data(), a.polarised_q.data() + n, q);
          std::copy(a.polarised_u.data(), a.polarised_u.data() + n, q + n);
        }
      }
    });
  });
}

// Angles by a polynomial atan2 good to 1e-9 rad (fast_atan2.hpp), cheaper than libm's correctly
// rounded one on this per-pixel path. Within 1e-6 rad of the horizon libm's is used (refined_zenith): there
// the distance to the ground, the ground side's interpolation variable, changes by orders of
// magnitude over angles of that size.
inline void SkyViewTable::angles_of(const Vec3& dir, double& theta, double& phi) const {
  // Dot products written out (Eigen's use SSE intrinsics, which keep a loop over directions from
  // vectorising).
  const double d0 = dir[0], d1 = dir[1], d2 = dir[2];
  const double x = d0 * toward_sun_[0] + d1 * toward_sun_[1] + d2 * toward_sun_[2];
  const double y = std::abs(d0 * across_[0] + d1 * across_[1] + d2 * across_[2]);
  const double z = d0 * up_[0] + d1 * up_[1] + d2 * up_[2];
  theta = detail::fast_atan2(std::sqrt(x * x + y * y), z);
  phi = detail::fast_atan2(y, x);  // in [0, pi]
}

inline double SkyViewTable::refined_zenith(const Vec3& dir, double theta) const {
  if (!(std::abs(theta - horizon_zenith_rad_) < 1e-6)) return theta;
  const double x = dir.dot(toward_sun_), y = dir.dot(across_), z = dir.dot(up_);
  return std::atan2(std::sqrt(x * x + y * y), z);
}

bool SkyViewTable::lookup(const Vec3& dir, RadianceParts& out) const {
  double theta, phi;
  angles_of(dir, theta, phi);
  theta = refined_zenith(dir, theta);
  Weights w;
  if (!weights(theta, phi, w)) return false;
  mix(w, out);
  return true;
}

void SkyViewTable::lookup_many(int count, const Vec3* dirs, float* out, bool* found) const {
  constexpr int kChunk = 64;
  double theta[kChunk], phi[kChunk];
  const size_t entry = static_cast<size_t>(parts_) * static_cast<size_t>(n_);
  float* parts[kMaxMedia + 1];
  // Successive directions between the same rows with the same row weights (a panorama's row of
  // pixels, a level camera's) share the rows' mix: only the columns' weights differ.
  MixBuffer acc(entry);
  Weights mixed;  // whose rows acc holds
  bool have = false;
  const bool rgb = n_ == 3 && parts_ == 3;
  for (int first = 0; first < count; first += kChunk) {
    const int m = std::min(kChunk, count - first);
    for (int k = 0; k < m; ++k) angles_of(dirs[first + k], theta[k], phi[k]);  // vectorised
    for (int k = 0; k < m; ++k) {
      float* o = out + static_cast<size_t>(first + k) * entry;
      for (int p = 0; p < parts_; ++p) parts[p] = o + static_cast<size_t>(p) * n_;
      Weights w;
      found[first + k] = weights(refined_zenith(dirs[first + k], theta[k]), phi[k], w);
      if (!found[first + k]) continue;
      if (!have || !same_rows(w, mixed)) {
        const float* at = first_entry(w);
        if (rgb)
          mix_rows<9>(at, res_.azimuths, w.row_w, w.n_rows, entry, acc.data());
        else
          mix_rows<0>(at, res_.azimuths, w.row_w, w.n_rows, entry, acc.data());
        mixed = w;
        have = true;
      }
      if (n_ == 3)  // as mix() does
        mix_columns<3>(acc.data(), w.w0, w.w1, n_, parts_, true, parts);
      else
        mix_columns<0>(acc.data(), w.w0, w.w1, n_, parts_, true, parts);
    }
  }
}

bool SkyViewTable::same_rows(const Weights& a, const Weights& b) {
  if (a.sky_side != b.sky_side || a.first_row != b.first_row || a.n_rows != b.n_rows || a.c0 != b.c0) return false;
  for (int i = 0; i < a.n_rows; ++i)
    if (a.row_w[i] != b.row_w[i]) return false;
  return true;
}

const float* SkyViewTable::first_entry(const Weights& w) const {
  return (w.sky_side ? entries_->sky : entries_->ground).data() +
         static_cast<size_t>(w.first_row) * static_cast<size_t>(res_.azimuths) * parts_ * static_cast<size_t>(n_) +
         static_cast<size_t>(w.c0) * parts_ * static_cast<size_t>(n_);
}

bool SkyViewTable::weights(double theta, double phi, Weights& w) const {
  const bool sky_side = theta < horizon_zenith_rad_;
  if (!sky_side && !res_.ground_side) return false;
  w.sky_side = sky_side;

  // The row pair around theta (placement_of says where to look; rounding is corrected by
  // comparing with the rows' own angles), weighted linearly in the interpolation variable.
  const std::vector<double>& row_theta = sky_side ? sky_theta_ : ground_theta_;
  const std::vector<double>& row_key = sky_side ? sky_key_ : ground_key_;
  const int rows = static_cast<int>(row_theta.size());
  const double away = sky_side ? -1.0 : 1.0;  // rows run away from the horizon
  const double placement = placement_of(sky_side, theta);
  int r0 = std::clamp(static_cast<int>(placement * (rows - 1)), 0, rows - 2);
  while (r0 > 0 && away * (theta - row_theta[static_cast<size_t>(r0)]) < 0.0) --r0;
  while (r0 < rows - 2 && away * (theta - row_theta[static_cast<size_t>(r0 + 1)]) > 0.0) ++r0;
  // Rows r0 - 1 .. r0 + 2 (three at the table's ends), weighted by Lagrange's cubic (or quadratic)
  // in the interpolation variable; columns c0 and c0 + 1 linearly in azimuth, in which the parts
  // change slowly (a cubic there halves the error at twice the cost: not worth it).
  const int first_row = std::max(0, r0 - 1), last_row = std::min(rows - 1, r0 + 2);
  const int n_rows = last_row - first_row + 1;
  const double key = (sky_side || rho_m_ <= 0.0) ? placement : key_of(sky_side, theta);
  const double* xs = row_key.data() + first_row;
  // Lagrange weights: products of (key - x_j) over j != i, times 1 / prod (x_i - x_j), which
  // depends only on the rows and is kept per row pair (sky_inv_den_, ground_inv_den_).
  const double* inv_den = (sky_side ? sky_inv_den_ : ground_inv_den_).data() + 4 * static_cast<size_t>(r0);
  double* row_w = w.row_w;
  w.first_row = first_row;
  w.n_rows = n_rows;
  if (n_rows == 4) {  // the common case, written out (the same products as the loop below)
    const double d0 = key - xs[0], d1 = key - xs[1], d2 = key - xs[2], d3 = key - xs[3];
    row_w[0] = d1 * d2 * d3 * inv_den[0];
    row_w[1] = d0 * d2 * d3 * inv_den[1];
    row_w[2] = d0 * d1 * d3 * inv_den[2];
    row_w[3] = d0 * d1 * d2 * inv_den[3];
  } else {
    for (int i = 0; i < n_rows; ++i) {
      double num = 1.0;
      for (int j = 0; j < n_rows; ++j)
        if (j != i) num *= key - xs[j];
      row_w[i] = num * inv_den[i];
    }
  }

  const int m = res_.azimuths;
  const double f = std::clamp(phi / kPi * (m - 1), 0.0, static_cast<double>(m - 1));
  const int c0 = std::min(static_cast<int>(f), m - 2);
  const double column_w[2] = {1.0 - (f - c0), f - c0};

  w.c0 = c0;
  w.w0 = static_cast<float>(column_w[0]);
  w.w1 = static_cast<float>(column_w[1]);
  return true;
}

void SkyViewTable::mix(const Weights& w, float* const* parts) const {
  const int m = res_.azimuths;
  const float* rows_at = first_entry(w);
  if (n_ == 3)  // the RGB-fast path's three wavelengths: loops of known length, unrolled
    mix_entries<3>(rows_at, m, w.row_w, w.n_rows, w.w0, w.w1, n_, parts_, true, parts);
  else
    mix_entries<0>(rows_at, m, w.row_w, w.n_rows, w.w0, w.w1, n_, parts_, true, parts);
}

void SkyViewTable::mix(const Weights& w, RadianceParts& out) const {
  out.scattered.resize(static_cast<size_t>(parts_ - 1));
  float* parts[kMaxMedia + 1];
  for (int s = 0; s + 1 < parts_; ++s) {
    out.scattered[static_cast<size_t>(s)].resize(n_);  // no-ops when the caller's parts have these sizes already
    parts[s] = out.scattered[static_cast<size_t>(s)].data();
  }
  out.phase_free.resize(n_);
  parts[parts_ - 1] = out.phase_free.data();
  mix(w, parts);
}

bool SkyViewTable::lookup_polarised(const Vec3& dir, RadianceParts& out) const {
  if (!polarised_) return false;
  double theta, phi;
  angles_of(dir, theta, phi);
  theta = refined_zenith(dir, theta);
  const int n = n_;
  out.polarised_q.resize(n);
  out.polarised_u.resize(n);
  Weights w;
  if (!weights(theta, phi, w)) return false;
  mix(w, out);
  const int m = res_.azimuths;
  const float* rows_at =
      (w.sky_side ? entries_->polarised_sky : entries_->polarised_ground).data() +
      static_cast<size_t>(w.first_row) * static_cast<size_t>(m) * kPolarisedParts * static_cast<size_t>(n) +
      static_cast<size_t>(w.c0) * kPolarisedParts * static_cast<size_t>(n);
  float* const parts[kPolarisedParts] = {out.polarised_q.data(), out.polarised_u.data()};
  mix_entries<0>(rows_at, m, w.row_w, w.n_rows, w.w0, w.w1, n, kPolarisedParts, false, parts);
  // The table holds the side towards +across; the mirror image's frame has e2 reversed, so U changes sign.
  if (dir.dot(across_) < 0.0) out.polarised_u = -out.polarised_u;
  return true;
}

}  // namespace skyspec
