// Air: Rayleigh scattering by its molecules, the coefficient derived per wavelength from the
// refractive index and the number density (rayleigh.hpp), or typed in (the seed tutorial's
// constants). Molecules do not absorb in the visible here (ozone is its own medium).
#include <cmath>
#include <sstream>

#include "physics/media/media.hpp"
#include "skyspec/error.hpp"
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
    const std::vector<RayleighDerivationStep> steps = derive_rayleigh(c.grid.nanometres(), r.derivation);
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
  return air;
}

}  // namespace skyspec
