#include "transport/multiple_scattering.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <istream>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <streambuf>
#include <string_view>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "base/atomic_file.hpp"
#include "base/cancellation.hpp"
#include "base/embedded_data.hpp"
#include "base/hashing_streambuf.hpp"
#include "base/preparation_progress.hpp"
#include "base/quadrature.hpp"
#include "skyspec/error.hpp"
#include "skyspec/phase_function.hpp"
#include "skyspec/units.hpp"
#include "transport/spherical_harmonics.hpp"
#include "transport/spin2_harmonics.hpp"

namespace skyspec {

// --- SourceTable --------------------------------------------------------------------------------

namespace {
constexpr int kMaxHarmonics = 91;  // degree 12
// The sun-angle columns are uniform in u in [0, 1] with mu_s = c + w sinh(a + u (b - a)), a and b
// the values of asinh((mu_s - c) / w) at mu_s = -1 and 1 (c = SourceTable::kSunColumnCentre,
// w = kSunColumnWidth): the spacing grows as sqrt(w^2 + (mu_s - c)^2), finest just below the
// horizon, where the sources fall by orders of magnitude from column to column as the planet's
// shadow rises through the air, and coarsest at the zenith and at night, where they change
// slowly or not at all.
struct SunColumnMap {
  static constexpr double c = SourceTable::kSunColumnCentre, w = SourceTable::kSunColumnWidth;
  double a = std::asinh((-1.0 - c) / w);
  double b = std::asinh((1.0 - c) / w);
};
const SunColumnMap kSunColumns;
double mu_from_u(double u) {
  return SunColumnMap::c + SunColumnMap::w * std::sinh(kSunColumns.a + u * (kSunColumns.b - kSunColumns.a));
}
double u_from_mu(double mu) {
  return (std::asinh((mu - SunColumnMap::c) / SunColumnMap::w) - kSunColumns.a) / (kSunColumns.b - kSunColumns.a);
}
}  // namespace

std::shared_ptr<const PhaseMoments> PhaseMoments::of(const AtmosphereModel& atm, int degree) {
  auto m = std::make_shared<PhaseMoments>();
  const int n = atm.grid().size();
  m->degree = degree;
  m->wavelengths = n;
  for (const Medium& medium : atm.media()) {
    if (!medium.scatters()) continue;
    OfMedium of;
    of.rayleigh = medium.phase.kind == MediumPhase::Kind::Rayleigh;
    of.sphere_matrix = medium.phase.kind == MediumPhase::Kind::Tabulated && degree >= 2;
    of.chi.assign(static_cast<size_t>(degree + 1) * n + SourceTable::kLookupSlack, 0.0f);
    m->phases_.push_back(medium.phase);
    for (int i = 0; i < n; ++i) {
      const auto phase = [&medium, i](double mu) { return medium.phase.at(i, mu); };
      // A tabulated function's moments exactly: a forward peak (fog's diffraction) can be narrower
      // than the Gauss-Legendre nodes' spacing near mu = 1 (0.27 degree for 512 nodes).
      const std::vector<double> chi =
          medium.phase.kind == MediumPhase::Kind::Tabulated
              ? piecewise_linear_legendre_moments(medium.phase.matrix->mu(),
                                                  medium.phase.matrix->a1()[static_cast<size_t>(i)], degree)
              : legendre_moments(phase, degree);
      for (int l = 0; l <= degree; ++l) {
        of.chi[static_cast<size_t>(l) * n + i] = static_cast<float>(chi[static_cast<size_t>(l)]);
        // Zero to rounding beyond l = 2 for molecules (the quadrature is exact for a quadratic).
        if (std::abs(chi[static_cast<size_t>(l)]) > 1e-9 * std::abs(chi[0]))
          of.nonzero_degree = std::max(of.nonzero_degree, l);
      }
    }
    m->media.push_back(std::move(of));
  }
  return m;
}

const std::vector<float>& PhaseMoments::polarising(int s) const {
  std::call_once(polarising_once_, [this] {
    polarising_.resize(media.size());
    for (size_t k = 0; k < media.size(); ++k) {
      if (!media[k].sphere_matrix) continue;
      const TabulatedScatteringMatrix& t = *phases_[k].matrix;
      std::vector<float>& out = polarising_[k];
      out.assign(static_cast<size_t>(degree + 1) * wavelengths + SourceTable::kLookupSlack, 0.0f);
      for (int i = 0; i < wavelengths; ++i) {
        const std::vector<double> gamma =
            piecewise_linear_spin_moments(t.mu(), t.b1()[static_cast<size_t>(i)], degree, 2, 0);
        for (int l = 2; l <= degree; ++l)
          out[static_cast<size_t>(l) * wavelengths + i] = static_cast<float>(gamma[static_cast<size_t>(l)]);
      }
    }
  });
  return polarising_.at(static_cast<size_t>(s));
}

void PhaseMoments::compute_skyline_moments() const {
  std::call_once(skyline_once_, [this] {
    const int n = wavelengths;
    const size_t per_skyline = static_cast<size_t>(degree + 1) * static_cast<size_t>(n);
    skyline_chi_.resize(phases_.size());
    skyline_gradient_chi_.resize(phases_.size());
    for (size_t k = 0; k < phases_.size(); ++k) {
      std::vector<float>& out = skyline_chi_[k];
      std::vector<float>& grad = skyline_gradient_chi_[k];
      out.assign(static_cast<size_t>(kSkylines) * per_skyline + SourceTable::kLookupSlack, 0.0f);
      grad.assign(out.size(), 0.0f);
      for (int i = 0; i < n; ++i) {
        const MediumPhase& phase = phases_[k];
        const auto p = [&phase, i](double mu) { return phase.at(i, mu); };
        const std::vector<double> hidden = skyline_legendre_moments(p, degree, kSkylines, kSkylineStep_rad);
        const std::vector<double> delta = skyline_gradient_moments(p, degree, kSkylines, kSkylineStep_rad);
        for (int j = 0; j < kSkylines; ++j)
          for (int l = 0; l <= degree; ++l) {
            const size_t at = static_cast<size_t>(j) * per_skyline + static_cast<size_t>(l) * static_cast<size_t>(n) +
                              static_cast<size_t>(i);
            const size_t from = static_cast<size_t>(j * (degree + 1) + l);
            out[at] = static_cast<float>(hidden[from]);
            grad[at] = static_cast<float>(delta[from]);
          }
      }
    }
  });
}

int PhaseMoments::nearest_skyline(double skyline_rad) {
  return static_cast<int>(std::lround(std::clamp(skyline_rad / kSkylineStep_rad, 0.0, kSkylines - 1.0)));
}

const std::vector<float>& PhaseMoments::skyline_chi(int s) const {
  compute_skyline_moments();
  return skyline_chi_.at(static_cast<size_t>(s));
}

const std::vector<float>& PhaseMoments::skyline_gradient_chi(int s) const {
  compute_skyline_moments();
  return skyline_gradient_chi_.at(static_cast<size_t>(s));
}

SourceTable::SourceTable(double planet_radius_m, double top_radius_m, int n_altitude, int n_sun,
                         std::shared_ptr<const PhaseMoments> moments, int degree, bool polarised)
    : R_(planet_radius_m),
      Rt_(top_radius_m),
      n_h_(n_altitude),
      n_mu_(n_sun),
      degree_(degree < 0 ? moments->degree : std::min(degree, moments->degree)),
      n_c_(skyspec::harmonic_count(degree_)),
      n_l_(moments->wavelengths),
      moments_(std::move(moments)),
      j_(static_cast<size_t>(n_altitude) * n_sun * n_c_ * n_l_ + kLookupSlack),
      g_(static_cast<size_t>(n_sun) * n_l_, 0.0f),
      polarised_(polarised),
      n_p_(polarised ? 3 + spin2_harmonic_count(degree_) : 0),
      p_(p_size()) {
  if (n_c_ > kMaxHarmonics) throw Error("the scattering-order tables take harmonics up to degree 12");
}

// The rows are uniform in x = ln(1 + h / H) / ln(1 + h_top / H), H = kRowAltitudeScale_m: nearly
// linear in h below H, logarithmic above. 16 rows over 60 km lie at 0, 0.13, 0.31, 0.57, 0.93, 1.46,
// 2.2, 3.3 km, ..., 29, 42, 60 km: the lowest kilometre, where the aerosol is and the observer
// usually stands, gets a third of them (docs/validation.md compares mappings).
double SourceTable::altitude_of_row_coordinate(double x) const {
  return kRowAltitudeScale_m * std::expm1(x * std::log1p((Rt_ - R_) / kRowAltitudeScale_m));
}

double SourceTable::row_coordinate_of_altitude(double h) const {
  return std::log1p(h / kRowAltitudeScale_m) / std::log1p((Rt_ - R_) / kRowAltitudeScale_m);
}

double SourceTable::altitude_m(int ih) const {
  return altitude_of_row_coordinate(static_cast<double>(ih) / (n_h_ - 1));
}

double SourceTable::mu_sun(int imu) const {
  if (imu == 0) return -1.0;  // the end columns exactly (sinh(asinh(x)) is x to rounding)
  if (imu == n_mu_ - 1) return 1.0;
  return mu_from_u(static_cast<double>(imu) / (n_mu_ - 1));
}

bool SourceTable::steep_pair(int ih, int imu) const {
  using Map = Eigen::Map<const Eigen::ArrayXf>;
  const Map x(&j_[index(ih, imu)], n_l_), y(&j_[index(ih, imu + 1)], n_l_);
  constexpr float r = kSteepRatio;
  return ((x > r * y) || (y > r * x)).any() && ((x > 0.0f) && (y > 0.0f)).all();
}

void SourceTable::prepare() {
  steep_.assign(static_cast<size_t>(n_h_) * (n_mu_ - 1), 0);
  log_mean_.assign(static_cast<size_t>(n_h_) * n_mu_ * n_l_ + kLookupSlack, 0.0f);
  for (int ih = 0; ih < n_h_; ++ih)
    for (int imu = 0; imu + 1 < n_mu_; ++imu) {
      if (!steep_pair(ih, imu)) continue;
      steep_[static_cast<size_t>(ih) * (n_mu_ - 1) + imu] = 1;
      for (int e = imu; e <= imu + 1; ++e)
        for (int i = 0; i < n_l_; ++i)
          log_mean_[(static_cast<size_t>(ih) * n_mu_ + e) * n_l_ + i] = std::log(j_[index(ih, e) + i]);
    }
  prepared_ = true;
}

// The four table entries around (r, mu_s) and their weights: bilinear. Along the sun angle the
// source can fall by orders of magnitude between two columns (inside the planet's shadow), where a
// linear blend lies far above the decay: each steep altitude row's weights (prepare()) are scaled,
// per wavelength, by the ratio of the geometric to the arithmetic mean of its two mean radiances
// (the harmonic l = 0), so that the mean follows an exponential between the columns and the
// harmonics keep their shape. Elsewhere (everywhere but near the terminator) the blend is left
// linear: there the factor, 2 sqrt(r) / (1 + r) for a ratio r of the two means, would be above 0.994.
struct SourceTable::Blend {
  int ih, im;
  const float *a, *b, *c, *d;    // entries (ih, im), (ih, im + 1), (ih + 1, im), (ih + 1, im + 1)
  float sa, sb, sc, sd;          // their bilinear weights
  const float* lower = nullptr;  // per-wavelength factors of row ih's weights (steep rows only)
  const float* upper = nullptr;  // and of row ih + 1's
};

SourceTable::Blend SourceTable::blend(double r_m, double mu_s, float* factors) const {
  if (!prepared_) throw std::logic_error("SourceTable::source: the table was not prepared after it was written");
  const double h = std::clamp(r_m - R_, 0.0, Rt_ - R_);
  const double fh = row_coordinate_of_altitude(h) * (n_h_ - 1);
  const double fm = std::clamp(u_from_mu(mu_s), 0.0, 1.0) * (n_mu_ - 1);
  const int ih = std::min(static_cast<int>(fh), n_h_ - 2), im = std::min(static_cast<int>(fm), n_mu_ - 2);
  const float ah = static_cast<float>(fh - ih), am = static_cast<float>(fm - im);
  Blend w{ih,
          im,
          &j_[index(ih, im)],
          &j_[index(ih, im + 1)],
          &j_[index(ih + 1, im)],
          &j_[index(ih + 1, im + 1)],
          (1 - ah) * (1 - am),
          (1 - ah) * am,
          ah * (1 - am),
          ah * am};
  const bool lower_steep = steep_[static_cast<size_t>(ih) * (n_mu_ - 1) + im] != 0;
  const bool upper_steep = steep_[static_cast<size_t>(ih + 1) * (n_mu_ - 1) + im] != 0;
  if (!lower_steep && !upper_steep) return w;
  const int padded = (n_l_ + kLookupSlack - 1) / kLookupSlack * kLookupSlack;
  using Lanes = Eigen::Array<float, kLookupSlack, 1>;
  using LanesMap = Eigen::Map<const Lanes, Eigen::Unaligned>;
  thread_local std::vector<float> row_factors;
  if (!factors) {
    row_factors.resize(2 * static_cast<size_t>(padded));
    factors = row_factors.data();
  }
  std::fill_n(factors, 2 * static_cast<size_t>(padded), 1.0f);
  // Over whole blocks of fixed size (Eigen's vectorised exp on every lane: a dynamic-size
  // expression would peel a head with the scalar expf depending on the buffer's alignment, so
  // that the last bit depended on the heap, hence on the thread); the lanes past the last
  // wavelength read the next harmonic or the spare floats and are never written out.
  const auto factor = [&](int row, const float* x, const float* y, float* out) {
    const float* lx = &log_mean_[(static_cast<size_t>(row) * n_mu_ + im) * n_l_];
    const float* ly = lx + n_l_;
    for (int i0 = 0; i0 < padded; i0 += kLookupSlack)
      Eigen::Map<Lanes, Eigen::Unaligned>(out + i0) = ((1 - am) * LanesMap(lx + i0) + am * LanesMap(ly + i0)).exp() /
                                                      ((1 - am) * LanesMap(x + i0) + am * LanesMap(y + i0)).max(1e-30f);
  };
  if (lower_steep) {
    factor(ih, w.a, w.b, factors);
    w.lower = factors;
  }
  if (upper_steep) {
    factor(ih + 1, w.c, w.d, factors + padded);
    w.upper = factors + padded;
  }
  return w;
}

// One node's look-up (harmonic_source): the blend of its four entries and its view direction's
// harmonics, as doubles and as floats.
struct SourceTable::NodeLookup {
  Blend w;
  double mv, cos_phi;
  double basis_d[kMaxHarmonics];
  float basis[kMaxHarmonics];
};

// The sums over the harmonics for each medium, per block of kLookupSlack wavelengths, of kRun
// nodes that blend the same four entries (each with its own weights and view direction): each
// entry's harmonics are loaded once for all of them. Successive nodes along a ray often lie between
// the same four entries, whose harmonics (4 x 66 x 41 floats at degree 10) are larger than a
// core's first-level cache. Each node's sums are the same to the last bit as alone (kRun = 1).
struct SourceTable::HarmonicSum {
  const NodeLookup* nodes;  // kRun of them
  int degree, n_l, media;
  int media_degree[kMaxMedia];
  const float* chi[kMaxMedia];
  float* const* out;  // node r's J_s at out[s] + r * out_stride
  size_t out_stride;

  // kMedia > 0: the number of media known at compile time; 0: `media` at run time.
  template <int kMedia, int kRun>
  void run() const {
    using Lanes = Eigen::Array<float, kLookupSlack, 1>;
    using LanesMap = Eigen::Map<const Lanes, Eigen::Unaligned>;
    const int count = kMedia > 0 ? kMedia : media;
    const Blend& first = nodes[0].w;
    const float *a = first.a, *b = first.b, *c = first.c, *d = first.d;
    for (int i0 = 0; i0 < n_l; i0 += kLookupSlack) {
      Lanes wa[kRun], wb[kRun], wc[kRun], wd[kRun];
      for (int r = 0; r < kRun; ++r) {
        const Blend& w = nodes[r].w;
        wa[r] = Lanes::Constant(w.sa), wb[r] = Lanes::Constant(w.sb), wc[r] = Lanes::Constant(w.sc),
        wd[r] = Lanes::Constant(w.sd);
        if (w.lower) {
          const LanesMap f(w.lower + i0);
          wa[r] *= f;
          wb[r] *= f;
        }
        if (w.upper) {
          const LanesMap f(w.upper + i0);
          wc[r] *= f;
          wd[r] *= f;
        }
      }
      Lanes sums[kRun][kMedia > 0 ? kMedia : kMaxMedia];
      for (int r = 0; r < kRun; ++r)
        for (int s = 0; s < count; ++s) sums[r][s] = Lanes::Zero();
      for (int l = 0; l <= degree; ++l) {
        Lanes pa[kRun], pb[kRun], pc[kRun], pd[kRun];
        for (int r = 0; r < kRun; ++r) pa[r] = pb[r] = pc[r] = pd[r] = Lanes::Zero();
        for (int m = 0; m <= l; ++m) {
          const int k = harmonic_index(l, m);
          const size_t o = static_cast<size_t>(k) * n_l + i0;
          const Lanes ea = LanesMap(a + o), eb = LanesMap(b + o), ec = LanesMap(c + o), ed = LanesMap(d + o);
          for (int r = 0; r < kRun; ++r) {
            const float y = nodes[r].basis[k];
            pa[r] += y * ea;
            pb[r] += y * eb;
            pc[r] += y * ec;
            pd[r] += y * ed;
          }
        }
        const size_t o = static_cast<size_t>(l) * n_l + i0;
        for (int r = 0; r < kRun; ++r) {
          const Lanes v = wa[r] * pa[r] + wb[r] * pb[r] + wc[r] * pc[r] + wd[r] * pd[r];
          for (int s = 0; s < count; ++s)
            if (l <= media_degree[s]) sums[r][s] += LanesMap(chi[s] + o) * v;
        }
      }
      for (int r = 0; r < kRun; ++r)
        for (int s = 0; s < count; ++s) {
          float* const dest = out[s] + static_cast<size_t>(r) * out_stride + i0;
          if (n_l - i0 >= kLookupSlack)
            Eigen::Map<Lanes, Eigen::Unaligned>{dest} = sums[r][s];
          else
            std::copy_n(sums[r][s].data(), std::min(n_l - i0, kLookupSlack), dest);
        }
    }
  }

  template <int kRun>
  void run_for_media() const {
    // Two media (air and aerosol, the common case) with a count the compiler knows, so that their
    // sums stay in registers; any number otherwise.
    if (media == 2)
      run<2, kRun>();
    else if (media == 4)  // two media and their light below a skyline (source_above_skyline)
      run<4, kRun>();
    else if (media == 6)  // two media, below a skyline and its gradient (skyline_sums)
      run<6, kRun>();
    else
      run<0, kRun>();
  }
};

void SourceTable::source_to_degree(int max_degree, double r_m, double mu, double mu_view, double nu,
                                   float* const* out) const {
  sources_to_degree(max_degree, 1, &r_m, &mu, &mu_view, nu, media_count(), n_l_, out);
}

// The table's light from below the skyline has the moments chi_l(gamma) of the nearest tabulated
// skyline (within half a degree); molecules' reach every degree (their phase function cut at a
// skyline is no longer a quadratic). One pass sums the whole source and that part (as twice the
// media) where the media fit twice into kMaxMedia.
bool SourceTable::source_above_skyline(double r_m, double mu, double mu_view, double nu, double skyline_rad,
                                       float* const* out, float* const* hidden, float* const* hidden_share,
                                       float* const* hidden_multiple) const {
  return source_above_skyline_with(nullptr, nullptr, r_m, mu, mu_view, nu, skyline_rad, out, hidden, hidden_share,
                                   hidden_multiple);
}

bool SourceTable::source_above_skyline_with(const SourceTable* below_table, float* const* below_hidden, double r_m,
                                            double mu, double mu_view, double nu, double skyline_rad, float* const* out,
                                            float* const* hidden, float* const* hidden_share,
                                            float* const* hidden_multiple) const {
  const int media = std::min(static_cast<int>(moments_->media.size()), kMaxMedia);
  if (3 * media <= kMaxMedia) {
    // One pass over the node's four entries for the whole source, its part below the skyline and
    // that part's gradient (two "nodes" of one blend: the view's harmonics and their derivative);
    // below_table (order 2's beside the sum), of the same degree, reuses both harmonics.
    const int j = PhaseMoments::nearest_skyline(skyline_rad);
    NodeLookup nodes[2];
    skyline_look_ups(r_m, mu, mu_view, nu, nullptr, nodes);
    for (int s = 0; s < media; ++s)
      std::copy_n(moments_->skyline_chi(s).data() + static_cast<size_t>(j) * (moments_->degree + 1) * n_l_, n_l_,
                  hidden_share[s]);
    skyline_sums(nodes, j, out, hidden);
    for (int s = 0; s < media; ++s) {
      for (int i = 0; i < n_l_; ++i) out[s][i] -= hidden[s][i];
      std::copy_n(hidden[s], n_l_, hidden_multiple[s]);
    }
    if (below_table) {
      NodeLookup below_nodes[2];
      below_table->skyline_look_ups(r_m, mu, mu_view, nu, below_table->degree_ == degree_ ? nodes : nullptr,
                                    below_nodes);
      below_table->skyline_sums(below_nodes, j, nullptr, below_hidden);
    }
    return true;
  }
  if (below_table) below_table->source_below_skyline(r_m, mu, mu_view, nu, skyline_rad, below_hidden);
  const int d = moments_->degree;
  const int j = PhaseMoments::nearest_skyline(skyline_rad);
  const size_t per_degree = static_cast<size_t>(n_l_), per_skyline = static_cast<size_t>(d + 1) * per_degree;
  const float* chi[kMaxMedia];
  int media_degree[kMaxMedia];
  float* sums[kMaxMedia];
  const bool one_pass = 2 * media <= kMaxMedia;
  for (int s = 0; s < media; ++s) {
    const PhaseMoments::OfMedium& m = moments_->media[static_cast<size_t>(s)];
    const float* below = moments_->skyline_chi(s).data() + static_cast<size_t>(j) * per_skyline;
    std::copy_n(below, per_degree, hidden_share[s]);
    chi[s] = m.chi.data();
    media_degree[s] = std::min(m.nonzero_degree, degree_);
    sums[s] = out[s];
    const int h = one_pass ? media + s : s;
    chi[h] = below;
    media_degree[h] = std::min(d, degree_);
    if (one_pass) sums[h] = hidden[s];
  }
  if (one_pass) {
    harmonic_source(degree_, r_m, mu, mu_view, nu, 2 * media, chi, media_degree, sums);
  } else {
    harmonic_source(degree_, r_m, mu, mu_view, nu, media, chi, media_degree, hidden, false);  // chi[s]: below
    for (int s = 0; s < media; ++s) {
      chi[s] = moments_->media[static_cast<size_t>(s)].chi.data();
      media_degree[s] = std::min(moments_->media[static_cast<size_t>(s)].nonzero_degree, degree_);
    }
    harmonic_source(degree_, r_m, mu, mu_view, nu, media, chi, media_degree, out);
  }
  add_skyline_gradient(r_m, mu, mu_view, nu, j, hidden);
  for (int s = 0; s < media; ++s) {
    for (size_t i = 0; i < per_degree; ++i) out[s][i] -= hidden[s][i];
    std::copy_n(hidden[s], per_degree, hidden_multiple[s]);
  }
  return true;
}

void SourceTable::add_skyline_gradient(double r_m, double mu, double mu_view, double nu, int skyline,
                                       float* const* hidden) const {
  const int media = std::min(static_cast<int>(moments_->media.size()), kMaxMedia);
  const int d = moments_->degree;
  const size_t per_degree = static_cast<size_t>(n_l_), per_skyline = static_cast<size_t>(d + 1) * per_degree;
  thread_local std::vector<float> gradient;
  gradient.resize(static_cast<size_t>(media) * per_degree + kLookupSlack);
  const float* chi[kMaxMedia];
  int media_degree[kMaxMedia];
  float* sums[kMaxMedia];
  for (int s = 0; s < media; ++s) {
    chi[s] = moments_->skyline_gradient_chi(s).data() + static_cast<size_t>(skyline) * per_skyline;
    media_degree[s] = std::min(d, degree_);
    sums[s] = gradient.data() + static_cast<size_t>(s) * per_degree;
  }
  harmonic_source(degree_, r_m, mu, mu_view, nu, media, chi, media_degree, sums, false, true);
  for (int s = 0; s < media; ++s)
    for (size_t i = 0; i < per_degree; ++i) hidden[s][i] += sums[s][i];
}

void SourceTable::skyline_look_ups(double r_m, double mu, double mu_view, double nu, const NodeLookup* shared,
                                   NodeLookup* nodes) const {
  if (shared) {  // another table's look-ups of the same node, to the same degree: its harmonics
    nodes[0] = shared[0];
    nodes[1] = shared[1];
    nodes[0].w = blend(r_m, mu);
  } else {
    look_up(degree_, r_m, mu, mu_view, nu, false, nullptr, nodes[0]);
    nodes[1] = nodes[0];
    upward_derivative_harmonics(degree_, nodes[0].mv, nodes[0].cos_phi, nodes[1].basis_d);
    for (int k = 0; k < skyspec::harmonic_count(degree_); ++k)
      nodes[1].basis[k] = static_cast<float>(nodes[1].basis_d[k]);
  }
  nodes[1].w = nodes[0].w;
}

void SourceTable::skyline_sums(const NodeLookup* nodes, int skyline, float* const* out, float* const* hidden) const {
  const int media = std::min(static_cast<int>(moments_->media.size()), kMaxMedia);
  const int d = moments_->degree;
  const size_t per_degree = static_cast<size_t>(n_l_), per_skyline = static_cast<size_t>(d + 1) * per_degree;
  const int own = out ? media : 0, sets = own + 2 * media;
  const float* chi[kMaxMedia];
  int media_degree[kMaxMedia];
  for (int s = 0; s < media; ++s) {
    if (out) {
      chi[s] = moments_->media[static_cast<size_t>(s)].chi.data();
      media_degree[s] = std::min(moments_->media[static_cast<size_t>(s)].nonzero_degree, degree_);
    }
    chi[own + s] = moments_->skyline_chi(s).data() + static_cast<size_t>(skyline) * per_skyline;
    chi[own + media + s] = moments_->skyline_gradient_chi(s).data() + static_cast<size_t>(skyline) * per_skyline;
    media_degree[own + s] = media_degree[own + media + s] = std::min(d, degree_);
  }
  // Both nodes' sums of every set: node 0's own and below-the-skyline ones and node 1's gradient
  // are kept (the other two products are not needed; their share of the pass is small).
  thread_local std::vector<float> sums;
  const size_t stride = static_cast<size_t>(sets) * per_degree;
  sums.resize(2 * stride + kLookupSlack);
  float* at[kMaxMedia];
  for (int s = 0; s < sets; ++s) at[s] = sums.data() + static_cast<size_t>(s) * per_degree;
  sum_harmonics(nodes, 2, degree_, sets, chi, media_degree, at, stride, false);
  for (int s = 0; s < media; ++s) {
    if (out) std::copy_n(at[s], per_degree, out[s]);
    const float* part = at[own + s];
    const float* gradient = at[own + media + s] + stride;
    for (size_t i = 0; i < per_degree; ++i) hidden[s][i] = part[i] + gradient[i];
  }
  if (out && polarised_ && degree_ >= 2) add_polarised_shares(nodes[0], degree_, media, out);
}

void SourceTable::source_below_skyline(double r_m, double mu, double mu_view, double nu, double skyline_rad,
                                       float* const* hidden) const {
  const int media = std::min(static_cast<int>(moments_->media.size()), kMaxMedia);
  const int d = moments_->degree;
  const int j = PhaseMoments::nearest_skyline(skyline_rad);
  const size_t per_skyline = static_cast<size_t>(d + 1) * static_cast<size_t>(n_l_);
  const float* chi[kMaxMedia];
  int media_degree[kMaxMedia];
  for (int s = 0; s < media; ++s) {
    chi[s] = moments_->skyline_chi(s).data() + static_cast<size_t>(j) * per_skyline;
    media_degree[s] = std::min(d, degree_);
  }
  harmonic_source(degree_, r_m, mu, mu_view, nu, media, chi, media_degree, hidden, false);
  add_skyline_gradient(r_m, mu, mu_view, nu, j, hidden);
}

bool ScatteringOrders::source_above_skyline(double r_m, double mu_sun, double mu_view, double nu, double skyline_rad,
                                            float* const* out, float* const* hidden, float* const* hidden_share,
                                            float* const* hidden_multiple) const {
  if (orders_.empty()) {
    sum_->source_above_skyline(r_m, mu_sun, mu_view, nu, skyline_rad, out, hidden, hidden_share, hidden_multiple);
    return true;
  }
  thread_local std::vector<float> once;
  const int n = sum_->wavelength_count();
  const int count = sum_->media_count();
  once.resize(static_cast<size_t>(count) * static_cast<size_t>(n) + SourceTable::kLookupSlack);
  float* ptr[kMaxMedia];
  for (int s = 0; s < count; ++s) ptr[s] = once.data() + static_cast<size_t>(s) * static_cast<size_t>(n);
  // Order 2's part below the skyline (its field is the light scattered once) at the same node.
  sum_->source_above_skyline_with(orders_.front().get(), ptr, r_m, mu_sun, mu_view, nu, skyline_rad, out, hidden,
                                  hidden_share, hidden_multiple);
  for (int s = 0; s < count; ++s)
    for (int i = 0; i < n; ++i) hidden_multiple[s][i] = std::max(0.0f, hidden[s][i] - ptr[s][i]);
  return true;
}

void SourceTable::look_up(int degree, double r_m, double mu, double mu_view, double nu, bool upward_derivative,
                          float* factors, NodeLookup& node) const {
  node.w = blend(r_m, mu, factors);
  // The view direction's azimuth from the sun's vertical plane at this point.
  const double mu_s = std::clamp(mu, -1.0, 1.0);
  const double mv = std::clamp(mu_view, -1.0, 1.0);
  const double sin_product = std::sqrt(std::max(0.0, (1.0 - mv * mv) * (1.0 - mu_s * mu_s)));
  const double cos_phi = sin_product > 1e-12 ? (nu - mv * mu_s) / sin_product : 1.0;
  node.mv = mv;
  node.cos_phi = cos_phi;
  double* basis_d = node.basis_d;
  symmetric_harmonics(degree, mv, cos_phi, basis_d);
  if (upward_derivative) upward_derivative_harmonics(degree, mv, cos_phi, basis_d);
  for (int k = 0; k < skyspec::harmonic_count(degree); ++k) node.basis[k] = static_cast<float>(basis_d[k]);
}

void SourceTable::upward_derivative_harmonics(int degree, double mv, double cos_phi, double* basis) {
  // d Y_lm / d(elevation) at the view direction, its azimuth held: a central difference of
  // 1e-4 rad (one-sided at the zenith and the nadir).
  constexpr double h = 1e-4;
  const double zenith = std::acos(mv);
  const double up = std::max(0.0, zenith - h), down = std::min(kPi, zenith + h);
  double above[kMaxHarmonics], below[kMaxHarmonics];
  symmetric_harmonics(degree, std::cos(up), cos_phi, above);
  symmetric_harmonics(degree, std::cos(down), cos_phi, below);
  for (int k = 0; k < skyspec::harmonic_count(degree); ++k) basis[k] = (above[k] - below[k]) / (down - up);
}

void SourceTable::harmonic_source(int degree, double r_m, double mu, double mu_view, double nu, int media,
                                  const float* const* chi, const int* media_degree, float* const* out,
                                  bool polarised_share, bool upward_derivative) const {
  NodeLookup node;
  look_up(degree, r_m, mu, mu_view, nu, upward_derivative, nullptr, node);
  sum_harmonics(&node, 1, degree, media, chi, media_degree, out, 0, polarised_share && !upward_derivative);
}

void SourceTable::sources_to_degree(int max_degree, int count, const double* r_m, const double* mu_sun,
                                    const double* mu_view, double nu, int media_given, int n, float* const* out) const {
  if (count <= 0) return;
  if (n < n_l_ || media_given < media_count())
    throw std::logic_error("SourceTable::sources: fewer wavelengths or media than the table's");
  const int degree = std::clamp(max_degree, 0, degree_);
  const int media = std::min(static_cast<int>(moments_->media.size()), kMaxMedia);
  const float* chi[kMaxMedia];
  int media_degree[kMaxMedia];
  for (int s = 0; s < media; ++s) {
    media_degree[s] = std::min(moments_->media[static_cast<size_t>(s)].nonzero_degree, degree);
    chi[s] = moments_->media[static_cast<size_t>(s)].chi.data();
  }
  const size_t padded = static_cast<size_t>((n_l_ + kLookupSlack - 1) / kLookupSlack * kLookupSlack);
  thread_local std::vector<NodeLookup> nodes;
  thread_local std::vector<float> factors;
  if (nodes.size() < static_cast<size_t>(count)) nodes.resize(static_cast<size_t>(count));
  if (factors.size() < 2 * padded * static_cast<size_t>(count)) factors.resize(2 * padded * static_cast<size_t>(count));
  for (int k = 0; k < count; ++k)
    look_up(degree, r_m[k], mu_sun[k], mu_view[k], nu, false, factors.data() + 2 * padded * static_cast<size_t>(k),
            nodes[static_cast<size_t>(k)]);
  // Runs of successive nodes between the same four entries, summed together.
  float* at[kMaxMedia];
  for (int k = 0; k < count;) {
    const Blend& w = nodes[static_cast<size_t>(k)].w;
    int run = 1;
    while (run < kMaxRun && k + run < count && nodes[static_cast<size_t>(k + run)].w.ih == w.ih &&
           nodes[static_cast<size_t>(k + run)].w.im == w.im)
      ++run;
    for (int s = 0; s < media; ++s) at[s] = out[s] + static_cast<size_t>(k) * static_cast<size_t>(n);
    sum_harmonics(&nodes[static_cast<size_t>(k)], run, degree, media, chi, media_degree, at, static_cast<size_t>(n),
                  true);
    k += run;
  }
}

void SourceTable::sum_harmonics(const NodeLookup* nodes, int count, int degree, int media, const float* const* chi,
                                const int* media_degree, float* const* out, size_t out_stride,
                                bool polarised_share) const {
  // J_s = sum_l chi_s,l sum_m Y_lm(view) a_lm, a_lm the blend of the four corners, per block of
  // wavelengths: the harmonics of each l are summed per corner first and blended once per l.
  // Blocks read past the last wavelength into the next harmonic or the spare floats; those lanes
  // are not written out.
  HarmonicSum sum{nodes, degree, n_l_, media, {}, {}, out, out_stride};
  for (int s = 0; s < media; ++s) {
    sum.media_degree[s] = media_degree[s];
    sum.chi[s] = chi[s];
  }
  // The run's length known at compile time, so that its nodes' sums stay in registers.
  using Run = void (HarmonicSum::*)() const;
  static constexpr Run kRuns[] = {&HarmonicSum::run_for_media<1>, &HarmonicSum::run_for_media<2>,
                                  &HarmonicSum::run_for_media<3>, &HarmonicSum::run_for_media<4>,
                                  &HarmonicSum::run_for_media<5>, &HarmonicSum::run_for_media<6>};
  static_assert(std::size(kRuns) == kMaxRun);
  if (count < 1 || count > kMaxRun) throw std::logic_error("SourceTable::sum_harmonics: a run of 1 to kMaxRun nodes");
  (sum.*kRuns[count - 1])();
  if (!(polarised_ && degree >= 2 && polarised_share)) return;
  for (int r = 0; r < count; ++r) {
    float* at[kMaxMedia];
    for (int s = 0; s < std::min(media, static_cast<int>(moments_->media.size())); ++s)
      at[s] = out[s] + static_cast<size_t>(r) * out_stride;
    add_polarised_shares(nodes[r], degree, media, at);
  }
}

void SourceTable::add_polarised_shares(const NodeLookup& node, int degree, int media, float* const* out) const {
  const Blend& w = node.w;
  // Polarisation's share of the intensity that molecules scatter, -2 B k^T D_pol k
  // (SingleScattering's polarised_sources derives it), B = 15 chi_2 / (8 pi) the phase
  // function's mu^2 coefficient; k^T D_pol k is even in the azimuth, so its sign does not matter.
  thread_local std::vector<float> tensor;
  tensor.resize(3 * static_cast<size_t>(n_l_));
  for (int j = 0; j < 3; ++j)
    mix(w, &SourceTable::p_index, p_, static_cast<size_t>(j) * n_l_, tensor.data() + static_cast<size_t>(j) * n_l_);
  const double mv = node.mv, cos_phi = node.cos_phi;
  const double sin_view = std::sqrt(std::max(0.0, 1.0 - mv * mv));
  const double kx = sin_view * std::clamp(cos_phi, -1.0, 1.0), kz = mv;
  const double ky2 = std::max(0.0, sin_view * sin_view - kx * kx);
  const float cxx = static_cast<float>(kx * kx - kz * kz), cyy = static_cast<float>(ky2 - kz * kz),
              cxz = static_cast<float>(2.0 * kx * kz);
  // The media's own sums only (source_above_skyline passes its part below the skyline after them).
  for (int s = 0; s < std::min(media, static_cast<int>(moments_->media.size())); ++s) {
    float* j = out[s];
    if (moments_->media[static_cast<size_t>(s)].sphere_matrix)
      add_polarising_share(w, degree, node.basis_d, moments_->polarising(s).data(), j);
    if (!moments_->media[static_cast<size_t>(s)].rayleigh) continue;
    const float* chi2 = &moments_->media[static_cast<size_t>(s)].chi[2 * static_cast<size_t>(n_l_)];
    for (int i = 0; i < n_l_; ++i) {
      const float mu2_coefficient = static_cast<float>(15.0 / (8.0 * kPi)) * chi2[i];
      j[i] -= 2.0f * mu2_coefficient * (cxx * tensor[i] + cyy * tensor[n_l_ + i] + cxz * tensor[2 * n_l_ + i]);
    }
  }
}

void SourceTable::add_polarising_share(const Blend& w, int degree, const double* basis, const float* gamma,
                                       float* out) const {
  // The polarisation's spin-2 harmonics c_lm turned into the intensity's by b1 (the transpose of
  // spin2_harmonics.hpp's b1 term): a_l0 = gamma_l c_l0, a_lm = gamma_l ((-1)^m c_lm + c_l,-m) / sqrt 2,
  // summed with the view direction's Y_lm.
  const int top = std::min(degree, degree_);
  if (top < 2) return;
  thread_local std::vector<float> c, sum;
  c.resize(static_cast<size_t>(spin2_harmonic_count(top)) * n_l_);
  sum.resize(static_cast<size_t>(n_l_));
  mix_rows(w, &SourceTable::p_index, p_, 3, spin2_harmonic_count(top), c.data());
  constexpr double kSqrtHalf = 0.70710678118654752440;
  for (int l = 2; l <= top; ++l) {
    std::fill(sum.begin(), sum.end(), 0.0f);
    for (int m = -l; m <= l; ++m) {
      const int a = std::abs(m);
      const double y = basis[harmonic_index(l, a)];
      const double weight = m == 0 ? y : kSqrtHalf * y * ((m > 0 && a % 2 == 1) ? -1.0 : 1.0);
      const float* row = c.data() + static_cast<size_t>(spin2_harmonic_index(l, m)) * n_l_;
      const float f = static_cast<float>(weight);
      for (int i = 0; i < n_l_; ++i) sum[static_cast<size_t>(i)] += f * row[i];
    }
    const float* g = gamma + static_cast<size_t>(l) * n_l_;
    for (int i = 0; i < n_l_; ++i) out[i] += g[i] * sum[static_cast<size_t>(i)];
  }
}

void SourceTable::mix(const Blend& w, size_t (SourceTable::*at)(int, int) const, const ZeroedFloats& data,
                      size_t offset, float* out) const {
  const float* a = &data[(this->*at)(w.ih, w.im) + offset];
  const float* b = &data[(this->*at)(w.ih, w.im + 1) + offset];
  const float* c = &data[(this->*at)(w.ih + 1, w.im) + offset];
  const float* d = &data[(this->*at)(w.ih + 1, w.im + 1) + offset];
  for (int i = 0; i < n_l_; ++i) {
    const float lower = w.lower ? w.lower[i] : 1.0f, upper = w.upper ? w.upper[i] : 1.0f;
    out[i] = lower * (w.sa * a[i] + w.sb * b[i]) + upper * (w.sc * c[i] + w.sd * d[i]);
  }
}

void SourceTable::mix_rows(const Blend& w, size_t (SourceTable::*at)(int, int) const, const ZeroedFloats& data,
                           int first_row, int rows, float* out) const {
  const size_t offset = static_cast<size_t>(first_row) * n_l_, count = static_cast<size_t>(rows) * n_l_;
  const float* a = &data[(this->*at)(w.ih, w.im) + offset];
  const float* b = &data[(this->*at)(w.ih, w.im + 1) + offset];
  const float* c = &data[(this->*at)(w.ih + 1, w.im) + offset];
  const float* d = &data[(this->*at)(w.ih + 1, w.im + 1) + offset];
  if (!w.lower && !w.upper) {
    for (size_t k = 0; k < count; ++k) out[k] = w.sa * a[k] + w.sb * b[k] + w.sc * c[k] + w.sd * d[k];
    return;
  }
  for (size_t r = 0; r < static_cast<size_t>(rows); ++r)
    for (size_t i = 0; i < static_cast<size_t>(n_l_); ++i) {
      const size_t k = r * n_l_ + i;
      const float lower = w.lower ? w.lower[i] : 1.0f, upper = w.upper ? w.upper[i] : 1.0f;
      out[k] = lower * (w.sa * a[k] + w.sb * b[k]) + upper * (w.sc * c[k] + w.sd * d[k]);
    }
}

bool SourceTable::rayleigh_moments(double r_m, double mu, float* out) const {
  if (degree_ < 2) return false;
  const Blend w = blend(r_m, mu);
  for (int m = 0; m <= 2; ++m)
    mix(w, &SourceTable::index, j_, static_cast<size_t>(harmonic_index(2, m)) * n_l_,
        out + static_cast<size_t>(m) * n_l_);
  float* tensor = out + 3 * static_cast<size_t>(n_l_);
  if (!polarised_) {
    std::fill(tensor, tensor + 3 * static_cast<size_t>(n_l_), 0.0f);
    return true;
  }
  for (int j = 0; j < 3; ++j)
    mix(w, &SourceTable::p_index, p_, static_cast<size_t>(j) * n_l_, tensor + static_cast<size_t>(j) * n_l_);
  return true;
}

int SourceTable::polarisation_harmonics(double r_m, double mu, int max_degree, float* out) const {
  const int degree = std::min(degree_, max_degree);
  if (!polarised_ || degree < 2) return 0;
  mix_rows(blend(r_m, mu), &SourceTable::p_index, p_, 3, spin2_harmonic_count(degree), out);
  return degree;
}

int SourceTable::field_harmonics(double r_m, double mu, int max_degree, float* out) const {
  const int degree = std::min(degree_, max_degree);
  if (degree < 0) return -1;
  mix_rows(blend(r_m, mu), &SourceTable::index, j_, 0, skyspec::harmonic_count(degree), out);
  return degree;
}

bool SourceTable::irradiance_on(double r_m, double mu, const Vec3& normal, float* out) const {
  // The clamped cosine's weights 2 pi int_0^1 mu P_l(mu) dmu (pi, 2 pi / 3, pi / 4, 0, -pi / 24, ...;
  // zero for odd l > 1), by Gauss-Legendre quadrature, once.
  static const std::vector<double> weight = [] {
    std::vector<double> x, wx;
    gauss_legendre(64, 0.0, 1.0, x, wx);
    std::vector<double> c(kMaxHarmonicDegree + 1, 0.0);
    for (size_t k = 0; k < x.size(); ++k) {
      double p0 = 1.0, p1 = x[k];
      c[0] += wx[k] * x[k] * p0;
      c[1] += wx[k] * x[k] * p1;
      for (int l = 2; l <= kMaxHarmonicDegree; ++l) {
        const double p2 = ((2 * l - 1) * x[k] * p1 - (l - 1) * p0) / l;
        c[static_cast<size_t>(l)] += wx[k] * x[k] * p2;
        p0 = p1;
        p1 = p2;
      }
    }
    for (double& v : c) v *= 2.0 * kPi;
    return c;
  }();
  const Blend w = blend(r_m, mu);
  const double mu_n = std::clamp(normal.z(), -1.0, 1.0), sin_n = std::sqrt(std::max(0.0, 1.0 - mu_n * mu_n));
  const double cos_phi = sin_n > 1e-12 ? std::clamp(normal.x() / sin_n, -1.0, 1.0) : 1.0;
  double y[skyspec::harmonic_count(kMaxHarmonicDegree)];
  symmetric_harmonics(degree_, mu_n, cos_phi, y);
  thread_local std::vector<float> block;
  block.resize(static_cast<size_t>(n_l_));
  std::fill(out, out + n_l_, 0.0f);
  for (int l = 0; l <= degree_; ++l) {
    if (std::abs(weight[static_cast<size_t>(l)]) < 1e-12) continue;  // odd l > 1
    for (int m = 0; m <= l; ++m) {
      const int k = harmonic_index(l, m);
      mix(w, &SourceTable::index, j_, static_cast<size_t>(k) * n_l_, block.data());
      const float f = static_cast<float>(weight[static_cast<size_t>(l)] * y[k]);
      for (int i = 0; i < n_l_; ++i) out[i] += f * block[static_cast<size_t>(i)];
    }
  }
  return true;
}

void SourceTable::ground_irradiance(double mu, float* out) const {
  const double fm = std::clamp(u_from_mu(mu), 0.0, 1.0) * (n_mu_ - 1);
  const int im = std::min(static_cast<int>(fm), n_mu_ - 2);
  const float am = static_cast<float>(fm - im);
  const float* a = g_at(im);
  const float* b = g_at(im + 1);
  for (int l = 0; l < n_l_; ++l) out[l] = (1 - am) * a[l] + am * b[l];
}

void SourceTable::add(const SourceTable& o) {
  prepared_ = false;
  const size_t block = static_cast<size_t>(o.n_c_) * n_l_;  // the other's harmonics, a prefix of ours
  for (size_t e = 0; e < static_cast<size_t>(n_h_) * n_mu_; ++e)
    for (size_t i = 0; i < block; ++i) j_[e * n_c_ * n_l_ + i] += o.j_[e * block + i];
  for (size_t i = 0; i < g_.size(); ++i) g_[i] += o.g_[i];
  if (polarised_ && o.polarised_) {
    const size_t rows = static_cast<size_t>(o.n_p_) * n_l_;  // the other's rows, a prefix of ours
    for (size_t e = 0; e < static_cast<size_t>(n_h_) * n_mu_; ++e)
      for (size_t i = 0; i < rows; ++i) p_[e * n_p_ * n_l_ + i] += o.p_[e * rows + i];
  }
}

void SourceTable::set_blend(const std::vector<const SourceTable*>& members,
                            const std::vector<std::vector<float>>& weights) {
  if (members.empty() || members.size() != weights.size())
    throw std::logic_error("SourceTable::set_blend: one weight row per member");
  for (size_t m = 0; m < members.size(); ++m)
    if (members[m]->n_h_ != n_h_ || members[m]->n_mu_ != n_mu_ || members[m]->n_c_ != n_c_ ||
        members[m]->n_l_ != n_l_ || members[m]->n_p_ != n_p_ || weights[m].size() != static_cast<size_t>(n_l_))
      throw std::logic_error("SourceTable::set_blend: a member of another shape");
  prepared_ = false;
  const size_t n = static_cast<size_t>(n_l_);
  // rows of n wavelengths: out row = sum_m w_m * member row, over `rows` rows of `data`
  const auto blend_rows = [&](float* out, size_t rows, auto data_of) {
    for (size_t r = 0; r < rows; ++r) {
      float* o = out + r * n;
      std::fill(o, o + n, 0.0f);
      for (size_t m = 0; m < members.size(); ++m) {
        const float* in = data_of(*members[m]) + r * n;
        const float* w = weights[m].data();
        for (size_t l = 0; l < n; ++l) o[l] += w[l] * in[l];
      }
    }
  };
  const size_t entries = static_cast<size_t>(n_h_) * n_mu_;
  blend_rows(j_.data(), entries * n_c_, [](const SourceTable& t) { return t.j_.data(); });
  for (size_t e = 0; e < entries; ++e) {  // harmonic 0, the mean radiance, at each entry
    float* mean = &j_[e * n_c_ * n];
    for (size_t l = 0; l < n; ++l) mean[l] = std::max(mean[l], 0.0f);
  }
  blend_rows(g_.data(), static_cast<size_t>(n_mu_), [](const SourceTable& t) { return t.g_.data(); });
  for (float& v : g_) v = std::max(v, 0.0f);
  if (p_size() > 0) blend_rows(p_.data(), entries * n_p_, [](const SourceTable& t) { return t.p_.data(); });
}

void SourceTable::set_geometric_blend(const SourceTable& a, const SourceTable& b, float t) {
  for (const SourceTable* x : {&a, &b})
    if (x->n_h_ != n_h_ || x->n_mu_ != n_mu_ || x->n_c_ != n_c_ || x->n_l_ != n_l_ || x->n_p_ != n_p_)
      throw std::logic_error("SourceTable::set_geometric_blend: a table of another shape");
  prepared_ = false;
  const size_t n = static_cast<size_t>(n_l_);
  // The factor that turns the linear blend of a0 and b0 into the geometric one.
  const auto factor = [t](float a0, float b0) {
    if (!(a0 > 0.0f && b0 > 0.0f)) return 1.0f;
    return std::exp((1.0f - t) * std::log(a0) + t * std::log(b0)) / ((1.0f - t) * a0 + t * b0);
  };
  const size_t entries = static_cast<size_t>(n_h_) * n_mu_;
  for (size_t e = 0; e < entries; ++e)
    for (size_t l = 0; l < n; ++l) {
      const size_t mean = e * n_c_ * n + l;
      const float f = factor(a.j_[mean], b.j_[mean]);
      for (size_t c = 0; c < static_cast<size_t>(n_c_); ++c) {
        const size_t i = mean + c * n;
        j_[i] = f * ((1.0f - t) * a.j_[i] + t * b.j_[i]);
      }
      for (size_t c = 0; c < static_cast<size_t>(n_p_); ++c) {
        const size_t i = (e * n_p_ + c) * n + l;
        p_[i] = f * ((1.0f - t) * a.p_[i] + t * b.p_[i]);
      }
    }
  for (size_t i = 0; i < g_.size(); ++i) g_[i] = factor(a.g_[i], b.g_[i]) * ((1.0f - t) * a.g_[i] + t * b.g_[i]);
}

void SourceTable::add_geometric_tail(const SourceTable& last, const SourceTable& before) {
  prepared_ = false;
  auto factor = [](float a, float b) {
    const float r = b > 0.0f ? std::clamp(a / b, 0.0f, 0.9f) : 0.0f;
    return r / (1.0f - r);
  };
  const size_t n_last = static_cast<size_t>(last.n_c_), n_before = static_cast<size_t>(before.n_c_);
  for (size_t e = 0; e < static_cast<size_t>(n_h_) * n_mu_; ++e)
    for (size_t i = 0; i < static_cast<size_t>(n_l_); ++i) {
      const float f = factor(last.j_[e * n_last * n_l_ + i], before.j_[e * n_before * n_l_ + i]);
      for (size_t c = 0; c < n_last; ++c) j_[(e * n_c_ + c) * n_l_ + i] += f * last.j_[(e * n_last + c) * n_l_ + i];
      if (polarised_ && last.polarised_)
        for (size_t c = 0; c < static_cast<size_t>(last.n_p_); ++c)
          p_[(e * n_p_ + c) * n_l_ + i] += f * last.p_[(e * last.n_p_ + c) * n_l_ + i];
    }
  for (size_t i = 0; i < g_.size(); ++i) g_[i] += factor(last.g_[i], before.g_[i]) * last.g_[i];
}

void SourceTable::write(std::ostream& out) const {
  const int32_t shape[4] = {n_h_, n_mu_, n_c_, n_l_};
  out.write(reinterpret_cast<const char*>(shape), sizeof shape);
  out.write(reinterpret_cast<const char*>(j_.data()), static_cast<std::streamsize>(j_size() * sizeof(float)));
  out.write(reinterpret_cast<const char*>(g_.data()), static_cast<std::streamsize>(g_.size() * sizeof(float)));
  if (p_size() > 0)
    out.write(reinterpret_cast<const char*>(p_.data()), static_cast<std::streamsize>(p_size() * sizeof(float)));
}

bool SourceTable::read(std::istream& in) {
  int32_t shape[4];
  if (!in.read(reinterpret_cast<char*>(shape), sizeof shape)) return false;
  if (shape[0] != n_h_ || shape[1] != n_mu_ || shape[2] != n_c_ || shape[3] != n_l_) return false;
  ZeroedFloats j(j_size() + kLookupSlack);
  std::vector<float> g(g_.size());
  if (!in.read(reinterpret_cast<char*>(j.data()), static_cast<std::streamsize>(j_size() * sizeof(float)))) return false;
  if (!in.read(reinterpret_cast<char*>(g.data()), static_cast<std::streamsize>(g.size() * sizeof(float)))) return false;
  ZeroedFloats p(p_size());
  if (p_size() > 0 &&
      !in.read(reinterpret_cast<char*>(p.data()), static_cast<std::streamsize>(p_size() * sizeof(float))))
    return false;
  for (size_t i = 0; i < j_size(); ++i)
    if (!std::isfinite(j[i])) return false;
  for (float v : g)
    if (!std::isfinite(v)) return false;
  for (size_t i = 0; i < p_size(); ++i)
    if (!std::isfinite(p[i])) return false;
  j_.swap(j);
  g_.swap(g);
  p_.swap(p);
  prepared_ = false;
  return true;
}

double SourceTable::mean_source() const {
  // The isotropic part: a_00 Y_00 = a_00 / sqrt(4 pi), the mean radiance.
  double s = 0.0;
  const size_t entries = static_cast<size_t>(n_h_) * n_mu_;
  for (size_t e = 0; e < entries; ++e)
    for (int i = 0; i < n_l_; ++i) s += j_[e * n_c_ * n_l_ + static_cast<size_t>(i)];
  return s / std::sqrt(4.0 * kPi) / static_cast<double>(entries * n_l_);
}

// --- ScatteringOrders ---------------------------------------------------------------------------

namespace {

// The light scattered once, order 2's field, is as sharp in direction as the scatterers' matrices
// (a rainbow, a halo, a forward lobe), far sharper than the quadrature's directions are apart (ten
// degrees and more): sampled at one direction, a bow narrower than that counts fully or not at all,
// depending on where it falls between the directions (its angle moves with the wavelength). So for
// the tabulated matrices each direction of integrate_order stands for its patch of the quadrature
// (between the cumulative Gauss weights in the zenith cosine, its midpoint cell in azimuth), split
// into kPatchRows x kPatchColumns parts of equal solid angle (DirectionQuadrature): a part's light
// is the matrix's mean over the part's range of scattering cosines (spanned by its corners and
// centre) times the direction's phase-free part (densities and transmittances, which change
// smoothly across the patch), and it enters the harmonics at the part's centre; the polarised
// tables' Q and U take b1's mean over all the parts at the direction itself (CosineRanges).
// Molecules and analytic phase functions, smooth, keep the direction's own value (the Gauss rule
// is exact for them).
constexpr int kPatchRows = DirectionQuadrature::kPatchRows, kPatchColumns = DirectionQuadrature::kPatchColumns,
              kPatchParts = kPatchRows * kPatchColumns;

struct Patch {
  double lo[kPatchParts], hi[kPatchParts];   // the parts' ranges of scattering cosines
  double mu[kPatchParts], phi[kPatchParts];  // their centres
};

// The parts of the patch mu in [mu_a, mu_b], phi in [phi_a, phi_b] (the zenith cosine and the
// azimuth from the sun's vertical) for a sun at zenith cosine mu_s.
void patch_parts(double mu_a, double mu_b, double phi_a, double phi_b, double mu_s, Patch& out) {
  const double sin_s = std::sqrt(std::max(0.0, 1.0 - mu_s * mu_s));
  const auto nu = [&](double mu, double phi) {
    return std::clamp(mu * mu_s + std::sqrt(std::max(0.0, 1.0 - mu * mu)) * sin_s * std::cos(phi), -1.0, 1.0);
  };
  const double dmu = (mu_b - mu_a) / kPatchRows, dphi = (phi_b - phi_a) / kPatchColumns;
  for (int a = 0; a < kPatchRows; ++a)
    for (int b = 0; b < kPatchColumns; ++b) {
      const double m0 = mu_a + a * dmu, p0 = phi_a + b * dphi;
      const int k = a * kPatchColumns + b;
      out.mu[k] = m0 + 0.5 * dmu;
      out.phi[k] = p0 + 0.5 * dphi;
      const double v[5] = {nu(m0, p0), nu(m0 + dmu, p0), nu(m0, p0 + dphi), nu(m0 + dmu, p0 + dphi),
                           nu(out.mu[k], out.phi[k])};
      out.lo[k] = *std::min_element(v, v + 5);
      out.hi[k] = *std::max_element(v, v + 5);
    }
}

// The tabulated scatterers' matrices (null for the others), in SingleScattering's order of scatterers.
std::vector<const TabulatedScatteringMatrix*> tabulated_matrices(const SingleScattering& integrator) {
  std::vector<const TabulatedScatteringMatrix*> out(static_cast<size_t>(integrator.scatterer_count()), nullptr);
  for (int k = 0; k < integrator.scatterer_count(); ++k) {
    const MediumPhase& phase =
        integrator.atmosphere().media()[static_cast<size_t>(integrator.medium_of_scatterer(k))].phase;
    if (phase.kind == MediumPhase::Kind::Tabulated) out[static_cast<size_t>(k)] = phase.matrix.get();
  }
  return out;
}

// Scratch memory of add_by_parts.
struct PartsScratch {
  PartsScratch(int wavelengths, int harmonics)
      : basis(static_cast<size_t>(harmonics)),
        part_basis(kPatchParts, harmonics + 1),
        part_means(wavelengths, kPatchParts),
        by_harmonic(wavelengths, harmonics + 1) {}
  std::vector<double> basis;
  Eigen::MatrixXf part_basis;   // [part, harmonic]: the harmonics (and last the zenith cosine) at the parts' centres
  Eigen::MatrixXf part_means;   // [wavelength, part]: a tabulated matrix's means over the parts
  Eigen::MatrixXf by_harmonic;  // [wavelength, harmonic]: part_means x part_basis
};

// Adds each tabulated scatterer's light of one direction by the parts of its patch (Patch) to the
// harmonics a ([wavelength, harmonic], the direction's quadrature weight applied) and, with_g, its
// light times the zenith cosine to g; the scatterer's phase-free part in `parts` is then zeroed,
// leaving the rest of the light to the direction's own value.
void add_by_parts(const std::vector<const TabulatedScatteringMatrix*>& tabulated, const Patch& patch, int degree,
                  double weight, bool with_g, RadianceParts& parts, PartsScratch& sc, Eigen::ArrayXXf& a, Spectrum& g) {
  const int n_c = static_cast<int>(sc.basis.size());
  for (int p = 0; p < kPatchParts; ++p) {
    symmetric_harmonics(degree, patch.mu[p], std::cos(patch.phi[p]), sc.basis.data());
    for (int c = 0; c < n_c; ++c) sc.part_basis(p, c) = static_cast<float>(sc.basis[static_cast<size_t>(c)]);
    sc.part_basis(p, n_c) = static_cast<float>(patch.mu[p]);
  }
  for (size_t k = 0; k < tabulated.size(); ++k) {
    if (!tabulated[k]) continue;
    const TabulatedScatteringMatrix& m = *tabulated[k];
    sc.part_means.setZero();
    for (int p = 0; p < kPatchParts; ++p)
      m.add_mean_phases(m.locate(patch.lo[p]), m.locate(patch.hi[p]), 1.0 / kPatchParts, sc.part_means.col(p).data());
    sc.by_harmonic.noalias() = sc.part_means * sc.part_basis;  // sum over the parts of mean x harmonic
    const Spectrum& free = parts.scattered[k];
    for (int c = 0; c < n_c; ++c) a.col(c) += static_cast<float>(weight) * free * sc.by_harmonic.col(c).array();
    if (with_g) g += static_cast<float>(weight) * free * sc.by_harmonic.col(n_c).array();
    parts.scattered[k].setZero();
  }
}

// Fill `table` with J and G computed from the radiance field that `sources` describes, integrated
// over the directions of `q`; with a stride > 1, only every stride-th entry (altitude x sun angle,
// row-major) is computed. With count_progress, each entry adds its rays to the preparation's
// progress (base/preparation_progress.hpp).
void integrate_order(const SingleScattering& integrator, const ScatteringSources& sources, const DirectionQuadrature& q,
                     SourceTable& table, int stride = 1, bool count_progress = false) {
  const AtmosphereModel& atm = integrator.atmosphere();
  const double R = atm.planet_radius_m();
  const int n = atm.grid().size();
  const Spectrum unit = Spectrum::Ones(n);
  std::vector<double> az(static_cast<size_t>(q.azimuth_nodes));
  for (int j = 0; j < q.azimuth_nodes; ++j) az[static_cast<size_t>(j)] = (j + 0.5) * kPi / q.azimuth_nodes;
  const double w_az = 2.0 * kPi / q.azimuth_nodes;  // both halves of the symmetric field
  const double d_az = kPi / q.azimuth_nodes;        // an azimuth node's cell
  // Order 2 with a tabulated matrix: its light by the parts of each direction's patch (Patch).
  const std::vector<const TabulatedScatteringMatrix*> tabulated = tabulated_matrices(integrator);
  const bool patches = sources.single && !sources.higher &&
                       std::any_of(tabulated.begin(), tabulated.end(), [](const auto* m) { return m != nullptr; });

  const int n_c = table.harmonic_count(), degree = table.degree();
  const bool polarised = table.polarised();
  const int n_p = table.polarisation_rows(), n_spin2 = spin2_harmonic_count(degree);
  struct Scratch {
    ScatteringWorkspace ws;
    Spectrum radiance, g, q, u, q_local, u_local;
    Eigen::ArrayXXf a;  // [wavelength, harmonic]
    // [wavelength, row]: the polarisation tensor's xx yy xz and the spin-2 harmonics (polarised tables)
    Eigen::ArrayXXf p;
    RadianceParts parts;
    std::vector<double> basis, spin2_q, spin2_u;
    Patch patch;
    CosineRanges ranges;
    PartsScratch by_parts;
    Scratch(int m, int c, int rows, int spin2)
        : ws(m),
          radiance(m),
          g(m),
          q(m),
          u(m),
          q_local(m),
          u_local(m),
          a(m, c),
          p(m, rows),
          parts(m),
          basis(static_cast<size_t>(c)),
          spin2_q(static_cast<size_t>(spin2)),
          spin2_u(static_cast<size_t>(spin2)),
          by_parts(m, c) {}
  };
  ScatteringSources ray_sources = sources;
  ray_sources.polarisation = polarised;
  tbb::enumerable_thread_specific<Scratch> scratch([n, n_c, n_p, n_spin2] { return Scratch(n, n_c, n_p, n_spin2); });
  const int entries = table.altitude_count() * table.sun_count();
  tbb::parallel_for(0, (entries + stride - 1) / stride, [&](int sample) {
    const int e = sample * stride;
    throw_if_cancelled();  // an entry is a few hundred rays: a request stops the tables within a second
    Scratch& sc = scratch.local();
    const int ih = e / table.sun_count(), imu = e % table.sun_count();
    // A centimetre inside the shell, so that rays from the table's end rows start strictly inside
    // the air (no tangent ambiguity at the ground or the top), and close enough that the end rows
    // stand for the shell's own altitudes also in a thin layer (the plane-parallel test layer of
    // docs/validation.md, "The published Rayleigh tables", says what a larger inset cost).
    constexpr double kInset = 0.01;
    const double r = std::clamp(R + table.altitude_m(ih), R + kInset, atm.top_radius_m() - kInset);
    const double mu_s = table.mu_sun(imu);
    const Vec3 x(0, 0, r), s(std::sqrt(std::max(0.0, 1 - mu_s * mu_s)), 0, mu_s);
    const double mu_horizon = -std::sqrt(std::max(0.0, 1 - (R / r) * (R / r)));
    std::vector<double> nodes, weights, gn, gw;
    const double panel = DirectionQuadrature::kHorizonPanelWidth;
    graded_gauss_legendre(q.sky_zenith_nodes, q.sky_horizon_nodes, panel, PanelEnd::lower, mu_horizon, 1.0, nodes,
                          weights);
    graded_gauss_legendre(q.ground_zenith_nodes, q.ground_horizon_nodes, panel, PanelEnd::upper, -1.0, mu_horizon, gn,
                          gw);
    const bool at_ground = ih == 0;
    sc.a.setZero();
    sc.g.setZero();
    sc.p.setZero();
    // mus descend from the top of their interval; each node's patch lies between the cumulative weights.
    auto integrate = [&](const std::vector<double>& mus, const std::vector<double>& ws_mu, double top, bool sky) {
      double patch_top = top;
      for (size_t i = 0; i < mus.size(); ++i) {
        const double mu = mus[i], sin_t = std::sqrt(std::max(0.0, 1 - mu * mu));
        const double patch_bottom = patch_top - ws_mu[i];
        for (double phi : az) {
          const Vec3 w(sin_t * std::cos(phi), sin_t * std::sin(phi), mu);
          const double weight = ws_mu[i] * w_az;
          if (patches) {
            patch_parts(patch_bottom, patch_top, phi - 0.5 * d_az, phi + 0.5 * d_az, mu_s, sc.patch);
            sc.ranges = CosineRanges{sc.patch.lo, sc.patch.hi, kPatchParts};
          }
          const CosineRanges* over = patches ? &sc.ranges : nullptr;
          if (polarised) {
            // The Stokes vector of the light arriving from w in its frame (e1, e2) and the polarised
            // part of its coherency matrix, C_pol = (Q (e1 e1^T - e2 e2^T) + U (e1 e2^T + e2 e1^T)) / 2,
            // summed into D_pol's xx, yy and xz (its xy and yz cancel between the two halves).
            integrator.radiance_parts(x, w, s, ray_sources, sc.ws, sc.parts);
            const Vec3 e1 = polarisation_frame(w, s), e2 = (-w).cross(e1);
            integrator.stokes(sc.parts, w, s, e1, unit, sc.ws, sc.radiance, sc.q, sc.u, over);
            const auto component = [&](int a, int b) {
              return static_cast<float>(0.5 * weight * (e1[a] * e1[b] - e2[a] * e2[b])) * sc.q +
                     static_cast<float>(0.5 * weight * (e1[a] * e2[b] + e2[a] * e1[b])) * sc.u;
            };
            sc.p.col(0) += component(0, 0);
            sc.p.col(1) += component(1, 1);
            sc.p.col(2) += component(0, 2);
            // The same polarisation relative to w's (e_theta, e_phi) (a turn of the frame in its
            // plane), projected on the spin-2 harmonics: c_lm += weight (Q lambda_lm cos m phi +
            // U lambda_lm sin m phi), even in phi like the tensor's terms.
            const double cos_phi = std::cos(phi), sin_phi = std::sin(phi);
            const Vec3 e_theta(mu * cos_phi, mu * sin_phi, -sin_t), e_phi(-sin_phi, cos_phi, 0.0);
            const double ta = e1.dot(e_theta), tb = e1.dot(e_phi), sa = e2.dot(e_theta), sb = e2.dot(e_phi);
            sc.q_local = static_cast<float>(0.5 * (ta * ta - sa * sa - tb * tb + sb * sb)) * sc.q +
                         static_cast<float>(ta * sa - tb * sb) * sc.u;
            sc.u_local = static_cast<float>(ta * tb - sa * sb) * sc.q + static_cast<float>(ta * sb + sa * tb) * sc.u;
            spin2_harmonics(degree, mu, cos_phi, sin_phi, sc.spin2_q.data(), sc.spin2_u.data());
            for (int c = 0; c < n_spin2; ++c)
              sc.p.col(3 + c) += static_cast<float>(weight * sc.spin2_q[static_cast<size_t>(c)]) * sc.q_local +
                                 static_cast<float>(weight * sc.spin2_u[static_cast<size_t>(c)]) * sc.u_local;
          } else if (patches) {
            integrator.radiance_parts(x, w, s, sources, sc.ws, sc.parts);
          } else {
            integrator.radiance(x, w, s, unit, sources, sc.ws, sc.radiance);
          }
          if (patches) {  // the tabulated scatterers' light by parts, the rest at the direction
            add_by_parts(tabulated, sc.patch, degree, weight, sky && at_ground, sc.parts, sc.by_parts, sc.a, sc.g);
            integrator.combine(sc.parts, w.dot(s), unit, sc.ws, sc.radiance);
          }
          symmetric_harmonics(degree, mu, std::cos(phi), sc.basis.data());
          for (int c = 0; c < n_c; ++c)
            sc.a.col(c) += static_cast<float>(weight * sc.basis[static_cast<size_t>(c)]) * sc.radiance;
          if (sky && at_ground) sc.g += static_cast<float>(mu * weight) * sc.radiance;
        }
        patch_top = patch_bottom;
      }
    };
    integrate(nodes, weights, 1.0, true);
    integrate(gn, gw, mu_horizon, false);
    float* out = table.j_at(ih, imu);
    for (int c = 0; c < n_c; ++c)
      std::copy(sc.a.col(c).data(), sc.a.col(c).data() + n, out + static_cast<size_t>(c) * n);
    if (at_ground) std::copy(sc.g.data(), sc.g.data() + n, table.g_at(imu));
    if (polarised)
      for (int c = 0; c < n_p; ++c)
        std::copy(sc.p.col(c).data(), sc.p.col(c).data() + n, table.p_at(ih, imu) + static_cast<size_t>(c) * n);
    if (count_progress) finish_preparation(q.rays());
  });
  table.prepare();
}

// A table read only up to a given degree (ScatteringOrders: building order k from order k - 1).
class SourceToDegree final : public InScatteringSource {
 public:
  SourceToDegree(const SourceTable& table, int degree, int polarisation_degree)
      : table_(table), degree_(degree), polarisation_degree_(polarisation_degree) {}
  void source(double r_m, double mu_sun, double mu_view, double nu, float* const* out) const override {
    table_.source_to_degree(degree_, r_m, mu_sun, mu_view, nu, out);
  }
  void sources(int count, const double* r_m, const double* mu_sun, const double* mu_view, double nu, int media, int n,
               float* const* out) const override {
    table_.sources_to_degree(degree_, count, r_m, mu_sun, mu_view, nu, media, n, out);
  }
  void ground_irradiance(double mu_sun, float* out) const override { table_.ground_irradiance(mu_sun, out); }
  bool rayleigh_moments(double r_m, double mu_sun, float* out) const override {
    return table_.rayleigh_moments(r_m, mu_sun, out);
  }
  int polarisation_harmonics(double r_m, double mu_sun, int max_degree, float* out) const override {
    return table_.polarisation_harmonics(r_m, mu_sun, std::min({max_degree, degree_, polarisation_degree_}), out);
  }
  int field_harmonics(double r_m, double mu_sun, int max_degree, float* out) const override {
    return table_.field_harmonics(r_m, mu_sun, std::min({max_degree, degree_, polarisation_degree_}), out);
  }

 private:
  const SourceTable& table_;
  int degree_, polarisation_degree_;
};

}  // namespace

bool ScatteringOrders::cuts_forward_peaks(const AtmosphereModel& atm, const MultipleScatteringSettings& settings) {
  if (!(settings.forward_cone_deg > 0.0) || settings.orders < 2) return false;
  for (const Medium& m : atm.media())
    if (m.phase.kind == MediumPhase::Kind::Tabulated && m.scatters()) return true;
  return false;
}

std::shared_ptr<const AtmosphereModel> ScatteringOrders::field_atmosphere_of(
    const AtmosphereModel& atm, const MultipleScatteringSettings& settings) {
  if (!cuts_forward_peaks(atm, settings)) return nullptr;
  std::optional<AtmosphereModel> cut = atm.with_forward_peaks_truncated(settings.forward_cone_deg * kPi / 180.0);
  if (!cut) return nullptr;
  return std::make_shared<const AtmosphereModel>(std::move(*cut));
}

ScatteringOrders::ScatteringOrders(const SingleScattering& integrator, const MultipleScatteringSettings& settings)
    : settings_(settings), field_atmosphere_(field_atmosphere_of(integrator.atmosphere(), settings)) {
  const auto t0 = std::chrono::steady_clock::now();
  const AtmosphereModel& field = field_atmosphere_ ? *field_atmosphere_ : integrator.atmosphere();
  // A medium confined to a region takes no part in the field (with_regional_media_as_probes).
  const std::optional<AtmosphereModel> probes = field.with_regional_media_as_probes();
  const AtmosphereModel& atm = probes ? *probes : field;
  const auto moments = PhaseMoments::of(atm, settings_.angular_degree);
  if (settings_.polarisation && settings_.angular_degree < 2 && settings_.orders >= 2)
    throw Error("polarised scattering-order tables need an angular degree of 2 or more (got " +
                std::to_string(settings_.angular_degree) + ")");
  auto make_table = [&] {
    return std::make_unique<SourceTable>(atm.planet_radius_m(), atm.top_radius_m(), settings_.altitude_samples,
                                         settings_.sun_samples, moments, -1, settings_.polarisation);
  };
  // The tables are built with their own, coarser ray quadrature, coarser still after order 2.
  const SingleScattering second_builder(atm, integrator.sun_columns(),
                                        IntegratorSettings{segments_of_order(settings_, 2)});
  const SingleScattering higher_builder(atm, integrator.sun_columns(),
                                        IntegratorSettings{segments_of_order(settings_, 3)});
  throw_if_cancelled();  // each table may be large: a request stops before the next is allocated
  // The work, in rays traced (each order's entries x its directions), for the progress a host shows.
  const long long entries = static_cast<long long>(settings_.altitude_samples) * settings_.sun_samples;
  long long rays = 0;
  for (int k = 2; k <= settings_.orders; ++k)
    rays += entries * quadrature_of_order(settings_.angular_degree, k, settings_.quadrature_refinement).rays();
  plan_preparation(rays, "building the scattering tables");
  sum_ = make_table();
  for (int k = 2; k <= settings_.orders; ++k) {
    throw_if_cancelled();
    const int degree = degree_of_order(settings_.angular_degree, k);
    auto table = std::make_unique<SourceTable>(atm.planet_radius_m(), atm.top_radius_m(), settings_.altitude_samples,
                                               settings_.sun_samples, moments, degree, settings_.polarisation);
    std::unique_ptr<SourceToDegree> source_of_previous;
    if (k > 2) source_of_previous = std::make_unique<SourceToDegree>(*orders_.back(), degree, kBuildPolarisationDegree);
    ScatteringSources previous;
    previous.single = k == 2;
    previous.higher = source_of_previous.get();
    integrate_order(k == 2 ? second_builder : higher_builder, previous,
                    quadrature_of_order(settings_.angular_degree, k, settings_.quadrature_refinement), *table, 1, true);
    sum_->add(*table);
    orders_.push_back(std::move(table));
  }
  if (orders_.size() >= 2) sum_->add_geometric_tail(*orders_.back(), *orders_[orders_.size() - 2]);
  sum_->prepare();
  build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

namespace {
// Bytes of one harmonic's values over a table's entries and wavelengths.
std::uint64_t bytes_per_harmonic(const MultipleScatteringSettings& st, int wavelengths) {
  return static_cast<std::uint64_t>(st.altitude_samples) * st.sun_samples * wavelengths * sizeof(float);
}
}  // namespace

std::uint64_t ScatteringOrders::cache_bytes(const MultipleScatteringSettings& st, int wavelengths) {
  // The sum and order 2's table, each with its polarisation tensor and spin-2 harmonics when polarised.
  const int d2 = degree_of_order(st.angular_degree, 2);
  std::uint64_t harmonics =
      static_cast<std::uint64_t>(skyspec::harmonic_count(st.angular_degree)) + skyspec::harmonic_count(d2);
  if (st.polarisation)
    harmonics += 2 * 3 + static_cast<std::uint64_t>(spin2_harmonic_count(st.angular_degree) + spin2_harmonic_count(d2));
  return bytes_per_harmonic(st, wavelengths) * harmonics;
}

std::size_t ScatteringOrders::bytes() const {
  std::size_t b = sum_->bytes();
  for (const auto& t : orders_) b += t->bytes();
  return b;
}

const SourceTable& ScatteringOrders::order(int k) const {
  if (k < 2 || k > settings_.orders)
    throw Error("scattering order " + std::to_string(k) + " is not among the tables' orders 2-" +
                std::to_string(settings_.orders));
  if (static_cast<size_t>(k - 2) >= orders_.size())
    throw Error("the table of scattering order " + std::to_string(k) +
                " is not kept in the table cache (order 2's and the sum of all orders are): built tables "
                "(render.cache_tables = false, or an empty cache) hold every order's");
  return *orders_[static_cast<size_t>(k - 2)];
}

std::uint64_t ScatteringOrders::table_bytes(const MultipleScatteringSettings& st, int wavelengths) {
  const std::uint64_t entry = bytes_per_harmonic(st, wavelengths);
  std::uint64_t harmonics = static_cast<std::uint64_t>(skyspec::harmonic_count(st.angular_degree));  // the sum
  for (int k = 2; k <= st.orders; ++k) harmonics += skyspec::harmonic_count(degree_of_order(st.angular_degree, k));
  if (st.polarisation) {  // each table's polarisation tensor and spin-2 harmonics
    harmonics += 3 * static_cast<std::uint64_t>(st.orders) + spin2_harmonic_count(st.angular_degree);
    for (int k = 2; k <= st.orders; ++k) harmonics += spin2_harmonic_count(degree_of_order(st.angular_degree, k));
  }
  return entry * harmonics;
}

int ScatteringOrders::degree_of_order(int angular_degree, int k) {
  if (angular_degree < 2) return angular_degree;
  return std::max(2, angular_degree - (k - 2));
}

int ScatteringOrders::segments_of_order(const MultipleScatteringSettings& settings, int k) {
  return k <= 2 ? settings.view_segments : settings.higher_order_segments;
}

DirectionQuadrature ScatteringOrders::quadrature_of_order(int angular_degree, int k, int refinement) {
  const int d = degree_of_order(angular_degree, k), extra = k == 2 ? 2 : 0;
  DirectionQuadrature q;
  q.sky_zenith_nodes = (std::max(8, d + 4) + extra) * refinement;
  q.ground_zenith_nodes = q.sky_zenith_nodes / 2;
  q.sky_horizon_nodes = 4 * refinement;
  q.ground_horizon_nodes = 2 * refinement;
  q.azimuth_nodes = (std::max(4, d) + extra) * refinement;
  return q;
}

double ScatteringOrders::estimate_build_seconds(const SingleScattering& integrator,
                                                const MultipleScatteringSettings& settings) {
  if (settings.orders < 2) return 0.0;
  const std::optional<AtmosphereModel> probes = integrator.atmosphere().with_regional_media_as_probes();
  const AtmosphereModel& atm = probes ? *probes : integrator.atmosphere();
  const SingleScattering second_builder(atm, integrator.sun_columns(),
                                        IntegratorSettings{segments_of_order(settings, 2)});
  const SingleScattering higher_builder(atm, integrator.sun_columns(),
                                        IntegratorSettings{segments_of_order(settings, 3)});
  // A table of the real shape holding only the sampled entries (J is alt x sun x wavelengths
  // floats; at the largest settings that is too much to allocate for an estimate, so the entries
  // are sampled from a table of at most 64 x 64 spread the same way).
  const int n_alt = std::min(settings.altitude_samples, 64), n_sun = std::min(settings.sun_samples, 64);
  const int entries = n_alt * n_sun, stride = std::max(1, entries / 48);
  const int sampled = (entries + stride - 1) / stride;
  const auto moments = PhaseMoments::of(atm, settings.angular_degree);
  SourceTable table(atm.planet_radius_m(), atm.top_radius_m(), n_alt, n_sun, moments, -1, settings.polarisation);
  const auto seconds_per_entry = [&](const ScatteringSources& sources, const DirectionQuadrature& q) {
    const auto t0 = std::chrono::steady_clock::now();
    integrate_order(sources.single ? second_builder : higher_builder, sources, q, table, stride);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / sampled;
  };
  // Order 2 integrates single scattering along its rays; order k > 2 looks order k - 1's table up
  // to order k's degree, at a cost per ray that grows with the harmonics read: timed per ray at the
  // largest and the smallest such degree (zero tables of those degrees, with the quadratures of
  // orders 3 and K), interpolated in the number of harmonics, times each order's rays.
  const int a = settings.angular_degree, refine = settings.quadrature_refinement;
  const double second = seconds_per_entry(ScatteringSources{true, nullptr}, quadrature_of_order(a, 2, refine));
  double higher = 0.0;
  if (settings.orders > 2) {
    const int d_max = degree_of_order(a, 3), d_min = degree_of_order(a, settings.orders);
    const DirectionQuadrature q_max = quadrature_of_order(a, 3, refine),
                              q_min = quadrature_of_order(a, settings.orders, refine);
    SourceTable big(atm.planet_radius_m(), atm.top_radius_m(), 4, 4, moments, d_max, settings.polarisation);
    big.prepare();
    const double t_max = seconds_per_entry(ScatteringSources{false, &big}, q_max) / q_max.rays();
    double t_min = t_max;
    if (d_min != d_max) {
      SourceTable small(atm.planet_radius_m(), atm.top_radius_m(), 4, 4, moments, d_min, settings.polarisation);
      small.prepare();
      t_min = seconds_per_entry(ScatteringSources{false, &small}, q_min) / q_min.rays();
    }
    const double c_max = harmonic_count(d_max), c_min = harmonic_count(d_min);
    for (int k = 3; k <= settings.orders; ++k) {
      const double c = harmonic_count(degree_of_order(a, k));
      const double per_ray = c_max == c_min ? t_max : t_min + (t_max - t_min) * (c - c_min) / (c_max - c_min);
      higher += per_ray * quadrature_of_order(a, k, refine).rays();
    }
  }
  const double all_entries = static_cast<double>(settings.altitude_samples) * settings.sun_samples;
  return all_entries * (second + higher);
}

namespace {
// The cache file: magic, key size and key (the inputs the tables depend on), table count, the
// tables a render reads (order 2's, whose field is the light scattered once, and the sum of all
// orders), and last a checksum of everything before it (SHA-256's first 64 bits), so that a file
// that was truncated, damaged or edited is rebuilt rather than trusted.
constexpr char kCacheMagic[] = "skyspec scattering orders v8\n";

}  // namespace

bool ScatteringOrders::save(const std::string& path, const std::string& key) const {
  try {
    AtomicOutputFile file(path);
    std::ofstream f(file.temporary_path(), std::ios::binary);
    HashingStreambuf hashing(f.rdbuf());
    std::ostream out(&hashing);
    out.write(kCacheMagic, sizeof kCacheMagic - 1);
    const uint64_t key_size = key.size();
    out.write(reinterpret_cast<const char*>(&key_size), sizeof key_size);
    out.write(key.data(), static_cast<std::streamsize>(key.size()));
    const int32_t count = orders_.empty() ? 0 : 1;
    out.write(reinterpret_cast<const char*>(&count), sizeof count);
    if (count == 1) orders_.front()->write(out);
    sum_->write(out);
    const uint64_t checksum = hashing.hash();
    f.write(reinterpret_cast<const char*>(&checksum), sizeof checksum);
    if (!out || !f.flush()) return false;
    f.close();
    file.commit();
    return true;
  } catch (const std::exception&) {
    return false;  // a cache that cannot be written only costs time
  }
}

std::unique_ptr<ScatteringOrders> ScatteringOrders::load(const std::string& path, const std::string& key,
                                                         const AtmosphereModel& own_atm,
                                                         const MultipleScatteringSettings& settings) {
  // Read straight into the tables (no copy of the file), hashing on the way; the tables are
  // trusted only if the checksum that follows them matches and nothing follows it.
  std::ifstream f(path, std::ios::binary);
  if (!f) return nullptr;
  HashingInStreambuf hashing(f.rdbuf());
  std::istream in(&hashing);
  std::string magic(sizeof kCacheMagic - 1, '\0');
  if (!in.read(magic.data(), static_cast<std::streamsize>(magic.size())) || magic != kCacheMagic) return nullptr;
  uint64_t key_size = 0;
  if (!in.read(reinterpret_cast<char*>(&key_size), sizeof key_size) || key_size != key.size()) return nullptr;
  std::string stored(key.size(), '\0');
  if (!in.read(stored.data(), static_cast<std::streamsize>(stored.size())) || stored != key) return nullptr;
  int32_t count = 0;
  if (!in.read(reinterpret_cast<char*>(&count), sizeof count) || count != (settings.orders >= 2 ? 1 : 0))
    return nullptr;
  std::unique_ptr<ScatteringOrders> o(new ScatteringOrders(settings));
  o->field_atmosphere_ = field_atmosphere_of(own_atm, settings);
  const AtmosphereModel& atm = o->field_atmosphere_ ? *o->field_atmosphere_ : own_atm;
  const auto moments = PhaseMoments::of(atm, settings.angular_degree);
  auto make_table = [&] {
    return std::make_unique<SourceTable>(atm.planet_radius_m(), atm.top_radius_m(), settings.altitude_samples,
                                         settings.sun_samples, moments, -1, settings.polarisation);
  };
  for (int k = 0; k < count; ++k) {
    auto t = std::make_unique<SourceTable>(atm.planet_radius_m(), atm.top_radius_m(), settings.altitude_samples,
                                           settings.sun_samples, moments,
                                           degree_of_order(settings.angular_degree, k + 2), settings.polarisation);
    if (!t->read(in)) return nullptr;
    t->prepare();
    o->orders_.push_back(std::move(t));
  }
  o->sum_ = make_table();
  if (!o->sum_->read(in)) return nullptr;
  uint64_t checksum = 0;
  if (!f.read(reinterpret_cast<char*>(&checksum), sizeof checksum) || checksum != hashing.hash()) return nullptr;
  if (f.peek() != std::char_traits<char>::eof()) return nullptr;
  o->sum_->prepare();
  return o;
}

std::unique_ptr<ScatteringOrders> ScatteringOrders::blended(const Blend& lower, const Blend& upper, float t,
                                                            const AtmosphereModel& own_atm,
                                                            const MultipleScatteringSettings& settings) {
  const auto t0 = std::chrono::steady_clock::now();
  std::unique_ptr<ScatteringOrders> o(new ScatteringOrders(settings));
  o->field_atmosphere_ = field_atmosphere_of(own_atm, settings);
  const AtmosphereModel& atm = o->field_atmosphere_ ? *o->field_atmosphere_ : own_atm;
  const auto moments = PhaseMoments::of(atm, settings.angular_degree);
  // One table (degree -1: the moments' own), blended from each member's table of that kind.
  const auto blend_of = [&](int degree, const SourceTable& (*of)(const ScatteringOrders&)) {
    const auto make = [&] {
      return std::make_unique<SourceTable>(atm.planet_radius_m(), atm.top_radius_m(), settings.altitude_samples,
                                           settings.sun_samples, moments, degree, settings.polarisation);
    };
    const auto linear = [&](const Blend& b) {
      std::vector<const SourceTable*> tables;
      for (const ScatteringOrders* m : b.members) tables.push_back(&of(*m));
      auto table = make();
      table->set_blend(tables, b.weights);
      return table;
    };
    std::unique_ptr<SourceTable> table = linear(lower);
    if (!upper.members.empty()) {
      const std::unique_ptr<SourceTable> high = linear(upper);
      auto low = std::move(table);
      table = make();
      table->set_geometric_blend(*low, *high, t);
    }
    table->prepare();
    return table;
  };
  if (settings.orders >= 2)
    o->orders_.push_back(blend_of(degree_of_order(settings.angular_degree, 2),
                                  [](const ScatteringOrders& m) -> const SourceTable& { return m.order(2); }));
  o->sum_ = blend_of(-1, [](const ScatteringOrders& m) -> const SourceTable& { return m.sum(); });
  o->build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return o;
}

}  // namespace skyspec
