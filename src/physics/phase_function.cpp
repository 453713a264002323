#include "skyspec/phase_function.hpp"

#include <cmath>
#include <sstream>

#include "skyspec/error.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

double AerosolPhase::operator()(double mu) const {
  return model == Model::HenyeyGreenstein ? henyey_greenstein_phase(mu, g) : cornette_shanks_phase(mu, g);
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
