// Light scattered more than once: scattering orders accumulated into precomputed tables.
//
// Method (in the spirit of Bruneton & Neyret 2008, with the 2-D source tables of Hillaire 2020):
// for every order k >= 2 the radiance field L_{k-1} of the previous order is tabulated over
// altitude and sun zenith cosine (the sky is symmetric about the axis through the planet's centre
// along the sun direction, so those two numbers fix it), per wavelength, per unit solar
// irradiance, by its spherical-harmonic coefficients up to `angular_degree` in the local frame
// (spherical_harmonics.hpp):
//
//   a_lm,k(r, mu_s) = integral over the sphere of L_{k-1}(x, w) Y_lm(w) dw,
//   G_k(mu_s)       = integral over the sky hemisphere of L_{k-1}(ground, w) cos(theta) dw,
//
// where L_1 is single scattering plus the direct sun reflected by the ground, and L_{k-1} for
// k > 2 is the radiance produced by the previous order's source along each ray (plus the ground's
// reflection of G_{k-1}). The in-scattering source of species s towards a view direction w is
// then J_s(w) = sum_l chi_s,l sum_m a_lm Y_lm(w), with chi_s,l the Legendre moments of its phase
// function: exact for Rayleigh (degree 2) from angular_degree 2 on, the aerosol's forward peak
// resolved up to the degree. angular_degree 0 is the isotropic approximation (J = the mean
// radiance for every species and direction). Everything else, extinction, shadow, ground,
// curvature, is as for single scattering. The directional integrals use Gauss-Legendre
// quadrature in the zenith cosine, split at the horizon, and the midpoint rule in azimuth over the
// half space (the field is symmetric about the sun's vertical plane), with as many nodes as the
// order's degree needs (ScatteringOrders::quadrature_of_order).
// The tables depend on the atmosphere and the grid only, not on the sun's spectrum.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "base/zeroed_floats.hpp"
#include "transport/single_scattering.hpp"

namespace skyspec {

struct MultipleScatteringSettings {
  int orders = 4;             ///< highest scattering order counted (1: single scattering only)
  int altitude_samples = 16;  ///< table rows, denser near the ground (SourceTable::altitude_m)
  int sun_samples = 72;       ///< table columns over mu_s in [-1, 1], denser near the horizon
  int view_segments = 24;     ///< quadrature segments of each ray while building order 2's table
  /// Quadrature segments of each ray while building the tables of orders 3 and up, whose sources
  /// (the previous order's field) vary more smoothly along a ray than single scattering does
  /// (segments_of_order; their error: docs/performance.md and docs/validation.md).
  int higher_order_segments = 16;
  /// Every order's direction nodes (quadrature_of_order) times this in each of the three
  /// dimensions: 1 for renders; more to check that the tables have converged.
  int quadrature_refinement = 1;
  int angular_degree = 0;  ///< spherical-harmonic degree of the tabulated fields (0: isotropic)
  /// The tables solve the problem scaled by delta-M: the forward peak of every tabulated scattering
  /// matrix cut off within this many degrees of forward (AtmosphereModel::with_forward_peaks_truncated;
  /// 0: nothing cut). Renders keep single scattering's uncut phase functions and march it, like the
  /// tables' light, through the cut atmosphere's extinction (InScatteringSource::field_atmosphere).
  /// A medium confined to a region takes no part in the tables' field, which it scatters
  /// (AtmosphereModel::with_regional_media_as_probes).
  double forward_cone_deg = 0.0;
  /// Carry the fields' linear polarisation from order to order (vector transport for the air; needs
  /// angular_degree >= 2): each table also holds its field's polarisation tensor
  /// (InScatteringSource::rayleigh_moments) and the spin-2 harmonics of its polarisation to the
  /// table's degree (InScatteringSource::polarisation_harmonics), and the intensity gets
  /// polarisation's share.
  bool polarisation = false;
};

/// The directions over which an order's radiance field is integrated at each table entry.
/// In the zenith cosine each side of the horizon is a graded Gauss-Legendre rule
/// (graded_gauss_legendre): a panel of kHorizonPanelWidth next to the horizon with its own nodes,
/// where the light of a thin layer peaks within a few hundredths of the horizontal (the line of
/// sight's path through the layer grows as 1 / |mu|), and the bulk's nodes on the rest.
struct DirectionQuadrature {
  static constexpr double kHorizonPanelWidth = 0.05;  ///< in the zenith cosine, each side of the horizon
  /// Order 2 with a tabulated matrix: each direction's patch in rows (zenith cosine) x columns
  /// (azimuth) of parts, over which the matrix is averaged (integrate_order, docs/physics.md).
  static constexpr int kPatchRows = 2, kPatchColumns = 4;
  int sky_zenith_nodes = 0;      ///< nodes above the horizon panel, up to the zenith
  int sky_horizon_nodes = 0;     ///< nodes in the panel just above the horizon
  int ground_zenith_nodes = 0;   ///< nodes below the horizon panel, down to the nadir
  int ground_horizon_nodes = 0;  ///< nodes in the panel just below the horizon
  int azimuth_nodes = 0;         ///< midpoint nodes over [0, pi]
  int rays() const {
    return (sky_zenith_nodes + sky_horizon_nodes + ground_zenith_nodes + ground_horizon_nodes) * azimuth_nodes;
  }
};

/// The Legendre moments chi_l (l <= degree) of each scattering medium's phase function per
/// wavelength (spherical_harmonics.hpp), as the source tables weight the harmonics; in the order
/// of SingleScattering's scatterers (the media that scatter, in AtmosphereModel::media()'s order).
struct PhaseMoments {
  int degree = 0, wavelengths = 0;
  struct OfMedium {
    /// Molecules: the polarisation tensor adds its share to J (SourceTable::source_to_degree).
    bool rayleigh = false;
    /// The highest l at which the moments are not zero: 2 for molecules (their phase function is
    /// a quadratic in the scattering cosine), or the degree if that is lower.
    int nonzero_degree = 0;
    /// [l][wavelength], followed by kLookupSlack zeros (SourceTable::source reads whole blocks).
    std::vector<float> chi;
    /// A tabulated (sphere) matrix, whose b1 turns polarisation into intensity (polarising()).
    bool sphere_matrix = false;
  };
  /// Skylines 0, 1, ..., 90 degrees above the view direction (SourceTable::source_above_skyline
  /// takes the nearest).
  static constexpr int kSkylines = 91;
  static constexpr double kSkylineStep_rad = 3.14159265358979323846 / 180.0;
  /// The moments of medium s's phase function over what a straight skyline hides
  /// (skyline_legendre_moments), [skyline][l][wavelength] followed by kLookupSlack zeros; computed
  /// on first use (only terrain asks for them), from the phase functions kept for that.
  const std::vector<float>& skyline_chi(int s) const;
  /// The tabulated skyline nearest to skyline_rad above the view direction (clamped to 0..90 degrees).
  static int nearest_skyline(double skyline_rad);
  /// The moments of its first-order correction (skyline_gradient_moments), laid out the same way.
  const std::vector<float>& skyline_gradient_chi(int s) const;
  /// Medium s's gamma_l = 2 pi int b1 d^l_{2,0} dmu (spin2_harmonics.hpp), [l][wavelength] (zero for
  /// l < 2), with which a polarised table's polarisation adds to a sphere's intensity
  /// (SourceTable::harmonic_source); empty unless OfMedium::sphere_matrix. Computed on first use.
  const std::vector<float>& polarising(int s) const;
  std::vector<OfMedium> media;
  static std::shared_ptr<const PhaseMoments> of(const AtmosphereModel& atm, int degree);

 private:
  std::vector<MediumPhase> phases_;  // the media's phase functions, for skyline_chi
  mutable std::once_flag skyline_once_, polarising_once_;
  mutable std::vector<std::vector<float>> polarising_;
  mutable std::vector<std::vector<float>> skyline_chi_, skyline_gradient_chi_;
  void compute_skyline_moments() const;
};

/// One scattering order (or a sum of orders): the harmonics of its radiance field over (r, mu_s)
/// and G over mu_s, per wavelength.
class SourceTable : public InScatteringSource {
 public:
  /// Wavelengths the look-up handles at once (one AVX-512 register, two AVX2 ones); the arrays it
  /// reads are followed by this many spare floats, so that the last block needs no special case.
  static constexpr int kLookupSlack = 16;
  /// degree <= moments->degree (default: the moments' degree). A polarised table also holds the
  /// field's polarisation tensor and the spin-2 harmonics of its polarisation per entry (p_at).
  SourceTable(double planet_radius_m, double top_radius_m, int n_altitude, int n_sun,
              std::shared_ptr<const PhaseMoments> moments, int degree = -1, bool polarised = false);
  /// Needs prepare() after the last change to the table.
  void source(double r_m, double mu_sun, double mu_view, double nu, float* const* out) const override {
    source_to_degree(degree_, r_m, mu_sun, mu_view, nu, out);
  }
  /// source() from the harmonics up to max_degree only (all of them if it is the table's degree or
  /// more): the field smoothed to that degree.
  void source_to_degree(int max_degree, double r_m, double mu_sun, double mu_view, double nu, float* const* out) const;
  /// source() at the points of one ray (InScatteringSource::sources): the same values, point k's at
  /// out[s] + k n (n at least the table's wavelengths, media its media).
  void sources(int count, const double* r_m, const double* mu_sun, const double* mu_view, double nu, int media, int n,
               float* const* out) const override {
    sources_to_degree(degree_, count, r_m, mu_sun, mu_view, nu, media, n, out);
  }
  /// sources() from the harmonics up to max_degree only (source_to_degree).
  void sources_to_degree(int max_degree, int count, const double* r_m, const double* mu_sun, const double* mu_view,
                         double nu, int media, int n, float* const* out) const;
  bool source_above_skyline(double r_m, double mu_sun, double mu_view, double nu, double skyline_rad, float* const* out,
                            float* const* hidden, float* const* hidden_share,
                            float* const* hidden_multiple) const override;
  /// source_above_skyline, and at the same node below_table's source_below_skyline into
  /// below_hidden (when below_table is not null: a table on the same grid, order 2's beside the
  /// sum), the two tables' look-ups sharing the view's harmonics where their degrees agree.
  bool source_above_skyline_with(const SourceTable* below_table, float* const* below_hidden, double r_m, double mu_sun,
                                 double mu_view, double nu, double skyline_rad, float* const* out, float* const* hidden,
                                 float* const* hidden_share, float* const* hidden_multiple) const;
  /// Only hidden[s] of source_above_skyline.
  void source_below_skyline(double r_m, double mu_sun, double mu_view, double nu, double skyline_rad,
                            float* const* hidden) const;
  void ground_irradiance(double mu_sun, float* out) const override;
  /// The field's quadrupole and (polarised tables) its polarisation tensor at (r, mu_s), blended as
  /// source() blends (InScatteringSource::rayleigh_moments). False if the degree is below 2.
  bool rayleigh_moments(double r_m, double mu_sun, float* out) const override;
  /// A polarised table's spin-2 harmonics of the polarisation to min(max_degree, degree()), blended
  /// as source() blends (InScatteringSource::polarisation_harmonics); 0 for other tables.
  int polarisation_harmonics(double r_m, double mu_sun, int max_degree, float* out) const override;
  /// The harmonics to min(max_degree, degree()), blended as source() blends.
  int field_harmonics(double r_m, double mu_sun, int max_degree, float* out) const override;
  /// The field's irradiance on a tilted surface (InScatteringSource::irradiance_on), blended as
  /// source() blends.
  bool irradiance_on(double r_m, double mu_sun, const Vec3& normal_local, float* out) const override;
  /// Makes the table ready for source() once it is filled: notes which pairs of neighbouring sun
  /// angles are steep (see source()) and keeps the logarithms of their mean radiance. add,
  /// add_geometric_tail and read undo it (source() then throws); after writing through j_at it
  /// must be called again too (that is not tracked).
  void prepare();

  /// The altitude scale of the rows' spacing (altitude_of_row_coordinate), m.
  static constexpr double kRowAltitudeScale_m = 300.0;
  /// Geometry of the table's samples: row i at altitude_of_row_coordinate(i / (rows - 1)).
  double altitude_m(int i_altitude) const;
  /// h(x) = H (exp(x ln(1 + h_top / H)) - 1) for x in [0, 1], H = kRowAltitudeScale_m, and its inverse.
  double altitude_of_row_coordinate(double x) const;
  double row_coordinate_of_altitude(double altitude_m) const;
  /// The sun-angle columns' spacing (multiple_scattering.cpp, mu_from_u): finest at the cosine
  /// kSunColumnCentre (the sun just below the horizon), growing as sqrt(width^2 + (mu_s - centre)^2).
  static constexpr double kSunColumnCentre = -0.02;
  static constexpr double kSunColumnWidth = 0.08;
  /// Column i's sun zenith cosine, from -1 (i = 0) to 1 (the last).
  double mu_sun(int i_sun) const;
  int altitude_count() const { return n_h_; }
  int wavelength_count() const { return n_l_; }
  int media_count() const { return std::min(static_cast<int>(moments_->media.size()), kMaxMedia); }
  int sun_count() const { return n_mu_; }
  int harmonic_count() const { return n_c_; }
  int degree() const { return degree_; }
  /// The coefficients of an entry: [harmonic][wavelength].
  /// Writing through j_at or g_at needs prepare() again before source() (not tracked: the
  /// builders write entries from many threads at once).
  float* j_at(int i_altitude, int i_sun) { return &j_[index(i_altitude, i_sun)]; }
  const float* j_at(int i_altitude, int i_sun) const { return &j_[index(i_altitude, i_sun)]; }
  /// A polarised table's polarisation at an entry: [row][wavelength], rows xx, yy, xz of the
  /// polarisation tensor (rayleigh_moments) and then the spin-2 harmonics c_lm at
  /// 3 + spin2_harmonic_index(l, m), 2 <= l <= degree() (polarisation_harmonics).
  float* p_at(int i_altitude, int i_sun) { return &p_[p_index(i_altitude, i_sun)]; }
  /// Rows of p_at per entry: 3 + spin2_harmonic_count(degree()) for a polarised table, else 0.
  int polarisation_rows() const { return n_p_; }
  bool polarised() const { return polarised_; }
  float* g_at(int i_sun) { return &g_[static_cast<size_t>(i_sun) * n_l_]; }
  const float* g_at(int i_sun) const { return &g_[static_cast<size_t>(i_sun) * n_l_]; }
  /// this += the orders after `last` estimated as a geometric series: sum over j >= 1 of
  /// r^j last = last r / (1 - r), with r = last / before per entry and wavelength (the ratio of the
  /// isotropic parts, and of G for G; 0 to 0.9). Successive orders tend to a constant ratio (the
  /// largest eigenvalue of the scattering operator), so the series stands for the orders not
  /// computed (docs/physics.md measures it).
  void add_geometric_tail(const SourceTable& last, const SourceTable& before);
  /// this += other (same altitudes, sun angles and wavelengths; other's degree at most this one's).
  void add(const SourceTable& other);
  /// This table's values replaced by sum_m weights[m][l] members[m]'s at each wavelength l (tables
  /// of this shape): the table of an atmosphere between the members' (ScatteringOrders::blended).
  /// The mean radiance (harmonic 0) and the ground's irradiance are kept from going below zero,
  /// where weights of both signs could take them in the planet's shadow. Needs prepare() after it.
  void set_blend(const std::vector<const SourceTable*>& members, const std::vector<std::vector<float>>& weights);
  /// This table's values replaced by a geometric blend of a and b (tables of this shape): at each
  /// entry and wavelength, (1 - t) a + t b scaled by exp((1 - t) ln a_0 + t ln b_0) / ((1 - t) a_0 +
  /// t b_0), a_0 and b_0 their mean radiances (harmonic 0; G's own values for G) where both are
  /// positive, else left linear. Exact where the light falls exponentially from a to b, as it does
  /// with the ozone column (the light's paths through the layer). Needs prepare() after it.
  void set_geometric_blend(const SourceTable& a, const SourceTable& b, float t);
  /// Exact binary form (for the disk cache): shape, then J and G as raw floats.
  void write(std::ostream& out) const;
  /// Reads what write() wrote; false (and the table untouched) if the stream is short or the shape
  /// differs from this table's.
  bool read(std::istream& in);
  /// Mean of the isotropic part of J (the mean radiance) over the table and the wavelengths (for
  /// diagnostics and tests).
  double mean_source() const;
  /// The table's floats in bytes.
  std::size_t bytes() const { return (j_size() + g_.size() + p_size()) * sizeof(float); }

 private:
  struct Blend;
  struct NodeLookup;
  struct HarmonicSum;
  /// Nodes summed at once when they blend the same four entries (sources_to_degree).
  static constexpr int kMaxRun = 6;
  /// out[s] = sum_l chi[s]_l sum_m a_lm Y_lm(view) to `degree` with the moments chi[s] up to
  /// media_degree[s], s < count (source_to_degree, source_above_skyline), and for the molecules
  /// among the first media their polarised share (unless polarised_share is false: parts of a
  /// source below a skyline); with upward_derivative, the harmonics' derivative towards the zenith
  /// (in the view's vertical plane) in the place of their values.
  void harmonic_source(int degree, double r_m, double mu, double mu_view, double nu, int count, const float* const* chi,
                       const int* media_degree, float* const* out, bool polarised_share = true,
                       bool upward_derivative = false) const;
  /// harmonic_source's look-up of one node: the blend (its per-wavelength factors in `factors`, 2
  /// blocks of wavelengths rounded up to kLookupSlack; null: the thread's own) and the harmonics.
  void look_up(int degree, double r_m, double mu, double mu_view, double nu, bool upward_derivative, float* factors,
               NodeLookup& node) const;
  /// harmonic_source's sums for `count` (at most kMaxRun) nodes between the same four entries,
  /// node r's at out[s] + r out_stride.
  void sum_harmonics(const NodeLookup* nodes, int count, int degree, int media, const float* const* chi,
                     const int* media_degree, float* const* out, size_t out_stride, bool polarised_share) const;
  /// A node's look-ups for the sums below a skyline: nodes[0] the blend and the view's harmonics,
  /// nodes[1] the same blend with the harmonics' upward derivative (harmonic_source's
  /// upward_derivative); the harmonics copied from `shared` (another table's, same degree) when
  /// not null.
  void skyline_look_ups(double r_m, double mu, double mu_view, double nu, const NodeLookup* shared,
                        NodeLookup* nodes) const;
  /// In one pass over a node's four entries (skyline_look_ups' two nodes): out[s] (when not null)
  /// the whole source with the polarised share, as harmonic_source, and hidden[s] its part below
  /// tabulated skyline `skyline` with the gradient's correction (add_skyline_gradient). Needs
  /// three sets of moments per medium within kMaxMedia.
  void skyline_sums(const NodeLookup* nodes, int skyline, float* const* out, float* const* hidden) const;
  /// d Y_lm / d(elevation) of the view direction (mv, cos_phi), to `degree`, into basis.
  static void upward_derivative_harmonics(int degree, double mv, double cos_phi, double* basis);
  /// The molecules' polarised share (and the spheres' polarising one) of one node's sums out[s],
  /// s among the first `media` (sum_harmonics' polarised_share).
  void add_polarised_shares(const NodeLookup& node, int degree, int media, float* const* out) const;
  /// hidden[s] += the first-order correction below the skyline (skyline_gradient_moments) of
  /// tabulated skyline `skyline`: the field's derivative towards the zenith at the view direction
  /// (harmonic_source's upward_derivative) weighted by its moments.
  void add_skyline_gradient(double r_m, double mu, double mu_view, double nu, int skyline, float* const* hidden) const;
  /// The four entries around (r, mu_s) and their weights (per wavelength in steep rows).
  Blend blend(double r_m, double mu_s, float* factors = nullptr) const;
  /// One row of n wavelengths blended as `w` says from `data` (laid out by `at`), from `offset` on.
  void mix(const Blend& w, size_t (SourceTable::*at)(int, int) const, const ZeroedFloats& data, size_t offset,
           float* out) const;
  /// out += a particle's intensity from the polarisation by its b1 (gamma: PhaseMoments::OfMedium::
  /// polarising), the view direction's harmonics `basis` to `degree`.
  void add_polarising_share(const Blend& w, int degree, const double* basis, const float* gamma, float* out) const;
  /// `rows` consecutive rows of n wavelengths from row first_row on, blended at once.
  void mix_rows(const Blend& w, size_t (SourceTable::*at)(int, int) const, const ZeroedFloats& data, int first_row,
                int rows, float* out) const;
  size_t index(int ih, int imu) const { return ((static_cast<size_t>(ih) * n_mu_ + imu) * n_c_) * n_l_; }
  size_t p_index(int ih, int imu) const { return (static_cast<size_t>(ih) * n_mu_ + imu) * n_p_ * n_l_; }
  size_t p_size() const { return static_cast<size_t>(n_h_) * n_mu_ * n_p_ * n_l_; }
  size_t j_size() const { return static_cast<size_t>(n_h_) * n_mu_ * n_c_ * n_l_; }
  /// Two neighbouring sun angles whose mean radiances differ by more than this factor are read
  /// in log space (source()). Below it the linear blend of an exponential errs by at most
  /// 1 - 2 sqrt(r) / (1 + r): 0.6 % at 1.25 (6 % at 2, the former value; docs/validation.md
  /// measures what that did to twilight skies).
  static constexpr float kSteepRatio = 1.25f;
  /// Whether the mean radiance changes more than kSteepRatio-fold between sun angles imu and
  /// imu + 1 at altitude ih (at some wavelength), both positive throughout.
  bool steep_pair(int ih, int imu) const;
  double R_, Rt_;
  int n_h_, n_mu_, degree_, n_c_, n_l_;
  std::shared_ptr<const PhaseMoments> moments_;
  ZeroedFloats j_;  // j_size() floats and kLookupSlack spare; large tables: zeroed pages on first use
  std::vector<float> g_;
  bool polarised_;
  int n_p_;         // polarisation_rows()
  ZeroedFloats p_;  // polarised tables: p_size() floats
  // Filled by prepare(): steep_[ih * (n_mu_ - 1) + imu] and the logarithm of each entry's mean
  // radiance (the harmonic l = 0) per wavelength, [ih][imu][wavelength] (entries of steep pairs;
  // 0 elsewhere), and kLookupSlack zeros.
  bool prepared_ = false;
  std::vector<unsigned char> steep_;
  std::vector<float> log_mean_;
};

/// Orders 2..K computed one from the other; source() and ground_irradiance() return their sum and,
/// for K >= 3, the orders after K as a geometric series (SourceTable::add_geometric_tail).
/// Order k's table holds the harmonics of L_{k-1} up to degree_of_order(k): each order's field is
/// smoother than the one before (every scattering blurs it), so later orders need fewer, and fewer
/// directions to integrate them (quadrature_of_order). Building order k reads order k - 1's table
/// only up to order k's degree: along a ray the source's angular shape is carried in the ray's
/// direction, so the source's harmonics above that degree would feed mainly the field's harmonics
/// above it, which order k's table does not keep (docs/validation.md measures the effect).
class ScatteringOrders : public InScatteringSource {
 public:
  /// The integrator provides the atmosphere, the sun columns and the single-scattering term.
  ScatteringOrders(const SingleScattering& integrator, const MultipleScatteringSettings& settings);
  void source(double r_m, double mu_sun, double mu_view, double nu, float* const* out) const override {
    sum_->source(r_m, mu_sun, mu_view, nu, out);
  }
  void sources(int count, const double* r_m, const double* mu_sun, const double* mu_view, double nu, int media, int n,
               float* const* out) const override {
    sum_->sources(count, r_m, mu_sun, mu_view, nu, media, n, out);
  }
  void ground_irradiance(double mu_sun, float* out) const override { sum_->ground_irradiance(mu_sun, out); }
  bool rayleigh_moments(double r_m, double mu_sun, float* out) const override {
    return sum_->rayleigh_moments(r_m, mu_sun, out);
  }
  int polarisation_harmonics(double r_m, double mu_sun, int max_degree, float* out) const override {
    return sum_->polarisation_harmonics(r_m, mu_sun, max_degree, out);
  }
  int field_harmonics(double r_m, double mu_sun, int max_degree, float* out) const override {
    return sum_->field_harmonics(r_m, mu_sun, max_degree, out);
  }
  bool irradiance_on(double r_m, double mu_sun, const Vec3& normal_local, float* out) const override {
    return sum_->irradiance_on(r_m, mu_sun, normal_local, out);
  }
  /// hidden_multiple: the sum's part less order 2's (whose field is the light scattered once).
  bool source_above_skyline(double r_m, double mu_sun, double mu_view, double nu, double skyline_rad, float* const* out,
                            float* const* hidden, float* const* hidden_share,
                            float* const* hidden_multiple) const override;

  int highest_order() const { return settings_.orders; }
  /// The degree of order k's table: angular_degree for order 2, one less per order after it, but
  /// never below 2 (Rayleigh's degree) unless angular_degree is below 2.
  static int degree_of_order(int angular_degree, int k);
  /// Building order k reads the polarisation's spin-2 harmonics of order k - 1 to this degree only
  /// (each table holds them to its own degree, and renders read the sum's all): the polarisation
  /// that light scattered once more keeps is smooth (docs/validation.md measures the effect).
  static constexpr int kBuildPolarisationDegree = 4;
  /// The directions order k's table is integrated over, for a table of degree d: Gauss-Legendre
  /// nodes max(8, d + 4) above the horizon and half as many below, max(4, d) azimuths over [0, pi];
  /// order 2, whose source (single scattering) is cheap to evaluate and whose field has the
  /// sharpest features (the aerosol's forward peak around the sun), two more of each.
  static DirectionQuadrature quadrature_of_order(int angular_degree, int k, int refinement = 1);
  /// The quadrature segments of each ray while building order k's table: view_segments for
  /// order 2, higher_order_segments after it.
  static int segments_of_order(const MultipleScatteringSettings& settings, int k);
  /// The table of order k, 2 <= k <= highest_order(). Tables read from the cache hold order 2's
  /// and the sum only (what renders read); asking one of them for a higher order throws Error.
  const SourceTable& order(int k) const;
  const SourceTable& sum() const { return *sum_; }
  double build_seconds() const { return build_seconds_; }
  /// The bytes of the tables held (every order's after a build, order 2's and the sum's after a load).
  std::size_t bytes() const;

  /// Seconds the constructor would take for these settings, without building them: order 2 and
  /// the look-ups of the higher orders are timed on a sample of entries with each order's
  /// directions and scaled by the entries (altitudes x sun angles) and the orders.
  static double estimate_build_seconds(const SingleScattering& integrator, const MultipleScatteringSettings& settings);
  /// Bytes of the tables these settings build (every order's and the sum) for n wavelengths.
  static std::uint64_t table_bytes(const MultipleScatteringSettings& settings, int wavelengths);
  /// Bytes of the tables save() writes (order 2's and the sum) for n wavelengths.
  static std::uint64_t cache_bytes(const MultipleScatteringSettings& settings, int wavelengths);

  /// The scaled atmosphere the tables solved (forward_cone_deg), null when nothing was cut.
  std::shared_ptr<const AtmosphereModel> field_atmosphere() const override { return field_atmosphere_; }
  /// The atmosphere the tables for these settings solve: `atm` with its forward peaks cut
  /// (forward_cone_deg), or null when there is nothing to cut.
  static std::shared_ptr<const AtmosphereModel> field_atmosphere_of(const AtmosphereModel& atm,
                                                                    const MultipleScatteringSettings& settings);
  /// Whether field_atmosphere_of cuts anything (without building the cut atmosphere).
  static bool cuts_forward_peaks(const AtmosphereModel& atm, const MultipleScatteringSettings& settings);

  /// Saves the tables a render reads (order 2's and the sum) to `path` atomically, tagged with
  /// `key` (the scene keys they depend on). Returns false (and leaves no file) if it cannot.
  bool save(const std::string& path, const std::string& key) const;
  /// Loads tables saved under exactly `key` for this atmosphere and settings; null if the file is
  /// missing, from another key or version, or damaged.
  static std::unique_ptr<ScatteringOrders> load(const std::string& path, const std::string& key,
                                                const AtmosphereModel& atm, const MultipleScatteringSettings& settings);
  /// Members and their weights per wavelength ([member][wavelength]) of one linear blend.
  struct Blend {
    std::vector<const ScatteringOrders*> members;
    std::vector<std::vector<float>> weights;
  };
  /// The tables of `atm` as a blend of other atmospheres' tables (the members, built with the same
  /// settings on the same wavelengths): at wavelength l, order 2's table and the sum are, for each
  /// of `lower` and `upper`, sum_m weights[m][l] times member m's (SourceTable::set_blend), and the
  /// two are combined geometrically, weighted 1 - t and t (SourceTable::set_geometric_blend; lower
  /// alone where upper has no members). Right where each wavelength's tables depend on the
  /// atmosphere through quantities of that wavelength alone that the weights interpolate
  /// (render/table_family.hpp says which; docs/jobs.md what the blend errs).
  static std::unique_ptr<ScatteringOrders> blended(const Blend& lower, const Blend& upper, float t,
                                                   const AtmosphereModel& atm,
                                                   const MultipleScatteringSettings& settings);

 private:
  explicit ScatteringOrders(const MultipleScatteringSettings& settings) : settings_(settings) {}
  MultipleScatteringSettings settings_;
  std::vector<std::unique_ptr<SourceTable>> orders_;
  std::unique_ptr<SourceTable> sum_;
  std::shared_ptr<const AtmosphereModel> field_atmosphere_;  // null: the integrator's own
  double build_seconds_ = 0.0;
};

}  // namespace skyspec
