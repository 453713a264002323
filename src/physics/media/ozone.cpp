// Ozone: absorption only, by a tent-shaped layer holding the scene's column (Dobson units); the
// cross-sections are the scene's own or the built-in laboratory table (233 K, 230-1060 nm:
// Serdyuchenko et al. 2014 and Bogumil et al. 2003; data/ozone/), averaged over each grid sample's bin.
#include <vector>

#include "physics/media/media.hpp"
#include "physics/ozone.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

double ozone_peak_number_density_per_m3(const OzoneSpec& o) {
  if (!o.enabled || !(o.column_DU > 0.0)) return 0.0;
  // Column = N_peak * (area under the tent) = N_peak (top - bottom) / 2.
  return o.column_DU * constants::kDobsonUnit_per_m2 /
         DensityProfile::tent(o.bottom_m, o.peak_m, o.top_m).tent_area_m();
}

std::optional<Medium> build_ozone(const MediumContext& c) {
  const OzoneSpec& o = c.spec.ozone;
  const double peak = ozone_peak_number_density_per_m3(o);
  if (!(peak > 0.0)) return std::nullopt;
  Medium ozone;
  ozone.name = "ozone";
  ozone.profile = DensityProfile::tent(o.bottom_m, o.peak_m, o.top_m);  // relative density 1 at the peak
  ozone.scattering_per_m = SpectrumD::Zero(c.grid.size());
  SpectrumD sigma(c.grid.size());
  if (!o.cross_section_m2.empty()) {
    for (int i = 0; i < c.grid.size(); ++i)
      sigma[i] = interpolate_linear(o.cross_section_wavelengths_nm, o.cross_section_m2, c.grid.nm(i));
  } else if (c.spec.gas_band_term >= 0 && c.grid.max_nm() > ozone_cross_section_table().max_nm()) {
    // A broadband irradiance's run: no absorption beyond the table (1060 nm), where the Chappuis
    // band's tail is about 1e-28 m^2 per molecule (an optical depth of 1e-5 for 300 DU).
    std::vector<double> inside;
    for (double nm : c.grid.nanometres())
      if (nm <= ozone_cross_section_table().max_nm()) inside.push_back(nm);
    sigma.setZero();
    if (!inside.empty()) {
      // Each sample's mean is its own band's, whatever the other samples (tabulated_spectrum.hpp).
      const WavelengthGrid sub = WavelengthGrid::from_list(inside).with_bandwidth(c.grid.bandwidth_nm());
      const SpectrumD part = ozone_cross_section_on_grid(sub, "spectrum");
      for (size_t k = 0; k < inside.size(); ++k)
        sigma[static_cast<Eigen::Index>(k)] = part[static_cast<Eigen::Index>(k)];
    }
  } else {
    sigma = ozone_cross_section_on_grid(c.grid, "spectrum");
  }
  ozone.extinction_per_m = sigma * peak;
  return ozone;
}

}  // namespace skyspec
