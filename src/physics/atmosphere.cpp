#include "skyspec/atmosphere.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "physics/ozone.hpp"
#include "skyspec/error.hpp"
#include "skyspec/phase_function.hpp"
#include "skyspec/standard_atmosphere.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

namespace {
// Ozone absorption cross-sections on the grid: the scene's own table if it has one, else the
// built-in laboratory data (233 K, 230-1060 nm: Serdyuchenko et al. 2014 and Bogumil et al. 2003;
// data/ozone/), averaged
// over each grid sample's bin.
SpectrumD ozone_cross_sections_m2(const OzoneSpec& o, const WavelengthGrid& grid) {
  SpectrumD sigma(grid.size());
  if (!o.cross_section_m2.empty()) {
    for (int i = 0; i < grid.size(); ++i)
      sigma[i] = interpolate_linear(o.cross_section_wavelengths_nm, o.cross_section_m2, grid.nm(i));
    return sigma;
  }
  return ozone_cross_section_on_grid(grid, "spectrum");
}
}  // namespace

std::string to_string(ProfileKind k) {
  switch (k) {
    case ProfileKind::Exponential:
      return "exponential";
    case ProfileKind::UsStandard1976:
      return "us1976";
    case ProfileKind::Constant:
      return "constant";
  }
  return "?";
}

DensityProfile make_profile(ProfileKind kind, double scale_height_m, double top_altitude_m) {
  switch (kind) {
    case ProfileKind::Exponential:
      return DensityProfile::exponential(scale_height_m);
    case ProfileKind::UsStandard1976:
      return DensityProfile::us_standard_1976(top_altitude_m);
    case ProfileKind::Constant:
      return DensityProfile::constant();
  }
  return DensityProfile::constant();
}

AtmosphereModel::AtmosphereModel(const AtmosphereSpec& spec, const WavelengthGrid& grid, bool cache_on_disk)
    : spec_(spec), grid_(grid) {
  const int n = grid.size();
  const auto& r = spec.rayleigh;

  // --- Rayleigh ---------------------------------------------------------------------------
  rayleigh_.profile = make_profile(r.profile, r.scale_height_m, spec.top_altitude_m);
  rayleigh_.scattering_per_m.resize(n);
  rayleigh_gamma_ = SpectrumD::Zero(n);  // typed-in coefficients carry no depolarisation
  if (r.source == RayleighSpec::Source::Derived) {
    // N(0): the standard atmosphere's sea-level state, or the ideal gas law at the given surface
    // pressure and temperature.
    if (r.profile == ProfileKind::UsStandard1976) {
      rayleigh_n0_per_m3_ = us_standard_atmosphere_1976(0.0).number_density_per_m3;
      rayleigh_n0_origin_ = "U.S. Standard Atmosphere 1976 at 0 m: N = P / (k T) = 101325 Pa / (k 288.15 K)";
    } else {
      rayleigh_n0_per_m3_ = r.surface_pressure_Pa / (constants::kBoltzmann_J_per_K * r.surface_temperature_K);
      std::ostringstream s;
      s << "ideal gas at the surface: N = P / (k T) = " << r.surface_pressure_Pa << " Pa / (k "
        << r.surface_temperature_K << " K)";
      rayleigh_n0_origin_ = s.str();
    }
    derivation_ = derive_rayleigh(grid.nanometres(), r.derivation);
    for (int i = 0; i < n; ++i) {
      const RayleighDerivationStep& step = derivation_[static_cast<size_t>(i)];
      rayleigh_.scattering_per_m[i] = step.cross_section_m2 * rayleigh_n0_per_m3_;
      rayleigh_gamma_[i] = rayleigh_gamma_from_depolarisation(depolarisation_ratio_from_king_factor(step.king_factor));
    }
  } else {
    if (r.fixed_wavelengths_nm.size() != r.fixed_beta_per_m.size())
      throw InputError("atmosphere.rayleigh.beta_per_m", std::to_string(r.fixed_beta_per_m.size()) + " values",
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
        m.enabled ? m.scattering_per_m * std::pow(grid.nm(i) / m.reference_wavelength_nm, -m.angstrom_exponent) : 0.0;
  mie_.extinction_per_m = mie_.scattering_per_m * m.extinction_to_scattering;
  mie_g_ = SpectrumD::Constant(n, m.phase.g);
  if (m.enabled && !m.table_wavelengths_nm.empty()) {
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
      mie_.scattering_per_m[i] = m.scattering_per_m * q_w(grid.nm(i)) / anchor;
      mie_.extinction_per_m[i] = mie_.scattering_per_m[i] / w;
      mie_g_[i] = interpolate_linear(x, m.table_g, grid.nm(i));
    }
  }

  if (m.enabled && m.model == MieSpec::Model::Opac) {
    // Microphysics: Lorenz-Mie over each component's size distribution (aerosol_components.hpp).
    AerosolMixtureOptics optics =
        aerosol_mixture_optics(m.opac, grid, "atmosphere.mie.opac", cache_on_disk);  // its keys' prefix
    mie_.scattering_per_m = optics.scattering_per_m;
    mie_.extinction_per_m = optics.extinction_per_m;
    mie_matrix_ = optics.matrix;
    for (int i = 0; i < n; ++i) mie_g_[i] = mie_matrix_->asymmetry(i);
  }

  // --- Ozone: absorption cross-section x number density at the layer's peak -----------------
  const auto& o = spec.ozone;
  ozone_.profile = DensityProfile::tent(o.bottom_m, o.peak_m, o.top_m);
  ozone_.scattering_per_m = SpectrumD::Zero(n);
  ozone_.extinction_per_m = SpectrumD::Zero(n);
  if (o.enabled && o.column_DU > 0.0) {
    // Column = N_peak * (area under the tent) = N_peak (top - bottom) / 2.
    ozone_peak_per_m3_ = o.column_DU * constants::kDobsonUnit_per_m2 / ozone_.profile.tent_area_m();
    const SpectrumD sigma = ozone_cross_sections_m2(o, grid);
    ozone_.extinction_per_m = sigma * ozone_peak_per_m3_;
  }

  // --- Ground -----------------------------------------------------------------------------
  ground_albedo_.resize(n);
  const auto& g = spec.ground;
  for (int i = 0; i < n; ++i)
    ground_albedo_[i] =
        g.albedo_values.empty() ? g.albedo : interpolate_linear(g.albedo_wavelengths_nm, g.albedo_values, grid.nm(i));
}

double AtmosphereModel::mie_phase_at(int i, double mu) const {
  if (mie_matrix_) return mie_matrix_->phase(i, mu);
  AerosolPhase p = spec_.mie.phase;
  p.g = mie_g_[i];
  return p(mu);
}

double interpolate_linear(const std::vector<double>& x, const std::vector<double>& y, double x0) {
  if (x.empty()) return 0.0;
  if (x0 <= x.front()) return y.front();
  if (x0 >= x.back()) return y.back();
  const auto it = std::upper_bound(x.begin(), x.end(), x0);
  const size_t i = static_cast<size_t>(it - x.begin());
  const double f = (x0 - x[i - 1]) / (x[i] - x[i - 1]);
  return y[i - 1] + f * (y[i] - y[i - 1]);
}

}  // namespace skyspec
