// The aerosol: the Angstrom law (or published spectral tables) with an analytic phase function,
// or OPAC's components by Lorenz-Mie theory with their whole scattering matrix
// (aerosol_components.hpp).
#include <cmath>
#include <string>

#include "physics/media/media.hpp"
#include "skyspec/aerosol_components.hpp"
#include "skyspec/error.hpp"

namespace skyspec {

std::optional<Medium> build_aerosol(const MediumContext& c) {
  const MieSpec& m = c.spec.mie;
  if (!m.enabled) return std::nullopt;
  const WavelengthGrid& grid = c.grid;
  const int n = grid.size();
  Medium a;
  a.name = "aerosol";
  a.profile = make_profile(m.profile, m.scale_height_m, c.spec.top_altitude_m);
  if (m.model == MieSpec::Model::Opac) {
    // Microphysics: Lorenz-Mie over each component's size distribution.
    AerosolMixtureOptics optics = aerosol_mixture_optics(m.opac, grid, "atmosphere.mie.opac", c.cache_on_disk);
    a.scattering_per_m = optics.scattering_per_m;
    a.extinction_per_m = optics.extinction_per_m;
    a.phase.kind = MediumPhase::Kind::Tabulated;
    a.phase.matrix = optics.matrix;
    a.phase.g.resize(n);
    for (int i = 0; i < n; ++i) a.phase.g[i] = optics.matrix->asymmetry(i);
    return a;
  }
  // The Angstrom law: beta(lambda) = beta_ref (lambda / lambda_ref)^-alpha, extinction a fixed ratio.
  a.phase.kind = MediumPhase::Kind::Analytic;
  a.phase.analytic_model = m.phase.model;
  a.phase.g = SpectrumD::Constant(n, m.phase.g);
  a.scattering_per_m.resize(n);
  for (int i = 0; i < n; ++i)
    a.scattering_per_m[i] = m.scattering_per_m * std::pow(grid.nm(i) / m.reference_wavelength_nm, -m.angstrom_exponent);
  a.extinction_per_m = a.scattering_per_m * m.extinction_to_scattering;
  if (!m.table_wavelengths_nm.empty()) {
    // Spectral tables (MieSpec): scattering scaled by Q w, extinction = scattering / w, g(lambda).
    const auto& x = m.table_wavelengths_nm;
    auto q_w = [&](double l) {
      return interpolate_linear(x, m.table_extinction_efficiency, l) *
             interpolate_linear(x, m.table_single_scattering_albedo, l);
    };
    const double anchor = q_w(m.reference_wavelength_nm);
    if (!(anchor > 0.0))
      throw InputError("atmosphere.mie.reference_wavelength_nm", std::to_string(m.reference_wavelength_nm),
                       "a wavelength where the aerosol tables' extinction efficiency x single-scattering albedo > 0");
    for (int i = 0; i < n; ++i) {
      const double w = interpolate_linear(x, m.table_single_scattering_albedo, grid.nm(i));
      a.scattering_per_m[i] = m.scattering_per_m * q_w(grid.nm(i)) / anchor;
      a.extinction_per_m[i] = a.scattering_per_m[i] / w;
      a.phase.g[i] = interpolate_linear(x, m.table_g, grid.nm(i));
    }
  }
  return a;
}

}  // namespace skyspec
