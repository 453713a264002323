#include "physics/media/media.hpp"

namespace skyspec {

const std::vector<MediumEntry>& medium_registry() {
  static const std::vector<MediumEntry> media = {
      {"air", build_air},
      {"aerosol", build_aerosol},
      {"ozone", build_ozone},
      {"fog", build_fog},
  };
  return media;
}

}  // namespace skyspec
