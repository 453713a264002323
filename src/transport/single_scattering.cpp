#include "transport/single_scattering.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>

#include "base/quadrature.hpp"
#include "skyspec/atmosphere.hpp"
#include "skyspec/error.hpp"
#include "skyspec/phase_function.hpp"
#include "skyspec/units.hpp"
#include "transport/multiple_scattering.hpp"  // gauss_legendre
#include "transport/optical_depth.hpp"
#include "transport/spherical_harmonics.hpp"
#include "transport/spin2_harmonics.hpp"

namespace skyspec {

ScatteringWorkspace::ScatteringWorkspace(int n)
    : view_tau(n), view_trans(n), source(n), ground_sun(n), ground_sky(n), surface_albedo_over_pi(n) {
  for (Sums& s : sums)
    for (Spectrum* v : {&s.single[0], &s.single[1], &s.higher[0], &s.higher[1], &s.q[0], &s.q[1], &s.u[0], &s.u[1]})
      v->setZero(n);
  for (Spectrum& p : phase) p.setZero(n);
}

void InScatteringSource::sources(int count, const double* r_m, const double* mu_sun, const double* mu_view, double nu,
                                 int media, int n, float* const* out) const {
  float* at[kMaxMedia];
  for (int k = 0; k < count; ++k) {
    for (int s = 0; s < media; ++s) at[s] = out[s] + static_cast<size_t>(k) * static_cast<size_t>(n);
    source(r_m[k], mu_sun[k], mu_view[k], nu, at);
  }
}

void RadianceParts::resize(int n, int scatterers) {
  scattered.resize(static_cast<size_t>(scatterers));
  for (Spectrum& s : scattered) s.setZero(n);
  phase_free.setZero(n);
}

void RadianceParts::set_zero() {
  for (Spectrum& s : scattered) s.setZero();
  phase_free.setZero();
}

namespace {
// The x axis of the scattering-order tables' local frame at a point whose zenith is z (unit): towards
// the sun's azimuth (any horizontal direction when the sun is at the zenith); y = z x x.
Vec3 tables_frame_x(const Vec3& z, const Vec3& sun) {
  Vec3 x = sun - sun.dot(z) * z;
  if (x.norm() < 1e-9) x = z.cross(std::abs(z.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0));
  return x.normalized();
}
}  // namespace

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
      media_(static_cast<int>(atm.media().size())),
      albedo_over_pi_((atm.ground_albedo() / kPi).cast<float>()),
      n_(atm.grid().size()),
      spin_moments_(std::make_shared<LazySpinMoments>()),
      field_integrators_(std::make_shared<FieldIntegrators>()) {
  for (int j = 0; j < media_; ++j) {
    const Medium& medium = atm.media()[static_cast<size_t>(j)];
    ext_[j] = medium.extinction_per_m.cast<float>();
    layer_[j] = !medium.profile.positive_everywhere();
    for (double h : medium.profile.breakpoints_m()) breakpoint_radii_m_.push_back(atm.planet_radius_m() + h);
    if (medium.region) {
      region_[j] = &*medium.region;
      has_regions_ = true;
    }
    if (!medium.scatters()) continue;
    Scatterer sc;
    sc.medium = j;
    sc.sca = medium.scattering_per_m.cast<float>();
    sc.phase = &medium.phase;
    if (sc.rayleigh()) {
      // The phase function per wavelength as A + B mu^2 (phase_function.hpp, Chandrasekhar).
      const SpectrumD& gamma = medium.phase.rayleigh_gamma;
      const SpectrumD scale = 3.0 / (16.0 * kPi * (1.0 + 2.0 * gamma));
      sc.phase_a = (scale * (1.0 + 3.0 * gamma)).cast<float>();
      sc.phase_b = (scale * (1.0 - gamma)).cast<float>();
    }
    scatterers_.push_back(std::move(sc));
  }
}

// The integrators of the field atmospheres a render's sources have shown, with the atmospheres
// (kept alive so that their addresses are not reused while they are listed).
struct SingleScattering::FieldIntegrators {
  std::mutex mutex;
  std::vector<std::pair<std::shared_ptr<const AtmosphereModel>, std::unique_ptr<SingleScattering>>> list;
};

const SingleScattering& SingleScattering::field_integrator(const ScatteringSources& sources) const {
  if (!sources.higher) return *this;
  std::shared_ptr<const AtmosphereModel> field = sources.higher->field_atmosphere();
  if (!field || field.get() == &atm_) return *this;
  FieldIntegrators& f = *field_integrators_;
  const std::lock_guard<std::mutex> lock(f.mutex);
  for (const auto& [a, integrator] : f.list)
    if (a == field) return *integrator;
  if (field->media().size() != atm_.media().size())
    throw Error("a source's field atmosphere has " + std::to_string(field->media().size()) +
                " media, the integrator's " + std::to_string(atm_.media().size()));
  auto integrator = std::make_unique<SingleScattering>(*field, sun_, settings_);
  f.list.emplace_back(field, std::move(integrator));
  return *f.list.back().second;
}

struct SingleScattering::LazySpinMoments {
  std::once_flag once;
  std::vector<SpinMoments> moments;
};

const std::vector<SingleScattering::SpinMoments>& SingleScattering::spin_moments() const {
  LazySpinMoments& lazy = *spin_moments_;
  std::call_once(lazy.once, [&] {
    constexpr int L = kMaxSpin2Degree;
    std::vector<double> mu, w;
    gauss_legendre(512, -1.0, 1.0, mu, w);
    std::vector<double> d22;  // d^l_22(mu[k]) at k (L + 1) + l, once an analytic phase function needs it
    for (const Scatterer& sc : scatterers_) {
      SpinMoments out;
      const MediumPhase& phase = *sc.phase;
      if (sc.rayleigh()) {
        lazy.moments.push_back(std::move(out));
        continue;
      }
      out.plus.assign(L + 1, Spectrum::Zero(n_));
      if (phase.kind == MediumPhase::Kind::Tabulated) {
        // A sphere's matrix: alpha_+ = (a1 + a3) / 2 (a2 = a1), alpha_- = (a1 - a3) / 2 and b1,
        // exact for the table's interpolant.
        const TabulatedScatteringMatrix& t = *phase.matrix;
        out.mirrored.assign(L + 1, Spectrum::Zero(n_));
        out.polarising.assign(L + 1, Spectrum::Zero(n_));
        std::vector<double> plus(t.mu().size()), minus(t.mu().size());
        for (int i = 0; i < n_; ++i) {
          const auto& a1 = t.a1()[static_cast<size_t>(i)];
          const auto& a3 = t.a3()[static_cast<size_t>(i)];
          for (size_t k = 0; k < plus.size(); ++k) {
            plus[k] = 0.5 * (a1[k] + a3[k]);
            minus[k] = 0.5 * (a1[k] - a3[k]);
          }
          const std::vector<double> bp = piecewise_linear_spin_moments(t.mu(), plus, L, 2, 2);
          const std::vector<double> bm = piecewise_linear_spin_moments(t.mu(), minus, L, 2, -2);
          const std::vector<double> g = piecewise_linear_spin_moments(t.mu(), t.b1()[static_cast<size_t>(i)], L, 2, 0);
          for (int l = 2; l <= L; ++l) {
            out.plus[static_cast<size_t>(l)][i] = static_cast<float>(bp[static_cast<size_t>(l)]);
            out.mirrored[static_cast<size_t>(l)][i] = static_cast<float>(bm[static_cast<size_t>(l)]);
            out.polarising[static_cast<size_t>(l)][i] = static_cast<float>(g[static_cast<size_t>(l)]);
          }
        }
      } else {
        if (d22.empty()) {
          d22.resize(mu.size() * (L + 1), 0.0);
          for (size_t k = 0; k < mu.size(); ++k)
            for (int l = 2; l <= L; ++l) d22[k * (L + 1) + static_cast<size_t>(l)] = wigner_d(l, 2, 2, mu[k]);
        }
        std::vector<double> beta(L + 1);
        for (int i = 0; i < n_; ++i) {
          std::fill(beta.begin(), beta.end(), 0.0);
          for (size_t k = 0; k < mu.size(); ++k) {
            const double pw = w[k] * phase.at(i, mu[k]);
            for (int l = 2; l <= L; ++l) beta[static_cast<size_t>(l)] += pw * d22[k * (L + 1) + static_cast<size_t>(l)];
          }
          for (int l = 2; l <= L; ++l)
            out.plus[static_cast<size_t>(l)][i] = static_cast<float>(2.0 * kPi * beta[static_cast<size_t>(l)]);
        }
      }
      lazy.moments.push_back(std::move(out));
    }
  });
  return lazy.moments;
}

void SingleScattering::optical_depth(const double* columns, Spectrum& tau) const {
  if (media_ >= 2)
    tau = ext_[0] * static_cast<float>(columns[0]) + ext_[1] * static_cast<float>(columns[1]);
  else
    tau = ext_[0] * static_cast<float>(columns[0]);
  for (int j = 2; j < media_; ++j) tau += ext_[j] * static_cast<float>(columns[j]);
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

// What the segments of a piece share at every wavelength: lengths, and each scattering medium's
// densities and their log ratios, for the fine rule (nodes k, k + 1) and the coarse one (nodes 2j,
// 2j + 2). In a named namespace: SingleScattering::PieceScratch (a member type) holds one.
namespace detail {
struct PieceSegments {
  int segments = 0;
  Eigen::ArrayXf dt, rho[kMaxMedia], log_ratio[kMaxMedia];  // fine: [k]; rho: [node]; per scatterer
  Eigen::ArrayXf dt2, log_ratio2[kMaxMedia];                // coarse: [j]
  Eigen::ArrayXf terms;                                     // scratch
};
}  // namespace detail

namespace {
using detail::PieceSegments;

inline float log_mean_term(float x, float f_a, float f_b) { return log_mean_branchless(f_a, f_b, x, 1e-2f); }

// out[j] = dt[j] logmean over nodes a = j s, b = (j + 1) s (s = stride: 1 for the fine rule, 2 for
// the coarse one) of one medium's integrand, for one wavelength. A separate function with plain
// pointers so that GCC vectorises it.
void log_mean_terms(int count, int stride, const float* __restrict tau, const float* __restrict trans,
                    const float* __restrict rho, const float* __restrict x, const float* __restrict dt,
                    float* __restrict out) {
  if (stride == 1) {
    for (int j = 0; j < count; ++j)
      out[j] = dt[j] * log_mean_term(x[j] - (tau[j] - tau[j + 1]), rho[j] * trans[j], rho[j + 1] * trans[j + 1]);
    return;
  }
  for (int j = 0; j < count; ++j) {
    const int a = j * stride, b = a + stride;
    out[j] = dt[j] * log_mean_term(x[j] - (tau[a] - tau[b]), rho[a] * trans[a], rho[b] * trans[b]);
  }
}

// The same for two media at once (a and b): the optical depths and transmittances are read once.
void log_mean_terms_2(int count, int stride, const float* __restrict tau, const float* __restrict trans,
                      const float* __restrict rho_a, const float* __restrict rho_b, const float* __restrict x_a,
                      const float* __restrict x_b, const float* __restrict dt, float* __restrict out_a,
                      float* __restrict out_b) {
  if (stride == 1) {
    for (int j = 0; j < count; ++j) {
      const float dtau = tau[j] - tau[j + 1];
      out_a[j] = dt[j] * log_mean_term(x_a[j] - dtau, rho_a[j] * trans[j], rho_a[j + 1] * trans[j + 1]);
      out_b[j] = dt[j] * log_mean_term(x_b[j] - dtau, rho_b[j] * trans[j], rho_b[j + 1] * trans[j + 1]);
    }
    return;
  }
  for (int j = 0; j < count; ++j) {
    const int a = j * stride, b = a + stride;
    const float dtau = tau[a] - tau[b];
    out_a[j] = dt[j] * log_mean_term(x_a[j] - dtau, rho_a[a] * trans[a], rho_a[b] * trans[b]);
    out_b[j] = dt[j] * log_mean_term(x_b[j] - dtau, rho_b[a] * trans[a], rho_b[b] * trans[b]);
  }
}

// Adds the fine and coarse log-mean sums over the piece's segments of scatterer sp, per
// wavelength. tau and trans: [node, wavelength], loops over nodes.
void accumulate_piece(const NodeArray& tau, const NodeArray& trans, PieceSegments& g, int sp, Spectrum& fine,
                      Spectrum& coarse) {
  const int segs = g.segments, pairs = segs / 2;
  g.terms.resize(segs);
  for (Eigen::Index l = 0; l < tau.cols(); ++l) {
    const float* ta = tau.col(l).data();
    const float* ea = trans.col(l).data();
    log_mean_terms(segs, 1, ta, ea, g.rho[sp].data(), g.log_ratio[sp].data(), g.dt.data(), g.terms.data());
    fine[l] += g.terms.head(segs).sum();
    log_mean_terms(pairs, 2, ta, ea, g.rho[sp].data(), g.log_ratio2[sp].data(), g.dt2.data(), g.terms.data());
    coarse[l] += g.terms.head(pairs).sum();
  }
}

// accumulate_piece for scatterers sa and sb together (single scattering: both see the same tau).
void accumulate_piece_2(const NodeArray& tau, const NodeArray& trans, PieceSegments& g, int sa, int sb,
                        Spectrum* sums_a, Spectrum* sums_b) {
  const int segs = g.segments, pairs = segs / 2;
  g.terms.resize(2 * segs);
  float* ta_terms = g.terms.data();
  float* tb_terms = g.terms.data() + segs;
  for (Eigen::Index l = 0; l < tau.cols(); ++l) {
    const float* ta = tau.col(l).data();
    const float* ea = trans.col(l).data();
    log_mean_terms_2(segs, 1, ta, ea, g.rho[sa].data(), g.rho[sb].data(), g.log_ratio[sa].data(),
                     g.log_ratio[sb].data(), g.dt.data(), ta_terms, tb_terms);
    sums_a[0][l] += g.terms.head(segs).sum();
    sums_b[0][l] += g.terms.segment(segs, segs).sum();
    log_mean_terms_2(pairs, 2, ta, ea, g.rho[sa].data(), g.rho[sb].data(), g.log_ratio2[sa].data(),
                     g.log_ratio2[sb].data(), g.dt2.data(), ta_terms, tb_terms);
    sums_a[1][l] += g.terms.head(pairs).sum();
    sums_b[1][l] += g.terms.segment(segs, pairs).sum();
  }
}

// The same for [wavelength, node] arrays (each node's wavelengths contiguous), segment by
// segment, every loop over wavelengths: the better order when there are many wavelengths and
// few nodes (the scattering-order tables' rays have 24 segments).
void segment_over_wavelengths(Eigen::Index n, const float* __restrict ta, const float* __restrict ea,
                              const float* __restrict tb, const float* __restrict eb, float x, float rho_a, float rho_b,
                              float dt, float* __restrict out) {
  for (Eigen::Index l = 0; l < n; ++l) out[l] += dt * log_mean_term(x - (ta[l] - tb[l]), rho_a * ea[l], rho_b * eb[l]);
}
// Two media at once.
void segment_over_wavelengths_2(Eigen::Index n, const float* __restrict ta, const float* __restrict ea,
                                const float* __restrict tb, const float* __restrict eb, float x_a, float a_a, float a_b,
                                float x_b, float b_a, float b_b, float dt, float* __restrict out_a,
                                float* __restrict out_b) {
  for (Eigen::Index l = 0; l < n; ++l) {
    const float dtau = ta[l] - tb[l];
    out_a[l] += dt * log_mean_term(x_a - dtau, a_a * ea[l], a_b * eb[l]);
    out_b[l] += dt * log_mean_term(x_b - dtau, b_a * ea[l], b_b * eb[l]);
  }
}
void accumulate_piece_by_wavelength_2(const NodeArray& tau, const NodeArray& trans, const PieceSegments& g, int sa,
                                      int sb, Spectrum* sums_a, Spectrum* sums_b) {
  const Eigen::Index n = tau.rows();
  const float* ra = g.rho[sa].data();
  const float* rb = g.rho[sb].data();
  for (int k = 0; k < g.segments; ++k)
    segment_over_wavelengths_2(n, tau.col(k).data(), trans.col(k).data(), tau.col(k + 1).data(),
                               trans.col(k + 1).data(), g.log_ratio[sa][k], ra[k], ra[k + 1], g.log_ratio[sb][k], rb[k],
                               rb[k + 1], g.dt[k], sums_a[0].data(), sums_b[0].data());
  for (int j = 0; j < g.segments / 2; ++j) {
    const int a = 2 * j, b = 2 * j + 2;
    segment_over_wavelengths_2(n, tau.col(a).data(), trans.col(a).data(), tau.col(b).data(), trans.col(b).data(),
                               g.log_ratio2[sa][j], ra[a], ra[b], g.log_ratio2[sb][j], rb[a], rb[b], g.dt2[j],
                               sums_a[1].data(), sums_b[1].data());
  }
}

void accumulate_piece_by_wavelength(const NodeArray& tau, const NodeArray& trans, const PieceSegments& g, int sp,
                                    Spectrum& fine, Spectrum& coarse) {
  const Eigen::Index n = tau.rows();
  const float* rho = g.rho[sp].data();
  for (int k = 0; k < g.segments; ++k)
    segment_over_wavelengths(n, tau.col(k).data(), trans.col(k).data(), tau.col(k + 1).data(), trans.col(k + 1).data(),
                             g.log_ratio[sp][k], rho[k], rho[k + 1], g.dt[k], fine.data());
  for (int j = 0; j < g.segments / 2; ++j) {
    const int a = 2 * j, b = 2 * j + 2;
    segment_over_wavelengths(n, tau.col(a).data(), trans.col(a).data(), tau.col(b).data(), trans.col(b).data(),
                             g.log_ratio2[sp][j], rho[a], rho[b], g.dt2[j], coarse.data());
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
  Columns c = columns_to_top_m(atm_, r, start.dot(d) / start.norm(), 256);
  for (int j = 0; j < media_; ++j)
    if (region_[j]) c[static_cast<size_t>(j)] = regional_column(j, start, d);
  Spectrum tau;
  optical_depth(c.data(), tau);
  out = (-tau).exp();
}

double SingleScattering::regional_column(int j, const Vec3& p, const Vec3& dir) const {
  double in0 = 0.0, in1 = 0.0;
  if (!region_[j]->crossing(p, dir, in0, in1)) return 0.0;
  const double r = p.norm(), Rt = atm_.top_radius_m(), R = atm_.planet_radius_m();
  const double t0 = std::max(0.0, in0), t1 = std::min(in1, distance_to_top_m(r, p.dot(dir) / r, Rt));
  if (!(t1 > t0)) return 0.0;
  const DensityProfile& profile = atm_.media()[static_cast<size_t>(j)].profile;
  const double dt = (t1 - t0) / kRegionChordSegments;
  double column = 0.0, log_a = profile.log_relative((p + t0 * dir).norm() - R);
  for (int k = 1; k <= kRegionChordSegments; ++k) {
    const double log_b = profile.log_relative((p + (t0 + k * dt) * dir).norm() - R);
    column += dt * log_mean(std::exp(log_a), std::exp(log_b), log_a - log_b);
    log_a = log_b;
  }
  return column;
}

Columns SingleScattering::sun_columns_at(const Vec3& p, double r, double mu_sun, const Vec3& s) const {
  Columns c = sun_.at(r, mu_sun);
  for (int j = 0; j < media_; ++j)
    if (region_[j]) c[static_cast<size_t>(j)] = regional_column(j, p, s);
  return c;
}

void SingleScattering::radiance(const Vec3& o, const Vec3& d, const Vec3& s, const Spectrum& sun_irradiance,
                                const ScatteringSources& sources, ScatteringWorkspace& ws, Spectrum& out) const {
  radiance_parts(o, d, s, sources, ws, ws.parts);
  combine(ws.parts, d.dot(s), sun_irradiance, ws, out);
}

namespace {
// L = E_sun [sum_s p_s scattered_s + phase_free] for one direction's parts (n values each): parts[s]
// the scatterers', phases[s] their phase functions per wavelength.
void combine_parts(Eigen::Index n, int scatterers, const float* const* parts, const Spectrum* phases,
                   const float* phase_free, const Spectrum& sun_irradiance, float* out) {
  using In = Eigen::Map<const Spectrum>;
  Eigen::Map<Spectrum> o(out, n);
  if (scatterers == 1) {
    o = (In(parts[0], n) * phases[0] + In(phase_free, n)) * sun_irradiance;
    return;
  }
  if (scatterers == 2) {  // air and aerosol: one expression
    o = (In(parts[0], n) * phases[0] + In(parts[1], n) * phases[1] + In(phase_free, n)) * sun_irradiance;
    return;
  }
  o = In(parts[0], n) * phases[0] + In(parts[1], n) * phases[1];
  for (int s = 2; s < scatterers; ++s) o += In(parts[s], n) * phases[s];
  o = (o + In(phase_free, n)) * sun_irradiance;
}
}  // namespace

void SingleScattering::phase_of(int s, double mu, Spectrum& p) const {
  const Scatterer& sc = scatterers_[static_cast<size_t>(s)];
  const MediumPhase& ph = *sc.phase;
  if (sc.rayleigh()) {
    p = sc.phase_a + sc.phase_b * static_cast<float>(mu * mu);
  } else if (ph.kind == MediumPhase::Kind::Tabulated) {
    const TabulatedScatteringMatrix::Position at = ph.matrix->locate(mu);
    for (int i = 0; i < n_; ++i) p[i] = static_cast<float>(ph.matrix->phase(i, at));
  } else if (ph.varies_with_wavelength()) {
    for (int i = 0; i < n_; ++i) p[i] = static_cast<float>(ph.analytic(i)(mu));
  } else {
    p.setConstant(static_cast<float>(ph.analytic(0)(mu)));
  }
}

namespace {
// One element of a tabulated matrix per wavelength, averaged over the ranges of `over` (each range's
// mean from the element's integral: exact for the interpolant).
void mean_over(const TabulatedScatteringMatrix& m, const CosineRanges& over,
               void (TabulatedScatteringMatrix::*add)(TabulatedScatteringMatrix::Position,
                                                      TabulatedScatteringMatrix::Position, double, float*) const,
               Spectrum& out) {
  out.setZero();
  const double weight = 1.0 / std::max(over.count, 1);
  for (int r = 0; r < over.count; ++r) (m.*add)(m.locate(over.lo[r]), m.locate(over.hi[r]), weight, out.data());
}
}  // namespace

void SingleScattering::phases_at(double mu, ScatteringWorkspace& ws, const CosineRanges* over) const {
  for (int s = 0; s < scatterer_count(); ++s) {
    const MediumPhase& ph = *scatterers_[static_cast<size_t>(s)].phase;
    if (over && ph.kind == MediumPhase::Kind::Tabulated)
      mean_over(*ph.matrix, *over, &TabulatedScatteringMatrix::add_mean_phases, ws.phase[s]);
    else
      phase_of(s, mu, ws.phase[s]);
  }
}

void SingleScattering::combine(const RadianceParts& parts, double mu, const Spectrum& sun_irradiance,
                               ScatteringWorkspace& ws, Spectrum& out, const CosineRanges* over) const {
  out.resize(n_);
  phases_at(mu, ws, over);
  const float* p[kMaxMedia];
  for (int s = 0; s < scatterer_count(); ++s) p[s] = parts.scattered[static_cast<size_t>(s)].data();
  combine_parts(n_, scatterer_count(), p, ws.phase, parts.phase_free.data(), sun_irradiance, out.data());
}

void SingleScattering::stokes(const RadianceParts& parts, const Vec3& view, const Vec3& sun, const Vec3& e1,
                              const Spectrum& sun_irradiance, ScatteringWorkspace& ws, Spectrum& I, Spectrum& Q,
                              Spectrum& U, const CosineRanges* over) const {
  const double mu = view.dot(sun);
  combine(parts, mu, sun_irradiance, ws, I, over);
  // From the parts' frame (e1p, k x e1p) into (e1, k x e1): turned by psi with cos psi = e1 . e1p,
  // sin psi = e1 . e2p (stokes_rotation): Q' = Q cos 2psi + U sin 2psi, U' = -Q sin 2psi + U cos 2psi.
  const Vec3 k = -view;
  const Vec3 e1p = polarisation_frame(view, sun), e2p = k.cross(e1p);
  const double c = e1.dot(e1p), s = e1.dot(e2p);
  const float c2 = static_cast<float>(c * c - s * s), s2 = static_cast<float>(2.0 * c * s);
  // Order 1 in the parts' frame, which contains the scattering plane: Q = E scattered_s b1_s(mu),
  // U = 0; molecules' b1 = -B (1 - mu^2), a table's its own, an analytic phase function none.
  Spectrum q_plane = Spectrum::Zero(n_);
  for (size_t j = 0; j < scatterers_.size(); ++j) {
    const Scatterer& sc = scatterers_[j];
    const Spectrum& part = parts.scattered[j];
    if (sc.rayleigh()) {
      q_plane += -(sc.phase_b * static_cast<float>(1.0 - mu * mu)) * part * sun_irradiance;
    } else if (sc.phase->kind == MediumPhase::Kind::Tabulated) {
      const TabulatedScatteringMatrix& table = *sc.phase->matrix;
      if (over) {
        Spectrum& b1 = ws.phase[j];  // the phase functions are in I already
        mean_over(table, *over, &TabulatedScatteringMatrix::add_mean_b1s, b1);
        q_plane += b1 * part * sun_irradiance;
        continue;
      }
      const TabulatedScatteringMatrix::Position at = table.locate(mu);
      for (Eigen::Index i = 0; i < n_; ++i)
        q_plane[i] += static_cast<float>(table.b1(static_cast<int>(i), at)) * part[i] * sun_irradiance[i];
    }
  }
  Spectrum u_plane = Spectrum::Zero(n_);
  if (parts.polarised_q.size() == n_) {
    q_plane += parts.polarised_q * sun_irradiance;
    u_plane += parts.polarised_u * sun_irradiance;
  }
  Q = c2 * q_plane + s2 * u_plane;
  U = -s2 * q_plane + c2 * u_plane;
}

void SingleScattering::combine_many(int count, const float* packed, const double* mu, const bool* use,
                                    const Spectrum& sun_irradiance, float* const* out, ScatteringWorkspace& ws) const {
  const int n = n_, parts = scatterer_count() + 1;
  // Analytic phase functions that are the same at every wavelength are evaluated for a chunk of
  // directions in one loop that vectorises; the others per direction (phases_at).
  constexpr int kChunk = 64;
  bool constant[kMaxMedia] = {};
  for (int s = 0; s < scatterer_count(); ++s) {
    const MediumPhase& ph = *scatterers_[static_cast<size_t>(s)].phase;
    constant[s] = ph.kind == MediumPhase::Kind::Analytic && !ph.varies_with_wavelength();
  }
  double pm[kMaxMedia][kChunk];
  for (int first = 0; first < count; first += kChunk) {
    const int m = std::min(kChunk, count - first);
    const double* u = mu + first;
    for (int s = 0; s < scatterer_count(); ++s) {
      if (!constant[s]) continue;
      const AerosolPhase phase = scatterers_[static_cast<size_t>(s)].phase->analytic(0);
      if (phase.model == AerosolPhase::Model::HenyeyGreenstein)
        for (int k = 0; k < m; ++k) pm[s][k] = henyey_greenstein_phase(u[k], phase.g);
      else
        for (int k = 0; k < m; ++k) pm[s][k] = cornette_shanks_phase(u[k], phase.g);
    }
    for (int k = 0; k < m; ++k) {
      if (!use[first + k]) continue;
      for (int s = 0; s < scatterer_count(); ++s) {
        if (constant[s])
          ws.phase[s].setConstant(static_cast<float>(pm[s][k]));
        else
          phase_of(s, u[k], ws.phase[s]);
      }
      const float* p = packed + static_cast<size_t>(first + k) * parts * static_cast<size_t>(n);
      const float* part[kMaxMedia];
      for (int s = 0; s < scatterer_count(); ++s) part[s] = p + static_cast<size_t>(s) * n;
      combine_parts(n, scatterer_count(), part, ws.phase, p + static_cast<size_t>(scatterer_count()) * n,
                    sun_irradiance, out[first + k]);
    }
  }
}

// A node of the quadrature: a point on the view ray, its densities, and the view-ray columns
// from the start of the ray to it.
struct SingleScattering::Node {
  double t;
  double r;
  double log_rho[kMaxMedia];  // per medium (a layer's is not used)
  double rho[kMaxMedia];      // exp(log_rho), once per node; a layer's directly
  double col[kMaxMedia];
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
  bool hits_ground = false;   // ends on the ground (the last node is the ground point)
  bool hits_terrain = false;  // ... and that ground is the terrain's surface
  // With the higher orders, a ray that ends on a surface where the terrain can matter: the
  // terrain's skyline above its end (Terrain::skyline_above), the sky hidden from the ray's points
  // (SkylineCut), and the parts of the ray outside the planet's shadow (the pieces' `lit` also
  // leave out the terrain's shadows).
  bool skyline_found = false;
  Vec3 skyline;
  IntervalSet planet_lit;
  std::vector<Piece> pieces;  // pieces[0 .. n_pieces): kept from ray to ray (no allocation)
  int n_pieces = 0;
  std::vector<Node> nodes;
  void add_piece(double t0, double t1, bool lit) {
    if (static_cast<size_t>(n_pieces) == pieces.size()) pieces.emplace_back();
    pieces[static_cast<size_t>(n_pieces++)] = Piece{t0, t1, lit};
  }
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
  ray.hits_terrain = false;
  ray.skyline_found = false;
  // The terrain: the ray ends where it meets the surface; it shadows the stretch found here.
  bool terrain_stretch = false;
  if (sources.terrain) {
    Interval stretch;
    terrain_stretch = sources.terrain->affected_stretch(o, d, t_begin, t_end, s, stretch);
    if (terrain_stretch) {
      const double t_hit = sources.terrain->intersect(o, d, stretch.t0_m, stretch.t1_m);
      if (t_hit < t_end) {
        t_end = t_hit;
        hits_ground = true;
        ray.hits_terrain = true;
      }
      if (sources.higher && hits_ground) {
        ray.skyline = sources.terrain->skyline_above(o, d, t_end);
        ray.skyline_found = true;
      }
    }
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
  const IntervalSet planet_lit = lit_intervals(o, d, t_begin, t_end, s, R);
  ray.planet_lit = planet_lit;
  thread_local std::vector<Interval> lit;
  lit.clear();
  for (int i = 0; i < planet_lit.count; ++i) lit.push_back(planet_lit.parts[i]);
  if (terrain_stretch && !lit.empty()) sunlit_past_terrain(o, d, s, *sources.terrain, lit);
  if (!sources.higher && lit.empty() && !sources.transmittance) return false;
  // Cuts: the ray's lowest point and where it crosses a layer's base or top.
  thread_local std::vector<double> cuts;
  cuts.clear();
  cuts.push_back(-o.dot(d));
  for (double rc : breakpoint_radii_m_) {
    const SphereHit crossing = intersect_sphere(o, d, rc);
    if (crossing.hit) {
      cuts.push_back(crossing.t_near_m);
      cuts.push_back(crossing.t_far_m);
    }
  }
  // ... and where it passes a regional medium's walls.
  for (int j = 0; j < media_ && has_regions_; ++j) {
    double in0 = 0.0, in1 = 0.0;
    if (region_[j] && region_[j]->crossing(o, d, in0, in1)) {
      cuts.push_back(in0);
      cuts.push_back(in1);
    }
  }
  std::sort(cuts.begin(), cuts.end());
  double a = t_begin;
  auto add = [&](double b, bool is_lit) {  // [a, b], cut where cuts fall inside it
    for (double c : cuts)
      if (c > a && c < b) {
        ray.add_piece(a, c, is_lit);
        a = c;
      }
    ray.add_piece(a, b, is_lit);
    a = b;
  };
  for (const Interval& part : lit) {
    if (part.t0_m > a) add(part.t0_m, false);  // [a, t0] dark
    add(part.t1_m, true);
  }
  if (a < t_end) add(t_end, false);
  return true;
}

// The lit parts of a ray (the planet's, in order) less the terrain's shadows: where the ray can
// meet the terrain's shadow (Terrain::affected_stretch), its sunlit parts.
void SingleScattering::sunlit_past_terrain(const Vec3& o, const Vec3& d, const Vec3& s, const Terrain& terrain,
                                           std::vector<Interval>& lit) {
  thread_local std::vector<Interval> out;
  out.clear();
  for (const Interval& part : lit) {
    Interval stretch;
    if (!terrain.affected_stretch(o, d, part.t0_m, part.t1_m, s, stretch)) {
      out.push_back(part);
      continue;
    }
    if (stretch.t0_m > part.t0_m) out.push_back({part.t0_m, stretch.t0_m});
    const size_t first = out.size();
    terrain.sunlit_parts(o, d, stretch.t0_m, stretch.t1_m, s, out);
    // Join a part that continues the one before it.
    if (first > 0 && out.size() > first && out[first].t0_m <= out[first - 1].t1_m) {
      out[first - 1].t1_m = out[first].t1_m;
      out.erase(out.begin() + static_cast<std::ptrdiff_t>(first));
    }
    if (part.t1_m > stretch.t1_m) {
      if (!out.empty() && out.back().t1_m >= stretch.t1_m)
        out.back().t1_m = part.t1_m;
      else
        out.push_back({stretch.t1_m, part.t1_m});
    }
  }
  lit.swap(out);
}

// The nodes: on pieces where light is collected, view_segments in all, shared in proportion to
// length (an even number per piece, so that pairs of segments form the coarse rule); on the
// others 8, which only carry the view columns across. Densities once per node; the columns by
// the log-mean rule for the positive profiles, the trapezoid rule for ozone.
void SingleScattering::place_nodes(const Vec3& o, const Vec3& d, const ScatteringSources& sources, Ray& ray) const {
  const double R = atm_.planet_radius_m();
  const std::vector<Medium>& media = atm_.media();
  const bool higher = sources.higher != nullptr;
  // Regional media: which are inside their region on the piece being placed (bit j). Outside,
  // a node's density is 0 and its log density the profile's (finite: the log-mean rule of 0 and 0
  // is 0); a node where a piece with other bits begins is repeated with that piece's densities.
  unsigned inside = 0;
  auto inside_on = [&](const Piece& pc) {
    unsigned bits = 0;
    const Vec3 mid = o + 0.5 * (pc.t0 + pc.t1) * d;
    for (int j = 0; j < media_; ++j)
      if (region_[j] && region_[j]->contains(mid)) bits |= 1u << j;
    return bits;
  };
  auto set_densities = [&](Node& n) {
    const double alt = n.r - R;
    for (int j = 0; j < media_; ++j) {
      const DensityProfile& profile = media[static_cast<size_t>(j)].profile;
      if (layer_[j]) {
        n.rho[j] = profile.relative(alt);
      } else {
        n.log_rho[j] = profile.log_relative(alt);
        n.rho[j] = std::exp(n.log_rho[j]);
      }
      if (region_[j] && !(inside & (1u << j))) n.rho[j] = 0.0;
    }
  };
  auto make_node = [&](double t) {
    Node n;
    n.t = t;
    n.r = (o + t * d).norm();
    set_densities(n);
    return n;
  };
  auto append = [&](double t) {
    Node next = make_node(t);
    const Node& prev = ray.nodes.back();
    const double dt = next.t - prev.t;
    for (int j = 0; j < media_; ++j)
      next.col[j] = layer_[j]
                        ? prev.col[j] + 0.5 * dt * (prev.rho[j] + next.rho[j])
                        : prev.col[j] + dt * log_mean(prev.rho[j], next.rho[j], prev.log_rho[j] - next.log_rho[j]);
    ray.nodes.push_back(next);
  };

  double total_len = 0.0;
  for (int i = 0; i < ray.n_pieces; ++i)
    if (ray.pieces[i].lit || higher) total_len += ray.pieces[i].t1 - ray.pieces[i].t0;
  ray.nodes.clear();
  if (has_regions_ && ray.n_pieces > 0) inside = inside_on(ray.pieces[0]);
  Node first = make_node(ray.t_begin);
  std::fill(first.col, first.col + kMaxMedia, 0.0);
  ray.nodes.push_back(first);
  for (int i = 0; i < ray.n_pieces; ++i) {
    Piece& pc = ray.pieces[i];
    if (has_regions_) {
      const unsigned bits = inside_on(pc);
      if (bits != inside) {
        inside = bits;
        Node again = ray.nodes.back();
        set_densities(again);
        ray.nodes.push_back(again);
      }
    }
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
      unsigned absent = 0;
      for (int j = 0; j < media_ && has_regions_; ++j)
        if (region_[j] && !(inside & (1u << j))) absent |= 1u << j;
      piece_node_positions(o, d, pc.t0, pc.t1, segs, absent, positions.data());
    } else {
      for (int k = 0; k <= segs; ++k) positions[static_cast<size_t>(k)] = pc.t0 + (pc.t1 - pc.t0) * k / segs;
    }
    for (int k = 1; k <= segs; ++k) append(k == segs ? pc.t1 : positions[static_cast<size_t>(k)]);
  }
}

// Where a piece's nodes lie: uniform in s(t) = (t - t0) / (t1 - t0) + sum_s c_s(t) / c_s(t1), the
// share of the piece's length plus the shares of its scattering media's columns (c_s(t), the
// column of medium s from t0 to t). A ray that runs low through
// dense air gets short segments there, where its integrand is large and its optical depth grows
// fastest, and at least a third of the nodes stay spread over its length. The columns come from a
// pilot of kPilotsPerSegment x segments + 1 points uniform in t, and s is inverted linearly between
// them. Nothing here depends on the wavelengths (adding one to the grid moves no node), and the
// sun only through the piece's ends (the shadow's edges).
void SingleScattering::piece_node_positions(const Vec3& o, const Vec3& d, double t0, double t1, int segments,
                                            unsigned absent, double* t) const {
  const double R = atm_.planet_radius_m();
  const int count = scatterer_count();
  const int pilots = kPilotsPerSegment * segments;
  const double dt = (t1 - t0) / pilots;
  thread_local std::vector<double> rho[kMaxMedia], share;
  for (int sp = 0; sp < count; ++sp) rho[sp].assign(static_cast<size_t>(pilots) + 1, 0.0);
  share.assign(static_cast<size_t>(pilots) + 1, 0.0);
  for (int k = 0; k <= pilots; ++k) {
    const double alt = (o + (t0 + dt * k) * d).norm() - R;
    for (int sp = 0; sp < count; ++sp)
      rho[sp][static_cast<size_t>(k)] =
          absent & (1u << medium_of_scatterer(sp))
              ? 0.0
              : std::exp(atm_.media()[static_cast<size_t>(medium_of_scatterer(sp))].profile.log_relative(alt));
  }
  // The columns by the trapezoid rule (they only place the nodes), then each medium's share.
  double total[kMaxMedia] = {};
  for (int sp = 0; sp < count; ++sp)
    for (int k = 1; k <= pilots; ++k)
      total[sp] += 0.5 * (rho[sp][static_cast<size_t>(k) - 1] + rho[sp][static_cast<size_t>(k)]);
  double running[kMaxMedia] = {};
  for (int k = 1; k <= pilots; ++k) {
    double v = static_cast<double>(k) / pilots;
    for (int sp = 0; sp < count; ++sp) {
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
// medium[sp]: scatterer sp's index among the media (the nodes' densities are per medium).
template <typename NodeT>
void fill_piece_segments(const NodeT* nodes, int segs, int scatterers, const int* medium, PieceSegments& g) {
  const int m = segs + 1;
  g.segments = segs;
  g.dt.resize(segs);
  g.dt2.resize(segs / 2);
  for (int sp = 0; sp < scatterers; ++sp) {
    const int j = medium[sp];
    g.rho[sp].resize(m);
    g.log_ratio[sp].resize(segs);
    g.log_ratio2[sp].resize(segs / 2);
    for (int k = 0; k < m; ++k) g.rho[sp][k] = static_cast<float>(nodes[k].rho[j]);
    for (int k = 0; k < segs; ++k)
      g.log_ratio[sp][k] = static_cast<float>(nodes[k].log_rho[j] - nodes[k + 1].log_rho[j]);
    for (int i = 0; i < segs / 2; ++i)
      g.log_ratio2[sp][i] = static_cast<float>(nodes[2 * i].log_rho[j] - nodes[2 * i + 2].log_rho[j]);
  }
  for (int k = 0; k < segs; ++k) g.dt[k] = static_cast<float>(nodes[k + 1].t - nodes[k].t);
  for (int j = 0; j < segs / 2; ++j) g.dt2[j] = static_cast<float>(nodes[2 * j + 2].t - nodes[2 * j].t);
}

}  // namespace

// Per thread, reused from ray to ray: [node, medium] columns, [node, wavelength] arrays (or
// [wavelength, node] with many wavelengths: by_node false, see accumulate_piece).
struct SingleScattering::PieceScratch {
  bool by_node = true;
  PieceSegments seg;
  int medium_of[kMaxMedia] = {};  // scatterer -> medium (fill_piece_segments)
  Eigen::ArrayXXf columns, view_columns;
  NodeArray tau, trans, source, view_tau, view_trans;
  std::vector<double> node_r, node_mu_sun;  // the sun columns' arguments at a piece's nodes
  std::vector<Columns> sun;
  // Per scatterer, [wavelength, node], as the source tables write them: J_s, and J_s + P_Q,s and
  // J_s + P_U,s (polarised_sources).
  Eigen::ArrayXXf source_t[kMaxMedia], source_q_t[kMaxMedia], source_u_t[kMaxMedia];
  // [wavelength, node]: SkylineCut's phase shares and the tables' light below the skyline
  Eigen::ArrayXXf hidden_share[kMaxMedia], hidden[kMaxMedia], hidden_multiple[kMaxMedia];
  std::vector<float> shadowed_ahead;                            // per node: SkylineCut::terrain_shadowed_ahead
  std::vector<double> source_r, source_mu_sun, source_mu_view;  // per node: InScatteringSource::sources's
  std::vector<float> moments;                                   // InScatteringSource::rayleigh_moments at one node
  std::vector<float> spin2;              // InScatteringSource::polarisation_harmonics at one node
  std::vector<double> spin2_q, spin2_u;  // the harmonics' Q and U parts in the node's view direction
  Spectrum q, u, pq, pu;                 // polarised_sources' sums at one node
  std::vector<float> field;              // InScatteringSource::field_harmonics at one node
  // polarised_sources' sums of one degree at one node, padded to whole blocks of 16 wavelengths:
  // the harmonics, their mirror images and the intensity's harmonics polarised
  std::vector<float> degree_q, degree_u, mirror_q, mirror_u, polarised_q, polarised_u;
};

// tau = sum_j beta_ext,j(l) columns[k, j] (the optical depth), as [node k, wavelength l] or [l, k].
void SingleScattering::optical_depths(const Eigen::ArrayXXf& columns, PieceScratch& sc, NodeArray& tau) const {
  const Eigen::Index m = columns.rows(), n = n_;
  if (sc.by_node) {
    tau.resize(m, n);
    for (Eigen::Index l = 0; l < n; ++l) {
      if (media_ >= 2)
        tau.col(l) = columns.col(0) * ext_[0][l] + columns.col(1) * ext_[1][l];
      else
        tau.col(l) = columns.col(0) * ext_[0][l];
      for (int j = 2; j < media_; ++j) tau.col(l) += columns.col(j) * ext_[j][l];
    }
    return;
  }
  tau.resize(n, m);
  for (Eigen::Index k = 0; k < m; ++k) {
    if (media_ >= 2)
      tau.col(k) = ext_[0] * columns(k, 0) + ext_[1] * columns(k, 1);
    else
      tau.col(k) = ext_[0] * columns(k, 0);
    for (int j = 2; j < media_; ++j) tau.col(k) += ext_[j] * columns(k, j);
  }
}

// Single scattering on one lit piece: the integrand of medium s is rho_s exp(-tau_view - tau_sun);
// its fine and coarse log-mean sums are added to ws.sums[s].single. The optical depths are the
// field atmosphere's (InScatteringSource::field_atmosphere: the light of the forward peaks goes on
// with the sun's and the view's unscattered light, Nakajima & Tanaka's single scattering), the
// phase functions and scattering coefficients the integrator's own.
void SingleScattering::single_scattering_piece(const Node* nodes, int m, const Vec3& o, const Vec3& d, const Vec3& sun,
                                               const SingleScattering& field, PieceScratch& sc,
                                               ScatteringWorkspace& ws) const {
  const double os = o.dot(sun), ds = d.dot(sun);
  sc.columns.resize(m, media_);
  sc.node_r.resize(static_cast<size_t>(m));
  sc.node_mu_sun.resize(static_cast<size_t>(m));
  sc.sun.resize(static_cast<size_t>(m));
  for (int k = 0; k < m; ++k) {
    sc.node_r[static_cast<size_t>(k)] = nodes[k].r;
    sc.node_mu_sun[static_cast<size_t>(k)] = (os + nodes[k].t * ds) / nodes[k].r;
  }
  sun_.at_many(m, sc.node_r.data(), sc.node_mu_sun.data(), sc.sun.data());
  if (has_regions_)
    for (int k = 0; k < m; ++k)
      for (int j = 0; j < media_; ++j)
        if (region_[j])
          sc.sun[static_cast<size_t>(k)][static_cast<size_t>(j)] = regional_column(j, o + nodes[k].t * d, sun);
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < media_; ++j)
      sc.columns(k, j) = static_cast<float>(nodes[k].col[j] + sc.sun[static_cast<size_t>(k)][static_cast<size_t>(j)]);
  field.optical_depths(sc.columns, sc, sc.tau);
  sc.trans = (-sc.tau).exp();
  // Two media at a time: their integrands share the optical depth and transmittance.
  int s = 0;
  for (; s + 1 < scatterer_count(); s += 2) {
    if (sc.by_node)
      accumulate_piece_2(sc.tau, sc.trans, sc.seg, s, s + 1, ws.sums[s].single, ws.sums[s + 1].single);
    else
      accumulate_piece_by_wavelength_2(sc.tau, sc.trans, sc.seg, s, s + 1, ws.sums[s].single, ws.sums[s + 1].single);
  }
  if (s < scatterer_count()) accumulate(sc, s, ws.sums[s].single);
}

// Higher orders on one piece: the integrand of medium s is beta_sca,s rho_s exp(-tau_view) J_s,
// J_s the higher-order source of that medium in the ray's direction. It is integrated by the same
// log-mean rule as single scattering, with tau' = tau_view - ln J_s in the place of the optical
// depth and T' = exp(-tau_view) J_s in the place of the transmittance (ln of the integrand is
// ln rho_s - tau' + const), once per medium. J is floored at a tiny positive value so that its
// logarithm is finite where the tables hold no light.
// The view ray and the Stokes frame of its polarised parts (polarisation_frame).
struct SingleScattering::RayFrame {
  Vec3 o, d, s, e1, e2;
};

// The higher orders' polarised sources at a piece's nodes (RadianceParts::polarised_q):
// source_q_t[s], source_u_t[s] become J_s + P_Q,s, J_s + P_U,s for each scattering medium s. For
// Rayleigh's matrix (molecules) with the King factor's
// depolarisation, light arriving with coherency matrices C(w) is scattered towards k as
//
//   I = 2 B tr(P D P) + (A - B) tr D,   Q = 2 B (e1^T D e1 - e2^T D e2),   U = 4 B e1^T D e2,
//
// with D = integral C(w) dw, P = 1 - k k^T and A + B mu^2 the phase function (at one unpolarised
// direction these are a1 and b1 of physics/scattering_matrix.hpp). The unpolarised part of D is
// (tr T 1 - T) / 2 with T the field's second moments, whose traceless part is sum_m a_2m K_m
// (spherical_harmonics.hpp); the scalar source J_R already holds its intensity, and the polarised
// part D_pol (traceless) adds -2 B k^T D_pol k to it (SourceTable::source adds that for polarised
// tables, so that the intensity is the vector one in every render). A particle's unit matrix
// scales each degree of the field's spin-2 harmonics by its moment beta_l (spin2_harmonics.hpp):
// P_s = sum_l beta_l,s sum_m c_lm (lambda_lm cos m phi, lambda_lm sin m phi) relative to the view
// direction's (e_theta, e_phi), turned into (e1, e2). At each node the tables' local frame (z up, x
// towards the sun's azimuth, y = z x x) is rebuilt and e1, e2 and the view direction are expressed
// in it.
// J + P is not negative for a real field (scattered light is at most fully polarised), which lets
// the log-mean rule integrate it; P is the difference of two such integrals. (A particle's source,
// from a truncated field, is not bound to that: where J_s + P_s would go below zero the rule's
// floor of 1e-30 clips it, an error the comparison with the reference includes.) False if
// `higher` does not resolve the quadrupole.
bool SingleScattering::polarised_sources(const Node* nodes, int m, const RayFrame& f, const InScatteringSource& higher,
                                         PieceScratch& sc) const {
  const Eigen::Index n = n_;
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
  bool particles = false;
  for (int s = 0; s < scatterer_count(); ++s) {
    sc.source_q_t[s].resize(n, m);
    sc.source_u_t[s].resize(n, m);
    particles = particles || !scatterers_[static_cast<size_t>(s)].rayleigh();
  }
  const int max_spin2 = particles ? kMaxSpin2Degree : 0;
  constexpr double kSqrtHalf = 0.70710678118654752440;
  // Spheres: their mirrored polarisation (alpha_-) and their b1 on the intensity's harmonics.
  // (Both branches lvalues: a temporary in one of them would make the operator copy the other.)
  static const std::vector<SpinMoments> kNoParticles;
  const std::vector<SpinMoments>& spin = particles ? spin_moments() : kNoParticles;
  bool mirroring = false, polarising = false;
  for (const SpinMoments& medium : spin) {
    mirroring = mirroring || !medium.mirrored.empty();
    polarising = polarising || !medium.polarising.empty();
  }
  // The harmonics' rows are read in whole blocks of 16 wavelengths: 16 spare floats after the last.
  const Eigen::Index padded = (n + 15) / 16 * 16;
  sc.spin2.resize(static_cast<size_t>(spin2_harmonic_count(max_spin2)) * static_cast<size_t>(n) + 16);
  sc.field.resize(polarising ? static_cast<size_t>(harmonic_count(max_spin2)) * static_cast<size_t>(n) + 16 : 0);
  for (std::vector<float>* v :
       {&sc.degree_q, &sc.degree_u, &sc.mirror_q, &sc.mirror_u, &sc.polarised_q, &sc.polarised_u})
    v->resize(static_cast<size_t>(padded));
  sc.spin2_q.resize(static_cast<size_t>(spin2_harmonic_count(max_spin2)));
  sc.spin2_u.resize(static_cast<size_t>(spin2_harmonic_count(max_spin2)));
  for (int k = 0; k < m; ++k) {
    const Vec3 p = f.o + nodes[k].t * f.d;
    const Vec3 z = p / p.norm();
    if (!higher.rayleigh_moments(nodes[k].r, f.s.dot(z), sc.moments.data())) return false;
    const Vec3 x = tables_frame_x(z, f.s), y = z.cross(x);
    const Vec3 e(f.e1.dot(x), f.e1.dot(y), f.e1.dot(z)), g(f.e2.dot(x), f.e2.dot(y), f.e2.dot(z));
    // The quadrupole's share, D's part -T / 2 with T = sum a_2m K_m (q, u), and the polarisation
    // tensor's (pq, pu), which molecules see.
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
    // The particles' share: the field's spin-2 harmonics at the view direction (its (e_theta,
    // e_phi) frame turned into (e1, e2): Q = A_qq Q_local + A_qu U_local, U = A_uq Q_local + A_uu
    // U_local), summed per degree and weighted by each particle's moments: beta_l for the
    // harmonics themselves, beta-_l for their mirror images and gamma_l for the intensity's
    // harmonics that b1 polarises (spin2_harmonics.hpp).
    const int degree =
        particles ? higher.polarisation_harmonics(nodes[k].r, f.s.dot(z), max_spin2, sc.spin2.data()) : 0;
    const int field_degree =
        polarising ? higher.field_harmonics(nodes[k].r, f.s.dot(z), max_spin2, sc.field.data()) : -1;
    const int top = std::max(degree, field_degree);
    if (top >= 2) {
      const double dx = f.d.dot(x), dy = f.d.dot(y), dz = std::clamp(f.d.dot(z), -1.0, 1.0);
      const double sin_t = std::sqrt(dx * dx + dy * dy);
      const double cos_phi = sin_t > 1e-12 ? dx / sin_t : 1.0, sin_phi = sin_t > 1e-12 ? dy / sin_t : 0.0;
      // e_theta, e_phi in the local frame; e and g are e1 and e2 there.
      const Vec3 e_theta(dz * cos_phi, dz * sin_phi, -sin_t), e_phi(-sin_phi, cos_phi, 0.0);
      const double ta = e_theta.dot(e), sa = e_theta.dot(g), tb = e_phi.dot(e), sb = e_phi.dot(g);
      const double a_qq = 0.5 * (ta * ta - tb * tb - sa * sa + sb * sb), a_qu = ta * tb - sa * sb;
      const double a_uq = ta * sa - tb * sb, a_uu = ta * sb + tb * sa;
      spin2_harmonics(top, dz, cos_phi, sin_phi, sc.spin2_q.data(), sc.spin2_u.data());
      // The harmonics' Q and U in (e1, e2).
      for (int c = 0; c < spin2_harmonic_count(top); ++c) {
        const double hq = sc.spin2_q[static_cast<size_t>(c)], hu = sc.spin2_u[static_cast<size_t>(c)];
        sc.spin2_q[static_cast<size_t>(c)] = a_qq * hq + a_qu * hu;
        sc.spin2_u[static_cast<size_t>(c)] = a_uq * hq + a_uu * hu;
      }
      for (int s = 0; s < scatterer_count(); ++s) {
        sc.source_q_t[s].col(k) = sc.source_t[s].col(k);
        sc.source_u_t[s].col(k) = sc.source_t[s].col(k);
      }
      // out_q, out_u = the sum of the rows `terms` passes (n wavelengths each) times (wq, wu); whole blocks
      // of 16 (the lanes past n read the next row or the spare floats and are not used).
      const auto sum_rows = [&](std::vector<float>& out_q, std::vector<float>& out_u, const auto& terms) {
        float* dq = out_q.data();
        float* du = out_u.data();
        std::fill(dq, dq + padded, 0.0f);
        std::fill(du, du + padded, 0.0f);
        terms([&](const float* row, double wq, double wu) {
          const float fq = static_cast<float>(wq), fu = static_cast<float>(wu);
          for (Eigen::Index i = 0; i < padded; ++i) {
            dq[i] += fq * row[i];
            du[i] += fu * row[i];
          }
        });
      };
      const auto spin2_row = [&](int l, int mm) {
        return sc.spin2.data() + static_cast<size_t>(spin2_harmonic_index(l, mm)) * static_cast<size_t>(n);
      };
      const auto hq = [&](int l, int mm) { return sc.spin2_q[static_cast<size_t>(spin2_harmonic_index(l, mm))]; };
      const auto hu = [&](int l, int mm) { return sc.spin2_u[static_cast<size_t>(spin2_harmonic_index(l, mm))]; };
      for (int l = 2; l <= top; ++l) {
        if (l <= degree) {
          sum_rows(sc.degree_q, sc.degree_u, [&](const auto& row) {
            for (int mm = -l; mm <= l; ++mm) row(spin2_row(l, mm), hq(l, mm), hu(l, mm));
          });
          if (mirroring)
            sum_rows(sc.mirror_q, sc.mirror_u, [&](const auto& row) {
              for (int mm = -l; mm <= l; ++mm) {
                const double sign = (mm % 2 == 0) ? 1.0 : -1.0;
                row(spin2_row(l, mm), sign * hq(l, -mm), sign * hu(l, -mm));
              }
            });
        }
        if (l <= field_degree)
          sum_rows(sc.polarised_q, sc.polarised_u, [&](const auto& row) {
            const float* a = sc.field.data() + static_cast<size_t>(harmonic_index(l, 0)) * static_cast<size_t>(n);
            row(a, hq(l, 0), hu(l, 0));
            for (int mm = 1; mm <= l; ++mm) {
              const double sign = (mm % 2 == 0) ? 1.0 : -1.0;
              const float* am = sc.field.data() + static_cast<size_t>(harmonic_index(l, mm)) * static_cast<size_t>(n);
              row(am, kSqrtHalf * (sign * hq(l, mm) + hq(l, -mm)), kSqrtHalf * (sign * hu(l, mm) + hu(l, -mm)));
            }
          });
        for (int s = 0; s < scatterer_count(); ++s) {
          const Scatterer& medium = scatterers_[static_cast<size_t>(s)];
          if (medium.rayleigh()) continue;
          const SpinMoments& moments = spin[static_cast<size_t>(s)];
          const size_t li = static_cast<size_t>(l);
          using Map = Eigen::Map<const Spectrum>;
          if (l <= degree) {
            sc.source_q_t[s].col(k) += moments.plus[li] * Map(sc.degree_q.data(), n);
            sc.source_u_t[s].col(k) += moments.plus[li] * Map(sc.degree_u.data(), n);
            if (!moments.mirrored.empty()) {
              sc.source_q_t[s].col(k) += moments.mirrored[li] * Map(sc.mirror_q.data(), n);
              sc.source_u_t[s].col(k) += moments.mirrored[li] * Map(sc.mirror_u.data(), n);
            }
          }
          if (l <= field_degree && !moments.polarising.empty()) {
            sc.source_q_t[s].col(k) += moments.polarising[li] * Map(sc.polarised_q.data(), n);
            sc.source_u_t[s].col(k) += moments.polarising[li] * Map(sc.polarised_u.data(), n);
          }
        }
      }
    }
    for (int s = 0; s < scatterer_count(); ++s) {
      const Scatterer& medium = scatterers_[static_cast<size_t>(s)];
      if (medium.rayleigh()) {
        sc.source_q_t[s].col(k) = sc.source_t[s].col(k) + 2.0f * medium.phase_b * (q + pq);
        sc.source_u_t[s].col(k) = sc.source_t[s].col(k) + 2.0f * medium.phase_b * (u + pu);
      } else if (top < 2) {
        sc.source_q_t[s].col(k) = sc.source_t[s].col(k);
        sc.source_u_t[s].col(k) = sc.source_t[s].col(k);
      }
    }
  }
  return true;
}

// A ray that ends on a surface (the terrain, or the sphere's ground where the terrain can matter)
// looks at what hides the sky behind it from the ray's points. Seen from a point p, the terrain's
// skyline above the ray's end (Terrain::skyline_above; the end itself if no terrain rises behind
// it) is taken as a straight crest: a great circle passing gamma(p) above the view direction d,
// gamma(p) the angle between d and the skyline point seen from p, and everything below it is the
// surface seen through the air between p and it. There the tables (built without terrain) hold
// the sky and the sphere's sunlit ground, J_hidden,s of the source
// (InScatteringSource::source_above_skyline, from the field's mean over each ring about d and its
// variation upwards around the ring).
// Where the terrain shadows the air in front of the surface, that light is replaced by the
// surface's, by the share that reaches p unscattered, T(p, hit), and by the air's own light
// scattered more than once (that air gets no direct sun):
//   J_s = J_s,tables - f_shadow [J_hidden,s - T h_s L_surface - (1 - T) J_hidden,s,multiple],
// f_shadow the share of the ray's length from p to its end in the terrain's shadow (not the
// planet's: the tables hold that), h_s the phase function's share of the hidden region and
// J_hidden,multiple the part of J_hidden from the tables' orders 3 and up (source_above_skyline's
// hidden_multiple). Where the air in front is lit the tables' light is kept: the lit air and the surface
// behind it make up for it (docs/terrain.md compares both choices with the reference on a sunlit
// face). In the shadow this is where
// the tables err most: looking towards the terrain, the aerosol's forward scattering sees the
// bright sky around the sun that the terrain hides. The skyline's shape (straight, level across
// d's vertical plane), the air in front seen along d only, and the sky the terrain hides from
// rays that end in the sky are approximations (docs/terrain.md measures what remains).
struct SingleScattering::SkylineCut {
  Vec3 o, d, skyline;
  Spectrum radiance;  // the surface's reflected radiance, per unit solar irradiance
  Spectrum tau_end;   // the view ray's optical depth to the surface
  const Ray* ray = nullptr;
  // The share of the ray's length from t to its end that the terrain (not the planet) shadows.
  double terrain_shadowed_ahead(double t) const {
    const double ahead = ray->t_end - t;
    if (!(ahead > 0.0)) return 0.0;
    double planet = 0.0, lit = 0.0;
    for (int i = 0; i < ray->planet_lit.count; ++i)
      planet += std::max(0.0, ray->planet_lit.parts[i].t1_m - std::max(t, ray->planet_lit.parts[i].t0_m));
    for (int i = 0; i < ray->n_pieces; ++i)
      if (ray->pieces[i].lit) lit += std::max(0.0, ray->pieces[i].t1 - std::max(t, ray->pieces[i].t0));
    return std::clamp((planet - lit) / ahead, 0.0, 1.0);
  }
};

bool SingleScattering::higher_orders_piece(const Node* nodes, int m, const Vec3& o, const Vec3& d, double os, double ds,
                                           const InScatteringSource& higher, const RegionalSource* regional,
                                           const SingleScattering& field, const RayFrame* polarisation,
                                           const SkylineCut* cut, PieceScratch& sc, ScatteringWorkspace& ws) const {
  const Eigen::Index n = n_;
  const double od = o.dot(d);
  const int count = scatterer_count();
  sc.view_columns.resize(m, media_);
  float* out[kMaxMedia];
  float* share[kMaxMedia];
  float* hidden[kMaxMedia];
  float* multiple[kMaxMedia];
  for (int s = 0; s < count; ++s) sc.source_t[s].resize(n, m);
  bool were_cut = false;
  if (cut) {
    for (int s = 0; s < count; ++s) {
      sc.hidden_share[s].resize(n, m);
      sc.hidden[s].resize(n, m);
      sc.hidden_multiple[s].resize(n, m);
    }
    sc.shadowed_ahead.resize(static_cast<size_t>(m));
  }
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < media_; ++j) sc.view_columns(k, j) = static_cast<float>(nodes[k].col[j]);
  if (!cut) {
    // Every node's source at once (InScatteringSource::sources): tables read what successive
    // nodes share once for them.
    sc.source_r.resize(static_cast<size_t>(m));
    sc.source_mu_sun.resize(static_cast<size_t>(m));
    sc.source_mu_view.resize(static_cast<size_t>(m));
    for (int k = 0; k < m; ++k) {
      const double r = nodes[k].r;
      sc.source_r[static_cast<size_t>(k)] = r;
      sc.source_mu_sun[static_cast<size_t>(k)] = (os + nodes[k].t * ds) / r;
      sc.source_mu_view[static_cast<size_t>(k)] = (od + nodes[k].t) / r;
    }
    for (int s = 0; s < count; ++s) out[s] = sc.source_t[s].data();
    higher.sources(m, sc.source_r.data(), sc.source_mu_sun.data(), sc.source_mu_view.data(), ds, count,
                   static_cast<int>(n), out);
    // In and about a region, every scatterer's source gains what the tables leave out.
    if (regional)
      for (int k = 0; k < m; ++k) {
        for (int s = 0; s < count; ++s) out[s] = sc.source_t[s].col(k).data();
        regional->add(o + nodes[k].t * d, -d, out);
      }
  }
  for (int k = 0; k < m && cut; ++k) {
    const double r = nodes[k].r;
    for (int s = 0; s < count; ++s) out[s] = sc.source_t[s].col(k).data();
    const double mu_sun = (os + nodes[k].t * ds) / r, mu_view = (od + nodes[k].t) / r;
    sc.shadowed_ahead[static_cast<size_t>(k)] = static_cast<float>(cut->terrain_shadowed_ahead(nodes[k].t));
    if (sc.shadowed_ahead[static_cast<size_t>(k)] > 0.0f) {
      const Vec3 towards = cut->skyline - (cut->o + nodes[k].t * cut->d);
      const double norm = towards.norm();
      const double gamma = norm > 0.0 ? std::acos(std::clamp(towards.dot(cut->d) / norm, -1.0, 1.0)) : 0.5 * kPi;
      for (int s = 0; s < count; ++s) {
        share[s] = sc.hidden_share[s].col(k).data();
        hidden[s] = sc.hidden[s].col(k).data();
        multiple[s] = sc.hidden_multiple[s].col(k).data();
      }
      if (higher.source_above_skyline(r, mu_sun, mu_view, ds, gamma, out, hidden, share, multiple)) {
        were_cut = true;
        continue;
      }
      for (int s = 0; s < count; ++s) {
        sc.hidden_share[s].col(k).setZero();
        sc.hidden[s].col(k).setZero();
        sc.hidden_multiple[s].col(k).setZero();
      }
    }
    higher.source(r, mu_sun, mu_view, ds, out);
    // In and about a region, every scatterer's source gains what the tables leave out.
    if (regional) regional->add(o + nodes[k].t * d, -d, out);
  }
  // The field's light travels to the camera through the field's atmosphere (field_atmosphere()).
  field.optical_depths(sc.view_columns, sc, sc.view_tau);
  sc.view_trans = (-sc.view_tau).exp();
  if (were_cut) {
    // Below the skyline: the surface's light in the place of the tables', by the share that comes
    // through the air unscattered and where that air is shadowed.
    for (int k = 0; k < m; ++k) {
      const float shadowed = sc.shadowed_ahead[static_cast<size_t>(k)];
      if (shadowed == 0.0f) continue;  // the node took the tables' source
      if (sc.by_node)
        sc.u = (sc.view_tau.row(k).transpose() - cut->tau_end).min(0.0f).exp();
      else
        sc.u = (sc.view_tau.col(k) - cut->tau_end).min(0.0f).exp();
      // source_t holds J_s - J_hidden,s (source_above_skyline); below the skyline, lit air in front
      // keeps the tables' light, shadowed air the surface through it and its own light scattered
      // more than once.
      for (int s = 0; s < count; ++s)
        sc.source_t[s].col(k) +=
            (1.0f - shadowed) * sc.hidden[s].col(k) + shadowed * (sc.u * sc.hidden_share[s].col(k) * cut->radiance +
                                                                  (1.0f - sc.u) * sc.hidden_multiple[s].col(k));
    }
  }
  // Each medium's sums with J_s; then, for polarisation, with J_s + P_Q,s and J_s + P_U,s.
  const bool polarised = polarisation && field.polarised_sources(nodes, m, *polarisation, higher, sc);
  for (int s = 0; s < count; ++s) {
    ScatteringWorkspace::Sums& sums = ws.sums[s];
    const Eigen::ArrayXXf* pass_sources[3] = {&sc.source_t[s], &sc.source_q_t[s], &sc.source_u_t[s]};
    Spectrum* pass_sums[3] = {sums.higher, sums.q, sums.u};
    for (int pass = 0; pass < (polarised ? 3 : 1); ++pass) {
      const Eigen::ArrayXXf& source_t = *pass_sources[pass];
      if (sc.by_node)
        sc.source = source_t.transpose().max(1e-30f);
      else
        sc.source = source_t.max(1e-30f);
      sc.trans = sc.view_trans * sc.source;
      sc.tau = sc.view_tau - sc.source.log();
      accumulate(sc, s, pass_sums[pass]);
    }
  }
  return polarised;
}

void SingleScattering::accumulate(PieceScratch& sc, int s, Spectrum* sums) const {
  if (sc.by_node)
    accumulate_piece(sc.tau, sc.trans, sc.seg, s, sums[0], sums[1]);
  else
    accumulate_piece_by_wavelength(sc.tau, sc.trans, sc.seg, s, sums[0], sums[1]);
}

// The ground at the ray's end: Lambertian reflection of the direct sun (order 1) and of the sky
// (higher orders), seen through the whole view ray; added to the phase-free part. With higher
// orders from a field atmosphere (InScatteringSource::field_atmosphere) the sun's light reaches
// the ground, and the ground's light the camera, through that atmosphere: the light of the forward
// peaks goes with them, as in the tables' own ground.
void SingleScattering::ground_reflection(const Node& ground, const Vec3& ground_point, const Vec3& s, double mu_sun,
                                         const ScatteringSources& sources, ScatteringWorkspace& ws,
                                         RadianceParts& parts) const {
  ground_irradiance_at(ground_point, s, mu_sun, sources, ws);
  field_integrator(sources).view_optical_depth(ground, ws.view_tau);
  ws.view_trans = (-ws.view_tau).exp();
  parts.phase_free += ws.view_trans * albedo_over_pi_at(ground_point, sources.terrain, ws) * ws.source;
}

void SingleScattering::ground_irradiance_at(const Vec3& ground_point, const Vec3& s, double mu_sun,
                                            const ScatteringSources& sources, ScatteringWorkspace& ws) const {
  const double R = atm_.planet_radius_m();
  ws.source.setZero();
  // The terrain may hide the sun from this point of the sphere's ground (a plain in a ridge's shadow).
  if (sources.single && mu_sun > 0.0 &&
      !(sources.terrain && sources.terrain->shadowed(ground_point + 1e-3 * ground_point.normalized(), s))) {
    Spectrum& tau_sun = ws.ground_sun;
    const Columns sun = sun_columns_at(ground_point, R, mu_sun, s);
    field_integrator(sources).optical_depth(sun.data(), tau_sun);
    ws.source = (-tau_sun).exp() * static_cast<float>(mu_sun);
  }
  if (sources.higher && sources.higher_light) {
    sources.higher->ground_irradiance(mu_sun, ws.ground_sky.data());
    if (sources.regional) sources.regional->add_ground(ground_point, ws.ground_sky.data());
    ws.source += ws.ground_sky;
  }
}

// The terrain at the ray's end: the same Lambertian reflection, with the surface's normal n. The
// sun lights it where it faces the sun and neither the terrain nor the planet hides it (the sun's
// columns at the point's own altitude); the higher orders' light is their field at the point's
// altitude and sun angle integrated about n (irradiance_on), or, from a source without an angular
// field, G (for a horizontal surface at height 0) times the view factor of an isotropic sky,
// (1 + n.up) / 2.
void SingleScattering::terrain_reflection(const Node& ground, const Vec3& p, const Vec3& s,
                                          const ScatteringSources& sources, ScatteringWorkspace& ws,
                                          RadianceParts& parts) const {
  terrain_irradiance(ground, p, s, sources, ws);
  field_integrator(sources).view_optical_depth(ground, ws.view_tau);
  ws.view_trans = (-ws.view_tau).exp();
  parts.phase_free += ws.view_trans * albedo_over_pi_at(p, sources.terrain, ws) * ws.source;
}

const Spectrum& SingleScattering::albedo_over_pi_at(const Vec3& p, const Terrain* terrain,
                                                    ScatteringWorkspace& ws) const {
  if (!terrain || !terrain->has_own_albedo() || !terrain->covers(p)) return albedo_over_pi_;
  if (terrain->own_albedo().size() == 0) {
    ws.surface_albedo_over_pi = albedo_over_pi_;
  } else {
    if (terrain->own_albedo().size() != n_)
      throw Error("terrain: an albedo of " + std::to_string(terrain->own_albedo().size()) + " wavelengths for " +
                  std::to_string(n_));
    ws.surface_albedo_over_pi = (terrain->own_albedo() / kPi).cast<float>();
  }
  if (terrain->has_albedo_map()) ws.surface_albedo_over_pi *= static_cast<float>(terrain->albedo_factor_under(p));
  return ws.surface_albedo_over_pi;
}

void SingleScattering::terrain_irradiance(const Node& ground, const Vec3& p, const Vec3& s,
                                          const ScatteringSources& sources, ScatteringWorkspace& ws) const {
  const Terrain& terrain = *sources.terrain;
  ws.source.setZero();
  const Vec3 up = p / p.norm(), n = terrain.normal_under(p);
  const double mu_sun = s.dot(up), incidence = s.dot(n);
  if (sources.single && incidence > 0.0) {
    const Vec3 start = p + 1e-3 * n;  // off the surface, which must not shadow its own point
    if (sphere_entry_distance(start, s, atm_.planet_radius_m()) == std::numeric_limits<double>::infinity() &&
        !terrain.shadowed(start, s)) {
      Spectrum& tau_sun = ws.ground_sun;
      const Columns sun = sun_columns_at(p, ground.r, mu_sun, s);
      field_integrator(sources).optical_depth(sun.data(), tau_sun);
      ws.source = (-tau_sun).exp() * static_cast<float>(incidence);
    }
  }
  if (sources.higher && sources.higher_light) {
    // The normal in the tables' local frame (z up, x towards the sun's azimuth).
    const Vec3 x = tables_frame_x(up, s);
    const Vec3 local(n.dot(x), n.dot(up.cross(x)), n.dot(up));
    if (!sources.higher->irradiance_on(ground.r, mu_sun, local, ws.ground_sky.data())) {
      sources.higher->ground_irradiance(mu_sun, ws.ground_sky.data());
      ws.ground_sky *= static_cast<float>(0.5 * (1.0 + n.dot(up)));
    }
    ws.source += ws.ground_sky;
  }
}

// The optical depth of the view ray from the camera to a node.
void SingleScattering::view_optical_depth(const Node& node, Spectrum& tau) const { optical_depth(node.col, tau); }

// The radiance parts of one traced ray: the log-mean sums over its pieces (single scattering on
// the lit ones, higher orders on all), Richardson-extrapolated, then the transmittance and the
// ground's reflection at its end.
void SingleScattering::integrate(const Ray& ray, const Vec3& o, const Vec3& d, const Vec3& s,
                                 const ScatteringSources& sources, ScatteringWorkspace& ws,
                                 RadianceParts& parts) const {
  parts.resize(n_, scatterer_count());
  const int count = scatterer_count();
  const bool higher = sources.higher != nullptr && sources.higher_light;
  const double os = o.dot(s), ds = d.dot(s);
  for (int j = 0; j < count; ++j)
    for (Spectrum* sum : {&ws.sums[j].single[0], &ws.sums[j].single[1], &ws.sums[j].higher[0], &ws.sums[j].higher[1],
                          &ws.sums[j].q[0], &ws.sums[j].q[1], &ws.sums[j].u[0], &ws.sums[j].u[1]})
      sum->setZero();
  RayFrame frame;
  bool polarised = false;  // whether the higher orders' sources had a quadrupole (all pieces or none)
  if (sources.polarisation) {
    frame = RayFrame{o, d, s, polarisation_frame(d, s), Vec3()};
    frame.e2 = (-d).cross(frame.e1);
  }

  const SingleScattering& field = field_integrator(sources);
  thread_local PieceScratch sc;
  sc.by_node = n_ < kWavelengthsForWavelengthLoops;
  for (int j = 0; j < count; ++j) sc.medium_of[j] = medium_of_scatterer(j);
  thread_local SkylineCut skyline;
  const bool cut = higher && ray.skyline_found;
  if (cut) {
    const Node& last = ray.nodes.back();
    skyline.o = o;
    skyline.d = d;
    skyline.skyline = ray.skyline;
    skyline.ray = &ray;
    if (ray.hits_terrain)
      terrain_irradiance(last, o + last.t * d, s, sources, ws);
    else
      ground_irradiance_at(o + last.t * d, s, (os + last.t * ds) / last.r, sources, ws);
    skyline.radiance = albedo_over_pi_at(o + last.t * d, sources.terrain, ws) * ws.source;
    field.view_optical_depth(last, skyline.tau_end);
  }
  for (int i = 0; i < ray.n_pieces; ++i) {
    const Piece& pc = ray.pieces[i];
    const bool single_here = sources.single && pc.lit;
    if (!single_here && !higher) continue;  // nothing to collect: its nodes only carried the columns
    const Node* nodes = ray.nodes.data() + pc.first_node;
    fill_piece_segments(nodes, pc.segments, count, sc.medium_of, sc.seg);
    if (single_here) single_scattering_piece(nodes, pc.segments + 1, o, d, s, field, sc, ws);
    if (higher)
      polarised |= higher_orders_piece(nodes, pc.segments + 1, o, d, os, ds, *sources.higher, sources.regional, field,
                                       sources.polarisation ? &frame : nullptr, cut ? &skyline : nullptr, sc, ws);
  }

  // beta_sca,s (the field atmosphere's) times each medium's integrals, summed over the media where
  // their phase functions are already inside (the higher orders).
  const std::vector<Scatterer>& field_scatterers = field.scatterers_;
  const auto sum_over_media = [&](auto&& term, Spectrum& out) {
    if (count >= 2)
      out = field_scatterers[0].sca * term(0) + field_scatterers[1].sca * term(1);
    else
      out = field_scatterers[0].sca * term(0);
    for (int j = 2; j < count; ++j) out += field_scatterers[static_cast<size_t>(j)].sca * term(j);
  };
  const auto ms = [&](int j) { return richardson(ws.sums[j].higher[0], ws.sums[j].higher[1]); };
  if (sources.single)
    for (int j = 0; j < count; ++j)
      parts.scattered[static_cast<size_t>(j)] =
          scatterers_[static_cast<size_t>(j)].sca * richardson(ws.sums[j].single[0], ws.sums[j].single[1]);
  if (higher && count > 0) sum_over_media(ms, parts.phase_free);
  if (sources.polarisation) {
    // Zero where nothing was polarised (no higher orders, or tables without a quadrupole).
    if (polarised && count > 0) {
      sum_over_media([&](int j) { return richardson(ws.sums[j].q[0], ws.sums[j].q[1]) - ms(j); }, parts.polarised_q);
      sum_over_media([&](int j) { return richardson(ws.sums[j].u[0], ws.sums[j].u[1]) - ms(j); }, parts.polarised_u);
    } else {
      parts.polarised_q.setZero(n_);
      parts.polarised_u.setZero(n_);
    }
  }

  const Node& last = ray.nodes.back();
  if (sources.transmittance) {
    view_optical_depth(last, ws.view_tau);
    *sources.transmittance = (-ws.view_tau).exp();
  }
  if (ray.hits_ground &&
      albedo_over_pi_at(o + last.t * d, sources.terrain, ws).maxCoeff() > 0.0f) {  // the last node is the ground point
    if (cut)  // the surface's radiance is known already (SkylineCut)
      parts.phase_free += (-skyline.tau_end).exp() * skyline.radiance;
    else if (ray.hits_terrain)
      terrain_reflection(last, o + last.t * d, s, sources, ws, parts);
    else
      ground_reflection(last, o + last.t * d, s, (os + last.t * ds) / last.r, sources, ws, parts);
  }
}

void SingleScattering::radiance_parts(const Vec3& o, const Vec3& d, const Vec3& s, const ScatteringSources& sources,
                                      ScatteringWorkspace& ws, RadianceParts& parts) const {
  parts.resize(n_, scatterer_count());
  if (sources.polarisation) {
    parts.polarised_q.setZero(n_);
    parts.polarised_u.setZero(n_);
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
  if (sources.transmittance || sources.polarisation || sources.terrain || has_regions_ ||
      o.norm() < atm_.planet_radius_m()) {
    for (int i = 0; i < count; ++i) radiance_parts(o, dirs[i], s, sources, ws, parts[i]);
    return;
  }
  thread_local Ray shared, own;
  bool have_shared = false;
  for (int i = 0; i < count; ++i) {
    const Vec3& d = dirs[i];
    if (!trace(o, d, s, sources, own)) {
      parts[i].resize(n_, scatterer_count());
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
