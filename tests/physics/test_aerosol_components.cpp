// Aerosols from microphysics (skyspec/aerosol_components.hpp): OPAC's components by Lorenz-Mie
// theory against OPAC's own optical properties (Hess, Koepke & Schult 1998; the values of its
// output files, data/aerosols/opac_components.csv), a published OPAC mixture, and the tabulated
// scattering matrix that the renderer and the Monte Carlo share (skyspec/tabulated_scattering.hpp).

#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "base/quadrature.hpp"
#include "release_stage.hpp"
#include "skyspec/aerosol_components.hpp"
#include "skyspec/error.hpp"
#include "skyspec/size_distribution.hpp"
#include "skyspec/sphere_ensemble.hpp"
#include "skyspec/units.hpp"

BOOST_AUTO_TEST_SUITE(test_aerosol_components)

using namespace skyspec;

namespace {
struct Computed {
  double extinction_per_km, single_scattering_albedo, asymmetry;
};
// One particle per cm^3 of a component, as OPAC counts it (all radii; the optics over its range).
Computed component_optics(int c, double rh, double nm) {
  const AerosolComponentState s = aerosol_component_state(c, rh, nm, "test");
  const SizeDistribution sizes = SizeDistribution::lognormal(s.median_radius_m, s.geometric_standard_deviation)
                                     .truncated(s.min_radius_m, s.max_radius_m);
  const SphereEnsembleOptics e = sphere_ensemble_optics(sizes, {s.m_real, s.m_imag}, nm * 1e-9, 1.0, {1.0});
  return {e.extinction_cross_section_m2 * aerosol_component_fraction_in_range(s) * 1e6 * 1e3,
          e.single_scattering_albedo(), e.asymmetry};
}

// The largest differences from OPAC over the given humidities and wavelengths, printed per component.
struct Worst {
  double extinction = 0.0, albedo = 0.0, asymmetry = 0.0;
};
Worst compare_with_opac(int c, const std::vector<int>& humidities, const std::vector<double>& wavelengths) {
  Worst w;
  for (int rh : humidities)
    for (double nm : wavelengths) {
      OpacPublishedOptics pub;
      if (!opac_published_optics(c, rh, nm, pub)) continue;
      const Computed got = component_optics(c, rh, nm);
      std::printf("%s%02d %6.0f nm: extinction %.5g / %.5g km^-1 (%+.2f %%), albedo %.4f / %.4f, g %.4f / %.4f\n",
                  aerosol_component_names()[static_cast<size_t>(c)], rh, nm, got.extinction_per_km,
                  pub.extinction_per_km, 100.0 * (got.extinction_per_km / pub.extinction_per_km - 1.0),
                  got.single_scattering_albedo, pub.single_scattering_albedo, got.asymmetry, pub.asymmetry);
      w.extinction = std::max(w.extinction, std::abs(got.extinction_per_km / pub.extinction_per_km - 1.0));
      w.albedo = std::max(w.albedo, std::abs(got.single_scattering_albedo - pub.single_scattering_albedo));
      w.asymmetry = std::max(w.asymmetry, std::abs(got.asymmetry - pub.asymmetry));
    }
  return w;
}
}  // namespace

// The check: an OPAC component integrated over its size distribution reproduces OPAC's
// single-scattering albedo and asymmetry parameter at 550 nm within 0.005. Every component dry,
// and the water-soluble, sea-salt and sulfate components at 70 % humidity. The mineral coarse mode
// (micm) is the exception: g 0.8870 against OPAC's 0.895; ours is converged (halving both
// quadrature steps moves it by less than 1e-5), so the difference is OPAC's own integration of its
// coarsest particles; it gets 0.01. (Left to the release stage: the mixture below runs the same
// code under the sanitizers.)
BOOST_AUTO_TEST_CASE(components_reproduce_opac_at_550nm,
                     *boost::unit_test::precondition(test::not_in_sanitizer_stage)) {
  for (int c = 0; c < kAerosolComponentCount; ++c) {
    const std::string name = aerosol_component_names()[static_cast<size_t>(c)];
    const bool swells = name == "waso" || name == "ssam" || name == "suso";
    const Worst w = compare_with_opac(c, swells ? std::vector<int>{0, 70} : std::vector<int>{0}, {550.0});
    BOOST_TEST(w.extinction < 0.01, name << ": extinction off by " << w.extinction);
    BOOST_TEST(w.albedo < 0.005, name << ": albedo off by " << w.albedo);
    BOOST_TEST(w.asymmetry < (name == "micm" ? 0.01 : 0.005), name << ": g off by " << w.asymmetry);
  }
}

// OPAC's "continental polluted" mixture at 80 % humidity (0.6 insoluble, 15700 water-soluble and
// 34300 soot particles per cm^3), as OPAC 3.1 printed it: extinction 0.1746 km^-1, scattering
// 0.1558 km^-1, albedo 0.8925, g 0.6977 at 550 nm (the OPAC run published by IPSL's ETHER centre,
// forge.ipsl.jussieu.fr/ether/export/1/trunk/hftp/iasi/aerosol/opac_calc/copo).
BOOST_AUTO_TEST_CASE(a_mixture_reproduces_opac) {
  AerosolMixture mix;
  mix.number_per_cm3[0] = 0.6;
  mix.number_per_cm3[1] = 15700.0;
  mix.number_per_cm3[2] = 34300.0;
  mix.relative_humidity_percent = 80.0;
  const AerosolMixtureOptics o = aerosol_mixture_optics(mix, WavelengthGrid::from_list({550.0}), "test");
  const double ext = o.extinction_per_m[0] * 1e3, sca = o.scattering_per_m[0] * 1e3;
  std::printf(
      "continental polluted, 80 %%, 550 nm: extinction %.4f km^-1 (OPAC 0.1746), albedo %.4f (0.8925), g %.4f "
      "(0.6977)\n",
      ext, sca / ext, o.matrix->asymmetry(0));
  BOOST_TEST(std::abs(ext / 0.1746 - 1.0) < 0.01);
  BOOST_TEST(std::abs(sca / ext - 0.8925) < 0.005);
  // g of the tabulated matrix (its piecewise-linear phase function), not of the series.
  BOOST_TEST(std::abs(o.matrix->asymmetry(0) - 0.6977) < 0.005);
}

BOOST_AUTO_TEST_CASE(humidity_and_wavelength_interpolation) {
  const int waso = 1;
  // At OPAC's humidities, OPAC's own radius and index; between them, in between.
  const AerosolComponentState at70 = aerosol_component_state(waso, 70.0, 550.0, "k");
  const AerosolComponentState at80 = aerosol_component_state(waso, 80.0, 550.0, "k");
  const AerosolComponentState at75 = aerosol_component_state(waso, 75.0, 550.0, "k");
  BOOST_TEST(at70.median_radius_m == 0.0285e-6, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(at70.m_real == 1.414, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(at75.median_radius_m == 0.5 * (at70.median_radius_m + at80.median_radius_m),
             boost::test_tools::tolerance(1e-12));
  // Between OPAC's wavelengths 500 and 550 nm (1.415 and 1.414 at 70 %).
  BOOST_TEST(aerosol_component_state(waso, 70.0, 525.0, "k").m_real == 1.4145, boost::test_tools::tolerance(1e-12));
  // A component that takes up no water is the same at every humidity.
  BOOST_TEST(aerosol_component_state(2, 95.0, 550.0, "k").median_radius_m ==
             aerosol_component_state(2, 0.0, 550.0, "k").median_radius_m);
  // Out of range: the key and what is allowed.
  try {
    aerosol_component_state(waso, 99.5, 550.0, "atmosphere.mie.opac.relative_humidity_percent");
    BOOST_FAIL("99.5 % accepted");
  } catch (const InputError& e) {
    BOOST_TEST(std::string(e.what()).find("atmosphere.mie.opac.relative_humidity_percent") != std::string::npos);
    BOOST_TEST(std::string(e.what()).find("<= 99") != std::string::npos);
  }
  BOOST_CHECK_THROW(aerosol_component_state(waso, 50.0, 240.0, "k"), InputError);
  AerosolMixture none;
  BOOST_CHECK_THROW(aerosol_mixture_optics(none, WavelengthGrid::from_list({550.0}), "k"), InputError);
}

// The tabulated matrix: its phase function integrates to 1 and has the series' g (to the
// tabulation's error), the Monte Carlo's sampling draws from exactly it, and its polarisation is
// the ensemble's at the nodes.
BOOST_AUTO_TEST_CASE(tabulated_matrix_is_one_consistent_function) {
  const AerosolMixture mix = AerosolMixture::continental_average();
  const WavelengthGrid grid = WavelengthGrid::from_list({450.0, 650.0});
  const AerosolMixtureOptics o = aerosol_mixture_optics(mix, grid, "test");
  const TabulatedScatteringMatrix& t = *o.matrix;
  std::vector<double> x, w;
  // Composite Gauss-Legendre on each tabulated interval: exact for the piecewise-linear function.
  gauss_legendre(2, 0.0, 1.0, x, w);
  for (int i = 0; i < 2; ++i) {
    double norm = 0.0, mean = 0.0, mean2 = 0.0;
    for (size_t k = 0; k + 1 < t.mu().size(); ++k) {
      const double a = t.mu()[k], h = t.mu()[k + 1] - a;
      for (size_t q = 0; q < x.size(); ++q) {
        const double mu = a + h * x[q], p = 2.0 * kPi * t.phase(i, mu) * h * w[q];
        norm += p;
        mean += p * mu;
        mean2 += p * mu * mu;
      }
    }
    BOOST_TEST(norm == 1.0, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(mean == t.asymmetry(i), boost::test_tools::tolerance(1e-10));
    // Sampling: the mean and mean square of a million draws within 5 standard errors.
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const int n = 1000000;
    double s1 = 0.0, s2 = 0.0;
    for (int k = 0; k < n; ++k) {
      const double mu = t.sample_mu(i, u(rng));
      s1 += mu;
      s2 += mu * mu;
    }
    const double var = mean2 - mean * mean;
    BOOST_TEST(std::abs(s1 / n - mean) < 5.0 * std::sqrt(var / n));
    BOOST_TEST(std::abs(s2 / n - mean2) < 5.0 * std::sqrt(1.0 / n));
    // Polarisation: -b1 / a1 at 90 degrees is positive (perpendicular, as Rayleigh's) for these
    // small particles, and between -1 and 1 everywhere.
    for (double mu : t.mu()) {
      const SphereMatrixElements e = t.elements(i, mu);
      BOOST_TEST(std::abs(e.b1) <= e.a1 * (1.0 + 1e-9));
    }
    const SphereMatrixElements side = t.elements(i, 0.0);
    BOOST_TEST(-side.b1 / side.a1 > 0.1);
  }
  // The table's g against the series' g of the same mixture, per wavelength: the tabulation's error.
  for (int i = 0; i < 2; ++i) {
    double sca = 0.0, g_sca = 0.0;
    for (int c = 0; c < kAerosolComponentCount; ++c) {
      if (!(mix.number_per_cm3[static_cast<size_t>(c)] > 0.0)) continue;
      const AerosolComponentState s = aerosol_component_state(c, mix.relative_humidity_percent, grid.nm(i), "test");
      const SizeDistribution sizes = SizeDistribution::lognormal(s.median_radius_m, s.geometric_standard_deviation)
                                         .truncated(s.min_radius_m, s.max_radius_m);
      const SphereEnsembleOptics e = sphere_ensemble_optics(sizes, {s.m_real, s.m_imag}, grid.nm(i) * 1e-9, 1.0, {1.0});
      const double c_sca = mix.number_per_cm3[static_cast<size_t>(c)] * aerosol_component_fraction_in_range(s) *
                           e.scattering_cross_section_m2;
      sca += c_sca;
      g_sca += c_sca * e.asymmetry;
    }
    std::printf("%g nm: g of the table %.5f, of the series %.5f\n", grid.nm(i), t.asymmetry(i), g_sca / sca);
    BOOST_TEST(std::abs(t.asymmetry(i) - g_sca / sca) < 2e-3);
  }
}

// Every humidity and wavelength of OPAC's table (250-2500 nm) against OPAC: minutes, so not in
// the test command; bench/opac_components.sh runs it and docs/validation.md has its worst values.
boost::test_tools::assertion_result asked_for_by_the_benchmark(boost::unit_test::test_unit_id) {
  boost::test_tools::assertion_result result(std::getenv("SKYSPEC_BENCH_OPAC") != nullptr);
  result.message() << "run by bench/opac_components.sh (SKYSPEC_BENCH_OPAC is not set)";
  return result;
}

BOOST_AUTO_TEST_CASE(all_opac_tables,
                     *boost::unit_test::disabled() * boost::unit_test::precondition(asked_for_by_the_benchmark)) {
  const std::vector<int> humidities = {0, 50, 70, 80, 90, 95, 98, 99};
  const std::vector<double> wavelengths = {250, 300, 350, 400,  450,  500,  550,  600,  650, 700,
                                           750, 800, 900, 1000, 1250, 1500, 1750, 2000, 2500};
  for (int c = 0; c < kAerosolComponentCount; ++c) {
    const Worst w = compare_with_opac(c, humidities, wavelengths);
    std::printf("| %s (%s) | %.2f %% | %.4f | %.4f |\n", aerosol_component_names()[static_cast<size_t>(c)],
                aerosol_component_description(c).c_str(), 100.0 * w.extinction, w.albedo, w.asymmetry);
  }
}

BOOST_AUTO_TEST_SUITE_END()
