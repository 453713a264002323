#include "skyspec/phase_function.hpp"

#include <cmath>
#include <sstream>

#include "skyspec/error.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

double rayleigh_phase(double mu) { return 3.0 / (16.0 * kPi) * (1.0 + mu * mu); }

double henyey_greenstein_phase(double mu, double g) {
  const double denom = 1.0 + g * g - 2.0 * g * mu;
  return (1.0 - g * g) / (4.0 * kPi * denom * std::sqrt(denom));
}

double cornette_shanks_phase(double mu, double g) {
  const double denom = 1.0 + g * g - 2.0 * g * mu;
  return 3.0 / (8.0 * kPi) * (1.0 - g * g) * (1.0 + mu * mu) /
         ((2.0 + g * g) * denom * std::sqrt(denom));
}

double AerosolPhase::operator()(double mu) const {
  return model == Model::HenyeyGreenstein ? henyey_greenstein_phase(mu, g)
                                          : cornette_shanks_phase(mu, g);
}

std::string to_string(AerosolPhase::Model m) {
  return m == AerosolPhase::Model::HenyeyGreenstein ? "henyey-greenstein" : "cornette-shanks";
}

std::string AerosolPhase::describe() const {
  std::ostringstream s;
  s << to_string(model) << ", g = " << g;
  return s.str();
}

AerosolPhase::Model parse_aerosol_phase_model(const std::string& name, const std::string& setting) {
  if (name == "henyey-greenstein") return AerosolPhase::Model::HenyeyGreenstein;
  if (name == "cornette-shanks") return AerosolPhase::Model::CornetteShanks;
  throw InputError(setting, "\"" + name + "\"", "one of: henyey-greenstein, cornette-shanks");
}

}  // namespace skyspec
