#include "transport/regional_orders.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>

#include "base/cancellation.hpp"
#include "base/preparation_progress.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

namespace {

// Two unit vectors perpendicular to w and to each other.
void perpendiculars(const Vec3& w, Vec3& a, Vec3& b) {
  const Vec3 helper = std::abs(w.z()) < 0.9 ? Vec3(0, 0, 1) : Vec3(1, 0, 0);
  a = w.cross(helper).normalized();
  b = w.cross(a);
}

// Heights (m above the ground) that split the column of `profile` from 0 to top_m into equal
// parts: `count` of them, the first at 0, the last where all but 1 % of the column lies below.
std::vector<double> column_heights(const DensityProfile& profile, double top_m, int count) {
  constexpr int kSteps = 4000;
  std::vector<double> cumulative(kSteps + 1, 0.0);
  const double dz = top_m / kSteps;
  for (int k = 1; k <= kSteps; ++k)
    cumulative[static_cast<size_t>(k)] =
        cumulative[static_cast<size_t>(k) - 1] + 0.5 * dz * (profile.relative((k - 1) * dz) + profile.relative(k * dz));
  const double total = cumulative.back();
  std::vector<double> out;
  for (int i = 0; i < count; ++i) {
    const double target = total * 0.99 * i / (count - 1);
    const auto it = std::lower_bound(cumulative.begin(), cumulative.end(), target);
    out.push_back(dz * static_cast<double>(it - cumulative.begin()));
  }
  for (size_t i = 1; i < out.size(); ++i) out[i] = std::max(out[i], out[i - 1] + 1.0);  // strictly rising
  return out;
}

}  // namespace

const std::vector<double>& RegionalSecondOrder::angle_edges_deg() {
  // Finer about rain's bows (the primary near 138, the secondary near 129 degrees) and forward,
  // where the phase function changes fastest.
  static const std::vector<double> edges = {0,   2,   5,   10,  20,  35,  50,  70,  90,
                                            110, 125, 130, 135, 139, 143, 150, 165, 180};
  return edges;
}

RegionalSecondOrder::RegionalSecondOrder(const SingleScattering& integrator, const ScatteringSources& sources,
                                         const Vec3& camera, const Vec3& sun, Grid grid, int threads)
    : grid_(grid), n_(integrator.atmosphere().grid().size()) {
  const AtmosphereModel& atm = integrator.atmosphere();
  planet_radius_m_ = atm.planet_radius_m();
  if (!sources.higher || grid_.across < 2 || grid_.heights < 2 || grid_.phi < 1) return;
  // The phase functions the source integrates: the field atmosphere's (the tables' scaled problem).
  const std::shared_ptr<const AtmosphereModel> field_atm = sources.higher->field_atmosphere();
  const AtmosphereModel& field = field_atm ? *field_atm : atm;
  const std::vector<double>& edges = angle_edges_deg();
  const int cells = static_cast<int>(edges.size()) - 1, phi_cells = grid_.phi;
  const double dphi = 2.0 * kPi / phi_cells;
  row_angles_rad_.assign(1, 0.0);
  for (int c = 0; c < cells; ++c)
    row_angles_rad_.push_back(0.5 * (edges[static_cast<size_t>(c)] + edges[static_cast<size_t>(c) + 1]) * kPi / 180.0);
  row_angles_rad_.push_back(kPi);
  // The light arriving at the grid's points is the scaled problem's, as the tables' is: marched
  // through the field atmosphere (its single scattering with the cut phase functions).
  const SingleScattering field_integrator(field, integrator.sun_columns(), integrator.settings());
  ScatteringSources own = sources;
  own.regional = nullptr;
  own.transmittance = nullptr;
  own.polarisation = false;

  // Each scatterer's cell weights towards -w: the integral of its phase function over each cell of
  // scattering angle, per wavelength (midpoint rule on 64 parts of it in mu), shared by the azimuth
  // cells. Every scatterer's source in the region is corrected: the air there scatters the region's
  // light too.
  scatterers_ = integrator.scatterer_count();
  const int scatterers = scatterers_;
  const size_t per_point = static_cast<size_t>(scatterers) * static_cast<size_t>(n_);
  values_per_point_ = per_point;
  std::vector<const MediumPhase*> phases;
  for (int s = 0; s < scatterers; ++s)
    phases.push_back(&field.media()[static_cast<size_t>(integrator.medium_of_scatterer(s))].phase);
  // weights[c][s * n + i]
  std::vector<Spectrum> weights(static_cast<size_t>(cells), Spectrum::Zero(static_cast<Eigen::Index>(per_point)));
  for (int c = 0; c < cells; ++c) {
    const double mu0 = std::cos(edges[static_cast<size_t>(c)] * kPi / 180.0);
    const double mu1 = std::cos(edges[static_cast<size_t>(c) + 1] * kPi / 180.0);
    constexpr int kParts = 64;
    for (int k = 0; k < kParts; ++k) {
      const double mu = mu0 + (mu1 - mu0) * (k + 0.5) / kParts;
      for (int s = 0; s < scatterers; ++s)
        for (int i = 0; i < n_; ++i)
          weights[static_cast<size_t>(c)][s * n_ + i] += static_cast<float>(
              phases[static_cast<size_t>(s)]->at(i, mu) * 2.0 * kPi * (mu0 - mu1) / kParts / phi_cells);
    }
  }
  // With more than one pass, the weights towards every kept direction d (direction_index): cell
  // (c, k)'s towards row r, azimuth k_d depend on r, c and k - k_d only. The integral of p_s over
  // the cell about its angle with d, on 8 x 8 sub-cells (equal in mu and azimuth), scaled so that
  // each direction's weights add up to the integral of p_s over the sphere (which the weights
  // towards -w give): the field's light, were it isotropic, keeps its amount.
  // directional_weights[(r * cells + c) * phi + dk][s * n + i]
  std::vector<Spectrum> directional_weights;
  if (grid_.passes > 1) {
    const int rows = cells + 2;
    directional_weights.assign(static_cast<size_t>(rows * cells * phi_cells),
                               Spectrum::Zero(static_cast<Eigen::Index>(per_point)));
    // The phase functions on a fine grid of scattering angle (0.05 degree), read at the sub-cells.
    constexpr int kBins = 3600;
    std::vector<float> fine(static_cast<size_t>(kBins + 1) * per_point);
    for (int b = 0; b <= kBins; ++b) {
      const double mu = std::cos(kPi * b / kBins);
      for (int s = 0; s < scatterers; ++s)
        for (int i = 0; i < n_; ++i)
          fine[static_cast<size_t>(b) * per_point + static_cast<size_t>(s * n_ + i)] =
              static_cast<float>(phases[static_cast<size_t>(s)]->at(i, mu));
    }
    Spectrum total = Spectrum::Zero(static_cast<Eigen::Index>(per_point));
    for (const Spectrum& w : weights) total += w * static_cast<float>(phi_cells);
    const auto fill_row = [&](const tbb::blocked_range<int>& range) {
      constexpr int kSub = 8;
      for (int r = range.begin(); r != range.end(); ++r) {
        const double mu_d = std::cos(row_angles_rad_[static_cast<size_t>(r)]);
        const double sin_d = std::sqrt(std::max(0.0, 1.0 - mu_d * mu_d));
        for (int dk = 0; dk < phi_cells; ++dk) {
          for (int c = 0; c < cells; ++c) {
            Spectrum& w = directional_weights[static_cast<size_t>((r * cells + c) * phi_cells + dk)];
            const double mu0 = std::cos(edges[static_cast<size_t>(c)] * kPi / 180.0);
            const double mu1 = std::cos(edges[static_cast<size_t>(c) + 1] * kPi / 180.0);
            const float solid_angle = static_cast<float>((mu0 - mu1) * dphi / (kSub * kSub));
            for (int a = 0; a < kSub; ++a) {
              const double mu = mu0 + (mu1 - mu0) * (a + 0.5) / kSub;
              const double sin_c = std::sqrt(std::max(0.0, 1.0 - mu * mu));
              for (int q = 0; q < kSub; ++q) {
                const double relative = (dk + (q + 0.5) / kSub - 0.5) * dphi;  // azimuth from d's
                const double cosine = std::clamp(mu * mu_d + sin_c * sin_d * std::cos(relative), -1.0, 1.0);
                const double bin = std::acos(cosine) / kPi * kBins;
                const int b = std::min(static_cast<int>(bin), kBins - 1);
                const float f = static_cast<float>(bin - b);
                const float* lo = fine.data() + static_cast<size_t>(b) * per_point;
                const float* hi = lo + per_point;
                for (size_t j = 0; j < per_point; ++j)
                  w[static_cast<Eigen::Index>(j)] += solid_angle * (lo[j] + f * (hi[j] - lo[j]));
              }
            }
          }
        }
        // One scale per row: every azimuth of it sees the same cells, rotated.
        Spectrum sum = Spectrum::Zero(static_cast<Eigen::Index>(per_point));
        for (int c = 0; c < cells; ++c)
          for (int dk = 0; dk < phi_cells; ++dk)
            sum += directional_weights[static_cast<size_t>((r * cells + c) * phi_cells + dk)];
        const Spectrum scale = (sum > 0.0f).select(total / sum, 0.0f);
        for (int c = 0; c < cells; ++c)
          for (int dk = 0; dk < phi_cells; ++dk)
            directional_weights[static_cast<size_t>((r * cells + c) * phi_cells + dk)] *= scale;
      }
    };
    tbb::task_arena arena(std::max(1, threads));
    arena.execute([&] { tbb::parallel_for(tbb::blocked_range<int>(1, rows), fill_row); });
  }

  for (int j = 0; j < static_cast<int>(atm.media().size()); ++j) {
    const Medium& medium = atm.media()[static_cast<size_t>(j)];
    if (!medium.region || !medium.scatters()) continue;
    Region region;
    region.medium = j;
    region.cylinder = *medium.region;
    perpendiculars(region.cylinder.axis, region.e1, region.e2);
    region.heights_m = column_heights(medium.profile, atm.spec().top_altitude_m, grid_.heights);
    regions_.push_back(std::move(region));
  }
  const int across = grid_.across, points = across * across * grid_.heights;
  for (Region& region : regions_)
    for (int p = 0; p < points; ++p) {
      const Vec3 x = grid_point(region, p);
      Frame f;
      f.w = x - camera;
      if (f.w.norm() < 1.0) f.w = region.cylinder.axis;  // the camera at the point: any direction
      f.w.normalize();
      perpendiculars(f.w, f.a, f.b);
      region.frames.push_back(f);
    }
  const int samples = cells * phi_cells;
  // The ground's grid: Delta E from the sky's light above each point.
  constexpr int kGroundRows = 8, kGroundAzimuths = 16;
  const int ground_points = across * across;
  const auto compute_ground = [&](const Region& region, std::vector<float>& ground) {
    ground.assign(static_cast<size_t>(ground_points) * static_cast<size_t>(n_), 0.0f);
    const auto work = [&](const tbb::blocked_range<int>& range) {
      ScatteringWorkspace ws(n_);
      Spectrum L(n_), E(n_), tables(n_), ones = Spectrum::Ones(n_);
      for (int g = range.begin(); g != range.end(); ++g) {
        throw_if_cancelled();
        const Vec3 x = ground_point(region, g);
        const Vec3 up = x.normalized();
        Vec3 a, b;
        perpendiculars(up, a, b);
        E.setZero();
        for (int row = 0; row < kGroundRows; ++row) {
          const double mu = (row + 0.5) / kGroundRows, sin_t = std::sqrt(1.0 - mu * mu);
          for (int k = 0; k < kGroundAzimuths; ++k) {
            const double phi = 2.0 * kPi * (k + 0.5) / kGroundAzimuths;
            const Vec3 look = mu * up + sin_t * (std::cos(phi) * a + std::sin(phi) * b);
            field_integrator.radiance(x, look, sun, ones, own, ws, L);
            E += static_cast<float>(mu * 2.0 * kPi / (kGroundRows * kGroundAzimuths)) * L;
          }
        }
        sources.higher->ground_irradiance(std::clamp(up.dot(sun), -1.0, 1.0), tables.data());
        const Spectrum delta = E - tables;
        std::copy(delta.data(), delta.data() + n_, ground.data() + static_cast<size_t>(g) * static_cast<size_t>(n_));
        finish_preparation(kGroundRows * kGroundAzimuths);
      }
    };
    tbb::task_arena arena(std::max(1, threads));
    arena.execute([&] { tbb::parallel_for(tbb::blocked_range<int>(0, ground_points, 2), work); });
  };
  // A region's Delta J of every scatterer at every grid point into `values`, from the light the
  // renderer sees with `own` sources: towards the camera, or with `every_direction` towards each
  // direction of direction_index.
  const auto compute = [&](const Region& region, std::vector<float>& values, bool every_direction) {
    const int directions = every_direction ? direction_count() : 1;
    const size_t stride = static_cast<size_t>(directions) * per_point;
    values.assign(static_cast<size_t>(points) * stride, 0.0f);
    const auto work = [&](const tbb::blocked_range<int>& range) {
      ScatteringWorkspace ws(n_);
      Spectrum L(n_), ones = Spectrum::Ones(n_);
      // The light arriving from each cell's centre, [cell * phi + k][wavelength].
      std::vector<Spectrum> arriving(static_cast<size_t>(samples), Spectrum::Zero(n_));
      Spectrum J(static_cast<Eigen::Index>(per_point)), tables = J;
      std::vector<float*> out(static_cast<size_t>(scatterers));
      for (int p = range.begin(); p != range.end(); ++p) {
        throw_if_cancelled();
        const Vec3 x = grid_point(region, p);
        const Frame& f = region.frames[static_cast<size_t>(p)];
        for (int c = 0; c < cells; ++c) {
          const double theta = row_angles_rad_[static_cast<size_t>(c) + 1];
          for (int k = 0; k < phi_cells; ++k) {
            const double phi = dphi * (k + 0.5);
            // Light arriving at x travelling along w_in, scattered by theta into -w (towards the
            // camera): seen from x looking along -w_in.
            const Vec3 w_in = -std::cos(theta) * f.w + std::sin(theta) * (std::cos(phi) * f.a + std::sin(phi) * f.b);
            field_integrator.radiance(x, -w_in, sun, ones, own, ws, arriving[static_cast<size_t>(c * phi_cells + k)]);
          }
        }
        const double r = x.norm();
        float* dest = values.data() + static_cast<size_t>(p) * stride;
        for (int row = 0; row < (every_direction ? cells + 2 : 1); ++row) {
          const bool pole = row == 0 || row == cells + 1;
          for (int kd = 0; kd < (pole ? 1 : phi_cells); ++kd) {
            J.setZero();
            for (int c = 0; c < cells; ++c)
              for (int k = 0; k < phi_cells; ++k) {
                const Spectrum& weight = row == 0
                                             ? weights[static_cast<size_t>(c)]
                                             : directional_weights[static_cast<size_t>(
                                                   (row * cells + c) * phi_cells + (k - kd + phi_cells) % phi_cells)];
                const Spectrum& l = arriving[static_cast<size_t>(c * phi_cells + k)];
                for (int s = 0; s < scatterers; ++s) J.segment(s * n_, n_) += weight.segment(s * n_, n_) * l;
              }
            // The direction the source is sent along, d, and the tables' source along it (seen
            // looking along -d).
            const double theta = row_angles_rad_[static_cast<size_t>(row)], phi = dphi * (kd + 0.5);
            const Vec3 d = -std::cos(theta) * f.w + std::sin(theta) * (std::cos(phi) * f.a + std::sin(phi) * f.b);
            for (int s = 0; s < scatterers; ++s) out[static_cast<size_t>(s)] = tables.data() + s * n_;
            sources.higher->source(r, x.dot(sun) / r, -x.dot(d) / r, -d.dot(sun), out.data());
            const Spectrum delta = J - tables;
            std::copy(delta.data(), delta.data() + per_point,
                      dest + (every_direction ? direction_index(row, kd) : 0) * per_point);
          }
        }
        finish_preparation(static_cast<long long>(samples));
      }
    };
    tbb::task_arena arena(std::max(1, threads));
    arena.execute([&] { tbb::parallel_for(tbb::blocked_range<int>(0, points, 4), work); });
  };
  // Pass 1 marches the light without any Delta J; each later pass with the one before it, which
  // keeps Delta J towards every direction of its cells (the light scattered three times by the
  // region's medium, and so on); the last towards the camera.
  // The work, in rays traced, for the progress a host shows (a bar on a terminal).
  plan_preparation(static_cast<long long>(grid_.passes) * static_cast<long long>(regions_.size()) *
                       (points * samples + ground_points * kGroundRows * kGroundAzimuths),
                   "computing the shower's own multiple scattering");
  for (int pass = 0; pass < grid_.passes; ++pass) {
    own.regional = pass == 0 ? nullptr : this;
    const bool every_direction = pass + 1 < grid_.passes;
    std::vector<std::vector<float>> next(regions_.size()), next_ground(regions_.size());
    for (size_t k = 0; k < regions_.size(); ++k) {
      compute(regions_[k], next[k], every_direction);
      compute_ground(regions_[k], next_ground[k]);
    }
    for (size_t k = 0; k < regions_.size(); ++k) {
      regions_[k].values = std::move(next[k]);
      regions_[k].ground = std::move(next_ground[k]);
    }
    directional_ = every_direction;
  }
}

int RegionalSecondOrder::direction_count() const {
  return 2 + static_cast<int>(row_angles_rad_.size() - 2) * grid_.phi;
}

size_t RegionalSecondOrder::direction_index(int row, int k) const {
  const int rows = static_cast<int>(row_angles_rad_.size());
  if (row == 0) return 0;
  if (row == rows - 1) return static_cast<size_t>(direction_count() - 1);
  return static_cast<size_t>(1 + (row - 1) * grid_.phi + k);
}

Vec3 RegionalSecondOrder::grid_point(const Region& region, int p) const {
  const int across = grid_.across;
  const int ix = p % across, iy = (p / across) % across, iz = p / (across * across);
  const double r = half_side_m(region);
  const double u = r * (2.0 * ix / (across - 1) - 1.0), v = r * (2.0 * iy / (across - 1) - 1.0);
  // 1 m above the ground, whose rays downwards then see it in front of them.
  return (planet_radius_m_ + region.heights_m[static_cast<size_t>(iz)] + 1.0) * region.cylinder.axis + u * region.e1 +
         v * region.e2;
}

Vec3 RegionalSecondOrder::ground_point(const Region& region, int g) const {
  const int across = grid_.across;
  const int ix = g % across, iy = g / across;
  const double half = half_side_m(region);
  const double u = half * (2.0 * ix / (across - 1) - 1.0), v = half * (2.0 * iy / (across - 1) - 1.0);
  const Vec3 p = planet_radius_m_ * region.cylinder.axis + u * region.e1 + v * region.e2;
  return (planet_radius_m_ + 1.0) * p.normalized();
}

bool RegionalSecondOrder::add_ground(const Vec3& ground_point, float* irradiance) const {
  const int across = grid_.across;
  for (const Region& region : regions_) {
    if (region.ground.empty()) continue;
    const Vec3 perp = ground_point - ground_point.dot(region.cylinder.axis) * region.cylinder.axis;
    const double half = half_side_m(region);
    const double fx = (perp.dot(region.e1) + half) / (2.0 * half) * (across - 1);
    const double fy = (perp.dot(region.e2) + half) / (2.0 * half) * (across - 1);
    if (!(fx >= 0.0 && fx <= across - 1.0 && fy >= 0.0 && fy <= across - 1.0) ||
        ground_point.dot(region.cylinder.axis) <= 0.0)
      continue;
    const int ix = std::min(static_cast<int>(fx), across - 2), iy = std::min(static_cast<int>(fy), across - 2);
    const double tx = fx - ix, ty = fy - iy;
    for (int corner = 0; corner < 4; ++corner) {
      const int dx = corner & 1, dy = corner >> 1;
      const float w = static_cast<float>((dx ? tx : 1.0 - tx) * (dy ? ty : 1.0 - ty));
      if (w == 0.0f) continue;
      const float* v =
          region.ground.data() + static_cast<size_t>((iy + dy) * across + ix + dx) * static_cast<size_t>(n_);
      for (int i = 0; i < n_; ++i) irradiance[i] += w * v[i];
    }
    return true;
  }
  return false;
}

bool RegionalSecondOrder::add(const Vec3& x, const Vec3& toward, float* const* out) const {
  for (const Region& region : regions_) {
    if (region.values.empty()) continue;
    const int across = grid_.across;
    const Vec3 perp = x - x.dot(region.cylinder.axis) * region.cylinder.axis;
    const double half = half_side_m(region);
    if (x.dot(region.cylinder.axis) <= 0.0 || std::abs(perp.dot(region.e1)) > half ||
        std::abs(perp.dot(region.e2)) > half)
      continue;  // beyond the grid's square: the tables' source alone
    const double scale = 0.5 * (across - 1) / half;
    const double fx = std::clamp((perp.dot(region.e1) + half) * scale, 0.0, across - 1.0);
    const double fy = std::clamp((perp.dot(region.e2) + half) * scale, 0.0, across - 1.0);
    const double z = x.norm() - planet_radius_m_;
    const std::vector<double>& h = region.heights_m;
    if (z > h.back()) return true;  // above the column's 99 %: nothing worth adding
    size_t kz = 0;
    while (kz + 2 < h.size() && z > h[kz + 1]) ++kz;
    const double fz = std::clamp((z - h[kz]) / (h[kz + 1] - h[kz]), 0.0, 1.0);
    const int ix = std::min(static_cast<int>(fx), across - 2), iy = std::min(static_cast<int>(fy), across - 2);
    const double tx = fx - ix, ty = fy - iy;
    const size_t per_point = values_per_point_;
    const size_t stride = directional_ ? static_cast<size_t>(direction_count()) * per_point : per_point;
    const auto accumulate = [&](const float* v, double weight) {
      const float w = static_cast<float>(weight);
      for (int s = 0; s < scatterers_; ++s)
        for (int i = 0; i < n_; ++i) out[s][i] += w * v[static_cast<size_t>(s * n_ + i)];
    };
    for (int corner = 0; corner < 8; ++corner) {
      const int dx = corner & 1, dy = (corner >> 1) & 1, dz = corner >> 2;
      const double w = (dx ? tx : 1.0 - tx) * (dy ? ty : 1.0 - ty) * (dz ? fz : 1.0 - fz);
      if (w == 0.0) continue;
      const size_t p = (static_cast<size_t>(kz + dz) * across + (iy + dy)) * across + (ix + dx);
      const float* v = region.values.data() + p * stride;
      if (!directional_) {
        accumulate(v, w);
        continue;
      }
      // `toward` in the point's frame: its angle from -w (between two rows) and its azimuth
      // about w (between two cells' centres), bilinearly.
      const Frame& f = region.frames[p];
      const double theta = std::acos(std::clamp(-toward.dot(f.w), -1.0, 1.0));
      double phi = std::atan2(toward.dot(f.b), toward.dot(f.a));
      if (phi < 0.0) phi += 2.0 * kPi;
      const auto upper = std::upper_bound(row_angles_rad_.begin(), row_angles_rad_.end(), theta);
      const int row = std::clamp(static_cast<int>(upper - row_angles_rad_.begin()) - 1, 0,
                                 static_cast<int>(row_angles_rad_.size()) - 2);
      const double t =
          std::clamp((theta - row_angles_rad_[static_cast<size_t>(row)]) /
                         (row_angles_rad_[static_cast<size_t>(row) + 1] - row_angles_rad_[static_cast<size_t>(row)]),
                     0.0, 1.0);
      const double u = phi / (2.0 * kPi) * grid_.phi - 0.5;
      const double k_floor = std::floor(u);
      const double fk = u - k_floor;
      const int k0 = (static_cast<int>(k_floor) + grid_.phi) % grid_.phi, k1 = (k0 + 1) % grid_.phi;
      for (int edge = 0; edge < 2; ++edge) {
        const int r = row + edge;
        const double wr = w * (edge ? t : 1.0 - t);
        if (wr == 0.0) continue;
        const size_t i0 = direction_index(r, k0), i1 = direction_index(r, k1);
        if (i0 == i1) {
          accumulate(v + i0 * per_point, wr);
        } else {
          accumulate(v + i0 * per_point, wr * (1.0 - fk));
          accumulate(v + i1 * per_point, wr * fk);
        }
      }
    }
    return true;
  }
  return false;
}

}  // namespace skyspec
