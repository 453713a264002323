// Air: Rayleigh scattering by its molecules, the coefficient derived per wavelength from the
// refractive index and the number density (rayleigh.hpp), or typed in (the seed tutorial's
// constants). Molecules do not absorb here (ozone is its own medium), except in a broadband
// irradiance's runs, where the uniformly mixed gases (oxygen, carbon dioxide, ...) absorb in their
// bands (gas_bands.hpp) with air's own profile.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "physics/gas_bands.hpp"
#include "physics/media/media.hpp"
#include "skyspec/error.hpp"
#include "skyspec/refractive_index.hpp"
#include "skyspec/standard_atmosphere.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

AirNumberDensity air_number_density(const RayleighSpec& r) {
  if (r.source != RayleighSpec::Source::Derived)
    return {0.0, "not used: coefficients typed in (atmosphere.rayleigh.source = \"fixed\")"};
  // The standard atmosphere's sea-level state, or the ideal gas law at the given surface pressure
  // and temperature.
  if (r.profile == ProfileKind::UsStandard1976)
    return {us_standard_atmosphere_1976(0.0).number_density_per_m3,
            "U.S. Standard Atmosphere 1976 at 0 m: N = P / (k T) = 101325 Pa / (k 288.15 K)"};
  std::ostringstream s;
  s << "ideal gas at the surface: N = P / (k T) = " << r.surface_pressure_Pa << " Pa / (k " << r.surface_temperature_K
    << " K)";
  return {r.surface_pressure_Pa / (constants::kBoltzmann_J_per_K * r.surface_temperature_K), s.str()};
}

double relative_surface_pressure(const RayleighSpec& r) {
  return r.profile == ProfileKind::UsStandard1976 ? 1.0 : r.surface_pressure_Pa / constants::kStandardPressure_Pa;
}

namespace {
// beta(lambda) typed in per wavelength: every grid wavelength must be listed.
SpectrumD fixed_coefficients(const RayleighSpec& r, const WavelengthGrid& grid) {
  if (r.fixed_wavelengths_nm.size() != r.fixed_beta_per_m.size())
    throw InputError("atmosphere.rayleigh.beta_per_m", std::to_string(r.fixed_beta_per_m.size()) + " values",
                     "one value per entry of atmosphere.rayleigh.wavelengths_nm (" +
                         std::to_string(r.fixed_wavelengths_nm.size()) + ")");
  SpectrumD beta(grid.size());
  for (int i = 0; i < grid.size(); ++i) {
    int found = -1;
    for (size_t k = 0; k < r.fixed_wavelengths_nm.size(); ++k)
      if (std::abs(r.fixed_wavelengths_nm[k] - grid.nm(i)) < 1e-6) found = static_cast<int>(k);
    if (found < 0) {
      std::ostringstream v;
      v << grid.nm(i) << " nm";
      throw InputError("spectrum", v.str(),
                       "only the wavelengths of atmosphere.rayleigh.wavelengths_nm when "
                       "atmosphere.rayleigh.source = \"fixed\" (coefficients are typed in, not derived)");
    }
    beta[i] = r.fixed_beta_per_m[static_cast<size_t>(found)];
  }
  return beta;
}

// Integral of rho from the ground to the top of the atmosphere, m (Simpson's rule on 4000 steps;
// the profiles are smooth).
double vertical_column_m(const DensityProfile& profile, double top_m) {
  const int n = 4000;  // even
  const double h = top_m / n;
  double sum = profile.relative(0.0) + profile.relative(top_m);
  for (int k = 1; k < n; ++k) sum += (k % 2 ? 4.0 : 2.0) * profile.relative(k * h);
  return sum * h / 3.0;
}

// Rayleigh steps at the grid's wavelengths; in a broadband run, wavelengths beyond the refractive
// index's range take its end's cross-section and King factor, the cross-section scaled by lambda^-4
// (what that costs: docs/physics.md, "Gas bands").
std::vector<RayleighDerivationStep> rayleigh_steps(const RayleighSpec& r, const WavelengthGrid& grid, bool broadband) {
  std::vector<double> nm = grid.nanometres();
  const double max_nm = validity(r.derivation.formula).max_nm;
  if (broadband)
    for (double& x : nm) x = std::min(x, max_nm);
  std::vector<RayleighDerivationStep> steps = derive_rayleigh(nm, r.derivation);
  for (size_t i = 0; i < nm.size(); ++i)
    if (grid.nanometres()[i] > nm[i]) steps[i].cross_section_m2 *= std::pow(nm[i] / grid.nanometres()[i], 4.0);
  return steps;
}
}  // namespace

std::optional<Medium> build_air(const MediumContext& c) {
  const RayleighSpec& r = c.spec.rayleigh;
  const int n = c.grid.size();
  Medium air;
  air.name = "air";
  air.profile = make_profile(r.profile, r.scale_height_m, c.spec.top_altitude_m);
  air.phase.kind = MediumPhase::Kind::Rayleigh;
  air.phase.rayleigh_gamma = SpectrumD::Zero(n);  // typed-in coefficients carry no depolarisation
  if (r.source == RayleighSpec::Source::Derived) {
    // beta = sigma(lambda) N(0); the King factor's depolarisation is also in the phase function.
    const double n0 = air_number_density(r).per_m3;
    const std::vector<RayleighDerivationStep> steps = rayleigh_steps(r, c.grid, c.spec.gas_band_term >= 0);
    air.scattering_per_m.resize(n);
    for (int i = 0; i < n; ++i) {
      const RayleighDerivationStep& step = steps[static_cast<size_t>(i)];
      air.scattering_per_m[i] = step.cross_section_m2 * n0;
      air.phase.rayleigh_gamma[i] =
          rayleigh_gamma_from_depolarisation(depolarisation_ratio_from_king_factor(step.king_factor));
    }
  } else {
    air.scattering_per_m = fixed_coefficients(r, c.grid);
  }
  air.extinction_per_m = air.scattering_per_m;
  if (c.spec.gas_band_term >= 0) {
    // The mixed gases' absorber amount along a path is its air column in units of the vertical
    // column at 101325 Pa: beta_abs(z) = a' (P_surface / 101325 Pa) rho(z) / integral rho dz.
    const double relative_pressure = relative_surface_pressure(r);
    const double per_air_mass = relative_pressure / vertical_column_m(air.profile, c.spec.top_altitude_m);
    for (int i = 0; i < n; ++i)
      air.extinction_per_m[i] +=
          gas_term_coefficients(c.spec.gas_band_term, c.grid.nm(i), c.spec.water_vapour.column_cm, relative_pressure)
              .mixed_gases_per_air_mass *
          per_air_mass;
  }
  return air;
}

}  // namespace skyspec
