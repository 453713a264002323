// Fog: droplets of liquid water near the ground. Their optics come from Lorenz-Mie theory over
// OPAC's fog size distribution (Hess, Koepke & Schult 1998, BAMS 79, 831; the distribution's
// parameters as OPAC's own output file "fogr00" states them): a modified gamma distribution
// dN/dr = A r^4 exp(-0.0562 r^1.77) (r in um) over 0.02-50 um, mode radius 8.06 um, with water's
// refractive index at 10 degC (IAPWS R9-97, water.hpp) and OPAC's absorption at 550 nm. The
// amount follows from the visibility (meteorological optical range): N = ln 20 / (V C_ext(550 nm)).
// Or droplets of about one size (FogSpec::Droplets::Lognormal: a median radius and a geometric
// standard deviation, cut at 3 of them either side), a cloud's, whose corona shows coloured rings.
// The result is the whole scattering matrix per wavelength, so the fog's corona, fogbow and glory
// (and their polarisation) are in every render that has fog.
#include <cmath>
#include <sstream>

#include "base/preparation_progress.hpp"
#include "physics/media/media.hpp"
#include "physics/particle_optics_cache.hpp"
#include "skyspec/size_distribution.hpp"
#include "skyspec/sphere_ensemble.hpp"
#include "skyspec/water.hpp"

namespace skyspec {

namespace {
constexpr int kFogOpticsFormat = 1;
constexpr double kTemperatureK = 283.15;      // 10 degC: a fog's typical temperature
constexpr double kAbsorptionIndex = 1.96e-9;  // OPAC's imaginary index of water at 550 nm (fogr00)
constexpr double kAlpha = 4.0, kB_per_um = 0.0562, kGamma = 1.77, kMinRadiusUm = 0.02, kMaxRadiusUm = 50.0;

SizeDistribution fog_droplets(const FogSpec& f) {
  if (f.droplets == FogSpec::Droplets::Lognormal) {
    return SizeDistribution::lognormal_within(f.median_radius_um * 1e-6, f.radius_spread, kDropCutSpreads);
  }
  // The modified gamma distribution's mode radius: r_c = (alpha / (B gamma))^(1 / gamma).
  const double mode_um = std::pow(kAlpha / (kB_per_um * kGamma), 1.0 / kGamma);
  return SizeDistribution::modified_gamma(mode_um * 1e-6, kAlpha, kGamma)
      .truncated(kMinRadiusUm * 1e-6, kMaxRadiusUm * 1e-6);
}

std::complex<double> water_index(double nm) {
  return {water_refractive_index(kTemperatureK, liquid_water_density_kg_per_m3(kTemperatureK), nm), kAbsorptionIndex};
}

// Per droplet (one per m^3): cross-sections and the unnormalised matrix rows, per wavelength.
RawParticleOptics compute(const WavelengthGrid& grid, const FogSpec& f) {
  const std::vector<double>& mu = aerosol_scattering_cosines();
  const SizeDistribution sizes = fog_droplets(f);
  RawParticleOptics o;
  const int n = grid.size();
  plan_preparation(n, "computing the fog's optics (Lorenz-Mie)");
  for (int i = 0; i < n; ++i) {
    const SphereEnsembleOptics e = sphere_ensemble_optics(sizes, water_index(grid.nm(i)), grid.nm(i) * 1e-9, 1.0, mu);
    append_sphere_optics(o, e.scattering_cross_section_m2, e.extinction_cross_section_m2, e.phase_matrix);
    finish_preparation(1);
  }
  return o;
}

std::string optics_key(const WavelengthGrid& grid, const FogSpec& f) {
  std::ostringstream key;
  key.precision(17);
  key << "skyspec fog optics, format " << kFogOpticsFormat;
  if (f.droplets == FogSpec::Droplets::Lognormal)
    key << "\nlognormal " << f.median_radius_um << ' ' << f.radius_spread << " cut at " << kDropCutSpreads;
  else
    key << "\nmodified gamma " << kAlpha << ' ' << kB_per_um << ' ' << kGamma << ' ' << kMinRadiusUm << ' '
        << kMaxRadiusUm;
  key << "\nwater " << kTemperatureK << ' ' << kAbsorptionIndex << "\nwavelengths_nm";
  for (double v : grid.nanometres()) key << ' ' << v;
  const SphereEnsembleSettings quadrature;
  key << "\ncosines " << aerosol_scattering_cosines().size() << "\nquadrature " << quadrature.panel_ln_radius << ' '
      << quadrature.panel_size_parameter << '\n';
  return key.str();
}
}  // namespace

double fog_extinction_cross_section_550nm_m2(const FogSpec& f) {
  const auto of = [](const FogSpec& spec) {
    return sphere_ensemble_optics(fog_droplets(spec), water_index(550.0), 550e-9, 1.0, {1.0})
        .extinction_cross_section_m2;
  };
  if (f.droplets == FogSpec::Droplets::Lognormal) return of(f);
  static const double opac = of(FogSpec{});  // every scene with OPAC's fog asks for it
  return opac;
}

std::optional<Medium> build_fog(const MediumContext& c) {
  const FogSpec& f = c.spec.fog;
  if (!f.enabled) return std::nullopt;
  const AerosolMixtureOptics per_droplet =
      cached_particle_optics(optics_key(c.grid, f), c.grid.size(), aerosol_scattering_cosines(), c.cache_on_disk,
                             [&] { return compute(c.grid, f); });
  const double droplets_per_m3 = std::log(20.0) / (f.visibility_m * fog_extinction_cross_section_550nm_m2(f));
  return particle_medium("fog", DensityProfile::exponential(f.scale_height_m), per_droplet, droplets_per_m3);
}

}  // namespace skyspec
