#include <boost/test/unit_test.hpp>

// Ozone: the 233 K cross-section table (Bogumil et al. 2003 in the ultraviolet and near infrared,
// Serdyuchenko et al. 2014 10 nm bin means between), its Hartley and Chappuis bands, Dobson units,
// the tent profile and the resulting vertical optical depth.

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "check_helpers.hpp"
#include "physics/ozone.hpp"
#include "skyspec/error.hpp"
#include "skyspec/units.hpp"

BOOST_AUTO_TEST_SUITE(test_ozone)

using namespace skyspec;
using test::error_setting;
using test::relative;

BOOST_AUTO_TEST_SUITE(cross_section)

BOOST_AUTO_TEST_CASE(table_covers_230_to_1060_nm_in_square_metres) {
  const TabulatedSpectrum& t = ozone_cross_section_table();
  BOOST_TEST((t.kind() == TabulatedSpectrum::Kind::BinAverages));
  BOOST_TEST(t.min_nm() == 230.0);
  BOOST_TEST(t.max_nm() == 1060.0);
  // 130 bins of 1 nm (230-360, Bogumil), 48 of 10 nm (Serdyuchenko), 22 of 10 nm (Bogumil).
  BOOST_TEST(t.values().size() == 200u);
  // In m^2 the cross-sections are 1e-29-2e-21 (the Hartley band's peak); a table left in cm^2 would
  // be 1e4 larger. Every bin mean is positive (single noisy points of the data are not).
  for (double sigma_m2 : t.values()) {
    BOOST_TEST(sigma_m2 > 1e-29);
    BOOST_TEST(sigma_m2 < 2e-21);
  }
  // Serdyuchenko's bins are read unchanged between 360 and 840 nm.
  BOOST_TEST(t.value_at(605.0) == 5.019e-25);
  BOOST_TEST(t.value_at(365.0) == 1.18e-27);
  BOOST_TEST(t.value_at(835.0) == 7.105e-27);
}

BOOST_AUTO_TEST_CASE(hartley_band_peaks_near_255_nm) {
  // The Hartley band's maximum is about 1.1e-17 cm^2 = 1.1e-21 m^2 near 255 nm (the laboratory
  // literature: Bass & Paur, Molina & Molina, Malicet et al.); the 1 nm bins peak at 255-256 nm.
  const TabulatedSpectrum& t = ozone_cross_section_table();
  double peak = 0.0, peak_nm = 0.0;
  for (double nm = 230.5; nm < 360.0; nm += 1.0)
    if (t.value_at(nm) > peak) peak = t.value_at(nm), peak_nm = nm;
  BOOST_TEST(peak_nm == 255.5);
  BOOST_TEST(peak > 1.10e-21);
  BOOST_TEST(peak < 1.20e-21);
  // The Huggins bands: three orders of magnitude down from 300 to 330 nm, the cut-off of the
  // ultraviolet that reaches the ground.
  BOOST_TEST(t.value_at(300.5) / t.value_at(330.5) > 30.0);
  BOOST_TEST(t.value_at(255.5) / t.value_at(340.5) > 5e3);
}

BOOST_AUTO_TEST_CASE(chappuis_band_peaks_near_600_nm) {
  // The Chappuis band's maximum, about 5e-21 cm^2 = 5e-25 m^2 just above 600 nm: the table's
  // largest bin mean is 600-610 nm, 5.019e-25 m^2.
  const TabulatedSpectrum& t = ozone_cross_section_table();
  // The visible part of the table: the bins from 360 to 840 nm.
  const auto first = std::find(t.nanometres().begin(), t.nanometres().end(), 360.0) - t.nanometres().begin();
  const auto peak = std::max_element(t.values().begin() + first, t.values().begin() + first + 48);
  const size_t bin = static_cast<size_t>(peak - t.values().begin());
  BOOST_TEST(t.nanometres()[bin] == 600.0);
  BOOST_TEST(*peak == 5.019e-25);
  // On a 10 nm grid the largest sample is 600 nm (its bin 595-605 straddles the two top bins).
  const WavelengthGrid grid = WavelengthGrid::uniform(360.0, 830.0, 10.0);
  const SpectrumD sigma = ozone_cross_section_on_grid(grid);
  Eigen::Index argmax = 0;
  sigma.maxCoeff(&argmax);
  BOOST_TEST(grid.nm(static_cast<int>(argmax)) == 600.0);
  BOOST_TEST(std::abs(sigma[argmax] - 0.5 * (4.701e-25 + 5.019e-25)) < 1e-30);
  // The band falls by two orders of magnitude towards the blue: the minimum near 380 nm.
  BOOST_TEST(t.value_at(375.0) < 1e-27);
}

BOOST_AUTO_TEST_CASE(grid_outside_the_table_is_an_input_error) {
  BOOST_TEST(error_setting([] { ozone_cross_section_on_grid(WavelengthGrid::uniform(220.0, 800.0, 10.0)); }) ==
             "spectrum");
  BOOST_TEST(error_setting([] { ozone_cross_section_on_grid(WavelengthGrid::uniform(400.0, 1100.0, 10.0)); }) ==
             "spectrum");
  BOOST_CHECK_NO_THROW(ozone_cross_section_on_grid(WavelengthGrid::uniform(230.0, 1060.0, 10.0)));
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(column_and_profile)

BOOST_AUTO_TEST_CASE(dobson_units) {
  BOOST_TEST(relative(dobson_units_to_per_m2(300.0), 8.0601e22) < 1e-12);
  BOOST_TEST(relative(per_m2_to_dobson_units(8.0601e22), 300.0) < 1e-12);
  BOOST_TEST(dobson_units_to_per_m2(1.0) == constants::kDobsonUnit_per_m2);
  BOOST_TEST(error_setting([] { dobson_units_to_per_m2(-5.0); }) == "ozone.column_DU");
  BOOST_TEST(error_setting([] { dobson_units_to_per_m2(5000.0, "atmosphere.ozone.column_DU"); }) ==
             "atmosphere.ozone.column_DU");
}

BOOST_AUTO_TEST_CASE(tent_profile_holds_the_column) {
  const OzoneTentProfile p = OzoneTentProfile::bruneton2017(300.0);
  const double column_per_m2 = 8.0601e22;
  // n_peak = N / 15 km (Bruneton's kMaxOzoneNumberDensity = 300 DU / 15000 m).
  BOOST_TEST(relative(p.peak_number_density_per_m3(), column_per_m2 / 15000.0) < 1e-12);
  BOOST_TEST(p.number_density_per_m3(5e3) == 0.0);
  BOOST_TEST(p.number_density_per_m3(10e3) == 0.0);
  BOOST_TEST(relative(p.number_density_per_m3(17.5e3), 0.5 * p.peak_number_density_per_m3()) < 1e-12);
  BOOST_TEST(relative(p.number_density_per_m3(25e3), p.peak_number_density_per_m3()) < 1e-12);
  BOOST_TEST(relative(p.number_density_per_m3(32.5e3), 0.5 * p.peak_number_density_per_m3()) < 1e-12);
  BOOST_TEST(p.number_density_per_m3(45e3) == 0.0);
  BOOST_TEST(relative(p.column_between_per_m2(0.0, 100e3), column_per_m2) < 1e-12);
  BOOST_TEST(relative(p.column_between_per_m2(10e3, 25e3), 0.5 * column_per_m2) < 1e-12);
  // The exact column against a fine midpoint sum of n(z).
  double sum = 0.0;
  const double dz_m = 1.0;
  for (double z = 0.5; z < 60e3; z += dz_m) sum += p.number_density_per_m3(z) * dz_m;
  BOOST_TEST(relative(sum, column_per_m2) < 1e-6);
  // A partial column, closed form: the part of the upper flank above 30 km is a triangle of
  // height n(30 km) = 2/3 n_peak and base 10 km.
  BOOST_TEST(relative(p.column_between_per_m2(30e3, 40e3), 0.5 * 10e3 * (2.0 / 3.0) * p.peak_number_density_per_m3()) <
             1e-12);
}

BOOST_AUTO_TEST_CASE(tent_profile_input_errors) {
  BOOST_TEST(error_setting([] { OzoneTentProfile(300.0, 25e3, 20e3, 40e3); }) == "ozone.peak_altitude_m");
  BOOST_TEST(error_setting([] { OzoneTentProfile(300.0, 10e3, 25e3, 25e3); }) == "ozone.top_altitude_m");
  BOOST_TEST(error_setting([] { OzoneTentProfile(300.0, -1.0, 25e3, 40e3); }) == "ozone.bottom_altitude_m");
  BOOST_TEST(error_setting([] { OzoneTentProfile::bruneton2017(-1.0); }) == "ozone.column_DU");
}

BOOST_AUTO_TEST_CASE(vertical_optical_depth_at_600_nm) {
  // tau = sigma N. With the 600-610 nm bin (5.019e-25 m^2) and 300 DU: 0.0405; the 600 nm sample
  // of a 10 nm grid (bin 595-605 nm, 4.86e-25 m^2) gives 0.0392. Commonly quoted: ~0.03-0.04 for
  // the Chappuis peak at 300 DU.
  const double column_per_m2 = dobson_units_to_per_m2(300.0);
  const double tau_bin = ozone_cross_section_table().value_at(600.0) * column_per_m2;
  BOOST_TEST(std::abs(tau_bin - 0.040452) < 1e-5);
  const WavelengthGrid grid = WavelengthGrid::uniform(360.0, 830.0, 10.0);
  const SpectrumD tau = ozone_vertical_optical_depth_on_grid(grid, 300.0);
  const double tau_600 = tau[grid.index_of(600.0)];
  BOOST_TEST_MESSAGE("vertical ozone optical depth, 300 DU: 600-610 nm bin " << tau_bin << ", 10 nm grid at 600 nm "
                                                                             << tau_600);
  BOOST_TEST(std::abs(tau_600 - 0.039172) < 1e-5);
  // The profile gives the same through its number density: integral sigma n(z) dz = sigma N.
  const OzoneTentProfile p = OzoneTentProfile::bruneton2017(300.0);
  BOOST_TEST(relative(ozone_cross_section_on_grid(grid)[grid.index_of(600.0)] * p.column_between_per_m2(0.0, 60e3),
                      tau_600) < 1e-12);
  // Blue light is barely touched: tau(450 nm) is 20 times smaller.
  BOOST_TEST(tau[grid.index_of(450.0)] < tau_600 / 15.0);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE_END()  // test_ozone
