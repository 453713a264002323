#include "transport/single_scattering.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "base/quadrature.hpp"
#include "skyspec/atmosphere.hpp"
#include "skyspec/phase_function.hpp"
#include "skyspec/units.hpp"
#include "transport/multiple_scattering.hpp"  // gauss_legendre
#include "transport/optical_depth.hpp"
#include "transport/spherical_harmonics.hpp"

namespace skyspec {

ScatteringWorkspace::ScatteringWorkspace(int n)
    : view_tau(n),
      view_trans(n),
      source(n),
      ground_sun(n),
      ground_sky(n),
      sum_rayleigh(n),
      sum_mie(n),
      coarse_rayleigh(n),
      coarse_mie(n),
      sum_ms_rayleigh(n),
      sum_ms_mie(n),
      coarse_ms_rayleigh(n),
      coarse_ms_mie(n),
      sum_ms_q(n),
      coarse_ms_q(n),
      sum_ms_u(n),
      coarse_ms_u(n),
      sum_ms_mq(n),
      coarse_ms_mq(n),
      sum_ms_mu(n),
      coarse_ms_mu(n),
      phase(n),
      parts(n) {}

Vec3 polarisation_frame(const Vec3& view, const Vec3& sun) {
  const Vec3 k = -view;
  Vec3 e1 = sun - sun.dot(k) * k;
  if (e1.norm() > 1e-9) return e1.normalized();
  // The sun on the view's axis: any perpendicular, the same for the same view.
  e1 = k.cross(std::abs(k.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0));
  return e1.normalized();
}

SingleScattering::SingleScattering(const AtmosphereModel& atm, const SunColumns& sun_columns, IntegratorSettings s)
    : atm_(atm),
      sun_(sun_columns),
      settings_(s),
      sca_rayleigh_(atm.rayleigh().scattering_per_m.cast<float>()),
      sca_mie_(atm.mie().scattering_per_m.cast<float>()),
      albedo_over_pi_((atm.ground_albedo() / kPi).cast<float>()) {
  // The Rayleigh phase function per wavelength as A + B mu^2 (phase_function.hpp, Chandrasekhar).
  const SpectrumD& gamma = atm.rayleigh_phase_gamma();
  const SpectrumD scale = 3.0 / (16.0 * kPi * (1.0 + 2.0 * gamma));
  rayleigh_phase_a_ = (scale * (1.0 + 3.0 * gamma)).cast<float>();
  rayleigh_phase_b_ = (scale * (1.0 - gamma)).cast<float>();
  {
    std::vector<double> mu, w;
    gauss_legendre(512, -1.0, 1.0, mu, w);
    mie_spin2_moment_.resize(gamma.size());
    for (Eigen::Index i = 0; i < gamma.size(); ++i) {
      double sum = 0.0;
      for (size_t k = 0; k < mu.size(); ++k)
        sum += w[k] * atm.mie_phase_at(static_cast<int>(i), mu[k]) * (1.0 + mu[k]) * (1.0 + mu[k]) / 4.0;
      mie_spin2_moment_[i] = static_cast<float>(2.0 * kPi * sum);
    }
  }
  ext_[kRayleigh] = atm.rayleigh().extinction_per_m.cast<float>();
  ext_[kMie] = atm.mie().extinction_per_m.cast<float>();
  ext_[kOzone] = atm.ozone().extinction_per_m.cast<float>();
}

namespace {

// The single-scattering integrand of species s on a segment [a, b] of the view ray is
// f(t) = rho_s(t) T(t), T the transmittance along view and sun paths; ln f is nearly linear in t,
// so its integral over the segment is dt * logmean(f_a, f_b) with x = ln f_a - ln f_b
// = (ln rho_a - ln rho_b) - (tau_a - tau_b) (log_mean_branchless, optical_depth.hpp).
//
// A piece of the ray is integrated all at once: the optical depths and transmittances of all its
// nodes at all wavelengths are one array, so that exp() runs over the whole of it, and the sums
// over segments are vector loops over nodes (few wavelengths: [node, wavelength], a wavelength's
// nodes contiguous; three for the RGB-fast path) or over wavelengths (many: [wavelength, node]).
using NodeArray = Eigen::ArrayXXf;
constexpr Eigen::Index kWavelengthsForWavelengthLoops = 8;  // one AVX vector of floats

}  // namespace

// What the segments of a piece share at every wavelength: lengths, densities and their log
// ratios, for the fine rule (nodes k, k + 1) and the coarse one (nodes 2j, 2j + 2). In a named
// namespace: SingleScattering::PieceScratch (a member type) holds one.
namespace detail {
struct PieceSegments {
  int segments = 0;
  Eigen::ArrayXf dt, rho[2], log_ratio[2];  // fine: [k]; rho: [node]
  Eigen::ArrayXf dt2, log_ratio2[2];        // coarse: [j]
  Eigen::ArrayXf terms_r, terms_m;          // scratch
};
}  // namespace detail

namespace {
using detail::PieceSegments;

inline float log_mean_term(float x, float f_a, float f_b) { return log_mean_branchless(f_a, f_b, x, 1e-2f); }

// out[j] = dt[j] logmean over nodes a = j s, b = (j + 1) s (s = stride: 1 for the fine rule, 2 for
// the coarse one) of both species' integrands, for one wavelength. A separate function with
// plain pointers so that GCC vectorises it.
void log_mean_terms(int count, int stride, const float* __restrict tau, const float* __restrict trans,
                    const float* __restrict rho_r, const float* __restrict rho_m, const float* __restrict x_r,
                    const float* __restrict x_m, const float* __restrict dt, float* __restrict out_r,
                    float* __restrict out_m) {
  if (stride == 1) {
    for (int j = 0; j < count; ++j) {
      const float dtau = tau[j] - tau[j + 1];
      out_r[j] = dt[j] * log_mean_term(x_r[j] - dtau, rho_r[j] * trans[j], rho_r[j + 1] * trans[j + 1]);
      out_m[j] = dt[j] * log_mean_term(x_m[j] - dtau, rho_m[j] * trans[j], rho_m[j + 1] * trans[j + 1]);
    }
    return;
  }
  for (int j = 0; j < count; ++j) {
    const int a = j * stride, b = a + stride;
    const float dtau = tau[a] - tau[b];
    out_r[j] = dt[j] * log_mean_term(x_r[j] - dtau, rho_r[a] * trans[a], rho_r[b] * trans[b]);
    out_m[j] = dt[j] * log_mean_term(x_m[j] - dtau, rho_m[a] * trans[a], rho_m[b] * trans[b]);
  }
}

// Adds the fine and coarse log-mean sums over the piece's segments of both species, per
// wavelength. tau and trans: [node, wavelength], loops over nodes.
void accumulate_piece(const NodeArray& tau, const NodeArray& trans, PieceSegments& g, Spectrum& fine_r,
                      Spectrum& fine_m, Spectrum& coarse_r, Spectrum& coarse_m) {
  const int segs = g.segments, pairs = segs / 2;
  g.terms_r.resize(segs);
  g.terms_m.resize(segs);
  for (Eigen::Index l = 0; l < tau.cols(); ++l) {
    const float* ta = tau.col(l).data();
    const float* ea = trans.col(l).data();
    log_mean_terms(segs, 1, ta, ea, g.rho[0].data(), g.rho[1].data(), g.log_ratio[0].data(), g.log_ratio[1].data(),
                   g.dt.data(), g.terms_r.data(), g.terms_m.data());
    fine_r[l] += g.terms_r.head(segs).sum();
    fine_m[l] += g.terms_m.head(segs).sum();
    log_mean_terms(pairs, 2, ta, ea, g.rho[0].data(), g.rho[1].data(), g.log_ratio2[0].data(), g.log_ratio2[1].data(),
                   g.dt2.data(), g.terms_r.data(), g.terms_m.data());
    coarse_r[l] += g.terms_r.head(pairs).sum();
    coarse_m[l] += g.terms_m.head(pairs).sum();
  }
}

// The same for [wavelength, node] arrays (each node's wavelengths contiguous), segment by
// segment, every loop over wavelengths: the better order when there are many wavelengths and
// few nodes (the scattering-order tables' rays have 24 segments).
void segment_over_wavelengths(Eigen::Index n, const float* __restrict ta, const float* __restrict ea,
                              const float* __restrict tb, const float* __restrict eb, float x_r, float r_a, float r_b,
                              float x_m, float m_a, float m_b, float dt, float* __restrict out_r,
                              float* __restrict out_m) {
  for (Eigen::Index l = 0; l < n; ++l) {
    const float dtau = ta[l] - tb[l];
    out_r[l] += dt * log_mean_term(x_r - dtau, r_a * ea[l], r_b * eb[l]);
    out_m[l] += dt * log_mean_term(x_m - dtau, m_a * ea[l], m_b * eb[l]);
  }
}
// One species' half of segment_over_wavelengths (a higher-order pass weights one species).
void segment_one_species(Eigen::Index n, const float* __restrict ta, const float* __restrict ea,
                         const float* __restrict tb, const float* __restrict eb, float x, float rho_a, float rho_b,
                         float dt, float* __restrict out) {
  for (Eigen::Index l = 0; l < n; ++l) out[l] += dt * log_mean_term(x - (ta[l] - tb[l]), rho_a * ea[l], rho_b * eb[l]);
}
// The fine and coarse sums of species sp only, [wavelength, node] arrays.
void accumulate_species_by_wavelength(const NodeArray& tau, const NodeArray& trans, const PieceSegments& g, int sp,
                                      Spectrum& fine, Spectrum& coarse) {
  const Eigen::Index n = tau.rows();
  const float* rho = g.rho[sp].data();
  for (int k = 0; k < g.segments; ++k)
    segment_one_species(n, tau.col(k).data(), trans.col(k).data(), tau.col(k + 1).data(), trans.col(k + 1).data(),
                        g.log_ratio[sp][k], rho[k], rho[k + 1], g.dt[k], fine.data());
  for (int j = 0; j < g.segments / 2; ++j) {
    const int a = 2 * j, b = 2 * j + 2;
    segment_one_species(n, tau.col(a).data(), trans.col(a).data(), tau.col(b).data(), trans.col(b).data(),
                        g.log_ratio2[sp][j], rho[a], rho[b], g.dt2[j], coarse.data());
  }
}

void accumulate_piece_by_wavelength(const NodeArray& tau, const NodeArray& trans, const PieceSegments& g,
                                    Spectrum& fine_r, Spectrum& fine_m, Spectrum& coarse_r, Spectrum& coarse_m) {
  const Eigen::Index n = tau.rows();
  const float* rr = g.rho[0].data();
  const float* rm = g.rho[1].data();
  for (int k = 0; k < g.segments; ++k)
    segment_over_wavelengths(n, tau.col(k).data(), trans.col(k).data(), tau.col(k + 1).data(), trans.col(k + 1).data(),
                             g.log_ratio[0][k], rr[k], rr[k + 1], g.log_ratio[1][k], rm[k], rm[k + 1], g.dt[k],
                             fine_r.data(), fine_m.data());
  for (int j = 0; j < g.segments / 2; ++j) {
    const int a = 2 * j, b = 2 * j + 2;
    segment_over_wavelengths(n, tau.col(a).data(), trans.col(a).data(), tau.col(b).data(), trans.col(b).data(),
                             g.log_ratio2[0][j], rr[a], rr[b], g.log_ratio2[1][j], rm[a], rm[b], g.dt2[j],
                             coarse_r.data(), coarse_m.data());
  }
}

}  // namespace

void SingleScattering::transmittance_to_space(const Vec3& o, const Vec3& d, Spectrum& out) const {
  const double R = atm_.planet_radius_m(), Rt = atm_.top_radius_m();
  out.setOnes();
  if (sphere_entry_distance(o, d, R) < std::numeric_limits<double>::infinity()) {  // the ground is in the way
    out.setZero();
    return;
  }
  const SphereHit top = intersect_sphere(o, d, Rt);
  if (!top.hit || top.t_far_m <= 0.0) return;
  // Columns from the entry point (or the origin, inside) to the exit.
  const Vec3 start = o + std::max(0.0, top.t_near_m) * d;
  const double r = std::min(start.norm(), Rt);
  const Columns c = columns_to_top_m(atm_, r, start.dot(d) / start.norm(), 256);
  Spectrum tau = ext_[kRayleigh] * static_cast<float>(c[kRayleigh]) + ext_[kMie] * static_cast<float>(c[kMie]) +
                 ext_[kOzone] * static_cast<float>(c[kOzone]);
  out = (-tau).exp();
}

void SingleScattering::radiance(const Vec3& o, const Vec3& d, const Vec3& s, const Spectrum& sun_irradiance,
                                const ScatteringSources& sources, ScatteringWorkspace& ws, Spectrum& out) const {
  radiance_parts(o, d, s, sources, ws, ws.parts);
  combine(ws.parts, d.dot(s), sun_irradiance, ws, out);
}

namespace {
// L = E_sun [p_R rayleigh + p_M mie + phase_free] for one direction's parts (n values each), with
// the aerosol's phase per wavelength where pm_spectral is given.
// The Rayleigh phase per wavelength is pr_a + pr_b mu^2 (the constructor's A and B).
void combine_parts(Eigen::Index n, const float* rayleigh, const float* mie, const float* phase_free,
                   const Spectrum& pr_a, const Spectrum& pr_b, float mu2, float pm, const Spectrum* pm_spectral,
                   const Spectrum& sun_irradiance, float* out) {
  using In = Eigen::Map<const Spectrum>;
  Eigen::Map<Spectrum> o(out, n);
  if (pm_spectral)
    o = (In(rayleigh, n) * (pr_a + pr_b * mu2) + In(mie, n) * *pm_spectral + In(phase_free, n)) * sun_irradiance;
  else
    o = (In(rayleigh, n) * (pr_a + pr_b * mu2) + In(mie, n) * pm + In(phase_free, n)) * sun_irradiance;
}

// The aerosol's phase function differs per wavelength: tabulated (microphysics), or an analytic
// model whose asymmetry differs per wavelength.
bool mie_phase_is_spectral(const AtmosphereModel& atm) { return atm.mie_matrix() || atm.mie_g_varies(); }

void spectral_mie_phase(const AtmosphereModel& atm, double mu, Spectrum& phase) {
  if (const TabulatedScatteringMatrix* table = atm.mie_matrix()) {
    const TabulatedScatteringMatrix::Position at = table->locate(mu);
    for (int i = 0; i < phase.size(); ++i) phase[i] = static_cast<float>(table->phase(i, at));
    return;
  }
  AerosolPhase p = atm.mie_phase();
  for (int i = 0; i < phase.size(); ++i) {
    p.g = atm.mie_g()[i];
    phase[i] = static_cast<float>(p(mu));
  }
}
}  // namespace

void SingleScattering::combine(const RadianceParts& parts, double mu, const Spectrum& sun_irradiance,
                               ScatteringWorkspace& ws, Spectrum& out) const {
  const Eigen::Index n = parts.rayleigh.size();
  out.resize(n);
  const bool varies = mie_phase_is_spectral(atm_);
  if (varies) spectral_mie_phase(atm_, mu, ws.phase);
  const float phase_m = varies ? 0.0f : static_cast<float>(atm_.mie_phase()(mu));
  combine_parts(n, parts.rayleigh.data(), parts.mie.data(), parts.phase_free.data(), rayleigh_phase_a_,
                rayleigh_phase_b_, static_cast<float>(mu * mu), phase_m, varies ? &ws.phase : nullptr, sun_irradiance,
                out.data());
}

void SingleScattering::stokes(const RadianceParts& parts, const Vec3& view, const Vec3& sun, const Vec3& e1,
                              const Spectrum& sun_irradiance, ScatteringWorkspace& ws, Spectrum& I, Spectrum& Q,
                              Spectrum& U) const {
  const double mu = view.dot(sun);
  combine(parts, mu, sun_irradiance, ws, I);
  // From the parts' frame (e1p, k x e1p) into (e1, k x e1): turned by psi with cos psi = e1 . e1p,
  // sin psi = e1 . e2p (stokes_rotation): Q' = Q cos 2psi + U sin 2psi, U' = -Q sin 2psi + U cos 2psi.
  const Vec3 k = -view;
  const Vec3 e1p = polarisation_frame(view, sun), e2p = k.cross(e1p);
  const double c = e1.dot(e1p), s = e1.dot(e2p);
  const float c2 = static_cast<float>(c * c - s * s), s2 = static_cast<float>(2.0 * c * s);
  // Order 1 in the parts' frame, which contains the scattering plane: Q = E rayleigh b1(mu), U = 0.
  Spectrum q_plane = -(rayleigh_phase_b_ * static_cast<float>(1.0 - mu * mu)) * parts.rayleigh * sun_irradiance;
  // An aerosol from microphysics polarises its order-1 light too: Q = E mie b1_M(mu).
  if (const TabulatedScatteringMatrix* table = atm_.mie_matrix()) {
    const TabulatedScatteringMatrix::Position at = table->locate(mu);
    for (Eigen::Index i = 0; i < q_plane.size(); ++i)
      q_plane[i] += static_cast<float>(table->b1(static_cast<int>(i), at)) * parts.mie[i] * sun_irradiance[i];
  }
  Spectrum u_plane = Spectrum::Zero(q_plane.size());
  if (parts.polarised_q.size() == q_plane.size()) {
    q_plane += parts.polarised_q * sun_irradiance;
    u_plane += parts.polarised_u * sun_irradiance;
  }
  Q = c2 * q_plane + s2 * u_plane;
  U = -s2 * q_plane + c2 * u_plane;
}

void SingleScattering::combine_many(int count, const float* packed, const double* mu, const bool* use,
                                    const Spectrum& sun_irradiance, float* const* out, ScatteringWorkspace& ws) const {
  const Eigen::Index n = sca_rayleigh_.size();
  const bool varies = mie_phase_is_spectral(atm_);
  const AerosolPhase mie = atm_.mie_phase();
  const bool hg = mie.model == AerosolPhase::Model::HenyeyGreenstein;
  constexpr int kChunk = 64;
  double pm[kChunk];
  for (int first = 0; first < count; first += kChunk) {
    const int m = std::min(kChunk, count - first);
    const double* u = mu + first;
    if (hg)
      for (int k = 0; k < m; ++k) pm[k] = henyey_greenstein_phase(u[k], mie.g);
    else
      for (int k = 0; k < m; ++k) pm[k] = cornette_shanks_phase(u[k], mie.g);
    for (int k = 0; k < m; ++k) {
      if (!use[first + k]) continue;
      if (varies) spectral_mie_phase(atm_, u[k], ws.phase);
      const float* p = packed + static_cast<size_t>(first + k) * 3 * static_cast<size_t>(n);
      combine_parts(n, p, p + n, p + 2 * n, rayleigh_phase_a_, rayleigh_phase_b_, static_cast<float>(u[k] * u[k]),
                    static_cast<float>(pm[k]), varies ? &ws.phase : nullptr, sun_irradiance, out[first + k]);
    }
  }
}

// A node of the quadrature: a point on the view ray, its densities, and the view-ray columns
// from the start of the ray to it.
struct SingleScattering::Node {
  double t;
  double r;
  double log_rho[2];  // Rayleigh, Mie
  double rho[2];      // exp(log_rho), once per node
  double rho_ozone;
  double col[kSpeciesCount];
};

// A stretch of the ray between cuts, lit by the sun or in the planet's shadow, and its nodes:
// nodes[first_node .. first_node + segments].
struct SingleScattering::Piece {
  double t0, t1;
  bool lit;
  int first_node = 0, segments = 0;
};

struct SingleScattering::Ray {
  double t_begin = 0.0, t_end = 0.0;
  bool hits_ground = false;  // ends on the ground (the last node is the ground point)
  Piece pieces[8];
  int n_pieces = 0;
  std::vector<Node> nodes;
};

// Where the ray o + t d runs in the atmosphere (up to the ground if it hits it, or up to a surface
// at max_distance_m), cut into pieces at the shadow boundaries (closed form) and at the ray's
// lowest point. False when there is nothing to integrate.
bool SingleScattering::trace(const Vec3& o, const Vec3& d, const Vec3& s, const ScatteringSources& sources,
                             Ray& ray) const {
  const double R = atm_.planet_radius_m(), Rt = atm_.top_radius_m();
  ray.n_pieces = 0;
  const SphereHit top = intersect_sphere(o, d, Rt);
  if (!top.hit || top.t_far_m <= 0.0) return false;
  const double t_begin = std::max(0.0, top.t_near_m);
  double t_end = top.t_far_m;
  bool hits_ground = false;
  const double t_ground = sphere_entry_distance(o, d, R);
  if (t_ground < t_end) {
    t_end = t_ground;
    hits_ground = true;
  }
  if (sources.max_distance_m < t_end) {
    t_end = sources.max_distance_m;
    hits_ground = false;
  }
  if (hits_ground && t_end == 0.0 && t_begin == 0.0) {
    // A camera on the ground (height 0) looking below the horizontal: the ground at the camera,
    // with no air in front of it. No pieces; the one node is the ground point (place_nodes,
    // integrate: only the ground's reflection).
    ray.t_begin = ray.t_end = 0.0;
    ray.hits_ground = true;
    return true;
  }
  if (!(t_end > t_begin)) return false;
  ray.t_begin = t_begin;
  ray.t_end = t_end;
  ray.hits_ground = hits_ground;

  // Shadowed pieces carry only higher-order light; without it they matter only for the view
  // columns. Without higher orders, a ray entirely in shadow sees nothing (its ground point is
  // dark too).
  const IntervalSet lit = lit_intervals(o, d, t_begin, t_end, s, R);
  if (!sources.higher && lit.count == 0 && !sources.transmittance) return false;
  const double t_low = -o.dot(d);
  double cuts[6];
  bool cut_lit[6];
  int n = 0;
  double t = t_begin;
  for (int i = 0; i < lit.count; ++i) {
    if (lit.parts[i].t0_m > t) {
      cuts[n] = lit.parts[i].t0_m;
      cut_lit[n++] = false;  // [t, t0] dark
    }
    cuts[n] = lit.parts[i].t1_m;
    cut_lit[n++] = true;
    t = lit.parts[i].t1_m;
  }
  if (t < t_end) {
    cuts[n] = t_end;
    cut_lit[n++] = false;
  }
  double a = t_begin;
  for (int i = 0; i < n; ++i) {
    const double b = cuts[i];
    if (t_low > a && t_low < b) {
      ray.pieces[ray.n_pieces++] = {a, t_low, cut_lit[i]};
      a = t_low;
    }
    ray.pieces[ray.n_pieces++] = {a, b, cut_lit[i]};
    a = b;
  }
  return true;
}

// The nodes: on pieces where light is collected, view_segments in all, shared in proportion to
// length (an even number per piece, so that pairs of segments form the coarse rule); on the
// others 8, which only carry the view columns across. Densities once per node; the columns by
// the log-mean rule for the positive profiles, the trapezoid rule for ozone.
void SingleScattering::place_nodes(const Vec3& o, const Vec3& d, const ScatteringSources& sources, Ray& ray) const {
  const double R = atm_.planet_radius_m();
  const DensityProfile& prof_r = atm_.rayleigh().profile;
  const DensityProfile& prof_m = atm_.mie().profile;
  const DensityProfile& prof_o = atm_.ozone().profile;
  const bool ozone = atm_.ozone().enabled();
  const bool higher = sources.higher != nullptr;
  auto make_node = [&](double t) {
    Node n;
    n.t = t;
    n.r = (o + t * d).norm();
    const double alt = n.r - R;
    n.log_rho[0] = prof_r.log_relative(alt);
    n.log_rho[1] = prof_m.log_relative(alt);
    n.rho[0] = std::exp(n.log_rho[0]);
    n.rho[1] = std::exp(n.log_rho[1]);
    n.rho_ozone = ozone ? prof_o.relative(alt) : 0.0;
    return n;
  };
  auto append = [&](double t) {
    Node next = make_node(t);
    const Node& prev = ray.nodes.back();
    const double dt = next.t - prev.t;
    for (int k = 0; k < 2; ++k)
      next.col[k] = prev.col[k] + dt * log_mean(prev.rho[k], next.rho[k], prev.log_rho[k] - next.log_rho[k]);
    next.col[kOzone] = prev.col[kOzone] + 0.5 * dt * (prev.rho_ozone + next.rho_ozone);
    ray.nodes.push_back(next);
  };

  double total_len = 0.0;
  for (int i = 0; i < ray.n_pieces; ++i)
    if (ray.pieces[i].lit || higher) total_len += ray.pieces[i].t1 - ray.pieces[i].t0;
  ray.nodes.clear();
  Node first = make_node(ray.t_begin);
  first.col[kRayleigh] = first.col[kMie] = first.col[kOzone] = 0.0;
  ray.nodes.push_back(first);
  for (int i = 0; i < ray.n_pieces; ++i) {
    Piece& pc = ray.pieces[i];
    const bool collect = (sources.single && pc.lit) || higher;
    int segs = 8;
    if (collect) {
      segs = std::max(2, static_cast<int>(std::lround(settings_.view_segments * (pc.t1 - pc.t0) / total_len)));
      segs += segs % 2;
    }
    pc.first_node = static_cast<int>(ray.nodes.size()) - 1;
    pc.segments = segs;
    thread_local std::vector<double> positions;
    positions.resize(static_cast<size_t>(segs) + 1);
    if (collect) {
      piece_node_positions(o, d, pc.t0, pc.t1, segs, positions.data());
    } else {
      for (int k = 0; k <= segs; ++k) positions[static_cast<size_t>(k)] = pc.t0 + (pc.t1 - pc.t0) * k / segs;
    }
    for (int k = 1; k <= segs; ++k) append(k == segs ? pc.t1 : positions[static_cast<size_t>(k)]);
  }
}

// Where a piece's nodes lie: uniform in s(t) = (t - t0) / (t1 - t0) + c_R(t) / c_R(t1) + c_M(t) / c_M(t1),
// the share of the piece's length plus the shares of its Rayleigh and aerosol columns (c_s(t), the
// column of species s from t0 to t, for each species that scatters). A ray that runs low through
// dense air gets short segments there, where its integrand is large and its optical depth grows
// fastest, and at least a third of the nodes stay spread over its length. The columns come from a
// pilot of kPilotsPerSegment x segments + 1 points uniform in t, and s is inverted linearly between
// them. Nothing here depends on the wavelengths (adding one to the grid moves no node), and the
// sun only through the piece's ends (the shadow's edges).
void SingleScattering::piece_node_positions(const Vec3& o, const Vec3& d, double t0, double t1, int segments,
                                            double* t) const {
  const double R = atm_.planet_radius_m();
  const DensityProfile* profiles[2] = {&atm_.rayleigh().profile, &atm_.mie().profile};
  const bool weighted[2] = {atm_.rayleigh().enabled(), atm_.mie().enabled()};
  const int pilots = kPilotsPerSegment * segments;
  const double dt = (t1 - t0) / pilots;
  thread_local std::vector<double> rho[2], share;
  for (auto* v : {&rho[0], &rho[1], &share}) v->assign(static_cast<size_t>(pilots) + 1, 0.0);
  for (int k = 0; k <= pilots; ++k) {
    const double alt = (o + (t0 + dt * k) * d).norm() - R;
    for (int sp = 0; sp < 2; ++sp)
      if (weighted[sp]) rho[sp][static_cast<size_t>(k)] = std::exp(profiles[sp]->log_relative(alt));
  }
  // The columns by the trapezoid rule (they only place the nodes), then each species' share.
  double total[2] = {0.0, 0.0};
  for (int sp = 0; sp < 2; ++sp)
    for (int k = 1; k <= pilots; ++k)
      total[sp] += 0.5 * (rho[sp][static_cast<size_t>(k) - 1] + rho[sp][static_cast<size_t>(k)]);
  double running[2] = {0.0, 0.0};
  for (int k = 1; k <= pilots; ++k) {
    double v = static_cast<double>(k) / pilots;
    for (int sp = 0; sp < 2; ++sp) {
      if (!(total[sp] > 0.0)) continue;
      running[sp] += 0.5 * (rho[sp][static_cast<size_t>(k) - 1] + rho[sp][static_cast<size_t>(k)]);
      v += running[sp] / total[sp];
    }
    share[static_cast<size_t>(k)] = v;
  }
  const double end = share[static_cast<size_t>(pilots)];
  t[0] = t0;
  t[segments] = t1;
  int j = 0;
  for (int k = 1; k < segments; ++k) {
    const double target = end * k / segments;
    while (j + 1 < pilots && share[static_cast<size_t>(j) + 1] < target) ++j;
    const double a = share[static_cast<size_t>(j)], b = share[static_cast<size_t>(j) + 1];
    const double f = b > a ? std::clamp((target - a) / (b - a), 0.0, 1.0) : 0.0;
    t[k] = t0 + dt * (j + f);
  }
}

// The integrals over the nodes for the direction d (the nodes' positions and columns may come
// from another ray with the same altitude profile: only the sun's angle is taken from d here).
namespace {

// A piece's segment lengths, densities and log density ratios, for the fine rule (nodes k, k + 1)
// and the coarse one (nodes 2j, 2j + 2).
template <typename NodeT>
void fill_piece_segments(const NodeT* nodes, int segs, PieceSegments& g) {
  const int m = segs + 1;
  g.segments = segs;
  g.dt.resize(segs);
  g.dt2.resize(segs / 2);
  for (int sp = 0; sp < 2; ++sp) {
    g.rho[sp].resize(m);
    g.log_ratio[sp].resize(segs);
    g.log_ratio2[sp].resize(segs / 2);
    for (int k = 0; k < m; ++k) g.rho[sp][k] = static_cast<float>(nodes[k].rho[sp]);
    for (int k = 0; k < segs; ++k)
      g.log_ratio[sp][k] = static_cast<float>(nodes[k].log_rho[sp] - nodes[k + 1].log_rho[sp]);
    for (int j = 0; j < segs / 2; ++j)
      g.log_ratio2[sp][j] = static_cast<float>(nodes[2 * j].log_rho[sp] - nodes[2 * j + 2].log_rho[sp]);
  }
  for (int k = 0; k < segs; ++k) g.dt[k] = static_cast<float>(nodes[k + 1].t - nodes[k].t);
  for (int j = 0; j < segs / 2; ++j) g.dt2[j] = static_cast<float>(nodes[2 * j + 2].t - nodes[2 * j].t);
}

}  // namespace

// Per thread, reused from ray to ray: [node, species] columns, [node, wavelength] arrays (or
// [wavelength, node] with many wavelengths: by_node false, see accumulate_piece).
struct SingleScattering::PieceScratch {
  bool by_node = true;
  bool ozone = false;
  PieceSegments seg;
  Eigen::ArrayXXf columns, view_columns;
  NodeArray tau, trans, source, view_tau, view_trans;
  std::vector<double> node_r, node_mu_sun;  // the sun columns' arguments at a piece's nodes
  std::vector<Columns> sun;
  Eigen::ArrayXXf source_t, source_mie_t;    // [wavelength, node], as the source tables write them
  Eigen::ArrayXXf source_q_t, source_u_t;    // J_R + P_Q, J_R + P_U (polarised_sources)
  Eigen::ArrayXXf source_mq_t, source_mu_t;  // J_M + P_M,Q, J_M + P_M,U
  std::vector<float> moments;                // InScatteringSource::rayleigh_moments at one node
  Spectrum q, u, pq, pu;                     // polarised_sources' sums at one node
  Spectrum unused[4];                        // the other species' sums of a higher-order pass
};

// tau = sum_s beta_ext,s(l) columns[k, s] (the optical depth), as [node k, wavelength l] or [l, k].
void SingleScattering::optical_depths(const Eigen::ArrayXXf& columns, PieceScratch& sc, NodeArray& tau) const {
  const Eigen::Index m = columns.rows(), n = sca_rayleigh_.size();
  if (sc.by_node) {
    tau.resize(m, n);
    for (Eigen::Index l = 0; l < n; ++l) {
      tau.col(l) = columns.col(kRayleigh) * ext_[kRayleigh][l] + columns.col(kMie) * ext_[kMie][l];
      if (sc.ozone) tau.col(l) += columns.col(kOzone) * ext_[kOzone][l];
    }
    return;
  }
  tau.resize(n, m);
  for (Eigen::Index k = 0; k < m; ++k) {
    tau.col(k) = ext_[kRayleigh] * columns(k, kRayleigh) + ext_[kMie] * columns(k, kMie);
    if (sc.ozone) tau.col(k) += ext_[kOzone] * columns(k, kOzone);
  }
}

// Single scattering on one lit piece: the integrand of species s is rho_s exp(-tau_view - tau_sun);
// its fine and coarse log-mean sums are added to `sums` (fine R, fine M, coarse R, coarse M).
void SingleScattering::single_scattering_piece(const Node* nodes, int m, double os, double ds, PieceScratch& sc,
                                               Spectrum* sums[4]) const {
  const int species = sc.ozone ? 3 : 2;
  sc.columns.resize(m, species);
  sc.node_r.resize(static_cast<size_t>(m));
  sc.node_mu_sun.resize(static_cast<size_t>(m));
  sc.sun.resize(static_cast<size_t>(m));
  for (int k = 0; k < m; ++k) {
    sc.node_r[static_cast<size_t>(k)] = nodes[k].r;
    sc.node_mu_sun[static_cast<size_t>(k)] = (os + nodes[k].t * ds) / nodes[k].r;
  }
  sun_.at_many(m, sc.node_r.data(), sc.node_mu_sun.data(), sc.sun.data());
  for (int k = 0; k < m; ++k)
    for (int sp = 0; sp < species; ++sp)
      sc.columns(k, sp) = static_cast<float>(nodes[k].col[sp] + sc.sun[static_cast<size_t>(k)][sp]);
  optical_depths(sc.columns, sc, sc.tau);
  sc.trans = (-sc.tau).exp();
  accumulate(sc, sums);
}

// Higher orders on one piece: the integrand of species s is beta_sca,s rho_s exp(-tau_view) J_s,
// J_s the higher-order source of that species in the ray's direction. It is integrated by the same
// log-mean rule as single scattering, with tau' = tau_view - ln J_s in the place of the optical
// depth and T' = exp(-tau_view) J_s in the place of the transmittance (ln of the integrand is
// ln rho_s - tau' + const), once per species. J is floored at a tiny positive value so that its
// logarithm is finite where the tables hold no light.
// The view ray and the Stokes frame of its polarised parts (polarisation_frame).
struct SingleScattering::RayFrame {
  Vec3 o, d, s, e1, e2;
};

// The higher orders' polarised sources at a piece's nodes (RadianceParts::polarised_q):
// source_q_t, source_u_t become J_R + P_Q, J_R + P_U for the air and source_mq_t, source_mu_t
// J_M + P_M,Q, J_M + P_M,U for the aerosol. For Rayleigh's matrix with the King factor's
// depolarisation, light arriving with coherency matrices C(w) is scattered towards k as
//
//   I = 2 B tr(P D P) + (A - B) tr D,   Q = 2 B (e1^T D e1 - e2^T D e2),   U = 4 B e1^T D e2,
//
// with D = integral C(w) dw, P = 1 - k k^T and A + B mu^2 the phase function (at one unpolarised
// direction these are a1 and b1 of physics/scattering_matrix.hpp). The unpolarised part of D is
// (tr T 1 - T) / 2 with T the field's second moments, whose traceless part is sum_m a_2m K_m
// (spherical_harmonics.hpp); the scalar source J_R already holds its intensity, and the polarised
// part D_pol (traceless) adds -2 B k^T D_pol k to it (SourceTable::source adds that for polarised
// tables, so that the intensity is the vector one in every render). The aerosol's unit matrix acts
// on the polarisation's degree-2 E-mode, rebuilt from D_pol (below). At each node the tables' local
// frame (z up, x towards the sun's azimuth, y = z x x) is rebuilt and e1, e2 are expressed in it.
// J + P is not negative for a real field (scattered light is at most fully polarised), which lets
// the log-mean rule integrate it; P is the difference of two such integrals. (The aerosol's source,
// from a truncated field, is not bound to that: where J_M + P_M would go below zero the rule's
// floor of 1e-30 clips it, an error the comparison with the reference includes.) False if
// `higher` does not resolve the quadrupole.
bool SingleScattering::polarised_sources(const Node* nodes, int m, const RayFrame& f, const InScatteringSource& higher,
                                         PieceScratch& sc) const {
  const Eigen::Index n = sca_rayleigh_.size();
  const auto& K = quadrupole_tensors();
  // D_pol's components xx, yy, xz as tensors (zz = -xx - yy).
  static const std::array<Eigen::Matrix3d, 3> E = [] {
    std::array<Eigen::Matrix3d, 3> e;
    e[0] << 1, 0, 0, 0, 0, 0, 0, 0, -1;
    e[1] << 0, 0, 0, 0, 1, 0, 0, 0, -1;
    e[2] << 0, 0, 1, 0, 0, 0, 1, 0, 0;
    return e;
  }();
  sc.moments.resize(6 * static_cast<size_t>(n));
  sc.source_q_t.resize(n, m);
  sc.source_u_t.resize(n, m);
  sc.source_mq_t.resize(n, m);
  sc.source_mu_t.resize(n, m);
  for (int k = 0; k < m; ++k) {
    const Vec3 p = f.o + nodes[k].t * f.d;
    const Vec3 z = p / p.norm();
    if (!higher.rayleigh_moments(nodes[k].r, f.s.dot(z), sc.moments.data())) return false;
    Vec3 x = f.s - f.s.dot(z) * z;
    if (x.norm() < 1e-9) x = z.cross(std::abs(z.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0));  // sun at the zenith
    x.normalize();
    const Vec3 y = z.cross(x);
    const Vec3 e(f.e1.dot(x), f.e1.dot(y), f.e1.dot(z)), g(f.e2.dot(x), f.e2.dot(y), f.e2.dot(z));
    // The quadrupole's share, D's part -T / 2 with T = sum a_2m K_m (q, u), and the polarisation
    // tensor's, which the aerosol's unit matrix sees too (pq, pu): the field's degree-2 E-mode,
    // C_pol(w) = P M P - P tr(P M P) / 2 with M = 5 D_pol / (8 pi) (its integral over the sphere is
    // 8 pi M / 5), scaled by the phase function's spin-2 moment and seen from k:
    // Q = e1^T M e1 - e2^T M e2, U = 2 e1^T M e2.
    Spectrum &q = sc.q, &u = sc.u, &pq = sc.pq, &pu = sc.pu;
    q.setZero(n);
    u.setZero(n);
    pq.setZero(n);
    pu.setZero(n);
    for (int j = 0; j < 3; ++j) {
      const Eigen::Matrix3d& km = K[static_cast<size_t>(j)];
      const Eigen::Map<const Spectrum> a(sc.moments.data() + static_cast<size_t>(j) * n, n);
      q += static_cast<float>(-0.5 * (e.dot(km * e) - g.dot(km * g))) * a;
      u += static_cast<float>(-e.dot(km * g)) * a;
      const Eigen::Matrix3d& ej = E[static_cast<size_t>(j)];
      const Eigen::Map<const Spectrum> d(sc.moments.data() + static_cast<size_t>(3 + j) * n, n);
      pq += static_cast<float>(e.dot(ej * e) - g.dot(ej * g)) * d;
      pu += static_cast<float>(2.0 * e.dot(ej * g)) * d;
    }
    constexpr float kEmode = static_cast<float>(5.0 / (8.0 * kPi));
    sc.source_mq_t.col(k) = sc.source_mie_t.col(k) + kEmode * mie_spin2_moment_ * pq;
    sc.source_mu_t.col(k) = sc.source_mie_t.col(k) + kEmode * mie_spin2_moment_ * pu;
    sc.source_q_t.col(k) = sc.source_t.col(k) + 2.0f * rayleigh_phase_b_ * (q + pq);
    sc.source_u_t.col(k) = sc.source_t.col(k) + 2.0f * rayleigh_phase_b_ * (u + pu);
  }
  return true;
}

bool SingleScattering::higher_orders_piece(const Node* nodes, int m, double os, double ds, double od,
                                           const InScatteringSource& higher, const RayFrame* polarisation,
                                           PieceScratch& sc, ScatteringWorkspace& ws, Spectrum* sums[4]) const {
  const int species = sc.ozone ? 3 : 2;
  const Eigen::Index n = sca_rayleigh_.size();
  sc.view_columns.resize(m, species);
  sc.source_t.resize(n, m);
  sc.source_mie_t.resize(n, m);
  for (int k = 0; k < m; ++k) {
    for (int sp = 0; sp < species; ++sp) sc.view_columns(k, sp) = static_cast<float>(nodes[k].col[sp]);
    const double r = nodes[k].r;
    higher.source(r, (os + nodes[k].t * ds) / r, (od + nodes[k].t) / r, ds, sc.source_t.col(k).data(),
                  sc.source_mie_t.col(k).data());
  }
  optical_depths(sc.view_columns, sc, sc.view_tau);
  sc.view_trans = (-sc.view_tau).exp();
  // Rayleigh's sums with J_R, the aerosol's with J_M; then, for polarisation, Rayleigh's with
  // J_R + P_Q and J_R + P_U, the aerosol's with J_M + P_M,Q and J_M + P_M,U. [wavelength, node] arrays: one species per
  // pass; [node, wavelength] (few wavelengths): each pass computes both and one is kept.
  const bool polarised = polarisation && polarised_sources(nodes, m, *polarisation, higher, sc);
  Spectrum* rayleigh_sums[4] = {sums[0], &sc.unused[0], sums[2], &sc.unused[1]};
  Spectrum* mie_sums[4] = {&sc.unused[2], sums[1], &sc.unused[3], sums[3]};
  Spectrum* q_sums[4] = {&ws.sum_ms_q, &sc.unused[0], &ws.coarse_ms_q, &sc.unused[1]};
  Spectrum* u_sums[4] = {&ws.sum_ms_u, &sc.unused[0], &ws.coarse_ms_u, &sc.unused[1]};
  Spectrum* mq_sums[4] = {&sc.unused[2], &ws.sum_ms_mq, &sc.unused[3], &ws.coarse_ms_mq};
  Spectrum* mu_sums[4] = {&sc.unused[2], &ws.sum_ms_mu, &sc.unused[3], &ws.coarse_ms_mu};
  const Eigen::ArrayXXf* pass_sources[6] = {&sc.source_t,   &sc.source_mie_t, &sc.source_q_t,
                                            &sc.source_u_t, &sc.source_mq_t,  &sc.source_mu_t};
  Spectrum** pass_sums[6] = {rayleigh_sums, mie_sums, q_sums, u_sums, mq_sums, mu_sums};
  for (int pass = 0; pass < (polarised ? 6 : 2); ++pass) {
    const Eigen::ArrayXXf& source_t = *pass_sources[pass];
    constexpr int kSpeciesOfPass[6] = {0, 1, 0, 0, 1, 1};  // whose density weights it: Rayleigh 0, aerosol 1
    const int sp = kSpeciesOfPass[pass];
    if (sc.by_node)
      sc.source = source_t.transpose().max(1e-30f);
    else
      sc.source = source_t.max(1e-30f);
    sc.trans = sc.view_trans * sc.source;
    sc.tau = sc.view_tau - sc.source.log();
    if (!sc.by_node) {
      accumulate_species_by_wavelength(sc.tau, sc.trans, sc.seg, sp, *pass_sums[pass][sp], *pass_sums[pass][2 + sp]);
      continue;
    }
    for (auto& u : sc.unused) u.setZero(n);
    accumulate(sc, pass_sums[pass]);
  }
  return polarised;
}

void SingleScattering::accumulate(PieceScratch& sc, Spectrum* sums[4]) const {
  if (sc.by_node)
    accumulate_piece(sc.tau, sc.trans, sc.seg, *sums[0], *sums[1], *sums[2], *sums[3]);
  else
    accumulate_piece_by_wavelength(sc.tau, sc.trans, sc.seg, *sums[0], *sums[1], *sums[2], *sums[3]);
}

// The ground at the ray's end: Lambertian reflection of the direct sun (order 1) and of the sky
// (higher orders), seen through the whole view ray; added to the phase-free part.
void SingleScattering::ground_reflection(const Node& ground, double mu_sun, const ScatteringSources& sources,
                                         ScatteringWorkspace& ws, RadianceParts& parts) const {
  const double R = atm_.planet_radius_m();
  view_optical_depth(ground, ws.view_tau);
  ws.view_trans = (-ws.view_tau).exp();
  ws.source.setZero();
  if (sources.single && mu_sun > 0.0) {
    Spectrum& tau_sun = ws.ground_sun;
    const Columns sun = sun_.at(R, mu_sun);
    tau_sun = ext_[kRayleigh] * static_cast<float>(sun[kRayleigh]) + ext_[kMie] * static_cast<float>(sun[kMie]) +
              ext_[kOzone] * static_cast<float>(sun[kOzone]);
    ws.source = (-tau_sun).exp() * static_cast<float>(mu_sun);
  }
  if (sources.higher) {
    sources.higher->ground_irradiance(mu_sun, ws.ground_sky.data());
    ws.source += ws.ground_sky;
  }
  parts.phase_free += ws.view_trans * albedo_over_pi_ * ws.source;
}

// The optical depth of the view ray from the camera to a node.
void SingleScattering::view_optical_depth(const Node& node, Spectrum& tau) const {
  tau = ext_[kRayleigh] * static_cast<float>(node.col[kRayleigh]) + ext_[kMie] * static_cast<float>(node.col[kMie]);
  if (atm_.ozone().enabled()) tau += ext_[kOzone] * static_cast<float>(node.col[kOzone]);
}

// The radiance parts of one traced ray: the log-mean sums over its pieces (single scattering on
// the lit ones, higher orders on all), Richardson-extrapolated, then the transmittance and the
// ground's reflection at its end.
void SingleScattering::integrate(const Ray& ray, const Vec3& o, const Vec3& d, const Vec3& s,
                                 const ScatteringSources& sources, ScatteringWorkspace& ws,
                                 RadianceParts& parts) const {
  parts.rayleigh.setZero();
  parts.mie.setZero();
  parts.phase_free.setZero();
  const bool higher = sources.higher != nullptr;
  const double os = o.dot(s), ds = d.dot(s), od = o.dot(d);
  for (Spectrum* sum :
       {&ws.sum_rayleigh, &ws.sum_mie, &ws.coarse_rayleigh, &ws.coarse_mie, &ws.sum_ms_rayleigh, &ws.sum_ms_mie,
        &ws.coarse_ms_rayleigh, &ws.coarse_ms_mie, &ws.sum_ms_q, &ws.coarse_ms_q, &ws.sum_ms_u, &ws.coarse_ms_u,
        &ws.sum_ms_mq, &ws.coarse_ms_mq, &ws.sum_ms_mu, &ws.coarse_ms_mu})
    sum->setZero();
  RayFrame frame;
  bool polarised = false;  // whether the higher orders' sources had a quadrupole (all pieces or none)
  if (sources.polarisation) {
    frame = RayFrame{o, d, s, polarisation_frame(d, s), Vec3()};
    frame.e2 = (-d).cross(frame.e1);
  }
  Spectrum* single_sums[4] = {&ws.sum_rayleigh, &ws.sum_mie, &ws.coarse_rayleigh, &ws.coarse_mie};
  Spectrum* higher_sums[4] = {&ws.sum_ms_rayleigh, &ws.sum_ms_mie, &ws.coarse_ms_rayleigh, &ws.coarse_ms_mie};

  thread_local PieceScratch sc;
  sc.ozone = atm_.ozone().enabled();
  sc.by_node = sca_rayleigh_.size() < kWavelengthsForWavelengthLoops;
  for (int i = 0; i < ray.n_pieces; ++i) {
    const Piece& pc = ray.pieces[i];
    const bool single_here = sources.single && pc.lit;
    if (!single_here && !higher) continue;  // nothing to collect: its nodes only carried the columns
    const Node* nodes = ray.nodes.data() + pc.first_node;
    fill_piece_segments(nodes, pc.segments, sc.seg);
    if (single_here) single_scattering_piece(nodes, pc.segments + 1, os, ds, sc, single_sums);
    if (higher)
      polarised |= higher_orders_piece(nodes, pc.segments + 1, os, ds, od, *sources.higher,
                                       sources.polarisation ? &frame : nullptr, sc, ws, higher_sums);
  }

  if (sources.single) {
    parts.rayleigh = sca_rayleigh_ * richardson(ws.sum_rayleigh, ws.coarse_rayleigh);
    parts.mie = sca_mie_ * richardson(ws.sum_mie, ws.coarse_mie);
  }
  if (higher)
    parts.phase_free = sca_rayleigh_ * richardson(ws.sum_ms_rayleigh, ws.coarse_ms_rayleigh) +
                       sca_mie_ * richardson(ws.sum_ms_mie, ws.coarse_ms_mie);
  if (sources.polarisation) {
    // Zero where nothing was polarised (no higher orders, or tables without a quadrupole).
    const Spectrum ms_rayleigh = richardson(ws.sum_ms_rayleigh, ws.coarse_ms_rayleigh);
    const Spectrum ms_mie = richardson(ws.sum_ms_mie, ws.coarse_ms_mie);
    if (polarised) {
      parts.polarised_q = sca_rayleigh_ * (richardson(ws.sum_ms_q, ws.coarse_ms_q) - ms_rayleigh) +
                          sca_mie_ * (richardson(ws.sum_ms_mq, ws.coarse_ms_mq) - ms_mie);
      parts.polarised_u = sca_rayleigh_ * (richardson(ws.sum_ms_u, ws.coarse_ms_u) - ms_rayleigh) +
                          sca_mie_ * (richardson(ws.sum_ms_mu, ws.coarse_ms_mu) - ms_mie);
    } else {
      parts.polarised_q.setZero(ms_rayleigh.size());
      parts.polarised_u.setZero(ms_rayleigh.size());
    }
  }

  const Node& last = ray.nodes.back();
  if (sources.transmittance) {
    view_optical_depth(last, ws.view_tau);
    *sources.transmittance = (-ws.view_tau).exp();
  }
  if (ray.hits_ground && albedo_over_pi_.maxCoeff() > 0.0f)  // the last node is the ground point
    ground_reflection(last, (os + last.t * ds) / last.r, sources, ws, parts);
}

void SingleScattering::radiance_parts(const Vec3& o, const Vec3& d, const Vec3& s, const ScatteringSources& sources,
                                      ScatteringWorkspace& ws, RadianceParts& parts) const {
  parts.rayleigh.setZero();
  parts.mie.setZero();
  parts.phase_free.setZero();
  if (sources.polarisation) {
    parts.polarised_q.setZero(sca_rayleigh_.size());
    parts.polarised_u.setZero(sca_rayleigh_.size());
  }
  if (sources.transmittance) sources.transmittance->setOnes();
  if (o.norm() < atm_.planet_radius_m()) {  // inside the planet
    if (sources.transmittance) sources.transmittance->setZero();
    return;
  }
  thread_local Ray ray;  // its nodes are reused from call to call
  if (!trace(o, d, s, sources, ray)) return;
  place_nodes(o, d, sources, ray);
  integrate(ray, o, d, s, sources, ws, parts);
}

void SingleScattering::radiance_parts_same_zenith(const Vec3& o, const Vec3* dirs, int count, const Vec3& s,
                                                  const ScatteringSources& sources, ScatteringWorkspace& ws,
                                                  RadianceParts* parts) const {
  if (sources.transmittance || sources.polarisation || o.norm() < atm_.planet_radius_m()) {
    for (int i = 0; i < count; ++i) radiance_parts(o, dirs[i], s, sources, ws, parts[i]);
    return;
  }
  thread_local Ray shared, own;
  bool have_shared = false;
  for (int i = 0; i < count; ++i) {
    const Vec3& d = dirs[i];
    if (!trace(o, d, s, sources, own)) {
      parts[i].rayleigh.setZero();
      parts[i].mie.setZero();
      parts[i].phase_free.setZero();
      continue;
    }
    bool lit_throughout = !own.hits_ground;
    for (int k = 0; k < own.n_pieces; ++k) lit_throughout = lit_throughout && own.pieces[k].lit;
    if (lit_throughout && have_shared) {
      // The same pieces as the shared ray's, to rounding (each ray's own intersections differ
      // from the shared one's in the last bits)?
      bool same = own.n_pieces == shared.n_pieces;
      const double tolerance = 1e-9 * shared.t_end;
      for (int k = 0; same && k < own.n_pieces; ++k)
        same = std::abs(own.pieces[k].t0 - shared.pieces[k].t0) <= tolerance &&
               std::abs(own.pieces[k].t1 - shared.pieces[k].t1) <= tolerance;
      if (same) {
        integrate(shared, o, d, s, sources, ws, parts[i]);
        continue;
      }
    }
    place_nodes(o, d, sources, own);
    integrate(own, o, d, s, sources, ws, parts[i]);
    if (lit_throughout && !have_shared) {
      std::swap(shared, own);
      have_shared = true;
    }
  }
}

}  // namespace skyspec
