// Water vapour: absorption only, in its near-infrared bands, in a broadband irradiance's runs
// (gas_bands.hpp): the scene's precipitable water in an exponential profile above the ground.
// Elsewhere skyspec does not model it (spectral files name the bands: unmodelled_absorption.hpp).
#include <cmath>

#include "base/text_format.hpp"
#include "physics/gas_bands.hpp"
#include "physics/media/media.hpp"
#include "skyspec/error.hpp"

namespace skyspec {

std::optional<Medium> build_water_vapour(const MediumContext& c) {
  const WaterVapourSpec& w = c.spec.water_vapour;
  if (!(w.column_cm >= 0.0 && w.column_cm <= 15.0))
    throw InputError(
        "atmosphere.water_vapour.column_cm", format_number(w.column_cm),
        "a precipitable water column from 0 to 15 cm (observed: about 0.1 in polar air to 7 in the tropics)");
  if (!(w.scale_height_m >= 100.0 && w.scale_height_m <= 10e3))
    throw InputError("atmosphere.water_vapour.scale_height_m", format_number(w.scale_height_m),
                     "a scale height from 100 to 10000 m (observed: about 2000 m)");
  if (c.spec.gas_band_term < 0 || w.column_cm == 0.0) return std::nullopt;
  Medium vapour;
  vapour.name = "water_vapour";
  vapour.profile = DensityProfile::exponential(w.scale_height_m);
  vapour.scattering_per_m = SpectrumD::Zero(c.grid.size());
  vapour.extinction_per_m = SpectrumD::Zero(c.grid.size());
  // Precipitable centimetres per metre at the ground: the column W over the profile's integral,
  // H (1 - exp(-top / H)).
  const double column_m = w.scale_height_m * -std::expm1(-c.spec.top_altitude_m / w.scale_height_m);
  const double cm_per_m = w.column_cm / column_m;
  const double relative_pressure = relative_surface_pressure(c.spec.rayleigh);
  for (int i = 0; i < c.grid.size(); ++i)
    vapour.extinction_per_m[i] =
        gas_term_coefficients(c.spec.gas_band_term, c.grid.nm(i), w.column_cm, relative_pressure).water_vapour_per_cm *
        cm_per_m;
  return vapour;
}

}  // namespace skyspec
