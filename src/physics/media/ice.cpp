// Ice: randomly oriented hexagonal prisms of ice near the ground (diamond dust) or in a cloud layer
// aloft (cirrostratus: DensityProfile::layer, its vertical optical depth given), whose refraction
// gives the 22 and 46 degree halos (ice_crystals.hpp: the ray tracing and its sources). Their
// scattering function per wavelength is geometric optics with the index of ice at that wavelength
// (Warren & Brandt 2008). Diffraction by the crystals' outlines takes half of their extinction
// (extinction efficiency 2 for crystals much larger than the wavelength) into a forward peak about
// lambda / D wide (0.4 degrees for crystals 50 um across): it is taken as unscattered light (the
// medium's extinction is the other half, refraction and reflection, less the rays those leave
// undeviated: compute_ice_optics), so that light reaches the camera as if it had not met those
// crystals; the sun's aureole from diffraction by ice is not in
// the image. Absorption is neglected (k < 1e-8 in the visible). Intensity only: the crystals'
// matrix is the phase function (b1 = b2 = 0, a3 = a1), so scenes with ice are refused for
// output.polarisation (scene_checks.cpp).
#include <cmath>
#include <sstream>

#include <tbb/parallel_for.h>

#include "base/preparation_progress.hpp"
#include "physics/media/media.hpp"
#include "physics/particle_optics_cache.hpp"
#include "skyspec/ice_crystals.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

namespace {
constexpr int kIceOpticsFormat = 2;
constexpr long long kIceRaysPerWavelength = 500000;
constexpr std::uint64_t kIceSeed = 0x1ce;

std::vector<double> make_ice_cosines() {
  std::vector<double> deg;
  for (int k = 0; k < 600; ++k) deg.push_back(0.1 * k);          // 0 - 59.9
  for (int k = 0; k <= 240; ++k) deg.push_back(60.0 + 0.5 * k);  // 60 - 180
  return cosines_of_degrees(deg);
}

// Per unit of extinction (refraction and reflection): the shares of the rays traced at each
// wavelength. The rays leaving within the first interval of forward (0.1 degree: those through
// two parallel faces, which leave undeviated) are taken as unscattered, like diffraction: the
// medium's extinction and scattering lose their share and the phase function is the rest,
// renormalised. Light scattered by exactly 0 degrees is the same as light not scattered, but as a
// spike 0.1 degree wide it would carry a large share of the light into quadratures over directions
// (the scattering-order tables') that cannot resolve it (docs/bows-and-halos.md).
RawParticleOptics compute_ice_optics(const WavelengthGrid& grid, double aspect_ratio) {
  const std::vector<double>& mu = ice_scattering_cosines();
  const int n = grid.size();
  std::vector<std::vector<double>> shares(static_cast<size_t>(n));
  plan_preparation(n, "tracing rays through ice crystals (halos)");
  tbb::parallel_for(0, n, [&](int i) {
    shares[static_cast<size_t>(i)] =
        hexagonal_prism_scattering(HexagonalPrism{aspect_ratio}, ice_refractive_index(grid.nm(i)), mu,
                                   kIceRaysPerWavelength, kIceSeed + static_cast<std::uint64_t>(i))
            .share;
    finish_preparation(1);
  });
  std::vector<double> kept(static_cast<size_t>(n));
  for (size_t i = 0; i < shares.size(); ++i) {
    std::vector<double>& share = shares[i];
    double total = 0.0;
    for (double v : share) total += v;
    kept[i] = 1.0 - share.back() / total;
    share.back() = 0.0;
  }
  RawParticleOptics optics = optics_from_shares(shares, mu);
  optics.sca = kept;
  optics.ext = kept;
  return optics;
}

std::string ice_optics_key(const WavelengthGrid& grid, double aspect_ratio) {
  std::ostringstream key;
  key.precision(17);
  key << "skyspec ice optics, format " << kIceOpticsFormat << "\nhexagonal prism " << aspect_ratio << "\nrays "
      << kIceRaysPerWavelength << ' ' << kIceSeed << "\nwavelengths_nm";
  for (double v : grid.nanometres()) key << ' ' << v;
  key << "\ncosines " << ice_scattering_cosines().size() << '\n';
  return key.str();
}
}  // namespace

DensityProfile cirrus_profile(const IceSpec& ice) {
  return DensityProfile::layer(ice.base_m, ice.top_m, 0.25 * (ice.top_m - ice.base_m));
}

const std::vector<double>& ice_scattering_cosines() {
  static const std::vector<double> mu = make_ice_cosines();
  return mu;
}

std::optional<Medium> build_ice(const MediumContext& c) {
  const IceSpec& ice = c.spec.ice;
  if (!ice.enabled) return std::nullopt;
  for (int i = 0; i < c.grid.size(); ++i)
    (void)ice_refractive_index(c.grid.nm(i), "spectrum");  // refused before any work
  const AerosolMixtureOptics unit =
      cached_particle_optics(ice_optics_key(c.grid, ice.aspect_ratio), c.grid.size(), ice_scattering_cosines(),
                             c.cache_on_disk, [&] { return compute_ice_optics(c.grid, ice.aspect_ratio); });
  // Half of the whole extinction: the other half is diffraction, taken as unscattered.
  if (ice.layer == IceSpec::Layer::Cloud) {
    const DensityProfile cloud = cirrus_profile(ice);
    return particle_medium("ice", cloud, unit, 0.5 * ice.optical_depth / cloud.layer_column_m());
  }
  const double beta = 0.5 * std::log(20.0) / ice.visibility_m;
  return particle_medium("ice", DensityProfile::exponential(ice.scale_height_m), unit, beta);
}

}  // namespace skyspec
