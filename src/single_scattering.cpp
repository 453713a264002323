#include "skyspec/single_scattering.hpp"

#include <algorithm>
#include <cmath>

#include "skyspec/phase_function.hpp"

namespace skyspec {

ScatteringWorkspace::ScatteringWorkspace(int n)
    : tau_a(n), tau_b(n), tau_c(n), trans_a(n), trans_b(n), trans_c(n), f_a(n), f_b(n), x(n),
      sum_rayleigh(n), sum_mie(n), coarse_rayleigh(n), coarse_mie(n) {}

SingleScattering::SingleScattering(const AtmosphereModel& atm, const SunColumns& sun_columns,
                                   IntegratorSettings s)
    : atm_(atm),
      sun_(sun_columns),
      settings_(s),
      ext_rayleigh_(atm.rayleigh().extinction_per_m.cast<float>()),
      ext_mie_(atm.mie().extinction_per_m.cast<float>()),
      sca_rayleigh_(atm.rayleigh().scattering_per_m.cast<float>()),
      sca_mie_(atm.mie().scattering_per_m.cast<float>()) {}

namespace {

// Add dt * logmean(f_a, f_b) to sum, elementwise, with x = ln f_a - ln f_b. Where |x| is small the
// series b (1 + x/2 + x^2/6 + x^3/24) avoids the cancellation in (a - b) / x.
void accumulate_log_mean(const Spectrum& f_a, const Spectrum& f_b, const Spectrum& x, float dt,
                         Spectrum& sum) {
  sum += dt * (x.abs() < 1e-2f)
                  .select(f_b * (1.0f + x * (0.5f + x * (1.0f / 6.0f + x * (1.0f / 24.0f)))),
                          (f_a - f_b) / x);
}

// A node of the quadrature: a point on the view ray.
struct Node {
  double t;
  double log_rho[kSpeciesCount];
};

}  // namespace

void SingleScattering::radiance(const Vec3& o, const Vec3& d, const Vec3& s, const Spectrum& sun_irradiance,
                                ScatteringWorkspace& ws, Spectrum& out) const {
  out.setZero();
  const double R = atm_.planet_radius_m(), Rt = atm_.top_radius_m();
  if (o.norm() < R) return;  // inside the planet

  // The part of the ray inside the atmosphere, up to the ground if it hits it.
  const SphereHit top = intersect_sphere(o, d, Rt);
  if (!top.hit || top.t_far_m <= 0.0) return;
  const double t_begin = std::max(0.0, top.t_near_m);
  double t_end = top.t_far_m;
  const SphereHit ground = intersect_sphere(o, d, R);
  if (ground.hit && ground.t_near_m > 0.0) t_end = std::min(t_end, ground.t_near_m);
  if (!(t_end > t_begin)) return;

  // Cut points: shadow boundaries and the ray's lowest point.
  const IntervalSet lit = lit_intervals(o, d, t_begin, t_end, s, R);
  if (lit.count == 0) return;
  const double t_low = -o.dot(d);

  const DensityProfile* profiles[kSpeciesCount] = {&atm_.rayleigh().profile, &atm_.mie().profile};
  auto make_node = [&](double t) {
    Node n;
    n.t = t;
    const Vec3 p = o + t * d;
    const double alt = p.norm() - R;
    for (int k = 0; k < kSpeciesCount; ++k) n.log_rho[k] = profiles[k]->log_relative(alt);
    return n;
  };

  // View-ray columns accumulate from t_begin across lit and shadowed parts alike.
  double view_col[kSpeciesCount] = {0.0, 0.0};
  Node prev = make_node(t_begin);
  auto advance_columns = [&](const Node& a, const Node& b) {
    const double dt = b.t - a.t;
    for (int k = 0; k < kSpeciesCount; ++k)
      view_col[k] += dt * log_mean(std::exp(a.log_rho[k]), std::exp(b.log_rho[k]), a.log_rho[k] - b.log_rho[k]);
  };
  // Shadowed stretch [prev.t, t]: only extinction along the view ray matters.
  auto skip_to = [&](double t) {
    if (!(t > prev.t)) return;
    const int n = 8;
    const double dt = (t - prev.t) / n;
    const double t0 = prev.t;
    for (int i = 1; i <= n; ++i) {
      Node next = make_node(i == n ? t : t0 + dt * i);
      advance_columns(prev, next);
      prev = next;
    }
  };

  // Spectral state at a node: tau, ln-free transmittance, then the integrands per species.
  auto eval_tau = [&](const Node& n, Spectrum& tau) {
    const Vec3 p = o + n.t * d;
    const double r = p.norm();
    const Columns sun = sun_.at(r, p.dot(s) / r);
    tau = ext_rayleigh_ * static_cast<float>(view_col[kRayleigh] + sun[kRayleigh]) +
          ext_mie_ * static_cast<float>(view_col[kMie] + sun[kMie]);
  };

  // Integrals over one segment [a, b] of rho_s exp(-tau) for both species, by the log-mean rule.
  auto accumulate_segment = [&](const Node& na, const Node& nb, const Spectrum& tau_a, const Spectrum& trans_a,
                                const Spectrum& tau_b, const Spectrum& trans_b, ScatteringWorkspace& w,
                                Spectrum& sum_r, Spectrum& sum_m) {
    const float seg = static_cast<float>(nb.t - na.t);
    for (int sp = 0; sp < kSpeciesCount; ++sp) {
      const float rho_a = static_cast<float>(std::exp(na.log_rho[sp]));
      const float rho_b = static_cast<float>(std::exp(nb.log_rho[sp]));
      w.x = static_cast<float>(na.log_rho[sp] - nb.log_rho[sp]) - (tau_a - tau_b);
      w.f_a = rho_a * trans_a;
      w.f_b = rho_b * trans_b;
      accumulate_log_mean(w.f_a, w.f_b, w.x, seg, sp == kRayleigh ? sum_r : sum_m);
    }
  };

  double total_lit = 0.0;
  for (int i = 0; i < lit.count; ++i) total_lit += lit.parts[i].length_m();
  ws.sum_rayleigh.setZero();
  ws.sum_mie.setZero();
  ws.coarse_rayleigh.setZero();
  ws.coarse_mie.setZero();

  for (int i = 0; i < lit.count; ++i) {
    const Interval& iv = lit.parts[i];
    skip_to(iv.t0_m);
    // Split the lit piece at the lowest point of the ray if it lies inside.
    double cuts[3] = {iv.t0_m, iv.t1_m, iv.t1_m};
    int n_pieces = 1;
    if (t_low > iv.t0_m && t_low < iv.t1_m) {
      cuts[1] = t_low;
      n_pieces = 2;
    }
    eval_tau(prev, ws.tau_a);
    ws.trans_a = (-ws.tau_a).exp();
    for (int pc = 0; pc < n_pieces; ++pc) {
      const double a = cuts[pc], b = cuts[pc + 1];
      // An even number of segments, so that pairs of them form the coarse rule.
      int segs = std::max(2, static_cast<int>(std::lround(settings_.view_segments * (b - a) / total_lit)));
      segs += segs % 2;
      const double dt = (b - a) / segs;
      Node pair_start = prev;
      ws.tau_c = ws.tau_a;
      ws.trans_c = ws.trans_a;
      for (int k = 1; k <= segs; ++k) {
        Node next = make_node(k == segs ? b : a + dt * k);
        advance_columns(prev, next);
        eval_tau(next, ws.tau_b);
        ws.trans_b = (-ws.tau_b).exp();
        accumulate_segment(prev, next, ws.tau_a, ws.trans_a, ws.tau_b, ws.trans_b, ws, ws.sum_rayleigh, ws.sum_mie);
        if (k % 2 == 0) {
          accumulate_segment(pair_start, next, ws.tau_c, ws.trans_c, ws.tau_b, ws.trans_b, ws, ws.coarse_rayleigh,
                             ws.coarse_mie);
          pair_start = next;
          ws.tau_c = ws.tau_b;
          ws.trans_c = ws.trans_b;
        }
        prev = next;
        ws.tau_a.swap(ws.tau_b);
        ws.trans_a.swap(ws.trans_b);
      }
    }
  }

  // Richardson extrapolation: the rule's error is O(dt^2), so (4 fine - coarse) / 3 cancels the
  // leading term. Clamped at 0 in case a coarse pair is far off (it never is for smooth integrands).
  ws.sum_rayleigh = ((4.0f * ws.sum_rayleigh - ws.coarse_rayleigh) * (1.0f / 3.0f)).max(0.0f);
  ws.sum_mie = ((4.0f * ws.sum_mie - ws.coarse_mie) * (1.0f / 3.0f)).max(0.0f);

  const double mu = d.dot(s);
  const float phase_r = static_cast<float>(rayleigh_phase(mu));
  const float phase_m = static_cast<float>(atm_.mie_phase()(mu));
  out = sun_irradiance * (sca_rayleigh_ * ws.sum_rayleigh * phase_r + sca_mie_ * ws.sum_mie * phase_m);
}

}  // namespace skyspec
