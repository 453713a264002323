#include "physics/sun_disk.hpp"

#include <cmath>

#include "skyspec/units.hpp"

namespace skyspec {

double sun_angular_radius_rad(double distance_au) {
  return std::asin(kSolarRadius_m / (distance_au * kAstronomicalUnit_m));
}

double limb_darkening_exponent(double lambda_nm) {
  const double lambda_um = lambda_nm * 1e-3;
  return 1.0 / lambda_um < 2.4 ? -0.023 + 0.292 / lambda_um : -0.507 + 0.441 / lambda_um;
}

double disk_centre_radiance_per_irradiance(double lambda_nm, double angular_radius_rad) {
  const double alpha = limb_darkening_exponent(lambda_nm);
  return (alpha + 2.0) / (2.0 * kPi * angular_radius_rad * angular_radius_rad);
}

void disk_radiance_per_irradiance(const WavelengthGrid& grid, double angular_radius_rad, double x, Spectrum& out) {
  out.resize(grid.size());
  if (!(x >= 0.0 && x <= 1.0)) {
    out.setZero();
    return;
  }
  const double mu = std::sqrt(1.0 - x * x);
  for (int i = 0; i < grid.size(); ++i) {
    const double alpha = limb_darkening_exponent(grid.nm(i));
    out[i] =
        static_cast<float>(disk_centre_radiance_per_irradiance(grid.nm(i), angular_radius_rad) * std::pow(mu, alpha));
  }
}

}  // namespace skyspec
