#include "render/sun_irradiance.hpp"

#include "physics/solar_spectrum.hpp"

namespace skyspec {

Spectrum scene_sun_irradiance(const Scene& s, const WavelengthGrid& grid) {
  if (s.sun.spectrum == SunSpec::Spectrum::Flat)
    return Spectrum::Constant(grid.size(), static_cast<float>(s.sun.spectral_irradiance_W_m2_nm));
  const double scale = 1.0 / (s.sun.distance_au * s.sun.distance_au);  // inverse-square law
  return (solar_irradiance_on_grid(grid, "spectrum") * scale).cast<float>();
}

}  // namespace skyspec
