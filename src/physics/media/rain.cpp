// Rain: water drops falling through the air near the ground, with water's index at 10 degC (IAPWS
// R9-97, water.hpp), in one of two models (atmosphere.rain.drops):
//
// - Marshall & Palmer's sizes (1948, J. Meteorol. 5, 165; size_distribution.hpp) for a rain rate,
//   by the geometric optics of a sphere (drop_optics.hpp: the Descartes-Fresnel model of the
//   primary and secondary rainbows, no supernumeraries). The scattering function does not depend
//   on the drops' sizes, which set only the amount: the drops' geometric cross-section pi <r^2> N
//   per m^3 is the medium's extinction at the ground. Diffraction, the other half of a drop's
//   extinction, stays within a few thousandths of a degree of forward for drops this large and is
//   taken as unscattered light. Polarised: P12 and P33 from the rays' s and p amplitudes (P34 = 0).
// - Drops of about one size: a lognormal distribution (median radius, geometric standard deviation,
//   cut at 3 of them either side) by Lorenz-Mie theory (sphere_ensemble.hpp), the whole matrix, so
//   the bows come with their supernumeraries (Airy's interference of the rays either side of the
//   Descartes ray). Their number is what carries the rain rate R at their fall speed:
//   N = R / integral (4/3 pi r^3) v(2 r) dN, with Atlas, Srivastava & Sekhon's (1973, Rev. Geophys.
//   Space Phys. 11, 1) fit to Gunn & Kinzer's (1949) measured fall speeds, v(D) = 9.65 - 10.3
//   exp(-0.6 D / mm) m/s (positive above D = 0.11 mm; the key's smallest median radius keeps the
//   cut distribution above that). The light diffracted within kForwardConeDeg of forward (the
//   drops' diffraction peak, a tenth of a degree wide, no grid can hold) is taken as unscattered
//   light, as in the geometric model: the matrix is flat inside that cone and the light it cuts
//   leaves the scattering and the extinction (the delta-M idea: tabulated_scattering.hpp).
//
// Absorption is neglected in both (less than 1e-4 over a 2 mm path in the visible).
#include <cmath>
#include <sstream>
#include <string>

#include <tbb/parallel_for.h>

#include "base/preparation_progress.hpp"
#include "base/text_format.hpp"
#include "physics/media/media.hpp"
#include "physics/particle_optics_cache.hpp"
#include "skyspec/drop_optics.hpp"
#include "skyspec/error.hpp"
#include "skyspec/size_distribution.hpp"
#include "skyspec/sphere_ensemble.hpp"
#include "skyspec/units.hpp"
#include "skyspec/water.hpp"

namespace skyspec {

namespace {
constexpr int kRainOpticsFormat = 2;
constexpr double kRainTemperatureK = 283.15;  // 10 degC

// Every 0.5 degree of scattering angle, every 0.1 degree from 120 to 150 (the bows and the band).
const std::vector<double>& rain_cosines() {
  static const std::vector<double> mu = [] {
    std::vector<double> deg;
    for (int k = 0; k < 240; ++k) deg.push_back(0.5 * k);          // 0 - 119.5
    for (int k = 0; k < 300; ++k) deg.push_back(120.0 + 0.1 * k);  // 120 - 149.9
    for (int k = 0; k <= 60; ++k) deg.push_back(150.0 + 0.5 * k);  // 150 - 180
    return cosines_of_degrees(deg);
  }();
  return mu;
}

// Per unit of extinction: the drops' matrix (P11, P12, P33; P34 = 0) at each wavelength.
RawParticleOptics compute_rain_optics(const WavelengthGrid& grid) {
  const std::vector<double>& mu = rain_cosines();
  const int n = grid.size();
  RawParticleOptics o;
  o.sca.assign(static_cast<size_t>(n), 1.0);
  o.ext.assign(static_cast<size_t>(n), 1.0);
  o.a1.resize(static_cast<size_t>(n));
  o.b1 = o.a3 = o.a1;
  o.b2.assign(static_cast<size_t>(n), std::vector<double>(mu.size(), 0.0));
  plan_preparation(n, "the rain drops' geometric optics (rainbows)");
  const double rho = liquid_water_density_kg_per_m3(kRainTemperatureK);
  tbb::parallel_for(0, n, [&](int i) {
    const DropMatrixShares m = drop_geometric_matrix(water_refractive_index(kRainTemperatureK, rho, grid.nm(i)), mu);
    const size_t w = static_cast<size_t>(i);
    o.a1[w] = node_densities(m.p11, mu);
    o.b1[w] = node_densities(m.p12, mu);
    o.a3[w] = node_densities(m.p33, mu);
    finish_preparation(1);
  });
  return o;
}

std::string rain_optics_key(const WavelengthGrid& grid) {
  std::ostringstream key;
  key.precision(17);
  key << "skyspec rain optics, format " << kRainOpticsFormat << "\ngeometric optics " << kMaxDropReflections
      << "\nwater " << kRainTemperatureK << "\nwavelengths_nm";
  for (double v : grid.nanometres()) key << ' ' << v;
  key << "\ncosines " << rain_cosines().size() << '\n';
  return key.str();
}

// The lognormal drops (Lorenz-Mie) ---------------------------------------------------------------

constexpr int kMieRainOpticsFormat = 2;
constexpr double kForwardConeDeg = 0.5;  // the diffraction peak taken as unscattered light
// Panels 4 wide in size parameter (8 nodes each): the bows' supernumeraries change over many
// units of x, so a quarter of sphere_ensemble's default resolution holds them (docs/bows-and-halos.md
// gives the measured difference from the default).
constexpr double kPanelSizeParameter = 4.0;

SizeDistribution lognormal_drops(const RainSpec& rain) {
  return SizeDistribution::lognormal_within(rain.median_radius_mm * 1e-3, rain.radius_spread, kDropCutSpreads);
}

// Atlas, Srivastava & Sekhon (1973): a drop of diameter D falls at 9.65 - 10.3 exp(-0.6 D / mm) m/s.
double fall_speed_m_per_s(double diameter_m) { return 9.65 - 10.3 * std::exp(-0.6 * diameter_m * 1e3); }

// How many drops per m^3 carry the rain rate: R = N integral (4/3 pi r^3) v(2 r) dN.
double lognormal_drops_per_m3(const RainSpec& rain) {
  const SizeDistribution d = lognormal_drops(rain);
  double flux_per_drop = 0.0;  // m^3 of water per second through a square metre, per drop per m^3
  for (const RadiusNode& node : d.quadrature(0.01, 1.0))
    flux_per_drop +=
        node.weight * (4.0 / 3.0) * kPi * std::pow(node.radius_m, 3) * fall_speed_m_per_s(2.0 * node.radius_m);
  return rain.rate_mm_per_h * 1e-3 / 3600.0 / flux_per_drop;
}

// Per drop (one per m^3): the matrix with its diffraction peak cut flat inside kForwardConeDeg, and
// the cross-sections without the cut light.
RawParticleOptics compute_lognormal_rain_optics(const WavelengthGrid& grid, const RainSpec& rain) {
  const std::vector<double>& mu = rain_cosines();
  const SizeDistribution drops = lognormal_drops(rain);
  const double rho = liquid_water_density_kg_per_m3(kRainTemperatureK),
               cone_mu = std::cos(kForwardConeDeg * kPi / 180.0);
  SphereEnsembleSettings quadrature;
  quadrature.panel_size_parameter = kPanelSizeParameter;
  RawParticleOptics o;
  const int n = grid.size();
  plan_preparation(n, "the rain drops' Lorenz-Mie optics (rainbows with supernumeraries)");
  for (int i = 0; i < n; ++i) {
    const std::complex<double> m(water_refractive_index(kRainTemperatureK, rho, grid.nm(i)), 0.0);
    const SphereEnsembleOptics e = sphere_ensemble_optics(drops, m, grid.nm(i) * 1e-9, 1.0, mu, quadrature);
    // The cone's nodes take the values at its edge (mu ascends: the edge is the last node below it).
    size_t edge = mu.size() - 1;
    while (edge > 0 && mu[edge] > cone_mu - 1e-12) --edge;
    std::vector<SphereScatteringMatrix> p = e.phase_matrix;
    for (size_t k = edge + 1; k < mu.size(); ++k) p[k] = p[edge];
    // The share of the light the flattened function keeps (trapezoidal, as the table integrates it).
    double kept = 0.0;
    for (size_t k = 0; k + 1 < mu.size(); ++k) kept += kPi * (p[k].s11 + p[k + 1].s11) * (mu[k + 1] - mu[k]);
    kept = std::min(kept, 1.0);
    // Water without absorption: the two series' sums agree to rounding, which must not let the
    // scattering exceed the extinction.
    const double c_ext = e.extinction_cross_section_m2, c_sca = std::min(e.scattering_cross_section_m2, c_ext);
    append_sphere_optics(o, c_sca * kept, c_ext - c_sca * (1.0 - kept), p);
    finish_preparation(1);
  }
  return o;
}

std::string lognormal_rain_optics_key(const WavelengthGrid& grid, const RainSpec& rain) {
  std::ostringstream key;
  key.precision(17);
  key << "skyspec rain optics, Lorenz-Mie, format " << kMieRainOpticsFormat << "\nlognormal " << rain.median_radius_mm
      << ' ' << rain.radius_spread << " cut " << kDropCutSpreads << "\nwater " << kRainTemperatureK << "\nforward cone "
      << kForwardConeDeg << "\nwavelengths_nm";
  for (double v : grid.nanometres()) key << ' ' << v;
  const SphereEnsembleSettings defaults;
  key << "\ncosines " << rain_cosines().size() << "\nquadrature " << defaults.panel_ln_radius << ' '
      << kPanelSizeParameter << '\n';
  return key.str();
}

std::optional<Medium> build_lognormal_rain(const MediumContext& c) {
  const RainSpec& rain = c.spec.rain;
  // Lorenz-Mie's series are exact to a size parameter of 2e4 (lorenz_mie.hpp): refused beyond,
  // before any work.
  const double largest_m = lognormal_drops(rain).max_radius_m(), shortest_nm = c.grid.min_nm();
  if (2.0 * kPi * largest_m / (shortest_nm * 1e-9) > kMaxMieSizeParameter)
    throw InputError("atmosphere.rain.median_radius_mm", format_number(rain.median_radius_mm),
                     "at most " +
                         format_number(std::floor(kMaxMieSizeParameter * shortest_nm * 1e-9 / (2.0 * kPi) * 1e6 /
                                                  std::pow(rain.radius_spread, kDropCutSpreads)) /
                                       1e3) +
                         " mm with radius_spread " + format_number(rain.radius_spread) + " and spectrum.min_nm " +
                         format_number(shortest_nm) +
                         " (the largest drops, median * spread^3, within Lorenz-Mie's size parameter 2e4)");
  const AerosolMixtureOptics per_drop =
      cached_particle_optics(lognormal_rain_optics_key(c.grid, rain), c.grid.size(), rain_cosines(), c.cache_on_disk,
                             [&] { return compute_lognormal_rain_optics(c.grid, rain); });
  return particle_medium("rain", DensityProfile::exponential(rain.scale_height_m), per_drop,
                         lognormal_drops_per_m3(rain));
}

std::optional<Medium> build_marshall_palmer_rain(const MediumContext& c) {
  const RainSpec& rain = c.spec.rain;
  const AerosolMixtureOptics unit =
      cached_particle_optics(rain_optics_key(c.grid), c.grid.size(), rain_cosines(), c.cache_on_disk,
                             [&] { return compute_rain_optics(c.grid); });
  const SizeDistribution drops = SizeDistribution::marshall_palmer(rain.rate_mm_per_h);
  const double geometric_cross_section_per_m = kPi * drops.moment(2) * drops.number_per_m3();
  return particle_medium("rain", DensityProfile::exponential(rain.scale_height_m), unit, geometric_cross_section_per_m);
}
}  // namespace

VerticalCylinder shower_region(const AtmosphereSpec& spec) {
  const RainSpec& rain = spec.rain;
  const double az = rain.shower_azimuth_deg * kPi / 180.0;
  // The axis through the point shower_distance_m east-north of the reference point (0, 0, R).
  const Vec3 centre(rain.shower_distance_m * std::sin(az), rain.shower_distance_m * std::cos(az), spec.planet_radius_m);
  return VerticalCylinder{centre.normalized(), rain.shower_radius_m};
}

std::optional<Medium> build_rain(const MediumContext& c) {
  const RainSpec& rain = c.spec.rain;
  if (!rain.enabled) return std::nullopt;
  std::optional<Medium> m =
      rain.drops == RainSpec::Drops::Lognormal ? build_lognormal_rain(c) : build_marshall_palmer_rain(c);
  if (m && rain.extent == RainSpec::Extent::Shower) m->region = shower_region(c.spec);
  return m;
}

}  // namespace skyspec
