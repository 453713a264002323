// Rain of drops of about one size by Lorenz-Mie theory (atmosphere.rain.drops = "lognormal",
// media/rain.cpp; issue 39): the primary bow and its supernumeraries where Airy theory puts them,
// the bow polarised, and the drops' number from the rain rate at their fall speed.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "release_stage.hpp"
#include "skyspec/atmosphere.hpp"
#include "skyspec/error.hpp"
#include "skyspec/spectrum.hpp"
#include "skyspec/units.hpp"
#include "skyspec/water.hpp"

BOOST_AUTO_TEST_SUITE(test_lognormal_rain)

using namespace skyspec;

namespace {
double water_index(double nm) { return water_refractive_index(283.15, liquid_water_density_kg_per_m3(283.15), nm); }

AtmosphereSpec lognormal_rain(double median_mm, double spread, double rate_mm_per_h) {
  AtmosphereSpec spec;
  spec.rain.enabled = true;
  spec.rain.drops = RainSpec::Drops::Lognormal;
  spec.rain.median_radius_mm = median_mm;
  spec.rain.radius_spread = spread;
  spec.rain.rate_mm_per_h = rate_mm_per_h;
  return spec;
}

// Airy theory of the primary bow (van de Hulst 1957, 13.2): near the Descartes ray the deviation
// is D(b) = D_R + D'' (b - b_R)^2 / 2 in the impact parameter b = sin i (radius 1), and the light
// scattered at theta goes as Ai^2(-z), z = (theta - D_R) x^(2/3) (2 / D'')^(1/3). Its maxima are
// at z = 1.0188 (the bow), 3.2482 and 4.8201 (the first two supernumeraries): their angles, degrees.
std::vector<double> airy_maxima_deg(double n, double x) {
  const auto deviation = [n](double b) { return kPi + 2.0 * std::asin(b) - 4.0 * std::asin(b / n); };
  const double b_r = std::sqrt((4.0 - n * n) / 3.0), h = 1e-4;
  const double second = (deviation(b_r + h) - 2.0 * deviation(b_r) + deviation(b_r - h)) / (h * h);
  std::vector<double> out;
  for (double z : {1.0188, 3.2482, 4.8201})
    out.push_back(radians_to_degrees(deviation(b_r) + z / (std::pow(x, 2.0 / 3.0) * std::cbrt(2.0 / second))));
  return out;
}
}  // namespace

// Drops of 0.25 mm (spread 1.05) at 450, 550 and 650 nm: the phase function's first three maxima
// beyond Descartes' angle, the bow and two supernumeraries, within 0.1 degree (the table's step
// there) of Airy's at the median radius; each supernumerary a distinct band (the dip before it
// under 0.2 of it for the first, 0.4 for the second); the bow more than 90 % polarised
// perpendicular to the scattering plane. This case and the next take 40 s under the sanitizers:
// left to the release stage (Lorenz-Mie runs under them in test_lorenz_mie and test_sphere_ensemble).
BOOST_AUTO_TEST_CASE(supernumeraries_where_airy_puts_them,
                     *boost::unit_test::precondition(test::not_in_sanitizer_stage)) {
  const std::vector<double> nm = {450.0, 550.0, 650.0};
  const AtmosphereModel model(lognormal_rain(0.25, 1.05, 1.0), WavelengthGrid::from_list(nm));
  const Medium* rain = model.medium("rain");
  BOOST_TEST_REQUIRE(rain != nullptr);
  const TabulatedScatteringMatrix& m = *rain->phase.matrix;
  for (int i = 0; i < 3; ++i) {
    const double n = water_index(nm[static_cast<size_t>(i)]);
    const std::vector<double> airy = airy_maxima_deg(n, 2.0 * kPi * 0.25e-3 / (nm[static_cast<size_t>(i)] * 1e-9));
    // Local maxima and the minima between them, from Descartes' angle outwards, every 0.02 degree.
    std::vector<double> maxima, peak, dip;
    double previous = 0.0, before = 0.0, lowest = 1e300;
    for (double deg = airy[0] - 1.0; deg < airy[2] + 0.5; deg += 0.02) {
      const double p = m.phase(i, std::cos(degrees_to_radians(deg)));
      lowest = std::min(lowest, p);
      if (previous > before && previous >= p && deg > airy[0] - 0.9) {
        maxima.push_back(deg - 0.02);
        peak.push_back(previous);
        dip.push_back(lowest);
        lowest = 1e300;
      }
      before = previous;
      previous = p;
    }
    BOOST_TEST_CONTEXT(nm[static_cast<size_t>(i)] << " nm") {
      BOOST_TEST_REQUIRE(maxima.size() >= 3u);
      for (size_t k = 0; k < 3; ++k) {
        BOOST_TEST_MESSAGE(nm[static_cast<size_t>(i)] << " nm: maximum " << k << " at " << maxima[k] << " deg, Airy "
                                                      << airy[k]);
        BOOST_TEST(std::abs(maxima[k] - airy[k]) <= 0.1);
      }
      const SphereMatrixElements bow = m.elements(i, std::cos(degrees_to_radians(maxima[0])));
      BOOST_TEST_MESSAGE(nm[static_cast<size_t>(i)] << " nm: the supernumeraries " << peak[1] / dip[1] << " and "
                                                    << peak[2] / dip[2] << " times the dips before them; the bow "
                                                    << -bow.b1 / bow.a1 << " polarised");
      BOOST_TEST(dip[1] < 0.2 * peak[1]);
      BOOST_TEST(dip[2] < 0.4 * peak[2]);
      BOOST_TEST(-bow.b1 / bow.a1 > 0.9);
    }
  }
}

// The rain rate carries the drops: N (4/3 pi r^3) v(2 r) = R for drops of nearly one size (spread
// 1.01: 0.25 mm, falling at 9.65 - 10.3 exp(-0.3) m/s by Atlas et al.'s law), so the extinction
// at the ground is N pi r^2 times the drops' efficiency without the light diffracted within half a
// degree (Q_ext = 2 less nearly all of diffraction's 1: between 1 and 1.05), proportional to R;
// the drops absorb nothing.
BOOST_AUTO_TEST_CASE(rain_rate_sets_the_number_of_drops,
                     *boost::unit_test::precondition(test::not_in_sanitizer_stage)) {
  const WavelengthGrid grid = WavelengthGrid::from_list({550.0});
  const AtmosphereModel one(lognormal_rain(0.25, 1.01, 1.0), grid), two(lognormal_rain(0.25, 1.01, 2.0), grid);
  const double r = 0.25e-3, v = 9.65 - 10.3 * std::exp(-0.6 * 0.5);
  const double drops_per_m3 = 1e-3 / 3600.0 / ((4.0 / 3.0) * kPi * r * r * r * v);
  const double efficiency = one.medium("rain")->extinction_per_m[0] / (drops_per_m3 * kPi * r * r);
  BOOST_TEST_MESSAGE("extinction over N pi r^2: " << efficiency);
  // The docs' scene (spread 1.1, 0.5 mm/h): its extinction at the ground, for docs/bows-and-halos.md.
  const AtmosphereModel docs(lognormal_rain(0.25, 1.1, 0.5), grid);
  BOOST_TEST_MESSAGE("0.25 mm, spread 1.1, 0.5 mm/h: " << docs.medium("rain")->extinction_per_m[0] * 1e3 << " per km");
  BOOST_TEST(efficiency > 1.0);
  BOOST_TEST(efficiency < 1.05);
  BOOST_TEST(two.medium("rain")->extinction_per_m[0] / one.medium("rain")->extinction_per_m[0] == 2.0,
             boost::test_tools::tolerance(1e-12));
  BOOST_TEST(one.medium("rain")->scattering_per_m[0] == one.medium("rain")->extinction_per_m[0],
             boost::test_tools::tolerance(1e-12));
}

// Drops whose size parameter would pass Lorenz-Mie's 2e4 at the grid's shortest wavelength are
// refused, naming the key, before any work.
BOOST_AUTO_TEST_CASE(drops_beyond_the_series_are_refused) {
  try {
    const AtmosphereModel model(lognormal_rain(0.5, 1.2, 1.0), WavelengthGrid::from_list({250.0, 550.0}));
    BOOST_FAIL("0.5 mm drops at 250 nm were accepted");
  } catch (const InputError& e) {
    BOOST_TEST_MESSAGE(e.what());
    BOOST_TEST(std::string(e.what()).find("atmosphere.rain.median_radius_mm") != std::string::npos);
  }
}

BOOST_AUTO_TEST_SUITE_END()
