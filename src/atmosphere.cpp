#include "skyspec/atmosphere.hpp"

#include <cmath>
#include <sstream>

#include "skyspec/error.hpp"
#include "skyspec/standard_atmosphere.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

std::string to_string(ProfileKind k) {
  switch (k) {
    case ProfileKind::Exponential: return "exponential";
    case ProfileKind::UsStandard1976: return "us1976";
    case ProfileKind::Constant: return "constant";
  }
  return "?";
}

DensityProfile make_profile(ProfileKind kind, double scale_height_m, double top_altitude_m) {
  switch (kind) {
    case ProfileKind::Exponential: return DensityProfile::exponential(scale_height_m);
    case ProfileKind::UsStandard1976: return DensityProfile::us_standard_1976(top_altitude_m);
    case ProfileKind::Constant: return DensityProfile::constant();
  }
  return DensityProfile::constant();
}

AtmosphereModel::AtmosphereModel(const AtmosphereSpec& spec, const WavelengthGrid& grid)
    : spec_(spec), grid_(grid) {
  const int n = grid.size();
  const auto& r = spec.rayleigh;

  // --- Rayleigh ---------------------------------------------------------------------------
  rayleigh_.profile = make_profile(r.profile, r.scale_height_m, spec.top_altitude_m);
  rayleigh_.scattering_per_m.resize(n);
  if (r.source == RayleighSpec::Source::Derived) {
    // N(0): the standard atmosphere's sea-level state, or the ideal gas law at the given surface
    // pressure and temperature.
    if (r.profile == ProfileKind::UsStandard1976) {
      rayleigh_n0_per_m3_ = us_standard_atmosphere_1976(0.0).number_density_per_m3;
      rayleigh_n0_origin_ = "U.S. Standard Atmosphere 1976 at 0 m: N = P / (k T) = 101325 Pa / (k 288.15 K)";
    } else {
      rayleigh_n0_per_m3_ =
          r.surface_pressure_Pa / (constants::kBoltzmann_J_per_K * r.surface_temperature_K);
      std::ostringstream s;
      s << "ideal gas at the surface: N = P / (k T) = " << r.surface_pressure_Pa << " Pa / (k "
        << r.surface_temperature_K << " K)";
      rayleigh_n0_origin_ = s.str();
    }
    derivation_ = derive_rayleigh(grid.nanometres(), r.derivation);
    for (int i = 0; i < n; ++i)
      rayleigh_.scattering_per_m[i] = derivation_[static_cast<size_t>(i)].cross_section_m2 * rayleigh_n0_per_m3_;
  } else {
    if (r.fixed_wavelengths_nm.size() != r.fixed_beta_per_m.size())
      throw InputError("atmosphere.rayleigh.beta_per_m",
                       std::to_string(r.fixed_beta_per_m.size()) + " values",
                       "one value per entry of atmosphere.rayleigh.wavelengths_nm (" +
                           std::to_string(r.fixed_wavelengths_nm.size()) + ")");
    rayleigh_n0_origin_ = "not used: coefficients typed in (atmosphere.rayleigh.source = \"fixed\")";
    for (int i = 0; i < n; ++i) {
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
      rayleigh_.scattering_per_m[i] = r.fixed_beta_per_m[static_cast<size_t>(found)];
    }
  }
  rayleigh_.extinction_per_m = rayleigh_.scattering_per_m;  // molecules do not absorb here

  // --- Mie aerosols: Angstrom law ---------------------------------------------------------
  const auto& m = spec.mie;
  mie_.profile = make_profile(m.profile, m.scale_height_m, spec.top_altitude_m);
  mie_.scattering_per_m.resize(n);
  for (int i = 0; i < n; ++i)
    mie_.scattering_per_m[i] =
        m.enabled ? m.scattering_per_m * std::pow(grid.nm(i) / m.reference_wavelength_nm, -m.angstrom_exponent)
                  : 0.0;
  mie_.extinction_per_m = mie_.scattering_per_m * m.extinction_to_scattering;
}

}  // namespace skyspec
