// Phase functions p(mu), normalised so that the integral over the sphere is 1 (units sr^-1).
// mu is the cosine of the angle between the direction the light travels after scattering
// towards the viewer, reversed (the view direction), and the direction towards the sun: mu = 1
// looks straight at the sun (forward scattering for g > 0).
#pragma once

#include <cmath>
#include <string>

#include "skyspec/units.hpp"

namespace skyspec {

// Inline, so that loops over many directions (SingleScattering::combine_many) vectorise.

/// Rayleigh: 3 / (16 pi) (1 + mu^2).
inline double rayleigh_phase(double mu) { return 3.0 / (16.0 * kPi) * (1.0 + mu * mu); }
/// Henyey & Greenstein 1941: (1 - g^2) / (4 pi (1 + g^2 - 2 g mu)^(3/2)).
inline double henyey_greenstein_phase(double mu, double g) {
  const double denom = 1.0 + g * g - 2.0 * g * mu;
  return (1.0 - g * g) / (4.0 * kPi * denom * std::sqrt(denom));
}
/// Cornette & Shanks 1992 (the seed tutorial's "Mie"):
/// 3 / (8 pi) (1 - g^2)(1 + mu^2) / ((2 + g^2)(1 + g^2 - 2 g mu)^(3/2)).
inline double cornette_shanks_phase(double mu, double g) {
  const double denom = 1.0 + g * g - 2.0 * g * mu;
  return 3.0 / (8.0 * kPi) * (1.0 - g * g) * (1.0 + mu * mu) / ((2.0 + g * g) * denom * std::sqrt(denom));
}

/// A selectable aerosol phase function.
struct AerosolPhase {
  enum class Model { HenyeyGreenstein, CornetteShanks };
  Model model = Model::CornetteShanks;
  double g = 0.76;  ///< asymmetry parameter, -1 < g < 1
  double operator()(double mu) const;
  std::string describe() const;
};

/// "henyey-greenstein" / "cornette-shanks"; throws InputError(setting) listing both.
AerosolPhase::Model parse_aerosol_phase_model(const std::string& name, const std::string& setting);
std::string to_string(AerosolPhase::Model m);

}  // namespace skyspec
