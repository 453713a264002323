#include "transport/monte_carlo.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/cancellation.hpp"
#include "skyspec/error.hpp"
#include "skyspec/phase_function.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

namespace {
constexpr std::int64_t kBatchPaths = 4096;  // paths per independently seeded batch
constexpr double kRouletteWeight = 0.1;     // Russian roulette below this path weight
constexpr int kMaxEvents = 100000;          // a path's events, a guard against endless loops
constexpr int kMaxComponents = 8;

// SplitMix64 (Steele, Lea & Flood 2014): turns (seed, stream, batch) into well-mixed 64-bit states.
std::uint64_t splitmix64(std::uint64_t& x) {
  std::uint64_t z = (x += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// Russian roulette on a transmittance estimate: below kRouletteTransmittance it survives with
// probability T / kRouletteTransmittance and is raised to that value, else it becomes 0 (unbiased;
// it stops tracking a ray whose remaining contribution is small).
constexpr double kRouletteTransmittance = 0.05;

// An orthonormal basis (u, v, d) around a unit vector d (Duff et al. 2017, "Building an
// orthonormal basis, revisited").
void basis_around(const Vec3& d, Vec3& u, Vec3& v) {
  const double sign = std::copysign(1.0, d.z());
  const double a = -1.0 / (sign + d.z());
  const double b = d.x() * d.y() * a;
  u = Vec3(1.0 + sign * d.x() * d.x() * a, sign * b, -sign * d.x());
  v = Vec3(b, sign + d.y() * d.y() * a, -d.y());
}

// The direction at cosine mu to d, at azimuth phi about it.
Vec3 rotate_about(const Vec3& d, double mu, double phi) {
  Vec3 u, v;
  basis_around(d, u, v);
  const double s = std::sqrt(std::max(0.0, 1.0 - mu * mu));
  return (s * std::cos(phi) * u + s * std::sin(phi) * v + mu * d).normalized();
}

// The first axis of a Stokes frame for light travelling along k: `reference` made perpendicular to
// k (any perpendicular axis if they are parallel).
Vec3 frame_axis(const Vec3& k, const Vec3& reference) {
  Vec3 e1 = reference - reference.dot(k) * k;
  if (e1.norm() < 1e-9) {
    Vec3 u, v;
    basis_around(k, u, v);
    return u;
  }
  return e1.normalized();
}
}  // namespace

// PCG32 (O'Neill 2014, "PCG: A family of simple fast space-efficient statistically good
// algorithms for random number generation", pcg32 XSH-RR), one stream per batch of paths.
struct MonteCarloIntegrator::Rng {
  std::uint64_t state = 0, inc = 1;
  Rng(std::uint64_t seed, std::uint64_t stream, std::uint64_t batch) {
    std::uint64_t x = seed ^ (stream * 0xD1B54A32D192ED03ull) ^ (batch * 0x8CB92BA72F3D8DD7ull);
    const std::uint64_t init = splitmix64(x);
    inc = (splitmix64(x) << 1u) | 1u;
    next();
    state += init;
    next();
  }
  std::uint32_t next() {
    const std::uint64_t old = state;
    state = old * 6364136223846793005ull + inc;
    const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<std::uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }
  /// Uniform in [0, 1) with 53 random bits.
  double uniform() {
    const std::uint64_t hi = next(), lo = next();
    return static_cast<double>(((hi << 32) | lo) >> 11) * 0x1.0p-53;
  }
  /// An exponential free path with unit mean: -ln(1 - xi), xi in [0, 1) so the log is finite.
  double exponential() { return -std::log1p(-uniform()); }
};

double MonteCarloIntegrator::roulette(double T, Rng& rng) {
  if (T >= kRouletteTransmittance) return T;
  return rng.uniform() * kRouletteTransmittance < T ? kRouletteTransmittance : 0.0;
}

MonteCarloMedium MonteCarloMedium::from_atmosphere(const AtmosphereModel& atm, int i) {
  MonteCarloMedium m;
  m.geometry = Geometry::SphericalShell;
  m.planet_radius_m = atm.planet_radius_m();
  m.top_altitude_m = atm.spec().top_altitude_m;
  for (const Medium& medium : atm.media()) {
    if (!medium.enabled()) continue;
    MonteCarloComponent c;
    c.profile = medium.profile;
    c.region = medium.region;
    c.scattering_per_m = medium.scattering_per_m[i];
    c.extinction_per_m = medium.extinction_per_m[i];
    const MediumPhase& p = medium.phase;
    switch (p.kind) {
      case MediumPhase::Kind::None:
        c.phase = MonteCarloComponent::Phase::None;
        break;
      case MediumPhase::Kind::Rayleigh:
        c.phase = MonteCarloComponent::Phase::Rayleigh;
        c.phase_parameter = p.rayleigh_gamma[i];
        break;
      case MediumPhase::Kind::Analytic:
        c.phase = p.analytic_model == AerosolPhase::Model::HenyeyGreenstein
                      ? MonteCarloComponent::Phase::HenyeyGreenstein
                      : MonteCarloComponent::Phase::CornetteShanks;
        c.phase_parameter = p.g[i];
        break;
      case MediumPhase::Kind::Tabulated:
        c.phase = MonteCarloComponent::Phase::Tabulated;
        c.phase_parameter = p.g[i];
        c.table = p.matrix;
        c.table_row = i;
        break;
    }
    m.components.push_back(std::move(c));
  }
  m.ground_albedo = atm.ground_albedo()[i];
  m.sun_irradiance = 1.0;
  return m;
}

MonteCarloIntegrator::MonteCarloIntegrator(MonteCarloMedium medium, const Vec3& sun_dir)
    : medium_(std::move(medium)), sun_(sun_dir.normalized()) {
  if (medium_.components.size() > static_cast<size_t>(kMaxComponents))
    throw Error("the Monte Carlo integrator takes at most 8 components");
  if (!(medium_.top_altitude_m > 0.0)) throw Error("the Monte Carlo medium needs a positive thickness");
  // sigma_bar = sum over species of beta_ext max_z rho(z). The profiles are monotone or
  // piecewise linear between nodes at most 10 m apart (the U.S. 1976 table's step) except at the
  // tent's corners, which are included, so the maximum over nodes is the maximum.
  for (const auto& c : medium_.components) {
    if (!(c.extinction_per_m >= c.scattering_per_m && c.scattering_per_m >= 0.0))
      throw Error("a Monte Carlo component needs 0 <= scattering <= extinction");
    double rho_max = 0.0;
    const int n = static_cast<int>(std::ceil(medium_.top_altitude_m / 10.0));
    for (int k = 0; k <= n; ++k)
      rho_max = std::max(rho_max, c.profile.relative(std::min(k * 10.0, medium_.top_altitude_m)));
    if (c.profile.kind() == DensityProfile::Kind::Tent) rho_max = std::max(rho_max, 1.0);
    majorant_ += c.extinction_per_m * rho_max;
  }
  majorant_ *= 1.0 + 1e-9;
}

double MonteCarloIntegrator::altitude(const Vec3& p) const {
  return medium_.geometry == MonteCarloMedium::Geometry::PlaneParallel ? p.z() : p.norm() - medium_.planet_radius_m;
}

Vec3 MonteCarloIntegrator::up(const Vec3& p) const {
  return medium_.geometry == MonteCarloMedium::Geometry::PlaneParallel ? Vec3(0, 0, 1) : p.normalized();
}

double MonteCarloIntegrator::distance_to_boundary(const Vec3& p, const Vec3& d, bool& ground, bool* on_terrain) const {
  const double t = distance_to_shell_boundary(p, d, ground);
  if (on_terrain) *on_terrain = false;
  if (!medium_.terrain) return t;
  const double hit = medium_.terrain->intersect(p, d, 0.0, t);
  if (!(hit < t)) return t;
  ground = true;
  if (on_terrain) *on_terrain = true;
  return hit;
}

Vec3 MonteCarloIntegrator::ground_normal(const Vec3& g) const {
  return medium_.terrain ? medium_.terrain->normal_under(g) : up(g);
}

double MonteCarloIntegrator::surface_albedo(const Vec3& g) const {
  if (!medium_.terrain || !medium_.terrain->covers(g)) return medium_.ground_albedo;
  return medium_.terrain_albedo.value_or(medium_.ground_albedo) * medium_.terrain->albedo_factor_under(g);
}

Vec3 MonteCarloIntegrator::snap_to_surface(const Vec3& g, bool on_terrain) const {
  if (!on_terrain) return snap_to_ground(g);
  return g + 1e-3 * medium_.terrain->normal_under(g);  // off the surface, which hides nothing from it
}

double MonteCarloIntegrator::distance_to_shell_boundary(const Vec3& p, const Vec3& d, bool& ground) const {
  ground = false;
  if (medium_.geometry == MonteCarloMedium::Geometry::PlaneParallel) {
    if (d.z() > 0.0) return std::max(0.0, (medium_.top_altitude_m - p.z()) / d.z());
    if (d.z() < 0.0) {
      ground = true;
      return std::max(0.0, p.z() / -d.z());
    }
    return std::numeric_limits<double>::infinity();
  }
  const SphereHit top = intersect_sphere(p, d, medium_.planet_radius_m + medium_.top_altitude_m);
  double t = top.hit ? std::max(0.0, top.t_far_m) : 0.0;
  if (p.dot(d) < 0.0) {
    const SphereHit g = intersect_sphere(p, d, medium_.planet_radius_m);
    if (g.hit && g.t_near_m >= 0.0 && g.t_near_m < t) {
      t = g.t_near_m;
      ground = true;
    }
  }
  return t;
}

double MonteCarloIntegrator::extinction_at(const Vec3& p) const {
  const double z = altitude(p);
  double sigma = 0.0;
  for (const auto& c : medium_.components) sigma += c.extinction_per_m * density_of(c, p, z);
  return sigma;
}

double MonteCarloIntegrator::scattering_at(const Vec3& p, double* per_component) const {
  const double z = altitude(p);
  double sigma = 0.0;
  for (size_t k = 0; k < medium_.components.size(); ++k) {
    const auto& c = medium_.components[k];
    per_component[k] = c.scattering_per_m > 0.0 ? c.scattering_per_m * density_of(c, p, z) : 0.0;
    sigma += per_component[k];
  }
  return sigma;
}

// Ratio tracking: T = prod over tentative collisions before the edge of (1 - sigma_t / sigma_bar).
double MonteCarloIntegrator::transmittance_to_sun(const Vec3& p, Rng& rng) const {
  bool ground = false;
  const double t_max = distance_to_boundary(p, sun_, ground);
  if (ground || !std::isfinite(t_max)) return 0.0;  // in the planet's (or the terrain's) shadow
  double T = 1.0, t = 0.0;
  if (majorant_ <= 0.0) return 1.0;
  while (true) {
    t += rng.exponential() / majorant_;
    if (t >= t_max) return T;
    T = roulette(T * (1.0 - extinction_at(p + t * sun_) / majorant_), rng);
    if (T == 0.0) return 0.0;
  }
}

double MonteCarloIntegrator::phase_to_sun(const double* scattering, double total, double mu) const {
  double p = 0.0;
  for (size_t k = 0; k < medium_.components.size(); ++k) {
    if (scattering[k] <= 0.0) continue;
    const auto& c = medium_.components[k];
    double pk = 0.0;
    switch (c.phase) {
      case MonteCarloComponent::Phase::Rayleigh:
        pk = rayleigh_phase(mu, c.phase_parameter);
        break;
      case MonteCarloComponent::Phase::HenyeyGreenstein:
        pk = henyey_greenstein_phase(mu, c.phase_parameter);
        break;
      case MonteCarloComponent::Phase::CornetteShanks:
        pk = cornette_shanks_phase(mu, c.phase_parameter);
        break;
      case MonteCarloComponent::Phase::Tabulated:
        pk = c.table->phase(c.table_row, mu);
        break;
      case MonteCarloComponent::Phase::None:
        break;
    }
    p += scattering[k] * pk;
  }
  return p / total;
}

ScatteringMatrix MonteCarloIntegrator::mixture_matrix(const double* scattering, double total, double mu) const {
  ScatteringMatrix f;
  for (size_t k = 0; k < medium_.components.size(); ++k) {
    if (scattering[k] <= 0.0) continue;
    const auto& c = medium_.components[k];
    ScatteringMatrix fk;
    switch (c.phase) {
      case MonteCarloComponent::Phase::Rayleigh:
        fk = rayleigh_scattering_matrix(mu, c.phase_parameter);
        break;
      case MonteCarloComponent::Phase::HenyeyGreenstein:
        fk = non_polarising_scattering_matrix(henyey_greenstein_phase(mu, c.phase_parameter));
        break;
      case MonteCarloComponent::Phase::CornetteShanks:
        fk = non_polarising_scattering_matrix(cornette_shanks_phase(mu, c.phase_parameter));
        break;
      case MonteCarloComponent::Phase::Tabulated: {
        // Spheres: a2 = a1, a4 = a3 (tabulated_scattering.hpp).
        const SphereMatrixElements e = c.table->elements(c.table_row, mu);
        fk.a1 = fk.a2 = e.a1;
        fk.a3 = fk.a4 = e.a3;
        fk.b1 = e.b1;
        fk.b2 = e.b2;
        break;
      }
      case MonteCarloComponent::Phase::None:
        continue;
    }
    fk *= scattering[k];
    f += fk;
  }
  f *= 1.0 / total;
  return f;
}

Vec3 MonteCarloIntegrator::sample_scattering(const double* scattering, double total, const Vec3& d, Rng& rng) const {
  // The species, in proportion to its scattering coefficient.
  size_t k = 0;
  double x = rng.uniform() * total;
  for (; k + 1 < medium_.components.size(); ++k) {
    if (x < scattering[k]) break;
    x -= scattering[k];
  }
  while (scattering[k] <= 0.0 && k > 0) --k;  // rounding at the end of the list
  const auto& c = medium_.components[k];
  const double a = c.phase_parameter;
  auto henyey_greenstein = [&rng](double g) {
    if (std::abs(g) < 1e-6) return 2.0 * rng.uniform() - 1.0;
    const double q = (1.0 - g * g) / (1.0 - g + 2.0 * g * rng.uniform());
    return std::clamp((1.0 + g * g - q * q) / (2.0 * g), -1.0, 1.0);
  };
  double mu = 0.0;
  switch (c.phase) {
    case MonteCarloComponent::Phase::Rayleigh: {
      // p(mu) proportional to (1 + 3 gamma) + (1 - gamma) mu^2: uniform proposals, accepted in
      // proportion (at least half of them).
      const double A = 1.0 + 3.0 * a, B = 1.0 - a;
      do mu = 2.0 * rng.uniform() - 1.0;
      while (rng.uniform() * (A + B) > A + B * mu * mu);
      break;
    }
    case MonteCarloComponent::Phase::HenyeyGreenstein:
      mu = henyey_greenstein(a);
      break;
    case MonteCarloComponent::Phase::CornetteShanks:
      // Cornette-Shanks = Henyey-Greenstein x 3 (1 + mu^2) / (2 (2 + g^2)): HG proposals accepted
      // with probability (1 + mu^2) / 2.
      do mu = henyey_greenstein(a);
      while (rng.uniform() * 2.0 > 1.0 + mu * mu);
      break;
    case MonteCarloComponent::Phase::Tabulated:
      mu = c.table->sample_mu(c.table_row, rng.uniform());
      break;
    case MonteCarloComponent::Phase::None:
      mu = 1.0;
      break;
  }
  return rotate_about(d, mu, 2.0 * kPi * rng.uniform());
}

// One path from p along d: its estimate of the radiance arriving at p from -d.
//
// Each straight segment of the path (from p along d to the ground or space) is crossed by a
// Poisson process of tentative collisions of rate sigma_seg = max(sigma_bar, K / length), K = 8
// (any rate >= sigma_t is valid; a thin segment still gets about K points). Two estimators use
// these points:
//   - the light the segment scatters towards p after coming from the sun (this order's share):
//     sum over points of T_j sigma_s(x_j) / sigma_seg p(mu) E T_sun(x_j), with T_j = prod over the
//     earlier points of (1 - sigma_t / sigma_seg), the ratio-tracking estimate of the
//     transmittance to x_j (the ratio-tracking form of the in-scattering integral; Novak et al.
//     2014, section 4), and the same T at the segment's end for the sun reflected by the ground;
//   - the continuation (the higher orders): the first point accepted with probability
//     sigma_t / sigma_seg is the real collision (delta tracking); the weight takes sigma_s / sigma_t
//     and the phase function gives the next direction. Without one the path goes on from the
//     ground (weight x albedo, a cosine-distributed direction) or ends in space.
// So every segment scores, even where most paths leave the medium without a collision.
template <int N>
Eigen::Matrix<double, N, 1> MonteCarloIntegrator::path(Vec3 p, Vec3 d, const Vec3& reference, int max_orders,
                                                       double sun_peak_share, Rng& rng) const {
  constexpr bool kStokes = N == 4;
  using Result = Eigen::Matrix<double, N, 1>;
  constexpr double kPointsPerSegment = 8.0;
  Result L = Result::Zero();
  double w = 1.0;
  const double E = medium_.sun_irradiance;
  double scattering[kMaxComponents] = {};
  // Vector transport: M maps the Stokes vector of the light arriving along the current segment
  // (travelling along k = -d), in the frame (e1, k x e1), to the observer's; w stays the scalar
  // part (albedos, roulette), so the intensity path is the scalar one.
  MuellerMatrix M = MuellerMatrix::Identity();
  Vec3 e1 = Vec3::Zero();
  if constexpr (kStokes) e1 = frame_axis(-d, reference);
  // The light leaving a scattering point towards the observer along -d, from light arriving along
  // k_in: returns n, the scattering plane's normal, and the rotation from the plane's outgoing
  // frame to (e1, k x e1).
  const auto scattering_plane = [&](const Vec3& k_in, const Vec3& k_out, Vec3& n) {
    n = k_in.cross(k_out);
    const double len = n.norm();
    n = len > 1e-12 ? Vec3(n / len) : Vec3(k_out.cross(e1));  // forward or backward: any plane
    const Vec3 e1_plane = n.cross(k_out);
    return stokes_rotation(e1.dot(e1_plane), e1.dot(n));
  };
  for (int order = 1; order <= kMaxEvents; ++order) {
    bool ground = false, on_terrain = false;
    const double t_max = distance_to_boundary(p, d, ground, &on_terrain);
    const double rate =
        std::isfinite(t_max) ? std::max(majorant_, kPointsPerSegment / std::max(t_max, 1e-300)) : majorant_;
    double T = 1.0, t = 0.0;
    double t_real = -1.0, albedo_real = 0.0;
    Vec3 d_real = d;
    double scattering_real[kMaxComponents] = {};
    double sigma_s_real = 0.0;
    // Rotation from the sun's scattering plane to the segment's frame (the same at every point).
    MuellerMatrix sun_rotation = MuellerMatrix::Identity();
    if constexpr (kStokes) {
      Vec3 n;
      sun_rotation = scattering_plane(-sun_, -d, n);
    }
    if (rate > 0.0 && t_max > 0.0) {
      const double mu_sun = d.dot(sun_);
      while (true) {
        t += rng.exponential() / rate;
        if (t >= t_max) break;
        const Vec3 x = p + t * d;
        const double sigma_t = extinction_at(x);
        const double sigma_s = scattering_at(x, scattering);
        if (T > 0.0 && sigma_s > 0.0) {
          const double k = w * T * sigma_s / rate * E * transmittance_to_sun(x, rng);
          if constexpr (kStokes) {
            if (k > 0.0) {
              const ScatteringMatrix f = mixture_matrix(scattering, sigma_s, mu_sun);
              L += k * (M * (sun_rotation * Stokes(f.a1, f.b1, 0.0, 0.0)));
            }
          } else {
            L[0] += k * phase_to_sun(scattering, sigma_s, mu_sun);
          }
        }
        if (t_real < 0.0 && rng.uniform() * rate < sigma_t) {
          t_real = t;
          albedo_real = sigma_s / sigma_t;
          if (order != max_orders && sigma_s > 0.0) {
            if (sun_peak_share > 0.0) {
              // A mixture of the phase function about d and about the sun: the weight is the
              // phase function over the mixture's density (MonteCarloSettings::sun_peak_share).
              d_real = sample_scattering(scattering, sigma_s, rng.uniform() < sun_peak_share ? sun_ : d, rng);
              const double p_path = phase_to_sun(scattering, sigma_s, d_real.dot(d));
              const double p_sun = phase_to_sun(scattering, sigma_s, d_real.dot(sun_));
              albedo_real *= p_path / ((1.0 - sun_peak_share) * p_path + sun_peak_share * p_sun);
            } else {
              d_real = sample_scattering(scattering, sigma_s, d, rng);
            }
            if constexpr (kStokes) {
              std::copy(scattering, scattering + kMaxComponents, scattering_real);
              sigma_s_real = sigma_s;
            }
          }
        }
        if (T > 0.0) T = roulette(T * (1.0 - sigma_t / rate), rng);
        if (T == 0.0 && (t_real >= 0.0 || order == max_orders)) break;  // nothing more to score or to find
      }
    }
    if (ground) {
      const Vec3 g = p + t_max * d;
      const Vec3 n = on_terrain ? ground_normal(g) : up(g);
      const double cos_sun = n.dot(sun_);
      const double albedo = surface_albedo(g);
      if (cos_sun > 0.0 && albedo > 0.0) {
        // Lambertian: unpolarised whatever the light it reflects.
        const double k = w * T * albedo / kPi * E * cos_sun * transmittance_to_sun(snap_to_surface(g, on_terrain), rng);
        if constexpr (kStokes)
          L += k * M.col(0);
        else
          L[0] += k;
      }
    }
    if (order == max_orders) return L;
    if (t_real >= 0.0) {
      p += t_real * d;
      w *= albedo_real;
      if constexpr (kStokes) {
        if (sigma_s_real > 0.0) {
          // M <- M R F(mu) / p(mu): the direction was drawn from p = a1, the matrix's own phase function.
          Vec3 n;
          const MuellerMatrix rotation = scattering_plane(-d_real, -d, n);
          const ScatteringMatrix f = mixture_matrix(scattering_real, sigma_s_real, d_real.dot(d));
          M = M * rotation * (f.matrix() / f.a1);
          e1 = n.cross(-d_real);  // the plane's incoming frame
        }
      }
      d = d_real;
    } else if (ground) {
      const Vec3 g = p + t_max * d;
      const Vec3 n = on_terrain ? ground_normal(g) : up(g);
      w *= surface_albedo(g);
      p = snap_to_surface(g, on_terrain);
      // Cosine-distributed about the surface's normal: mu = sqrt(xi) (Malley's method).
      double mu = 0.0;
      do mu = std::sqrt(rng.uniform());
      while (mu <= 1e-9);
      d = rotate_about(n, mu, 2.0 * kPi * rng.uniform());
      if constexpr (kStokes) {
        // The reflected light is unpolarised: only I of the arriving light matters.
        M.rightCols<3>().setZero();
        e1 = frame_axis(-d, n);
      }
    } else {
      return L;  // into space: the sun is a point, never hit
    }
    if (w <= 0.0) return L;
    if (w < kRouletteWeight) {
      if (rng.uniform() * kRouletteWeight >= w) return L;
      w = kRouletteWeight;
    }
  }
  return L;
}

Vec3 MonteCarloIntegrator::snap_to_ground(Vec3 p) const {
  if (medium_.geometry == MonteCarloMedium::Geometry::PlaneParallel)
    p.z() = 0.0;
  else
    p *= medium_.planet_radius_m / p.norm();
  return p;
}

template <int N>
std::array<MonteCarloValue, N> MonteCarloIntegrator::estimate(ProbeKind kind, const Vec3& origin_m, const Vec3& dir,
                                                              const Vec3& reference, const MonteCarloSettings& s,
                                                              std::uint64_t stream) const {
  using Sum = Eigen::Matrix<double, N, 1>;
  if (s.paths < 2) throw Error("the Monte Carlo estimate needs at least 2 paths");
  if (!(s.sun_peak_share >= 0.0 && s.sun_peak_share <= 0.5))
    throw Error("the Monte Carlo's share of scatterings drawn about the sun must be within 0 to 0.5");
  const std::int64_t batches = (s.paths + kBatchPaths - 1) / kBatchPaths;
  std::vector<Sum> sum(static_cast<size_t>(batches)), sum_sq(static_cast<size_t>(batches));
  // An observer outside the medium starts where its line of sight enters it.
  Vec3 origin = origin_m;
  bool outside = false;
  if (kind == ProbeKind::Radiance && altitude(origin) > medium_.top_altitude_m) {
    outside = true;
    if (medium_.geometry == MonteCarloMedium::Geometry::SphericalShell) {
      const SphereHit h = intersect_sphere(origin, dir, medium_.planet_radius_m + medium_.top_altitude_m);
      if (h.hit && h.t_near_m >= 0.0) {
        origin += h.t_near_m * dir;
        outside = false;
      }
    } else if (dir.z() < 0.0) {
      origin += (origin.z() - medium_.top_altitude_m) / -dir.z() * dir;
      origin.z() = medium_.top_altitude_m;
      outside = false;
    }
  }
  const int threads = s.threads > 0 ? s.threads : tbb::this_task_arena::max_concurrency();
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, batches, 1), [&](const tbb::blocked_range<std::int64_t>& r) {
      for (std::int64_t b = r.begin(); b != r.end(); ++b) {
        throw_if_cancelled();
        Rng rng(s.seed, stream, static_cast<std::uint64_t>(b));
        const std::int64_t n = std::min(kBatchPaths, s.paths - b * kBatchPaths);
        Sum acc = Sum::Zero(), acc_sq = Sum::Zero();
        for (std::int64_t k = 0; k < n; ++k) {
          Sum x = Sum::Zero();
          if (kind == ProbeKind::Radiance) {
            if (!outside) x = path<N>(origin, dir, reference, s.max_orders, s.sun_peak_share, rng);
          } else {
            // E = integral of L cos over the hemisphere = pi x mean of L over cosine-distributed
            // directions; the observer looks along -(arrival direction), i.e. into the hemisphere.
            double mu = 0.0;
            do mu = std::sqrt(rng.uniform());
            while (mu <= 1e-9);
            const Vec3 look = rotate_about(dir, mu, 2.0 * kPi * rng.uniform());
            x = kPi * path<N>(origin, look, reference, s.max_orders, s.sun_peak_share, rng);
          }
          acc += x;
          acc_sq += x.cwiseProduct(x);
        }
        sum[static_cast<size_t>(b)] = acc;
        sum_sq[static_cast<size_t>(b)] = acc_sq;
      }
    });
  });
  // Batches in order: the same sums whatever the threads did.
  Sum total = Sum::Zero(), total_sq = Sum::Zero();
  for (std::int64_t b = 0; b < batches; ++b) {
    total += sum[static_cast<size_t>(b)];
    total_sq += sum_sq[static_cast<size_t>(b)];
  }
  const double n = static_cast<double>(s.paths);
  std::array<MonteCarloValue, N> values;
  for (int i = 0; i < N; ++i) {
    MonteCarloValue& v = values[static_cast<size_t>(i)];
    v.paths = s.paths;
    v.mean = total[i] / n;
    const double var = std::max(0.0, (total_sq[i] - total[i] * total[i] / n) / (n - 1.0));
    v.standard_error = std::sqrt(var / n);
  }
  return values;
}

MonteCarloValue MonteCarloIntegrator::radiance(const Vec3& origin_m, const Vec3& look, const MonteCarloSettings& s,
                                               std::uint64_t stream) const {
  return estimate<1>(ProbeKind::Radiance, origin_m, look.normalized(), Vec3::Zero(), s, stream)[0];
}

MonteCarloStokes MonteCarloIntegrator::stokes_radiance(const Vec3& origin_m, const Vec3& look, const Vec3& reference,
                                                       const MonteCarloSettings& s, std::uint64_t stream) const {
  return estimate<4>(ProbeKind::Radiance, origin_m, look.normalized(), reference, s, stream);
}

MonteCarloValue MonteCarloIntegrator::irradiance(const Vec3& origin_m, const Vec3& normal, const MonteCarloSettings& s,
                                                 std::uint64_t stream) const {
  return estimate<1>(ProbeKind::Irradiance, origin_m, normal.normalized(), Vec3::Zero(), s, stream)[0];
}

}  // namespace skyspec
