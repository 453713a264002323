// Small atmospheres with known closed-form answers, shared by the physics tests.
#pragma once

#include <array>
#include <utility>
#include <vector>

#include "skyspec/atmosphere.hpp"
#include "transport/optical_depth.hpp"
#include "transport/single_scattering.hpp"

namespace skyspec::test {

/// The outputs of InScatteringSource::source for an atmosphere of air and aerosol: {air's, aerosol's}
/// (the array is a temporary: pass .data() within one expression, as pair_of does).
struct SourcePair {
  std::array<float*, 2> out;
  operator float* const*() const { return out.data(); }
};
inline SourcePair pair_of(float* air, float* aerosol) { return SourcePair{{air, aerosol}}; }

/// The seed tutorial's three wavelengths and its typed-in Rayleigh coefficients at them.
inline const std::vector<double> kSeedNm = {440, 550, 680};
inline const std::vector<double> kSeedBetaRayleigh = {33.1e-6, 13.5e-6, 5.8e-6};

/// Typed-in Rayleigh coefficients on the grid (so a test controls beta exactly), Mie optional.
inline AtmosphereSpec simple_atmosphere(ProfileKind profile, double top_m, const std::vector<double>& nm,
                                        const std::vector<double>& beta_rayleigh, double beta_mie,
                                        double mie_ratio = 1.1) {
  AtmosphereSpec a;
  a.planet_radius_m = 6360e3;
  a.top_altitude_m = top_m;
  a.rayleigh.source = RayleighSpec::Source::Fixed;
  a.rayleigh.profile = profile;
  a.rayleigh.scale_height_m = 8000;
  a.rayleigh.fixed_wavelengths_nm = nm;
  a.rayleigh.fixed_beta_per_m = beta_rayleigh;
  a.mie.enabled = beta_mie > 0;
  a.mie.profile = profile;
  a.mie.scale_height_m = 1200;
  a.mie.scattering_per_m = beta_mie;
  a.mie.angstrom_exponent = 0;
  a.mie.extinction_to_scattering = mie_ratio;
  a.ozone.enabled = false;
  return a;
}

/// The whole chain a radiance needs: the atmosphere on a wavelength list, its sun-column table and
/// an integrator over them (members in that order, each referring to the ones before).
struct IntegratorChain {
  IntegratorChain(const AtmosphereSpec& spec, const std::vector<double>& nm, SunColumnTable::Resolution resolution,
                  int view_segments)
      : atm(spec, WavelengthGrid::from_list(nm)),
        table(atm, resolution),
        columns(table),
        integrator(atm, columns, {view_segments}) {}
  /// The same over an atmosphere built by the caller (e.g. with media of its own).
  IntegratorChain(AtmosphereModel model, SunColumnTable::Resolution resolution, int view_segments)
      : atm(std::move(model)), table(atm, resolution), columns(table), integrator(atm, columns, {view_segments}) {}
  AtmosphereModel atm;
  SunColumnTable table;
  TableSunColumns columns;
  SingleScattering integrator;
};

}  // namespace skyspec::test
