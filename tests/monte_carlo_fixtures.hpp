// Media for the Monte Carlo tests: a homogeneous Rayleigh slab 1 m thick, so that a coefficient in
// m^-1 is the optical thickness.
#pragma once

#include <vector>

#include "atmosphere_fixtures.hpp"
#include "transport/monte_carlo.hpp"

namespace skyspec::test {

inline MonteCarloMedium rayleigh_slab(double tau, double single_scattering_albedo, double ground_albedo,
                                      double sun_irradiance, double rayleigh_gamma = 0.0) {
  MonteCarloMedium m;
  m.geometry = MonteCarloMedium::Geometry::PlaneParallel;
  m.top_altitude_m = 1.0;
  MonteCarloComponent c;
  c.profile = DensityProfile::constant();
  c.extinction_per_m = tau;
  c.scattering_per_m = tau * single_scattering_albedo;
  c.phase = MonteCarloComponent::Phase::Rayleigh;
  c.phase_parameter = rayleigh_gamma;
  m.components.push_back(c);
  m.ground_albedo = ground_albedo;
  m.sun_irradiance = sun_irradiance;
  return m;
}

/// The wavelengths and the deterministic side of the order-1 comparisons with the Monte Carlo:
/// the default atmosphere over a ground of albedo 0.3, a fine sun-column table, 128 view segments.
inline const std::vector<double> kOrderOneNm = {400, 550, 700};
inline IntegratorChain default_air_over_ground() {
  AtmosphereSpec spec;
  spec.ground.albedo = 0.3;
  return IntegratorChain(spec, kOrderOneNm, {256, 512, 64}, 128);  // guaranteed copy elision
}

}  // namespace skyspec::test
