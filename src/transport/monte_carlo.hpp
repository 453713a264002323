// The Monte Carlo reference: radiance of all scattering orders by backward path tracing, written
// independently of the deterministic integrator (single_scattering.hpp, multiple_scattering.hpp):
// its own sampling, no tables, no quadrature.
//
// For one wavelength a path starts at the observer and runs against the light:
//
//   free paths       delta (Woodcock) tracking against a constant rate sigma_seg >= sigma_t(z)
//                    everywhere in the medium: a tentative collision at distance -ln(1 - xi) /
//                    sigma_seg is real with probability sigma_t(z) / sigma_seg (Woodcock et al.
//                    1965; Novak et al. 2014, "Residual ratio tracking", section 3);
//   each segment     scores the sun's light it scatters towards the observer at every tentative
//                    collision, weighted by the ratio-tracking transmittance to it (so that thin
//                    segments, which most paths cross without a collision, still score);
//   absorption       the weight is multiplied by the single-scattering albedo sigma_s / sigma_t at
//                    each real collision (no path ends in absorption);
//   the sun          next-event estimation at those points and where a segment meets the ground:
//                    weight x phase (or a / pi cos) x E_sun x T(point -> sun), T estimated by ratio
//                    tracking (Cramer 1978; Novak et al. 2014, eq. 6), 0 in the planet's shadow;
//   scattering       a species is chosen in proportion to its sigma_s and the new direction is
//                    sampled exactly from its phase function (Rayleigh with depolarisation and
//                    Cornette-Shanks by rejection, Henyey-Greenstein by inversion);
//   the ground       Lambertian: weight x albedo, a cosine-distributed new direction (about the
//                    terrain's normal where a terrain is given, which also ends segments and hides
//                    the sun);
//   termination      leaving the medium, the order limit, or Russian roulette on small weights.
//
// Each path's contribution is an unbiased estimate of the radiance (per unit solar irradiance
// unless the medium says otherwise); the mean over N paths and its standard error
// sqrt(var / N) are reported. The sun is a point (a direction): the sun's disk and the direct
// beam are never part of the estimate, as the deterministic renderer's sky radiance excludes them.
//
// The medium is given per wavelength (MonteCarloMedium): components with a density profile, a
// scattering and an extinction coefficient and a phase function, in a spherical shell or, for
// published plane-parallel benchmarks, a flat slab.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "physics/scattering_matrix.hpp"
#include "skyspec/atmosphere.hpp"
#include "skyspec/density_profile.hpp"
#include "skyspec/geometry.hpp"
#include "skyspec/tabulated_scattering.hpp"
#include "skyspec/terrain.hpp"

namespace skyspec {

/// One species of the medium at one wavelength.
struct MonteCarloComponent {
  enum class Phase { None, Rayleigh, HenyeyGreenstein, CornetteShanks, Tabulated };
  DensityProfile profile = DensityProfile::constant();
  double scattering_per_m = 0.0;  ///< at relative density 1
  double extinction_per_m = 0.0;  ///< at relative density 1, >= scattering_per_m
  Phase phase = Phase::None;      ///< None only for a purely absorbing species
  double phase_parameter = 0.0;   ///< Rayleigh: gamma (phase_function.hpp); the aerosol models: g
  /// Tabulated: the scattering matrix (polarising) and the wavelength's row in it.
  std::shared_ptr<const TabulatedScatteringMatrix> table;
  int table_row = 0;
  /// Shell geometry: only inside this vertical cylinder (Medium::region), tracked in three
  /// dimensions like every other component (the majorant bounds it everywhere). Empty: everywhere.
  std::optional<VerticalCylinder> region;
};

/// The medium at one wavelength.
struct MonteCarloMedium {
  enum class Geometry { SphericalShell, PlaneParallel };
  Geometry geometry = Geometry::SphericalShell;
  /// Shell: the planet's radius (world space is planet-centred); slab: ignored (the ground is z = 0).
  double planet_radius_m = 6360e3;
  double top_altitude_m = 60e3;  ///< the medium ends here
  std::vector<MonteCarloComponent> components;
  double ground_albedo = 0.0;  ///< Lambertian
  /// Terrain on the shell's ground (terrain.hpp), Lambertian with terrain_albedo (unset: the
  /// ground's) times its albedo map's factor (Terrain::albedo_factor_under) wherever the ground
  /// lies over its grid (Terrain::covers): it ends the segments
  /// that meet it, shadows the points it hides the sun from, and reflects paths about its own
  /// normal. Null: none.
  std::shared_ptr<const Terrain> terrain;
  std::optional<double> terrain_albedo;
  double sun_irradiance = 1.0;  ///< irradiance normal to the sun's direction at the top

  /// Wavelength i of an atmosphere on its grid: a component per medium that extinguishes light
  /// (AtmosphereModel::media(), in its order), with its phase function at that wavelength; per
  /// unit solar irradiance.
  static MonteCarloMedium from_atmosphere(const AtmosphereModel& atmosphere, int wavelength_index);
};

struct MonteCarloSettings {
  std::int64_t paths = 65536;  ///< per probe and wavelength
  std::uint64_t seed = 1;
  int max_orders = 0;  ///< 0: all orders; k: events (scattering or ground) up to k
  int threads = 0;     ///< 0: all cores
  /// The share of scatterings whose new direction is drawn from the phase function about the
  /// direction towards the sun instead of about the path's own (0 to 0.5; 0: none). The weight
  /// takes p / ((1 - s) p + s p_sun), so the estimate stays unbiased; a path that turns towards the
  /// sun inside a forward peak (fog, rain, ice) then scores often and little instead of rarely and
  /// hugely (directional importance sampling: Buras & Mayer 2011, JQSRT 112, 434).
  double sun_peak_share = 0.0;
};

/// What one estimate gives: the mean over the paths and its standard error.
struct MonteCarloValue {
  double mean = 0.0;
  double standard_error = 0.0;
  std::int64_t paths = 0;
};

/// A Stokes vector [I, Q, U, V] estimated by the same paths: each component's mean and standard error.
using MonteCarloStokes = std::array<MonteCarloValue, 4>;

class MonteCarloIntegrator {
 public:
  /// sun_dir: unit vector towards the sun (world space of the medium's geometry).
  MonteCarloIntegrator(MonteCarloMedium medium, const Vec3& sun_dir);

  /// Radiance arriving at origin_m from direction -look (the observer looks along `look`, unit).
  /// `stream` separates independent estimates that share a seed (probe, wavelength): results
  /// depend on seed, stream and paths only, never on the number of threads.
  MonteCarloValue radiance(const Vec3& origin_m, const Vec3& look, const MonteCarloSettings& settings,
                           std::uint64_t stream) const;
  /// The Stokes vector [I, Q, U, V] of that radiance (vector transport: scattering matrices, the
  /// frames rotated between events; physics/scattering_matrix.hpp). Q and U refer to the frame
  /// (e1, e2, k) of the arriving light, k = -look: e1 is `reference` made perpendicular to k (for
  /// example the local vertical: Q > 0 is light polarised in the vertical plane), e2 = k x e1.
  /// The ground reflects as a depolarising Lambertian surface; aerosols neither polarise nor
  /// depolarise (non_polarising_scattering_matrix). I differs from radiance() by the coupling of
  /// polarisation into intensity (docs/validation.md, "Polarisation", measures it).
  MonteCarloStokes stokes_radiance(const Vec3& origin_m, const Vec3& look, const Vec3& reference,
                                   const MonteCarloSettings& settings, std::uint64_t stream) const;
  /// Irradiance on a surface at origin_m facing `normal` (unit) from the light scattered or
  /// reflected towards it (the direct sun excluded): the integral of radiance x cos over the
  /// hemisphere around normal, by cosine-distributed look directions.
  MonteCarloValue irradiance(const Vec3& origin_m, const Vec3& normal, const MonteCarloSettings& settings,
                             std::uint64_t stream) const;

  /// The majorant of the extinction coefficient used by the free-path sampling, m^-1.
  double majorant_per_m() const { return majorant_; }
  const MonteCarloMedium& medium() const { return medium_; }

 private:
  struct Rng;
  enum class ProbeKind { Radiance, Irradiance };
  /// N = 1: the radiance (scalar transport); N = 4: the Stokes vector in the frame of `reference`.
  template <int N>
  std::array<MonteCarloValue, N> estimate(ProbeKind kind, const Vec3& origin_m, const Vec3& dir, const Vec3& reference,
                                          const MonteCarloSettings& s, std::uint64_t stream) const;
  template <int N>
  Eigen::Matrix<double, N, 1> path(Vec3 p, Vec3 d, const Vec3& reference, int max_orders, double sun_peak_share,
                                   Rng& rng) const;
  double altitude(const Vec3& p) const;
  Vec3 up(const Vec3& p) const;
  Vec3 snap_to_ground(Vec3 p) const;
  /// Distance along d to where the ray leaves the medium, and whether it ends on the ground.
  /// on_terrain: the ground met is the terrain's surface (then snap_to_ground lifts the point off
  /// it along its normal rather than onto the sphere).
  double distance_to_boundary(const Vec3& p, const Vec3& d, bool& ground, bool* on_terrain = nullptr) const;
  double distance_to_shell_boundary(const Vec3& p, const Vec3& d, bool& ground) const;
  Vec3 ground_normal(const Vec3& g) const;
  Vec3 snap_to_surface(const Vec3& g, bool on_terrain) const;
  /// The Lambertian albedo of the surface at g: the terrain's over its grid (Terrain::covers), else
  /// the ground's.
  double surface_albedo(const Vec3& g) const;
  /// Coefficients at a point (a regional component's only inside its region).
  double extinction_at(const Vec3& p) const;
  double scattering_at(const Vec3& p, double* per_component) const;
  /// Component k's density relative to altitude 0 at p, whose altitude is z.
  double density_of(const MonteCarloComponent& c, const Vec3& p, double z) const {
    return c.region && !c.region->contains(p) ? 0.0 : c.profile.relative(z);
  }
  double transmittance_to_sun(const Vec3& p, Rng& rng) const;
  static double roulette(double transmittance, Rng& rng);
  double phase_to_sun(const double* scattering, double total_scattering, double mu) const;
  /// The scattering matrix of the mixture at a point (each species' matrix weighted by its share
  /// of the scattering coefficient); its a1 is phase_to_sun.
  ScatteringMatrix mixture_matrix(const double* scattering, double total_scattering, double mu) const;
  Vec3 sample_scattering(const double* scattering, double total_scattering, const Vec3& d, Rng& rng) const;

  MonteCarloMedium medium_;
  Vec3 sun_;
  double majorant_ = 0.0;
};

}  // namespace skyspec
