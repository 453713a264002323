// Small atmospheres with known closed-form answers, shared by the physics tests.
#pragma once

#include "skyspec/atmosphere.hpp"

namespace skyspec::test {

/// Typed-in Rayleigh coefficients on the grid (so a test controls beta exactly), Mie optional.
inline AtmosphereSpec simple_atmosphere(ProfileKind profile, double top_m, const std::vector<double>& nm,
                                        const std::vector<double>& beta_rayleigh, double beta_mie,
                                        double mie_ratio = 1.1) {
  AtmosphereSpec a;
  a.planet_radius_m = 6360e3;
  a.top_altitude_m = top_m;
  a.rayleigh.source = RayleighSpec::Source::Fixed;
  a.rayleigh.profile = profile;
  a.rayleigh.scale_height_m = 8000;
  a.rayleigh.fixed_wavelengths_nm = nm;
  a.rayleigh.fixed_beta_per_m = beta_rayleigh;
  a.mie.enabled = beta_mie > 0;
  a.mie.profile = profile;
  a.mie.scale_height_m = 1200;
  a.mie.scattering_per_m = beta_mie;
  a.mie.angstrom_exponent = 0;
  a.mie.extinction_to_scattering = mie_ratio;
  return a;
}

}  // namespace skyspec::test
