#include "transport/optical_depth.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include <tbb/parallel_for.h>
#include <Eigen/Core>

#include "base/cancellation.hpp"
#include "base/recent_values.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

namespace {
// ln rho at every altitude of `alt` (one call per path, so that exponential profiles, the common
// case, are evaluated as one vector expression).
void log_relative_all(const DensityProfile& profile, const Eigen::ArrayXd& alt, Eigen::ArrayXd& out) {
  if (profile.kind() == DensityProfile::Kind::Exponential) {
    out = alt * (-1.0 / profile.scale_height_m());
    return;
  }
  for (Eigen::Index k = 0; k < alt.size(); ++k) out[k] = profile.log_relative(alt[k]);
}

// Sum over k < count of log_mean(e[k s], e[(k + 1) s], l[k s] - l[(k + 1) s]): the log-mean rule on
// the pieces between nodes `stride` apart. Each term is computed without a branch so that the
// loop vectorises; the terms are then summed by Eigen's (vectorised) reduction.
double log_mean_sum(const Eigen::ArrayXd& e, const Eigen::ArrayXd& l, Eigen::Index count, Eigen::Index stride,
                    Eigen::ArrayXd& terms) {
  terms.resize(count);
  const double* __restrict ep = e.data();
  const double* __restrict lp = l.data();
  double* __restrict out = terms.data();
  for (Eigen::Index k = 0; k < count; ++k)
    out[k] = log_mean_branchless(ep[k * stride], ep[(k + 1) * stride], lp[k * stride] - lp[(k + 1) * stride], 1e-3);
  return terms.sum();
}

// Altitudes of the nodes of `segments` equal pieces (an even number) of the straight path from
// radius r, zenith cosine mu, over [ta, tb]; the nodes are evaluated together, as arrays, so that
// the square roots (and the exponentials below) vectorise.
void node_altitudes(double planet_radius_m, double r_m, double mu, double ta, double tb, int segments,
                    Eigen::ArrayXd& alt) {
  const double dt = (tb - ta) / segments;
  const Eigen::Index n = segments + 1;
  thread_local Eigen::ArrayXd t;  // reused: this runs for every table entry
  t = ta + dt * Eigen::ArrayXd::LinSpaced(n, 0.0, static_cast<double>(segments));
  t[n - 1] = tb;
  alt = (r_m * r_m + t * t + 2.0 * r_m * mu * t).max(0.0).sqrt() - planet_radius_m;
}

// Column of one profile over those nodes (spacing dt): on each piece ln rho is taken as linear in
// t (exact for an exponential profile along a radial path, second order otherwise), and the result
// is Richardson-extrapolated against the same rule on pairs of pieces, which cancels the
// second-order error term.
double column_on_nodes(const DensityProfile& profile, const Eigen::ArrayXd& alt, double dt, int segments) {
  thread_local Eigen::ArrayXd l, e, terms;
  const Eigen::Index n = alt.size();
  if (!profile.positive_everywhere()) {
    // A layer with zero density outside: trapezoid rule on rho itself, extrapolated (Simpson).
    e.resize(n);
    for (Eigen::Index k = 0; k < n; ++k) e[k] = profile.relative(alt[k]);
    const double ends = 0.5 * (e[0] + e[n - 1]);
    const double fine = dt * (e.sum() - ends);
    const double even = Eigen::Map<const Eigen::ArrayXd, 0, Eigen::InnerStride<2>>(e.data(), segments / 2 + 1).sum();
    const double coarse = 2.0 * dt * (even - ends);
    return richardson(fine, coarse);
  }
  l.resize(n);
  log_relative_all(profile, alt, l);
  e = l.exp();
  const double fine = dt * log_mean_sum(e, l, segments, 1, terms);
  const double coarse = 2.0 * dt * log_mean_sum(e, l, segments / 2, 2, terms);
  return richardson(fine, coarse);
}

// The columns of `count` profiles along [ta, tb] of that path, on one set of nodes.
void columns_piece(const DensityProfile* const* profiles, int count, double planet_radius_m, double r_m, double mu,
                   double ta, double tb, int segments, double* out) {
  if (!(tb > ta) || segments < 1) return;
  segments += segments % 2;
  thread_local Eigen::ArrayXd alt;
  node_altitudes(planet_radius_m, r_m, mu, ta, tb, segments, alt);
  const double dt = (tb - ta) / segments;
  for (int i = 0; i < count; ++i) out[i] += column_on_nodes(*profiles[i], alt, dt, segments);
}

// Where the ray from (r, mu) crosses the profiles' breakpoints (DensityProfile::breakpoints_m)
// between 0 and d, with its lowest point, sorted; empty if no profile has a breakpoint.
void breakpoint_cuts(const DensityProfile* const* profiles, int count, double planet_radius_m, double r_m, double mu,
                     double d, std::vector<double>& cuts) {
  cuts.clear();
  for (int i = 0; i < count; ++i)
    for (double h : profiles[i]->breakpoints_m()) {
      // |r + t| = R + h: t^2 + 2 r mu t + r^2 - (R + h)^2 = 0.
      const double rc = planet_radius_m + h;
      const double disc = r_m * r_m * (mu * mu - 1.0) + rc * rc;
      if (!(disc > 0.0)) continue;
      for (double t : {-r_m * mu - std::sqrt(disc), -r_m * mu + std::sqrt(disc)})
        if (t > 0.0 && t < d) cuts.push_back(t);
    }
  if (cuts.empty()) return;
  const double t_low = -r_m * mu;
  if (t_low > 0.0 && t_low < d) cuts.push_back(t_low);
  std::sort(cuts.begin(), cuts.end());
}

// Columns from (r, mu) to the top, split at the ray's lowest point when it descends first, and
// where it crosses a profile's breakpoints (a cloud layer's base and top), the segments shared in
// proportion to length.
void columns_to_top(const DensityProfile* const* profiles, int count, double planet_radius_m, double top_radius_m,
                    double r_m, double mu, int segments, double* out) {
  for (int i = 0; i < count; ++i) out[i] = 0.0;
  const double d = distance_to_top_m(r_m, mu, top_radius_m);
  thread_local std::vector<double> cuts;
  breakpoint_cuts(profiles, count, planet_radius_m, r_m, mu, d, cuts);
  if (!cuts.empty()) {
    double a = 0.0;
    cuts.push_back(d);
    for (double b : cuts) {
      if (b > a) {
        const int s = std::max(2, static_cast<int>(std::lround(segments * (b - a) / d)));
        columns_piece(profiles, count, planet_radius_m, r_m, mu, a, b, s, out);
      }
      a = b;
    }
    return;
  }
  const double t_low = -r_m * mu;  // lowest point of the ray (ahead only if mu < 0)
  if (t_low > 0.0 && t_low < d) {
    const int s1 = std::max(1, static_cast<int>(std::lround(segments * t_low / d)));
    const int s2 = std::max(1, segments - s1);
    columns_piece(profiles, count, planet_radius_m, r_m, mu, 0.0, t_low, s1, out);
    columns_piece(profiles, count, planet_radius_m, r_m, mu, t_low, d, s2, out);
    return;
  }
  columns_piece(profiles, count, planet_radius_m, r_m, mu, 0.0, d, segments, out);
}
}  // namespace

double column_to_top_m(const DensityProfile& profile, double planet_radius_m, double top_radius_m, double r_m,
                       double mu, int segments) {
  const DensityProfile* profiles[1] = {&profile};
  double column = 0.0;
  columns_to_top(profiles, 1, planet_radius_m, top_radius_m, r_m, mu, segments, &column);
  return column;
}

Columns columns_to_top_m(const AtmosphereModel& atm, double r_m, double mu, int segments) {
  // All media on the same nodes: their altitudes are computed once.
  const DensityProfile* profiles[kMaxMedia];
  const int count = static_cast<int>(atm.media().size());
  for (int i = 0; i < count; ++i) profiles[i] = &atm.media()[static_cast<size_t>(i)].profile;
  Columns c{};
  columns_to_top(profiles, count, atm.planet_radius_m(), atm.top_radius_m(), r_m, mu, segments, c.data());
  return c;
}

namespace {
// The inverse of the table's x_mu (SunColumnTable::place): the zenith cosine at radius r of the
// direction whose distance to the top is x_mu of the way from its minimum (straight up) to its
// value at the horizon.
double mu_of(double r, double x_mu, double R, double Rt, double H) {
  const double rho = std::sqrt(std::max((r - R) * (r + R), 0.0));
  const double d_min = Rt - r, d_max = rho + H;
  const double d = d_min + x_mu * (d_max - d_min);
  return d <= 0.0 ? 1.0 : std::clamp((H * H - rho * rho - d * d) / (2.0 * r * d), -1.0, 1.0);
}
}  // namespace

SunColumnTable::SunColumnTable(const AtmosphereModel& atm, Resolution res, MuBand band)
    : media_(static_cast<int>(atm.media().size())),
      R_(atm.planet_radius_m()),
      Rt_(atm.top_radius_m()),
      H_(std::sqrt((Rt_ - R_) * (Rt_ + R_))),
      res_(res),
      data_(static_cast<size_t>(res.n_r) * static_cast<size_t>(res.n_mu)),
      first_(static_cast<size_t>(res.n_r), 0),
      end_(static_cast<size_t>(res.n_r), res.n_mu) {
  const auto radius_of_row = [&](int ir) {
    const double rho = H_ * static_cast<double>(std::clamp(ir, 0, res_.n_r - 1)) / (res_.n_r - 1);
    return std::sqrt(rho * rho + R_ * R_);
  };
  for (const Medium& m : atm.media()) profiles_.push_back(m.profile);
  const bool whole = band.lo <= -1.0 && band.hi >= 1.0;
  tbb::parallel_for(0, res_.n_r, [&](int ir) {
    throw_if_cancelled();  // a row of the table: a request stops it within a second
    const double r = radius_of_row(ir);
    if (!whole) {
      // The band of the look-ups at radii up to the next row's (the band widens with altitude).
      double lo = band.lo, hi = band.hi;
      if (band.camera_radius_m > 0.0) {
        const double reach = std::acos(std::min(1.0, R_ / band.camera_radius_m)) +
                             std::acos(std::min(1.0, R_ / radius_of_row(ir + 1))) + 1e-6;  // rad, rounding to spare
        lo = std::max(lo, std::cos(std::min(kPi, band.sun_zenith_rad + reach)));
        hi = std::min(hi, std::cos(std::max(0.0, band.sun_zenith_rad - reach)));
      }
      // The columns look-ups at radii between the neighbouring rows use, with a cell to spare on
      // either side (x_mu decreases with mu).
      double x_lo = 1.0, x_hi = 0.0;
      for (int k : {ir - 1, ir, ir + 1}) {
        const double rk = radius_of_row(k);
        x_lo = std::min(x_lo, place(rk, hi).x_mu);
        x_hi = std::max(x_hi, place(rk, lo).x_mu);
      }
      first_[static_cast<size_t>(ir)] = std::max(0, static_cast<int>(std::floor(x_lo * (res_.n_mu - 1))) - 1);
      end_[static_cast<size_t>(ir)] = std::min(res_.n_mu, static_cast<int>(std::ceil(x_hi * (res_.n_mu - 1))) + 2);
    }
    for (int im = first_[static_cast<size_t>(ir)]; im < end_[static_cast<size_t>(ir)]; ++im) {
      const double mu = mu_of(r, static_cast<double>(im) / (res_.n_mu - 1), R_, Rt_, H_);
      data_[static_cast<size_t>(ir) * res_.n_mu + im] = integrate(r, mu);
    }
  });
}

SunColumnTable::MuBand SunColumnTable::band_seen_from(const AtmosphereModel& atm, const Vec3& origin_m,
                                                      const Vec3& sun_dir) {
  const double R = atm.planet_radius_m(), Rt = atm.top_radius_m(), r = origin_m.norm();
  if (!(r >= R) || !std::isfinite(r)) return MuBand{};
  const double reach = std::acos(std::min(1.0, R / r)) + std::acos(R / Rt) + 1e-6;  // rad, with rounding to spare
  const double theta = std::acos(std::clamp(origin_m.dot(sun_dir) / r, -1.0, 1.0));
  return MuBand{std::cos(std::min(kPi, theta + reach)), std::cos(std::max(0.0, theta - reach)), r, theta};
}

long SunColumnTable::computed_entries() const {
  long n = 0;
  for (size_t i = 0; i < first_.size(); ++i) n += end_[i] - first_[i];
  return n;
}

// A look-up outside the computed band: the columns at the same (r, x_mu), integrated directly.
Columns SunColumnTable::direct(double r, double x_mu) const { return integrate(r, mu_of(r, x_mu, R_, Rt_, H_)); }

Columns SunColumnTable::integrate(double r, double mu) const {
  const DensityProfile* profiles[kMaxMedia];
  for (int i = 0; i < media_; ++i) profiles[i] = &profiles_[static_cast<size_t>(i)];
  Columns c{};
  columns_to_top(profiles, media_, R_, Rt_, r, mu, res_.segments, c.data());
  return c;
}

std::shared_ptr<const SunColumnTable> SunColumnTable::shared(const AtmosphereModel& atm, Resolution res, MuBand band) {
  // What the table depends on: the numbers exactly (hexadecimal floats), the profiles as they
  // describe themselves (to 12 significant digits, as in the scattering-order tables' key).
  std::ostringstream key;
  key << std::hexfloat << atm.planet_radius_m() << ' ' << atm.top_radius_m() << '\n'
      << res.n_r << ' ' << res.n_mu << ' ' << res.segments << '\n'
      << band.lo << ' ' << band.hi << ' ' << band.camera_radius_m << ' ' << band.sun_zenith_rad << '\n';
  for (const Medium& m : atm.media()) key << m.profile.describe() << '\n';
  // The newest and three more (of at most kSharedBytes in all; a larger table is not kept).
  static RecentValues<SunColumnTable> recent(3, kSharedBytes,
                                             [](const SunColumnTable& t) { return t.data_.size() * sizeof(Columns); });
  return recent.get(key.str(), [&] { return std::make_shared<const SunColumnTable>(atm, res, band); });
}

// Written with selects on values rather than branches, and inline, so that lookup_many's loop
// over points vectorises (it needs -fno-math-errno and -fno-trapping-math, CMakeLists.txt).
inline SunColumnTable::Place SunColumnTable::place(double r_m, double mu) const {
  const auto max = [](double a, double b) { return a > b ? a : b; };  // on values (std::max
  const auto min = [](double a, double b) { return a < b ? a : b; };  // returns references)
  const double r = min(max(r_m, R_), Rt_);
  const double rho = std::sqrt(max((r - R_) * (r + R_), 0.0));
  const double d_min = Rt_ - r, d_max = rho + H_;
  const double d = distance_to_top_m(r, mu, Rt_);
  const bool span = d_max > d_min;
  const double x = (d - d_min) / (span ? d_max - d_min : 1.0);
  const double x_mu = span ? min(max(x, 0.0), 1.0) : 0.0;
  return Place{r, x_mu, rho / H_ * (res_.n_r - 1), x_mu * (res_.n_mu - 1)};
}

inline Columns SunColumnTable::interpolate(const Place& p) const {
  const int ir = std::min(static_cast<int>(p.fr), res_.n_r - 2);
  const int im = std::min(static_cast<int>(p.fm), res_.n_mu - 2);
  for (int k : {ir, ir + 1})
    if (im < first_[static_cast<size_t>(k)] || im + 2 > end_[static_cast<size_t>(k)]) return direct(p.r, p.x_mu);
  const double ar = p.fr - ir, am = p.fm - im;
  const Columns& c00 = data_[static_cast<size_t>(ir) * res_.n_mu + im];
  const Columns& c01 = data_[static_cast<size_t>(ir) * res_.n_mu + im + 1];
  const Columns& c10 = data_[static_cast<size_t>(ir + 1) * res_.n_mu + im];
  const Columns& c11 = data_[static_cast<size_t>(ir + 1) * res_.n_mu + im + 1];
  Columns out{};
  for (int s = 0; s < media_; ++s)
    out[s] = (1 - ar) * ((1 - am) * c00[s] + am * c01[s]) + ar * ((1 - am) * c10[s] + am * c11[s]);
  return out;
}

Columns SunColumnTable::lookup(double r_m, double mu) const { return interpolate(place(r_m, mu)); }

void SunColumnTable::lookup_many(int count, const double* r_m, const double* mu, Columns* out) const {
  constexpr int kChunk = 64;
  double r[kChunk], x_mu[kChunk], fr[kChunk], fm[kChunk];
  for (int first = 0; first < count; first += kChunk) {
    const int m = std::min(kChunk, count - first);
    for (int k = 0; k < m; ++k) {
      const Place p = place(r_m[first + k], mu[first + k]);
      r[k] = p.r;
      x_mu[k] = p.x_mu;
      fr[k] = p.fr;
      fm[k] = p.fm;
    }
    for (int k = 0; k < m; ++k) out[first + k] = interpolate(Place{r[k], x_mu[k], fr[k], fm[k]});
  }
}

}  // namespace skyspec
