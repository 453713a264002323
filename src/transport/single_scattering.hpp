// Radiance along a view ray: single scattering (Nishita et al. 1993; the seed tutorial's
// equation 4), plus, when given, light scattered more than once from precomputed source tables,
// and light reflected by a Lambertian ground:
//
//   L(lambda) = E_sun sum_s beta_sca,s p_s(mu) int rho_s(t) exp(-tau_view(0,t) - tau_sun(t)) dt  (order 1)
//             + E_sun int exp(-tau_view(0,t)) sum_s beta_sca,s rho_s(t) J_s(r(t), mu_s(t), d) dt  (orders >= 2)
//             + exp(-tau_view(0,T)) a / pi [E_sun T_sun(g) max(0, mu_s(g)) + E_sun G(mu_s(g))]  (ground at g)
//
// with s over the scattering media and tau = sum_j beta_ext,j C_j over all media (AtmosphereModel::
// media(): air, aerosol, ozone, ...). J_s is medium s's in-scattering source of the higher orders
// towards the view direction d per unit solar irradiance, G the ground irradiance they give (see
// multiple_scattering.hpp). All wavelengths are carried together as one vector.
//
// Quadrature: the ray is cut at the shadow boundaries (closed form) and at its lowest point, and
// each piece into segments. For the single-scattering term, ln of the integrand rho_s exp(-tau)
// is taken as linear on a segment, which integrates exactly where the density is exponential and
// the optical depth linear (the log-mean rule); it is second order, and pairs of segments give a
// coarse estimate of the same integral so that Richardson extrapolation, (4 fine - coarse) / 3,
// removes the leading error term at the cost of one extra log-mean per pair. The higher-order
// term uses the same log-mean rule with J_s folded into the exponent, per medium. Columns of media
// whose density is a layer (zero outside it, such as ozone's) use the trapezoid rule; a scattering
// medium's density is positive everywhere (medium.hpp).
// View-ray columns are accumulated along the way; columns towards the sun come from the
// SunColumnTable, except those of a medium confined to a region (Medium::region, a shower): rays
// are also cut at its walls, its density is 0 on the pieces outside, and its column towards the
// sun is the chord through it (regional_column).
#pragma once

#include <limits>
#include <memory>
#include <vector>

#include "skyspec/geometry.hpp"
#include "skyspec/medium.hpp"
#include "skyspec/spectrum.hpp"
#include "skyspec/terrain.hpp"
#include "transport/optical_depth.hpp"

namespace skyspec {

struct IntegratorSettings {
  int view_segments = 64;  ///< segments along each view ray, in total
};

/// Radiance divided by what depends on the scattering angle: along a straight ray towards a sun at
/// infinity the angle between view and sun is the same at every point, so the phase functions
/// factor out of the single-scattering integrals, and the radiance is
///
///   L(lambda) = E_sun(lambda) [sum_s p_s(mu, lambda) scattered_s(lambda) + phase_free(lambda)]
///
/// with mu the cosine of the scattering angle and s over the scattering media
/// (SingleScattering::scatterer_count(), in AtmosphereModel::media()'s order). scattered_s is
/// beta_sca,s times the order-1 integral of medium s; `phase_free` holds the higher orders (their
/// phase functions are inside the tables' sources) and the ground (per unit solar irradiance). All
/// are smooth functions of the view direction, which is what makes them worth tabulating
/// (sky_view_table.hpp); the phase functions, peaked near the sun, are evaluated exactly afterwards.
///
/// With ScatteringSources::polarisation, polarised_q and polarised_u hold the linear polarisation
/// of the higher orders' light, per unit solar irradiance: the Stokes Q and U of
/// E_sun int exp(-tau_view) sum_s beta_sca,s rho_s P_s(r(t), mu_s(t), d) dt, with P_s the polarised
/// source of medium s at each point: for molecules (MediumPhase::Kind::Rayleigh), Rayleigh's
/// scattering matrix acting on the light arriving there, which it sees only through D = the
/// integral of the light's coherency matrix over all directions (P_Q = 2 B (e1^T D e1 - e2^T D e2),
/// P_U = 4 B e1^T D e2, B the phase function's mu^2 coefficient); for particles, their unit matrix
/// acting on the polarisation's quadrupole (polarised_sources has the equations; the tables give D's parts,
/// InScatteringSource::rayleigh_moments). The frame is the ray's polarisation_frame(): it stays
/// the same along the ray, so the sources of all its points add up. Empty otherwise.
struct RadianceParts {
  explicit RadianceParts(int n_wavelengths = 0, int scatterers = 0) { resize(n_wavelengths, scatterers); }
  /// Sizes the parts (zeros); keeps them (no allocation) when they have these sizes already.
  void resize(int n_wavelengths, int scatterers);
  void set_zero();
  std::vector<Spectrum> scattered;  ///< per scattering medium
  Spectrum phase_free;
  Spectrum polarised_q, polarised_u;
};

/// The scattering cosines a direction of a coarse quadrature stands for (the patch of directions
/// about it), as `count` ranges [lo[i], hi[i]] of equal solid angle. combine() and stokes() then
/// take each tabulated scatterer's matrix as its mean over them: a rainbow or a halo narrower than
/// the quadrature's spacing counts with its share of the patch instead of being hit or missed by
/// its one direction (the polarised scattering-order tables' order 2: integrate_order in
/// multiple_scattering.cpp, which takes the intensity part by part). Analytic phase functions and
/// molecules, smooth, keep their value at the direction's own cosine.
struct CosineRanges {
  const double* lo = nullptr;
  const double* hi = nullptr;
  int count = 0;
};

/// The Stokes frame of a view ray's polarised parts: e1 = the sun direction's component
/// perpendicular to the view, normalised (any unit vector perpendicular to the view when the sun
/// lies on its axis); e2 = k x e1 with k = -view, the direction the light travels. In this frame
/// Rayleigh's singly scattered light has U = 0.
Vec3 polarisation_frame(const Vec3& view, const Vec3& sun);

/// Per-thread scratch memory (spectral arrays are allocated once and reused).
struct ScatteringWorkspace {
  explicit ScatteringWorkspace(int n_wavelengths);
  Spectrum view_tau, view_trans, source, ground_sun, ground_sky;  // the ground's light
  Spectrum surface_albedo_over_pi;                                // the terrain's where it differs from the ground's
  /// The fine and coarse (paired) log-mean sums of one scattering medium: of order 1, of the
  /// higher orders' J_s, and (polarisation) of J_s + P_Q,s and J_s + P_U,s.
  struct Sums {
    Spectrum single[2], higher[2], q[2], u[2];
  };
  Sums sums[kMaxMedia];
  Spectrum phase[kMaxMedia];  // each scattering medium's phase function per wavelength at one mu
  RadianceParts parts;
};

/// How the sun's columns are obtained at a point; the table in production, closed forms in tests.
class SunColumns {
 public:
  virtual ~SunColumns() = default;
  virtual Columns at(double r_m, double mu_sun) const = 0;
  /// at() for count points at once (the integrator asks for all nodes of a piece of a ray).
  virtual void at_many(int count, const double* r_m, const double* mu_sun, Columns* out) const {
    for (int k = 0; k < count; ++k) out[k] = at(r_m[k], mu_sun[k]);
  }
};

class TableSunColumns : public SunColumns {
 public:
  explicit TableSunColumns(const SunColumnTable& t) : table_(t) {}
  Columns at(double r_m, double mu_sun) const override { return table_.lookup(r_m, mu_sun); }
  void at_many(int count, const double* r_m, const double* mu_sun, Columns* out) const override {
    table_.lookup_many(count, r_m, mu_sun, out);
  }

 private:
  const SunColumnTable& table_;
};

/// The in-scattering source of the higher orders: J_s(r, mu_s, view) = integral over the sphere of
/// p_s(view . w) L(r, mu_s, w) dw for each scattering medium s, radiance per unit scattering
/// coefficient and per unit solar irradiance (sr^-1), at altitude r, sun zenith cosine mu_s, for a
/// view direction with zenith cosine mu_view at cosine nu to the sun; and the irradiance G(mu_s)
/// it puts on the ground (per unit solar irradiance). Implemented by the scattering-order tables.
/// Both are called in the middle of an integration and must not themselves call
/// SingleScattering's radiance functions on the same thread (the integrator keeps a ray's nodes
/// per thread).
class InScatteringSource {
 public:
  virtual ~InScatteringSource() = default;
  /// J_s for each scattering medium s: out[s] (n floats each), in SingleScattering's order of them.
  virtual void source(double r_m, double mu_sun, double mu_view, double nu, float* const* out) const = 0;
  /// source() at `count` points of one ray (nu, the cosine between the ray and the sun, the same
  /// for all): point k's J_s at out[s] + k n for the `media` scattering media, n the wavelengths.
  /// The same values as source() at each; a table may read what neighbouring points share once for
  /// all of them.
  virtual void sources(int count, const double* r_m, const double* mu_sun, const double* mu_view, double nu, int media,
                       int n, float* const* out) const;
  virtual void ground_irradiance(double mu_sun, float* out) const = 0;
  /// What a scattering matrix reads of the radiance field that the source scatters, at
  /// (r, mu_s), per unit solar irradiance, in the local frame (z up, x towards the sun's azimuth):
  /// out[j n + i] for n wavelengths, rows j = 0, 1, 2 the field's quadrupole a_2m (m = j; its real
  /// spherical-harmonic coefficients, spherical_harmonics.hpp), rows 3, 4, 5 the xx, yy and xz
  /// components of its polarisation tensor D_pol = integral of C_pol(w) dw (C_pol the polarised
  /// part of the coherency matrix of the light arriving from w; traceless, so zz = -xx - yy; xy and
  /// yz vanish by the field's symmetry about the sun's vertical plane), zero where the field is
  /// taken as unpolarised. False (out untouched) if the source does not resolve the quadrupole.
  /// RadianceParts::polarised_q says how the integrator uses them.
  virtual bool rayleigh_moments(double /*r_m*/, double /*mu_sun*/, float* /*out*/) const { return false; }
  /// The polarisation of the same field in finer angular detail: its spin-2 harmonics c_lm
  /// (spin2_harmonics.hpp: Q and U relative to each direction's (e_theta, e_phi) in the same local
  /// frame) for 2 <= l <= the degree returned (at most max_degree), per unit solar irradiance, at
  /// out[spin2_harmonic_index(l, m) n + i]. What a particle's unit scattering matrix scatters of the
  /// polarised light (SingleScattering's polarised_sources). 0 (out untouched) where the field is
  /// taken as unpolarised.
  virtual int polarisation_harmonics(double /*r_m*/, double /*mu_sun*/, int /*max_degree*/, float* /*out*/) const {
    return 0;
  }
  /// The field's (intensity's) real spherical harmonics a_lm (spherical_harmonics.hpp) at (r, mu_s)
  /// for l <= the degree returned (at most max_degree), per unit solar irradiance, at
  /// out[harmonic_index(l, m) n + i]: what a particle's b1 polarises (polarised_sources). -1 (out
  /// untouched) if the source has no angular field.
  virtual int field_harmonics(double /*r_m*/, double /*mu_sun*/, int /*max_degree*/, float* /*out*/) const {
    return -1;
  }
  /// The irradiance the field puts on a surface at (r, mu_s) whose unit normal is normal_local in
  /// the same local frame (z up, x towards the sun's azimuth), per unit solar irradiance: the
  /// integral of L(w) max(0, n . w) over the sphere, from the field's harmonics
  /// (E(n) = sum_l 2 pi int_0^1 mu P_l(mu) dmu sum_m a_lm Y_lm(n), the clamped cosine's
  /// Legendre expansion and the addition theorem). False (out untouched) if the source has no
  /// angular field.
  virtual bool irradiance_on(double /*r_m*/, double /*mu_sun*/, const Vec3& /*normal_local*/, float* /*out*/) const {
    return false;
  }
  /// source() split at a straight skyline passing skyline_rad (0 to pi / 2) above the view
  /// direction, where a surface in front hides the sky: hidden[s] = the integral of
  /// p_s(view . w) L(w) over the directions below it, each ring about the view direction counted
  /// with the share of it below the skyline, with its mean radiance and its first Fourier term
  /// around the ring (the field's variation upwards; skyline_legendre_moments and
  /// skyline_gradient_moments: the addition theorem with the phase function's moments over that
  /// region); out[s] = J_s less
  /// hidden[s]; hidden_share[s] = the same integral of p_s alone (what a uniform radiance there
  /// adds per unit radiance); hidden_multiple[s] = the part of hidden[s] from the field's light
  /// scattered more than once (hidden[s] from a source that does not separate it). The field is
  /// the one source() uses. False (nothing written) if the source has no angular field.
  virtual bool source_above_skyline(double /*r_m*/, double /*mu_sun*/, double /*mu_view*/, double /*nu*/,
                                    double /*skyline_rad*/, float* const* /*out*/, float* const* /*hidden*/,
                                    float* const* /*hidden_share*/, float* const* /*hidden_multiple*/) const {
    return false;
  }
  /// The atmosphere whose radiance field the source holds, when that is not the integrator's own:
  /// the scaled problem of delta-M (AtmosphereModel::with_forward_peaks_truncated), in which the
  /// light of the particles' forward peaks travels with the unscattered light. The integrator then
  /// weights the sources with that atmosphere's scattering coefficients and carries them, the
  /// light reflected by the ground and the light scattered once along the view ray and the sun's
  /// with its extinction; single scattering keeps the uncut phase functions and scattering
  /// coefficients (Nakajima & Tanaka 1988's correction of single scattering, "TMS"). Null: the
  /// integrator's own atmosphere.
  virtual std::shared_ptr<const AtmosphereModel> field_atmosphere() const { return nullptr; }
};

/// What the scattering-order tables leave out of a regional medium's source (Medium::region: they
/// hold the field without it): added to J_s at the integrator's nodes (regional_orders.hpp).
class RegionalSource {
 public:
  virtual ~RegionalSource() = default;
  /// Adds to out[s] (n floats each, one per scatterer) every scatterer's source at x (a point
  /// inside a regional medium) sent along `toward` (unit: from x towards the ray's origin). False
  /// (out untouched) where it holds nothing.
  virtual bool add(const Vec3& x, const Vec3& toward, float* const* out) const = 0;
  /// Adds to `irradiance` (n floats, per unit solar irradiance) what the tables leave out of the
  /// sky's light on a horizontal ground at `ground_point` (on the sphere) near a regional medium.
  /// False (untouched) where it holds nothing.
  virtual bool add_ground(const Vec3& ground_point, float* irradiance) const = 0;
};

/// What a radiance evaluation includes.
struct ScatteringSources {
  bool single = true;                          ///< order 1: air scattering + direct sun off the ground
  const InScatteringSource* higher = nullptr;  ///< orders >= 2 from tables (or one order while building them)
  /// False: `higher` only shapes the march (its nodes, where it places them, and its field
  /// atmosphere's extinction, as with its light), and its light is left out, so that the light scattered
  /// once is the same to the last bit as with it (SkyViewResolution::higher_sky_rows).
  bool higher_light = true;
  /// Aerial perspective: integrate only up to this distance along the ray (a surface there hides
  /// what lies behind, including the ground), and, when `transmittance` is given, return the
  /// transmittance from the origin to the end of the integrated stretch.
  double max_distance_m = std::numeric_limits<double>::infinity();
  Spectrum* transmittance = nullptr;
  /// Also integrate the higher orders' polarisation (RadianceParts::polarised_q and polarised_u),
  /// where `higher` resolves the field's quadrupole (InScatteringSource::rayleigh_moments).
  bool polarisation = false;
  /// Terrain (terrain.hpp) that hides what lies behind it and shadows the air: the ray ends where
  /// it meets the surface, whose Lambertian reflection (albedo a) of the sun, where the terrain
  /// does not hide it, and of the sky is added as the ground's is; single scattering is collected
  /// only where the sun is visible past the terrain (Terrain::sunlit_parts: exact to its sampling).
  /// The higher orders' sources are the tables' (computed without terrain), less what the terrain
  /// hides from the points of a ray that ends on a surface where its shadow falls on the ray
  /// (SkylineCut in single_scattering.cpp; docs/terrain.md gives the error). Their irradiance on a surface of
  /// normal n is the tables' field integrated about n (InScatteringSource::irradiance_on), or G
  /// times the sky's share it sees, (1 + n.up) / 2, from a source without an angular field.
  const Terrain* terrain = nullptr;
  /// With `higher`: what the tables leave out of a regional medium's source (RegionalSecondOrder:
  /// for rays from the camera it was made for). Null: the tables' source alone.
  const RegionalSource* regional = nullptr;
};

class SingleScattering {
 public:
  /// The atmosphere and sun-column provider must outlive this object.
  SingleScattering(const AtmosphereModel& atm, const SunColumns& sun_columns, IntegratorSettings s);

  /// Radiance seen from origin_m looking along dir (unit), for a sun in direction sun_dir (unit)
  /// with spectral irradiance sun_irradiance (per wavelength). Writes `out` (grid size).
  /// Rays that start below the ground give 0.
  void radiance(const Vec3& origin_m, const Vec3& dir, const Vec3& sun_dir, const Spectrum& sun_irradiance,
                const ScatteringSources& sources, ScatteringWorkspace& ws, Spectrum& out) const;
  /// Single scattering only (order 1).
  void radiance(const Vec3& origin_m, const Vec3& dir, const Vec3& sun_dir, const Spectrum& sun_irradiance,
                ScatteringWorkspace& ws, Spectrum& out) const {
    radiance(origin_m, dir, sun_dir, sun_irradiance, ScatteringSources{}, ws, out);
  }

  /// The same radiance split into its phase-free parts (RadianceParts), per unit solar irradiance.
  void radiance_parts(const Vec3& origin_m, const Vec3& dir, const Vec3& sun_dir, const ScatteringSources& sources,
                      ScatteringWorkspace& ws, RadianceParts& parts) const;
  /// radiance_parts for `count` directions dirs[i] (unit) that all make the same angle with the
  /// zenith at origin_m, such as a row of the sky-view table; parts[i] receives direction i's.
  /// Along such rays the altitude is the same function of distance, so wherever a ray is lit from
  /// end to end and does not end on the ground, the quadrature's nodes, their densities and the
  /// view-ray columns to them are those of the first such ray, computed once; only the sun's
  /// angle, and what depends on it, is evaluated per ray. Other rays are integrated one by one.
  /// The results are radiance_parts's, to rounding. sources.transmittance must be null.
  void radiance_parts_same_zenith(const Vec3& origin_m, const Vec3* dirs, int count, const Vec3& sun_dir,
                                  const ScatteringSources& sources, ScatteringWorkspace& ws,
                                  RadianceParts* parts) const;
  /// L = E_sun [sum_s p_s(mu) scattered_s + phase_free] for mu = cos(scattering angle); with
  /// `over`, the tabulated p_s are their means over its ranges.
  void combine(const RadianceParts& parts, double mu, const Spectrum& sun_irradiance, ScatteringWorkspace& ws,
               Spectrum& out, const CosineRanges* over = nullptr) const;
  /// The polarisation of combine()'s light: the Stokes vector [I, Q, U] (V = 0) of the light
  /// arriving along k = -view, in the frame (e1, k x e1) (e1 unit, perpendicular to view). I is
  /// combine()'s radiance. Q and U are order 1's light polarised by each medium's scattering
  /// matrix, E scattered_s b1_s(mu) in the scattering plane's frame (molecules: b1 = -B (1 - mu^2)
  /// with B the phase function's mu^2 coefficient, physics/scattering_matrix.hpp; a tabulated
  /// matrix: its b1; an analytic phase function does not polarise), plus, if the parts hold them,
  /// the higher orders' polarised_q and polarised_u, all turned from polarisation_frame() into
  /// (e1, k x e1). The ground depolarises. With `over`, the tabulated a1 and b1 are their means
  /// over its ranges.
  void stokes(const RadianceParts& parts, const Vec3& view, const Vec3& sun, const Vec3& e1,
              const Spectrum& sun_irradiance, ScatteringWorkspace& ws, Spectrum& I, Spectrum& Q, Spectrum& U,
              const CosineRanges* over = nullptr) const;
  /// combine() for `count` directions whose parts are packed as SkyViewTable::lookup_many gives
  /// them ((scatterer_count() + 1) n floats each: each medium's, then phase-free; n wavelengths): direction k, at
  /// cosine mu[k] to the sun, goes to out[k] (n floats) where use[k]. The phase functions of all of them are evaluated
  /// in one loop that vectorises. The same values as combine().
  void combine_many(int count, const float* packed, const double* mu, const bool* use, const Spectrum& sun_irradiance,
                    float* const* out, ScatteringWorkspace& ws) const;

  /// Transmittance from origin_m along dir to the edge of the atmosphere (0 if the ray hits the
  /// ground): the attenuation of the sun's disk seen in that direction.
  void transmittance_to_space(const Vec3& origin_m, const Vec3& dir, Spectrum& out) const;

  const AtmosphereModel& atmosphere() const { return atm_; }
  /// The scattering media (RadianceParts::scattered, InScatteringSource::source): how many, and
  /// each one's index in AtmosphereModel::media().
  int scatterer_count() const { return static_cast<int>(scatterers_.size()); }
  int medium_of_scatterer(int s) const { return scatterers_[static_cast<size_t>(s)].medium; }
  const SunColumns& sun_columns() const { return sun_; }
  const IntegratorSettings& settings() const { return settings_; }

 private:
  const AtmosphereModel& atm_;
  const SunColumns& sun_;
  IntegratorSettings settings_;
  int media_ = 0;               ///< AtmosphereModel::media().size()
  Spectrum ext_[kMaxMedia];     ///< each medium's extinction at relative density 1
  bool layer_[kMaxMedia] = {};  ///< its density is a layer (trapezoid rule for its columns)
  /// Where a medium is confined (Medium::region; null: everywhere). trace() cuts rays at the
  /// walls, so that each piece lies wholly inside or outside; outside, the nodes' density is 0.
  const VerticalCylinder* region_[kMaxMedia] = {};
  bool has_regions_ = false;
  /// The column of regional medium j from p along dir (unit) to the top of the atmosphere, inside
  /// its region: the log-mean rule on kRegionChordSegments pieces of the chord (exact for an
  /// exponential profile where the altitude is linear along each piece). Replaces the sun-column
  /// table's value, which is the column of the medium everywhere.
  double regional_column(int j, const Vec3& p, const Vec3& dir) const;
  static constexpr int kRegionChordSegments = 8;
  /// The sun's columns at p (radius r, sun zenith cosine mu_sun): the table's, with regional
  /// media's chords.
  Columns sun_columns_at(const Vec3& p, double r, double mu_sun, const Vec3& s) const;
  /// Radii of the media's density breakpoints (DensityProfile::breakpoints_m: a cloud layer's base
  /// and top), where trace() cuts rays into pieces so that nodes fall inside any layer, however thin.
  std::vector<double> breakpoint_radii_m_;
  Spectrum albedo_over_pi_;
  int n_ = 0;  ///< wavelengths
  /// A scattering medium as the integrator uses it.
  struct Scatterer {
    int medium = 0;  ///< index in AtmosphereModel::media()
    Spectrum sca;    ///< beta_sca at relative density 1
    const MediumPhase* phase = nullptr;
    /// Molecules: the phase function per wavelength as A + B mu^2.
    Spectrum phase_a, phase_b;
    bool rayleigh() const { return phase->kind == MediumPhase::Kind::Rayleigh; }
  };
  std::vector<Scatterer> scatterers_;
  /// A particle's moments for the polarisation's spin-2 harmonics (spin2_harmonics.hpp), per l =
  /// 0..kMaxSpin2Degree (0 below l = 2): beta_l of alpha_+ (the phase function for the unit matrix)
  /// with d^l_22; for tabulated (sphere) matrices also beta-_l of alpha_- = (a1 - a3) / 2 with
  /// d^l_{2,-2} (the polarisation mirrored in the scattering plane) and gamma_l of b1 with d^l_{2,0}
  /// (unpolarised light polarised), else those two empty. Empty for molecules.
  struct SpinMoments {
    std::vector<Spectrum> plus, mirrored, polarising;
  };
  /// Computed on the first polarised render (polarised_sources), once per integrator and its copies.
  const std::vector<SpinMoments>& spin_moments() const;
  struct LazySpinMoments;
  std::shared_ptr<LazySpinMoments> spin_moments_;
  /// The integrator of the atmosphere whose field `sources.higher` holds (its field_atmosphere()),
  /// on the same sun columns, built on first use and kept; *this for its own atmosphere or without
  /// higher orders.
  const SingleScattering& field_integrator(const ScatteringSources& sources) const;
  struct FieldIntegrators;
  std::shared_ptr<FieldIntegrators> field_integrators_;
  /// Each scatterer's phase function at mu (the tabulated ones' means over `over` if given) into
  /// ws.phase[s]; one scatterer's into p.
  void phases_at(double mu, ScatteringWorkspace& ws, const CosineRanges* over = nullptr) const;
  void phase_of(int s, double mu, Spectrum& p) const;

  // The quadrature along one ray (single_scattering.cpp): where the ray runs in the atmosphere,
  // its pieces (lit or in shadow), the nodes on them, and the integration over the nodes.
  struct Node;
  struct Piece;
  struct Ray;
  bool trace(const Vec3& o, const Vec3& d, const Vec3& s, const ScatteringSources& sources, Ray& ray) const;
  static void sunlit_past_terrain(const Vec3& o, const Vec3& d, const Vec3& s, const Terrain& terrain,
                                  std::vector<Interval>& lit);
  void place_nodes(const Vec3& o, const Vec3& d, const ScatteringSources& sources, Ray& ray) const;
  /// `absent`: bit j set for a regional medium outside its region on the piece (no share).
  void piece_node_positions(const Vec3& o, const Vec3& d, double t0, double t1, int segments, unsigned absent,
                            double* t) const;
  static constexpr int kPilotsPerSegment = 2;  ///< density samples per segment that place the nodes
  void integrate(const Ray& ray, const Vec3& o, const Vec3& d, const Vec3& s, const ScatteringSources& sources,
                 ScatteringWorkspace& ws, RadianceParts& parts) const;
  // integrate's steps, one piece of a ray at a time (PieceScratch: per-thread arrays).
  struct PieceScratch;
  void optical_depths(const Eigen::ArrayXXf& columns, PieceScratch& sc, Eigen::ArrayXXf& tau) const;
  void single_scattering_piece(const Node* nodes, int m, const Vec3& o, const Vec3& d, const Vec3& s,
                               const SingleScattering& field, PieceScratch& sc, ScatteringWorkspace& ws) const;
  struct RayFrame;
  struct SkylineCut;
  /// True if it integrated the polarised sources too. With `cut`, the sky the terrain at the
  /// ray's end hides is the surface's light (SkylineCut).
  bool higher_orders_piece(const Node* nodes, int m, const Vec3& o, const Vec3& d, double os, double ds,
                           const InScatteringSource& higher, const RegionalSource* regional,
                           const SingleScattering& field, const RayFrame* polarisation, const SkylineCut* cut,
                           PieceScratch& sc, ScatteringWorkspace& ws) const;
  bool polarised_sources(const Node* nodes, int m, const RayFrame& frame, const InScatteringSource& higher,
                         PieceScratch& sc) const;
  /// Adds scatterer s's fine and coarse sums over the piece (sc.tau, sc.trans) to sums[0], sums[1].
  void accumulate(PieceScratch& sc, int s, Spectrum* sums) const;
  /// sum_j beta_ext,j columns[j] over the media.
  void optical_depth(const double* columns, Spectrum& tau) const;
  void ground_reflection(const Node& ground, const Vec3& ground_point, const Vec3& s, double mu_sun,
                         const ScatteringSources& sources, ScatteringWorkspace& ws, RadianceParts& parts) const;
  /// The irradiance (per unit solar irradiance) on the sphere's ground there, into ws.source.
  void ground_irradiance_at(const Vec3& ground_point, const Vec3& s, double mu_sun, const ScatteringSources& sources,
                            ScatteringWorkspace& ws) const;
  /// The irradiance (per unit solar irradiance) on the terrain at the ray's end p, with its normal
  /// and shadow, into ws.source.
  void terrain_irradiance(const Node& ground, const Vec3& p, const Vec3& s, const ScatteringSources& sources,
                          ScatteringWorkspace& ws) const;
  /// Its reflection seen through the view ray, added to the phase-free part.
  /// albedo / pi of the surface at a ray's end p: the ground's, or over the terrain's grid
  /// (Terrain::covers) its own albedo (or the ground's) times its map's factor under p.
  const Spectrum& albedo_over_pi_at(const Vec3& p, const Terrain* terrain, ScatteringWorkspace& ws) const;
  void terrain_reflection(const Node& ground, const Vec3& p, const Vec3& s, const ScatteringSources& sources,
                          ScatteringWorkspace& ws, RadianceParts& parts) const;
  void view_optical_depth(const Node& node, Spectrum& tau) const;
};

}  // namespace skyspec
