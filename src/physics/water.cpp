#include "skyspec/water.hpp"

#include <cmath>

#include "base/text_format.hpp"
#include "skyspec/error.hpp"

namespace skyspec {

double water_refractive_index(double temperature_K, double density_kg_per_m3, double wavelength_nm) {
  if (!(temperature_K >= 261.15 && temperature_K <= 773.15))
    throw InputError("water.temperature_K", format_number(temperature_K), "261.15-773.15 K (IAPWS R9-97's range)");
  if (!(density_kg_per_m3 >= 0.0 && density_kg_per_m3 <= 1060.0))
    throw InputError("water.density_kg_per_m3", format_number(density_kg_per_m3),
                     "0-1060 kg/m^3 (IAPWS R9-97's range)");
  if (!(wavelength_nm >= 200.0 && wavelength_nm <= 1100.0))
    throw InputError("wavelength_nm", format_number(wavelength_nm), "200-1100 nm (IAPWS R9-97's range for water)");
  constexpr double a0 = 0.244257733, a1 = 9.74634476e-3, a2 = -3.73234996e-3, a3 = 2.68678472e-4, a4 = 1.58920570e-3,
                   a5 = 2.45934259e-3, a6 = 0.900704920, a7 = -1.66626219e-2;
  constexpr double lambda_uv = 0.2292020, lambda_ir = 5.432937;
  const double t = temperature_K / 273.15, rho = density_kg_per_m3 / 1000.0, l2 = std::pow(wavelength_nm / 589.0, 2);
  const double a = rho * (a0 + a1 * rho + a2 * t + a3 * l2 * t + a4 / l2 + a5 / (l2 - lambda_uv * lambda_uv) +
                          a6 / (l2 - lambda_ir * lambda_ir) + a7 * rho * rho);
  // a = (n^2 - 1) / (n^2 + 2)  =>  n^2 = (1 + 2a) / (1 - a)
  return std::sqrt((1.0 + 2.0 * a) / (1.0 - a));
}

double liquid_water_density_kg_per_m3(double temperature_K) {
  if (!(temperature_K >= 273.15 && temperature_K <= 423.15))
    throw InputError("water.temperature_K", format_number(temperature_K),
                     "273.15-423.15 K (Kell 1975's range for liquid water)");
  const double t = temperature_K - 273.15;
  return (999.83952 +
          t * (16.945176 + t * (-7.9870401e-3 + t * (-46.170461e-6 + t * (105.56302e-9 - t * 280.54253e-12))))) /
         (1.0 + 16.879850e-3 * t);
}

}  // namespace skyspec
