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

/// Rayleigh without depolarisation: 3 / (16 pi) (1 + mu^2).
inline double rayleigh_phase(double mu) { return 3.0 / (16.0 * kPi) * (1.0 + mu * mu); }

/// Rayleigh scattering by anisotropic molecules (Chandrasekhar 1950, Radiative Transfer, ch. I
/// section 18; written for air by Bucholtz 1995, Appl. Opt. 34(15), eq. 12):
///   p(mu) = 3 / (16 pi (1 + 2 gamma)) ((1 + 3 gamma) + (1 - gamma) mu^2),  gamma = rho / (2 - rho),
/// with rho the depolarisation ratio; gamma = 0 gives rayleigh_phase(mu). Its integral over the
/// sphere is 1 for every gamma.
inline double rayleigh_phase(double mu, double gamma) {
  return 3.0 / (16.0 * kPi * (1.0 + 2.0 * gamma)) * ((1.0 + 3.0 * gamma) + (1.0 - gamma) * mu * mu);
}
/// The depolarisation ratio rho that a King factor F = (6 + 3 rho) / (6 - 7 rho) stands for:
/// rho = 6 (F - 1) / (3 + 7 F) (Bucholtz 1995, eq. 13 inverted).
inline double depolarisation_ratio_from_king_factor(double king_factor) {
  return 6.0 * (king_factor - 1.0) / (3.0 + 7.0 * king_factor);
}
/// gamma = rho / (2 - rho), the phase function's anisotropy term (Bucholtz 1995, after eq. 12).
inline double rayleigh_gamma_from_depolarisation(double depolarisation_ratio) {
  return depolarisation_ratio / (2.0 - depolarisation_ratio);
}
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
