#include <boost/test/unit_test.hpp>

// The gases' absorption bands (gas_bands.hpp): Bird & Riordan's (1986) band transmittances, their
// exponential sums against the closed form, and each wavelength's terms (one gas by the sum, the
// other by Beer-Lambert's law where both absorb) against the product of the two band models along
// vertical and slant paths.

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "physics/gas_bands.hpp"
#include "physics/solar_spectrum.hpp"

BOOST_AUTO_TEST_SUITE(test_gas_bands)

using namespace skyspec;

namespace {
// Sum over the terms of w_i exp(-(k_w u_w + k_u u_u)) at one wavelength.
double terms_transmittance(double nm, double water_cm, double air_masses) {
  double t = 0.0;
  for (int i = 0; i < exponential_term_count(); ++i) {
    const GasTermCoefficients c = gas_term_coefficients(i, nm, water_cm, 1.0);
    if (!c.absorbs) return 1.0;
    t += c.weight * std::exp(-(c.water_vapour_per_cm * water_cm + c.mixed_gases_per_air_mass) * air_masses);
  }
  return t;
}
// Bird & Riordan's eqs. 2-8 and 2-11 along a path of `air_masses` with `water_cm` in the vertical.
double band_model(double nm, double water_cm, double air_masses) {
  return band_transmittance(GasBand::WaterVapour, band_coefficient(GasBand::WaterVapour, nm) * water_cm * air_masses) *
         band_transmittance(GasBand::MixedGases, band_coefficient(GasBand::MixedGases, nm) * air_masses);
}
}  // namespace

// Published coefficients (Bird & Riordan 1986, table 1) read from the embedded file: the 940 nm
// water band, the oxygen A band, the 1.4 um water band.
BOOST_AUTO_TEST_CASE(coefficients_are_bird_and_riordans) {
  BOOST_TEST(band_model_wavelengths_nm().size() == 122u);
  BOOST_TEST(band_model_wavelengths_nm().front() == 300.0);
  BOOST_TEST(band_model_wavelengths_nm().back() == 4000.0);
  BOOST_TEST(band_coefficient(GasBand::WaterVapour, 937.0) == 55.0);
  BOOST_TEST(band_coefficient(GasBand::MixedGases, 762.5) == 4.0);
  BOOST_TEST(band_coefficient(GasBand::WaterVapour, 1395.0) == 1000.0);
  BOOST_TEST(band_coefficient(GasBand::WaterVapour, 550.0) == 0.0);
  // Linear between wavelengths, none outside.
  BOOST_TEST(band_coefficient(GasBand::WaterVapour, 933.5) == 41.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(band_coefficient(GasBand::WaterVapour, 5000.0) == 0.0);
}

// Eq. (2) against eq. (1): within 0.0024 in transmittance for every absorber amount, weights
// summing to 1 (a path without absorber transmits everything).
BOOST_AUTO_TEST_CASE(exponential_sums_match_the_band_model) {
  for (GasBand gas : {GasBand::WaterVapour, GasBand::MixedGases}) {
    const auto& terms = exponential_sum(gas);
    BOOST_TEST(static_cast<int>(terms.size()) == exponential_term_count());
    double total = 0.0, largest = 0.0;
    for (const ExponentialTerm& t : terms) {
      BOOST_TEST(t.weight > 0.0);
      total += t.weight;
    }
    BOOST_TEST(total == 1.0, boost::test_tools::tolerance(1e-9));
    for (int k = 0; k <= 1300; ++k) {
      const double x = std::pow(10.0, -6.0 + 0.01 * k);
      double sum = 0.0;
      for (const ExponentialTerm& t : terms) sum += t.weight * std::exp(-t.k * x);
      largest = std::max(largest, std::abs(sum - band_transmittance(gas, x)));
    }
    BOOST_TEST_MESSAGE((gas == GasBand::WaterVapour ? "water vapour" : "mixed gases")
                       << ": largest |sum - T| " << largest);
    BOOST_TEST(largest < 0.0024);
  }
}

// Each wavelength's terms against the product of the two band models, 1.42 cm of water: within
// 0.0024 where one gas absorbs; where both do, the weaker one's Beer-Lambert coefficient is exact on
// the reference path (1.5 air masses) only. Over the solar spectrum the direct beam's error is a
// few tenths of a percent at most (the message gives the figures docs/physics.md quotes).
BOOST_AUTO_TEST_CASE(terms_match_both_band_models) {
  const auto& nodes = band_model_wavelengths_nm();
  for (double m : {1.0, 1.5, 3.0, 6.0}) {
    double largest_single = 0.0, largest_overlap = 0.0, energy = 0.0, energy_error = 0.0;
    for (size_t j = 0; j < nodes.size(); ++j) {
      const double nm = nodes[j], exact = band_model(nm, 1.42, m), terms = terms_transmittance(nm, 1.42, m);
      const bool both = band_coefficient(GasBand::WaterVapour, nm) > 0 && band_coefficient(GasBand::MixedGases, nm) > 0;
      (both ? largest_overlap : largest_single) =
          std::max(both ? largest_overlap : largest_single, std::abs(terms - exact));
      // Trapezoid weights over the band model's wavelengths.
      const double width = 0.5 * (nodes[std::min(j + 1, nodes.size() - 1)] - nodes[j == 0 ? 0 : j - 1]);
      const double sun = solar_irradiance_table().value_at(nm) * width;
      energy += sun * exact;
      energy_error += sun * (terms - exact);
    }
    std::printf("%g air masses: largest |terms - band models| %.4f (one gas), %.4f (both); direct beam %+.3f %%\n", m,
                largest_single, largest_overlap, 100.0 * energy_error / energy);
    BOOST_TEST(largest_single < 0.0024);
    BOOST_TEST(largest_overlap < 0.1);
    BOOST_TEST(std::abs(energy_error / energy) < 0.003);
  }
}

// The broadband irradiance integrates over Bird & Riordan's wavelengths with the trapezoid rule,
// each sample the solar spectrum's mean over 10 nm: at the top of the atmosphere that is the
// table's exact integral over 300-4000 nm within 0.1 % (the message gives the figures
// docs/physics.md quotes, and what lies outside the band).
BOOST_AUTO_TEST_CASE(the_wavelengths_integrate_the_solar_spectrum) {
  const auto& nodes = band_model_wavelengths_nm();
  const TabulatedSpectrum& sun = solar_irradiance_table();
  const auto mean = [&](double nm) {
    const double lo = std::max(nm - 5.0, sun.min_nm()), hi = std::min(nm + 5.0, sun.max_nm());
    return sun.mean(lo, hi);
  };
  double trapezoid = 0.0;
  for (size_t j = 1; j < nodes.size(); ++j)
    trapezoid += 0.5 * (nodes[j] - nodes[j - 1]) * (mean(nodes[j]) + mean(nodes[j - 1]));
  const double exact = sun.integral(300.0, 4000.0);
  std::printf(
      "top of the atmosphere, 300-4000 nm: trapezoid %.1f W/m2, table %.1f W/m2 (%+.3f %%); 280-300 nm %.1f "
      "W/m2, 280-4000 nm %.1f W/m2\n",
      trapezoid, exact, 100.0 * (trapezoid / exact - 1.0), sun.integral(280.0, 300.0), sun.integral(280.0, 4000.0));
  BOOST_TEST(std::abs(trapezoid / exact - 1.0) < 0.001);
}

BOOST_AUTO_TEST_SUITE_END()
