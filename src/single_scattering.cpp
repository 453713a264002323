#include "skyspec/single_scattering.hpp"

#include <algorithm>
#include <cmath>

#include "skyspec/atmosphere.hpp"
#include "skyspec/optical_depth.hpp"
#include "skyspec/phase_function.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

ScatteringWorkspace::ScatteringWorkspace(int n)
    : tau_a(n), tau_b(n), tau_c(n), trans_a(n), trans_b(n), trans_c(n),
      view_tau(n), view_trans(n), source(n), ms_a(n), ms_b(n), ms_c(n), ms_trans_a(n), ms_trans_b(n), ms_trans_c(n),
      sum_rayleigh(n), sum_mie(n), coarse_rayleigh(n), coarse_mie(n), sum_ms_rayleigh(n), sum_ms_mie(n),
      coarse_ms_rayleigh(n), coarse_ms_mie(n), phase(n), parts(n) {}

SingleScattering::SingleScattering(const AtmosphereModel& atm, const SunColumns& sun_columns,
                                   IntegratorSettings s)
    : atm_(atm),
      sun_(sun_columns),
      settings_(s),
      sca_rayleigh_(atm.rayleigh().scattering_per_m.cast<float>()),
      sca_mie_(atm.mie().scattering_per_m.cast<float>()),
      albedo_over_pi_((atm.ground_albedo() / kPi).cast<float>()) {
  ext_[kRayleigh] = atm.rayleigh().extinction_per_m.cast<float>();
  ext_[kMie] = atm.mie().extinction_per_m.cast<float>();
  ext_[kOzone] = atm.ozone().extinction_per_m.cast<float>();
}

namespace {

// The single-scattering integrand of species s on a segment [a, b] of the view ray is
// f(t) = rho_s(t) T(t), T the transmittance along view and sun paths; ln f is nearly linear in t,
// so its integral over the segment is dt * logmean(f_a, f_b) with x = ln f_a - ln f_b
// = (ln rho_a - ln rho_b) - (tau_a - tau_b). This adds that to sum_rayleigh and sum_mie, for every
// wavelength, by log_mean_branchless (optical_depth.hpp), so that this one loop, the innermost
// operation of every march, vectorises (Eigen's select() would be evaluated one element at a time).
struct SpeciesAtNodes {
  float log_ratio;     // ln rho_a - ln rho_b
  float rho_a, rho_b;  // relative densities at the two nodes
};
inline float log_mean_term(float x, float f_a, float f_b) { return log_mean_branchless(f_a, f_b, x, 1e-2f); }
void accumulate_segment_integrals(const Spectrum& tau_a, const Spectrum& trans_a, const Spectrum& tau_b,
                                  const Spectrum& trans_b, SpeciesAtNodes rayleigh, SpeciesAtNodes mie, float dt,
                                  Spectrum& sum_rayleigh, Spectrum& sum_mie) {
  const float* __restrict ta = tau_a.data();
  const float* __restrict tb = tau_b.data();
  const float* __restrict ea = trans_a.data();
  const float* __restrict eb = trans_b.data();
  float* __restrict out_r = sum_rayleigh.data();
  float* __restrict out_m = sum_mie.data();
  const Eigen::Index n = sum_rayleigh.size();
  for (Eigen::Index i = 0; i < n; ++i) {
    const float dtau = ta[i] - tb[i];
    out_r[i] += dt * log_mean_term(rayleigh.log_ratio - dtau, rayleigh.rho_a * ea[i], rayleigh.rho_b * eb[i]);
    out_m[i] += dt * log_mean_term(mie.log_ratio - dtau, mie.rho_a * ea[i], mie.rho_b * eb[i]);
  }
}

// A node of the quadrature: a point on the view ray.
struct Node {
  double t;
  double r;
  double mu_sun;
  double log_rho[2];  // Rayleigh, Mie
  double rho[2];      // exp(log_rho), once per node
  double rho_ozone;
};

// A stretch of the ray between cuts, lit by the sun or in the planet's shadow.
struct Piece {
  double t0, t1;
  bool lit;
};

}  // namespace

void SingleScattering::transmittance_to_space(const Vec3& o, const Vec3& d, Spectrum& out) const {
  const double R = atm_.planet_radius_m(), Rt = atm_.top_radius_m();
  out.setOnes();
  const SphereHit ground = intersect_sphere(o, d, R);
  if (o.norm() < R || (ground.hit && ground.t_near_m > 0.0)) {
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

void SingleScattering::combine(const RadianceParts& parts, double mu, const Spectrum& sun_irradiance,
                               ScatteringWorkspace& ws, Spectrum& out) const {
  const float phase_r = static_cast<float>(rayleigh_phase(mu));
  if (atm_.mie_g_varies()) {
    // A spectral aerosol: the phase function's asymmetry differs per wavelength.
    AerosolPhase phase = atm_.mie_phase();
    for (int i = 0; i < ws.phase.size(); ++i) {
      phase.g = atm_.mie_g()[i];
      ws.phase[i] = static_cast<float>(phase(mu));
    }
    out = (parts.rayleigh * phase_r + parts.mie * ws.phase + parts.isotropic) * sun_irradiance;
  } else {
    const float phase_m = static_cast<float>(atm_.mie_phase()(mu));
    out = (parts.rayleigh * phase_r + parts.mie * phase_m + parts.isotropic) * sun_irradiance;
  }
}

void SingleScattering::radiance_parts(const Vec3& o, const Vec3& d, const Vec3& s, const ScatteringSources& sources,
                                      ScatteringWorkspace& ws, RadianceParts& parts) const {
  parts.rayleigh.setZero();
  parts.mie.setZero();
  parts.isotropic.setZero();
  if (sources.transmittance) sources.transmittance->setOnes();
  const double R = atm_.planet_radius_m(), Rt = atm_.top_radius_m();
  if (o.norm() < R) {  // inside the planet
    if (sources.transmittance) sources.transmittance->setZero();
    return;
  }

  // The part of the ray inside the atmosphere, up to the ground if it hits it, or up to a surface
  // at max_distance_m.
  const SphereHit top = intersect_sphere(o, d, Rt);
  if (!top.hit || top.t_far_m <= 0.0) return;
  const double t_begin = std::max(0.0, top.t_near_m);
  double t_end = top.t_far_m;
  bool hits_ground = false;
  const SphereHit ground = intersect_sphere(o, d, R);
  if (ground.hit && ground.t_near_m > 0.0 && ground.t_near_m < t_end) {
    t_end = ground.t_near_m;
    hits_ground = true;
  }
  if (sources.max_distance_m < t_end) {
    t_end = sources.max_distance_m;
    hits_ground = false;
  }
  if (!(t_end > t_begin)) return;

  // Pieces: cut at the shadow boundaries (closed form) and at the ray's lowest point. Shadowed
  // pieces carry only higher-order light; without it they matter only for the view columns.
  const IntervalSet lit = lit_intervals(o, d, t_begin, t_end, s, R);
  const bool higher = sources.higher != nullptr;
  // Without higher orders, a ray entirely in shadow sees nothing (its ground point is dark too).
  if (!higher && lit.count == 0 && !sources.transmittance) return;
  const double t_low = -o.dot(d);
  Piece pieces[8];
  int n_pieces = 0;
  {
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
        pieces[n_pieces++] = {a, t_low, cut_lit[i]};
        a = t_low;
      }
      pieces[n_pieces++] = {a, b, cut_lit[i]};
      a = b;
    }
  }

  const DensityProfile& prof_r = atm_.rayleigh().profile;
  const DensityProfile& prof_m = atm_.mie().profile;
  const DensityProfile& prof_o = atm_.ozone().profile;
  const bool ozone = atm_.ozone().enabled();
  auto make_node = [&](double t) {
    Node n;
    n.t = t;
    const Vec3 p = o + t * d;
    n.r = p.norm();
    n.mu_sun = p.dot(s) / n.r;
    const double alt = n.r - R;
    n.log_rho[0] = prof_r.log_relative(alt);
    n.log_rho[1] = prof_m.log_relative(alt);
    n.rho[0] = std::exp(n.log_rho[0]);
    n.rho[1] = std::exp(n.log_rho[1]);
    n.rho_ozone = ozone ? prof_o.relative(alt) : 0.0;
    return n;
  };

  // View-ray columns from t_begin: log-mean rule for the positive profiles, trapezoid for ozone.
  double view_col[kSpeciesCount] = {0.0, 0.0, 0.0};
  auto advance_columns = [&](const Node& a, const Node& b) {
    const double dt = b.t - a.t;
    for (int k = 0; k < 2; ++k)
      view_col[k] += dt * log_mean(a.rho[k], b.rho[k], a.log_rho[k] - b.log_rho[k]);
    view_col[kOzone] += 0.5 * dt * (a.rho_ozone + b.rho_ozone);
  };
  auto view_tau = [&](Spectrum& tau) {
    tau = ext_[kRayleigh] * static_cast<float>(view_col[kRayleigh]) + ext_[kMie] * static_cast<float>(view_col[kMie]);
    if (ozone) tau += ext_[kOzone] * static_cast<float>(view_col[kOzone]);
  };
  // Total optical depth view + sun at a lit node.
  auto total_tau = [&](const Node& n, Spectrum& tau) {
    const Columns sun = sun_.at(n.r, n.mu_sun);
    tau = ext_[kRayleigh] * static_cast<float>(view_col[kRayleigh] + sun[kRayleigh]) +
          ext_[kMie] * static_cast<float>(view_col[kMie] + sun[kMie]);
    if (ozone) tau += ext_[kOzone] * static_cast<float>(view_col[kOzone] + sun[kOzone]);
  };
  // Higher orders: the integrand of species s is beta_sca,s rho_s exp(-tau_view) J, J the
  // higher-order source. It is integrated by the same log-mean rule as single scattering, with
  // tau' = tau_view - ln J in the place of the optical depth and T' = exp(-tau_view) J in the
  // place of the transmittance (ln of the integrand is ln rho_s - tau' + const). J is floored at
  // a tiny positive value so that its logarithm is finite where the tables hold no light.
  auto higher_node = [&](const Node& n, Spectrum& tau, Spectrum& trans) {
    sources.higher->source(n.r, n.mu_sun, ws.source.data());
    view_tau(ws.view_tau);
    ws.source = ws.source.max(1e-30f);
    tau = ws.view_tau - ws.source.log();
    trans = (-ws.view_tau).exp() * ws.source;
  };
  // Single-scattering integrals over one segment [a, b] for both species, by the log-mean rule.
  auto accumulate_segment = [&](const Node& na, const Node& nb, const Spectrum& tau_a, const Spectrum& trans_a,
                                const Spectrum& tau_b, const Spectrum& trans_b, Spectrum& sum_r, Spectrum& sum_m) {
    auto species = [&](int sp) {
      return SpeciesAtNodes{static_cast<float>(na.log_rho[sp] - nb.log_rho[sp]), static_cast<float>(na.rho[sp]),
                            static_cast<float>(nb.rho[sp])};
    };
    accumulate_segment_integrals(tau_a, trans_a, tau_b, trans_b, species(0), species(1),
                                 static_cast<float>(nb.t - na.t), sum_r, sum_m);
  };

  double total_len = 0.0;
  for (int i = 0; i < n_pieces; ++i)
    if (pieces[i].lit || higher) total_len += pieces[i].t1 - pieces[i].t0;
  ws.sum_rayleigh.setZero();
  ws.sum_mie.setZero();
  ws.coarse_rayleigh.setZero();
  ws.coarse_mie.setZero();
  ws.sum_ms_rayleigh.setZero();
  ws.sum_ms_mie.setZero();
  ws.coarse_ms_rayleigh.setZero();
  ws.coarse_ms_mie.setZero();

  Node prev = make_node(t_begin);
  for (int i = 0; i < n_pieces; ++i) {
    const Piece& pc = pieces[i];
    const bool single_here = sources.single && pc.lit;
    if (!single_here && !higher) {
      // Nothing to collect: only the view columns advance, on a few segments.
      const int n = 8;
      const double dt = (pc.t1 - pc.t0) / n;
      for (int k = 1; k <= n; ++k) {
        const Node next = make_node(k == n ? pc.t1 : pc.t0 + dt * k);
        advance_columns(prev, next);
        prev = next;
      }
      continue;
    }
    // An even number of segments, so that pairs of them form the coarse rule.
    int segs = std::max(2, static_cast<int>(std::lround(settings_.view_segments * (pc.t1 - pc.t0) / total_len)));
    segs += segs % 2;
    const double dt = (pc.t1 - pc.t0) / segs;
    if (single_here) {
      total_tau(prev, ws.tau_a);
      ws.trans_a = (-ws.tau_a).exp();
      ws.tau_c = ws.tau_a;
      ws.trans_c = ws.trans_a;
    }
    if (higher) {
      higher_node(prev, ws.ms_a, ws.ms_trans_a);
      ws.ms_c = ws.ms_a;
      ws.ms_trans_c = ws.ms_trans_a;
    }
    Node pair_start = prev;
    for (int k = 1; k <= segs; ++k) {
      const Node next = make_node(k == segs ? pc.t1 : pc.t0 + dt * k);
      advance_columns(prev, next);
      if (single_here) {
        total_tau(next, ws.tau_b);
        ws.trans_b = (-ws.tau_b).exp();
        accumulate_segment(prev, next, ws.tau_a, ws.trans_a, ws.tau_b, ws.trans_b, ws.sum_rayleigh, ws.sum_mie);
      }
      if (higher) {
        higher_node(next, ws.ms_b, ws.ms_trans_b);
        accumulate_segment(prev, next, ws.ms_a, ws.ms_trans_a, ws.ms_b, ws.ms_trans_b, ws.sum_ms_rayleigh,
                           ws.sum_ms_mie);
      }
      if (k % 2 == 0) {
        if (single_here) {
          accumulate_segment(pair_start, next, ws.tau_c, ws.trans_c, ws.tau_b, ws.trans_b, ws.coarse_rayleigh,
                             ws.coarse_mie);
          ws.tau_c = ws.tau_b;
          ws.trans_c = ws.trans_b;
        }
        if (higher) {
          accumulate_segment(pair_start, next, ws.ms_c, ws.ms_trans_c, ws.ms_b, ws.ms_trans_b, ws.coarse_ms_rayleigh,
                             ws.coarse_ms_mie);
          ws.ms_c = ws.ms_b;
          ws.ms_trans_c = ws.ms_trans_b;
        }
        pair_start = next;
      }
      prev = next;
      if (single_here) {
        ws.tau_a.swap(ws.tau_b);
        ws.trans_a.swap(ws.trans_b);
      }
      if (higher) {
        ws.ms_a.swap(ws.ms_b);
        ws.ms_trans_a.swap(ws.ms_trans_b);
      }
    }
  }

  // Richardson extrapolation: each rule's error is O(dt^2), so (4 fine - coarse) / 3 cancels the
  // leading term. Clamped at 0 in case a coarse pair is far off (it never is for smooth integrands).
  if (sources.single) {
    parts.rayleigh = sca_rayleigh_ * ((4.0f * ws.sum_rayleigh - ws.coarse_rayleigh) * (1.0f / 3.0f)).max(0.0f);
    parts.mie = sca_mie_ * ((4.0f * ws.sum_mie - ws.coarse_mie) * (1.0f / 3.0f)).max(0.0f);
  }
  if (higher)
    parts.isotropic = sca_rayleigh_ * ((4.0f * ws.sum_ms_rayleigh - ws.coarse_ms_rayleigh) * (1.0f / 3.0f)).max(0.0f) +
                      sca_mie_ * ((4.0f * ws.sum_ms_mie - ws.coarse_ms_mie) * (1.0f / 3.0f)).max(0.0f);

  if (sources.transmittance) {
    view_tau(ws.view_tau);
    *sources.transmittance = (-ws.view_tau).exp();
  }

  // The ground: Lambertian reflection of the direct sun (order 1) and of the sky (higher orders),
  // seen through the whole view ray.
  if (hits_ground && albedo_over_pi_.maxCoeff() > 0.0f) {
    const Node g = prev;  // the last node is the ground point
    view_tau(ws.view_tau);
    ws.view_trans = (-ws.view_tau).exp();
    ws.source.setZero();
    if (sources.single && g.mu_sun > 0.0) {
      Spectrum& tau_sun = ws.tau_c;  // free at this point
      const Columns sun = sun_.at(R, g.mu_sun);
      tau_sun = ext_[kRayleigh] * static_cast<float>(sun[kRayleigh]) + ext_[kMie] * static_cast<float>(sun[kMie]) +
                ext_[kOzone] * static_cast<float>(sun[kOzone]);
      ws.source = (-tau_sun).exp() * static_cast<float>(g.mu_sun);
    }
    if (higher) {
      sources.higher->ground_irradiance(g.mu_sun, ws.ms_c.data());
      ws.source += ws.ms_c;
    }
    parts.isotropic += ws.view_trans * albedo_over_pi_ * ws.source;
  }
}

}  // namespace skyspec

namespace skyspec {
const char* build_stamp_single_scattering() { return __DATE__ " " __TIME__; }
}  // namespace skyspec
