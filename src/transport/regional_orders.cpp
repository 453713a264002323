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
  const int cells = static_cast<int>(edges.size()) - 1;
  // The light arriving at the grid's points is the scaled problem's, as the tables' is: marched
  // through the field atmosphere (its single scattering with the cut phase functions).
  const SingleScattering field_integrator(field, integrator.sun_columns(), integrator.settings());
  ScatteringSources own = sources;
  own.regional = nullptr;
  own.transmittance = nullptr;
  own.polarisation = false;

  // Each scatterer's cell weights: the integral of its phase function over each cell of
  // scattering angle, per wavelength (midpoint rule on 64 parts of it in mu), shared by the azimuth
  // cells. Every scatterer's source in the region is corrected: the air there scatters the region's
  // light too.
  const int scatterers = integrator.scatterer_count();
  values_per_point_ = static_cast<size_t>(scatterers) * static_cast<size_t>(n_);
  std::vector<std::vector<Spectrum>> weights(static_cast<size_t>(scatterers));
  for (int s = 0; s < scatterers; ++s) {
    const MediumPhase& phase = field.media()[static_cast<size_t>(integrator.medium_of_scatterer(s))].phase;
    std::vector<Spectrum>& weight = weights[static_cast<size_t>(s)];
    weight.assign(static_cast<size_t>(cells), Spectrum::Zero(n_));
    for (int c = 0; c < cells; ++c) {
      const double mu0 = std::cos(edges[static_cast<size_t>(c)] * kPi / 180.0);
      const double mu1 = std::cos(edges[static_cast<size_t>(c) + 1] * kPi / 180.0);
      constexpr int kParts = 64;
      for (int k = 0; k < kParts; ++k) {
        const double mu = mu0 + (mu1 - mu0) * (k + 0.5) / kParts;
        for (int i = 0; i < n_; ++i)
          weight[static_cast<size_t>(c)][i] +=
              static_cast<float>(phase.at(i, mu) * 2.0 * kPi * (mu0 - mu1) / kParts / grid_.phi);
      }
    }
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
  const size_t per_point = static_cast<size_t>(scatterers) * static_cast<size_t>(n_);
  // A region's Delta J of every scatterer at every grid point into `values`, from the light the
  // renderer sees with `own` sources.
  const auto compute = [&](const Region& region, std::vector<float>& values) {
    values.assign(static_cast<size_t>(points) * per_point, 0.0f);
    const auto work = [&](const tbb::blocked_range<int>& range) {
      ScatteringWorkspace ws(n_);
      Spectrum L(n_), ones = Spectrum::Ones(n_);
      std::vector<Spectrum> J(static_cast<size_t>(scatterers), Spectrum::Zero(n_)), tables = J;
      std::vector<float*> out(static_cast<size_t>(scatterers));
      for (int p = range.begin(); p != range.end(); ++p) {
        throw_if_cancelled();
        const Vec3 x = grid_point(region, p);
        Vec3 w = x - camera;
        if (w.norm() < 1.0) w = region.cylinder.axis;  // the camera at the point: any direction
        w.normalize();
        Vec3 a, b;
        perpendiculars(w, a, b);
        for (Spectrum& j : J) j.setZero();
        for (int c = 0; c < cells; ++c) {
          const double theta = 0.5 * (edges[static_cast<size_t>(c)] + edges[static_cast<size_t>(c) + 1]) * kPi / 180.0;
          for (int k = 0; k < grid_.phi; ++k) {
            const double phi = 2.0 * kPi * (k + 0.5) / grid_.phi;
            // Light arriving at x travelling along w_in, scattered by theta into -w (towards the
            // camera): seen from x looking along -w_in.
            const Vec3 w_in = -std::cos(theta) * w + std::sin(theta) * (std::cos(phi) * a + std::sin(phi) * b);
            field_integrator.radiance(x, -w_in, sun, ones, own, ws, L);
            for (int s = 0; s < scatterers; ++s)
              J[static_cast<size_t>(s)] += weights[static_cast<size_t>(s)][static_cast<size_t>(c)] * L;
          }
        }
        const double r = x.norm();
        for (size_t q = 0; q < out.size(); ++q) out[q] = tables[q].data();
        sources.higher->source(r, x.dot(sun) / r, x.dot(w) / r, w.dot(sun), out.data());
        finish_preparation(static_cast<long long>(cells) * grid_.phi);
        float* dest = values.data() + static_cast<size_t>(p) * per_point;
        for (int s = 0; s < scatterers; ++s) {
          const Spectrum delta = J[static_cast<size_t>(s)] - tables[static_cast<size_t>(s)];
          std::copy(delta.data(), delta.data() + n_, dest + static_cast<size_t>(s) * static_cast<size_t>(n_));
        }
      }
    };
    tbb::task_arena arena(std::max(1, threads));
    arena.execute([&] { tbb::parallel_for(tbb::blocked_range<int>(0, points, 4), work); });
  };
  // Pass 1 marches the light without any Delta J; each later pass with the one before it, taken
  // for every direction at a point as it is for the camera's (the light scattered three times by
  // the region's medium, approximately).
  // The work, in rays traced, for the progress a host shows (a bar on a terminal).
  plan_preparation(
      static_cast<long long>(grid_.passes) * static_cast<long long>(regions_.size()) * points * cells * grid_.phi,
      "computing the shower's own multiple scattering");
  for (int pass = 0; pass < grid_.passes; ++pass) {
    own.regional = pass == 0 ? nullptr : this;
    std::vector<std::vector<float>> next(regions_.size());
    for (size_t k = 0; k < regions_.size(); ++k) compute(regions_[k], next[k]);
    for (size_t k = 0; k < regions_.size(); ++k) regions_[k].values = std::move(next[k]);
  }
}

Vec3 RegionalSecondOrder::grid_point(const Region& region, int p) const {
  const int across = grid_.across;
  const int ix = p % across, iy = (p / across) % across, iz = p / (across * across);
  const double r = region.cylinder.radius_m;
  const double u = r * (2.0 * ix / (across - 1) - 1.0), v = r * (2.0 * iy / (across - 1) - 1.0);
  // 1 m above the ground, whose rays downwards then see it in front of them.
  return (planet_radius_m_ + region.heights_m[static_cast<size_t>(iz)] + 1.0) * region.cylinder.axis + u * region.e1 +
         v * region.e2;
}

bool RegionalSecondOrder::add(int scatterer, const Vec3& x, float* out) const {
  for (const Region& region : regions_) {
    if (region.values.empty() || !region.cylinder.contains(x)) continue;
    const int across = grid_.across;
    const Vec3 perp = x - x.dot(region.cylinder.axis) * region.cylinder.axis;
    const double scale = 0.5 * (across - 1) / region.cylinder.radius_m;
    const double fx = std::clamp((perp.dot(region.e1) + region.cylinder.radius_m) * scale, 0.0, across - 1.0);
    const double fy = std::clamp((perp.dot(region.e2) + region.cylinder.radius_m) * scale, 0.0, across - 1.0);
    const double z = x.norm() - planet_radius_m_;
    const std::vector<double>& h = region.heights_m;
    if (z > h.back()) return true;  // above the column's 99 %: nothing worth adding
    size_t kz = 0;
    while (kz + 2 < h.size() && z > h[kz + 1]) ++kz;
    const double fz = std::clamp((z - h[kz]) / (h[kz + 1] - h[kz]), 0.0, 1.0);
    const int ix = std::min(static_cast<int>(fx), across - 2), iy = std::min(static_cast<int>(fy), across - 2);
    const double tx = fx - ix, ty = fy - iy;
    const size_t per_point = values_per_point_;
    for (int corner = 0; corner < 8; ++corner) {
      const int dx = corner & 1, dy = (corner >> 1) & 1, dz = corner >> 2;
      const double w = (dx ? tx : 1.0 - tx) * (dy ? ty : 1.0 - ty) * (dz ? fz : 1.0 - fz);
      if (w == 0.0) continue;
      const size_t p = (static_cast<size_t>(kz + dz) * across + (iy + dy)) * across + (ix + dx);
      const float* v = region.values.data() + p * per_point + static_cast<size_t>(scatterer) * static_cast<size_t>(n_);
      for (int i = 0; i < n_; ++i) out[i] += static_cast<float>(w) * v[i];
    }
    return true;
  }
  return false;
}

}  // namespace skyspec
