// Rain: water drops of Marshall & Palmer's sizes (1948, J. Meteorol. 5, 165; size_distribution.hpp)
// for a rain rate, falling through the air near the ground. Their scattering per wavelength is the
// geometric optics of a sphere of water (drop_optics.hpp: the Descartes-Fresnel model of the
// primary and secondary rainbows) with water's index at 10 degC (IAPWS R9-97, water.hpp); it does
// not depend on the drops' sizes, which set only the amount: the drops' geometric cross-section
// pi <r^2> N per m^3 is the medium's extinction at the ground. Diffraction, the other half of a
// drop's extinction, stays within a few thousandths of a degree of forward for drops this large
// and is taken as unscattered light. Absorption is neglected (less than 1e-4 over a 2 mm path in
// the visible). Polarised: the matrix's P12 and P33 from the rays' s and p amplitudes (P34 = 0).
#include <cmath>
#include <sstream>

#include <tbb/parallel_for.h>

#include "base/preparation_progress.hpp"
#include "physics/media/media.hpp"
#include "physics/particle_optics_cache.hpp"
#include "skyspec/drop_optics.hpp"
#include "skyspec/size_distribution.hpp"
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
}  // namespace

std::optional<Medium> build_rain(const MediumContext& c) {
  const RainSpec& rain = c.spec.rain;
  if (!rain.enabled) return std::nullopt;
  const AerosolMixtureOptics unit =
      cached_particle_optics(rain_optics_key(c.grid), c.grid.size(), rain_cosines(), c.cache_on_disk,
                             [&] { return compute_rain_optics(c.grid); });
  const SizeDistribution drops = SizeDistribution::marshall_palmer(rain.rate_mm_per_h);
  const double geometric_cross_section_per_m = kPi * drops.moment(2) * drops.number_per_m3();
  return particle_medium("rain", DensityProfile::exponential(rain.scale_height_m), unit, geometric_cross_section_per_m);
}

}  // namespace skyspec
