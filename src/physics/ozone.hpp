// Ozone: absorption cross-section, column amount and vertical profile.
//
// Ozone absorbs without scattering. Its volume absorption coefficient at altitude z is
//   beta_abs(lambda, z) = sigma(lambda) n(z)        [m^-1 = m^2 * m^-3],
// and the vertical optical depth of the whole layer is tau(lambda) = sigma(lambda) * N, where
// N = integral n(z) dz is the column in molecules m^-2. In the visible, absorption is the Chappuis
// band (about 450-750 nm, peak near 600 nm): weak per molecule (~5e-25 m^2) but it is what makes
// the twilight zenith blue rather than grey-yellow once the sunlight's path is long.
//
// Cross-section table, 233 K (a typical stratospheric temperature), bin means in m^2 per molecule
// read as piecewise constant (data/ozone/, provenance in data/README.md): 360-840 nm in 10 nm bins
// from Serdyuchenko et al. (2014) / Gorshelev et al. (2014), IUP Bremen (their integrals are
// exactly the published means times 10 nm); 230-360 nm in 1 nm bins (the Hartley and Huggins
// bands) and 840-1060 nm in 10 nm bins from Bogumil, Orphal & Burrows (2003, SCIAMACHY, the mean
// of their 223 K and 243 K spectra). Where the two overlap they differ by a few percent in absolute
// scale (data/README.md compares them).
//
// Column: in Dobson units, 1 DU = 2.6867e20 molecules m^-2 (a 10 um layer of pure ozone at 0 degC
// and 1 atm; constants::kDobsonUnit_per_m2). A typical mid-latitude column is ~300 DU.
//
// Profile: the "tent" of Bruneton's 2017 reference implementation (precomputed_atmospheric_
// scattering, atmosphere/demo/demo.cc): zero below 10 km, rising linearly to a peak at 25 km, falling
// linearly to zero at 40 km. Its integral is (40 - 10) km / 2 = 15 km times the peak density, so
// n_peak = N / 15 km. Bruneton cites it as an approximation of a profile in a lecture note,
// "Introduction to atmospheric chemistry" (University of Kelaniya), p. 10. Real profiles peak at
// 20-25 km and vary with latitude and season; the column matters more than the shape for sky colour.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "base/tabulated_spectrum.hpp"
#include "skyspec/spectrum.hpp"

namespace skyspec {

/// The 233 K cross-section table, m^2 per molecule, 230-1060 nm (see the file comment).
const TabulatedSpectrum& ozone_cross_section_table();

/// The embedded data files the table is made of (data/ozone/), for provenance records.
const std::vector<std::string_view>& ozone_cross_section_files();

/// The table's mean cross-section over each grid sample's band, lambda +- bandwidth/2
/// (tabulated_spectrum.hpp), m^2: the same at a wavelength whatever the grid's other samples.
/// Throws InputError(setting, ...) if a grid wavelength lies outside 230-1060 nm.
SpectrumD ozone_cross_section_on_grid(const WavelengthGrid& grid, const std::string& setting = "spectrum");

/// Column in molecules m^-2 from Dobson units, and back. dobson_units_to_per_m2 throws
/// InputError(setting, ...) unless 0 <= column <= 1000 DU (observed columns lie within ~100-600).
double dobson_units_to_per_m2(double column_DU, const std::string& setting = "ozone.column_DU");
double per_m2_to_dobson_units(double column_per_m2);

/// tau(lambda) = sigma(lambda) N for a vertical path through the whole ozone layer, on the grid.
SpectrumD ozone_vertical_optical_depth_on_grid(const WavelengthGrid& grid, double column_DU,
                                               const std::string& setting = "spectrum");

/// A tent-shaped number-density profile holding a given column (see the file comment).
class OzoneTentProfile {
 public:
  /// Bruneton's 2017 profile: 10 km, 25 km, 40 km. Throws InputError(setting, ...) for a column
  /// outside 0-1000 DU.
  static OzoneTentProfile bruneton2017(double column_DU, const std::string& setting = "ozone.column_DU");
  /// Any tent: zero below bottom_m and above top_m, peak at peak_m. Throws InputError naming
  /// "ozone.bottom_altitude_m" / "ozone.peak_altitude_m" / "ozone.top_altitude_m" unless
  /// 0 <= bottom_m < peak_m < top_m <= 100 km.
  OzoneTentProfile(double column_DU, double bottom_m, double peak_m, double top_m,
                   const std::string& column_setting = "ozone.column_DU");

  double column_DU() const { return column_DU_; }
  double column_per_m2() const { return column_per_m2_; }
  double bottom_altitude_m() const { return bottom_m_; }
  double peak_altitude_m() const { return peak_m_; }
  double top_altitude_m() const { return top_m_; }
  /// n_peak = N / ((top - bottom) / 2), molecules m^-3.
  double peak_number_density_per_m3() const { return peak_per_m3_; }
  /// n(z), molecules m^-3 (zero outside the tent; any altitude accepted).
  double number_density_per_m3(double altitude_m) const;
  /// integral_z0^z1 n(z) dz, molecules m^-2, exact (z0 <= z1, any altitudes).
  double column_between_per_m2(double z0_m, double z1_m) const;

 private:
  double column_DU_, column_per_m2_, bottom_m_, peak_m_, top_m_, peak_per_m3_;
  /// integral from -infinity to z.
  double cumulative_per_m2(double z_m) const;
};

}  // namespace skyspec
