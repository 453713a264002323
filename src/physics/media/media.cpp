#include "physics/media/media.hpp"

#include <utility>

namespace skyspec {

const std::vector<MediumEntry>& medium_registry() {
  // One medium per line.
  // clang-format off
  static const std::vector<MediumEntry> media = {
      {"air", build_air},
      {"aerosol", build_aerosol},
      {"ozone", build_ozone},
      {"fog", build_fog},
      {"ice", build_ice},
      {"rain", build_rain},
      {"water_vapour", build_water_vapour},
  };
  // clang-format on
  return media;
}

Medium particle_medium(const char* name, DensityProfile profile, const AerosolMixtureOptics& per_particle,
                       double amount) {
  Medium m;
  m.name = name;
  m.profile = std::move(profile);
  m.scattering_per_m = per_particle.scattering_per_m * amount;
  m.extinction_per_m = per_particle.extinction_per_m * amount;
  m.phase.kind = MediumPhase::Kind::Tabulated;
  m.phase.matrix = per_particle.matrix;
  return m;
}

}  // namespace skyspec
