// The forward peak cut off a tabulated scattering matrix (truncate_forward_peak) and the scaled
// atmosphere built with it (AtmosphereModel::with_forward_peaks_truncated): the share cut against
// the closed form for a Henyey-Greenstein function, the function unchanged outside the cone, its
// polarisation unchanged inside, and the scaled coefficients keeping absorption.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "skyspec/atmosphere.hpp"
#include "skyspec/spectrum.hpp"
#include "skyspec/tabulated_scattering.hpp"
#include "skyspec/units.hpp"

using namespace skyspec;

namespace {

double henyey_greenstein(double g, double mu) {
  return (1.0 - g * g) / (4.0 * kPi * std::pow(1.0 + g * g - 2.0 * g * mu, 1.5));
}

// 2 pi times the integral of HG over [-1, mu]: (1 - g^2) / (2 g) (1 / sqrt(1 + g^2 - 2 g mu) - 1 / (1 + g)).
double henyey_greenstein_below(double g, double mu) {
  return (1.0 - g * g) / (2.0 * g) * (1.0 / std::sqrt(1.0 + g * g - 2.0 * g * mu) - 1.0 / (1.0 + g));
}

// HG of asymmetries gs (one row per wavelength) on nodes even in the scattering angle, with a
// polarisation b1 = -0.3 (1 - mu^2) a1 and a3 = mu a1, b2 = 0.1 (1 - mu^2) a1.
TabulatedScatteringMatrix henyey_greenstein_table(const std::vector<double>& gs, int nodes) {
  std::vector<double> mu(static_cast<size_t>(nodes));
  for (int k = 0; k < nodes; ++k) mu[static_cast<size_t>(k)] = -std::cos(kPi * k / (nodes - 1));
  mu.front() = -1.0;
  mu.back() = 1.0;
  std::vector<std::vector<double>> a1, b1, a3, b2;
  for (double g : gs) {
    std::vector<double> p, q, r, t;
    for (double m : mu) {
      const double a = henyey_greenstein(g, m);
      p.push_back(a);
      q.push_back(-0.3 * (1.0 - m * m) * a);
      r.push_back(m * a);
      t.push_back(0.1 * (1.0 - m * m) * a);
    }
    a1.push_back(p);
    b1.push_back(q);
    a3.push_back(r);
    b2.push_back(t);
  }
  return TabulatedScatteringMatrix(mu, a1, b1, a3, b2);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(test_forward_truncation)

BOOST_AUTO_TEST_CASE(share_cut_from_henyey_greenstein_is_the_closed_form) {
  const std::vector<double> gs = {0.5, 0.85, 0.95};
  const TabulatedScatteringMatrix table = henyey_greenstein_table(gs, 40001);
  for (double cone_deg : {3.0, 10.0, 25.0}) {
    const double cone = cone_deg * kPi / 180.0, mu_c = std::cos(cone);
    const TruncatedScatteringMatrix cut = truncate_forward_peak(table, cone);
    for (size_t i = 0; i < gs.size(); ++i) {
      const double g = gs[i];
      // What stays: the function below the cone, and its value at the edge across the cone.
      const double kept = henyey_greenstein_below(g, mu_c) + 2.0 * kPi * henyey_greenstein(g, mu_c) * (1.0 - mu_c);
      BOOST_TEST_MESSAGE("g " << g << ", cone " << cone_deg << " deg: cut " << cut.removed[i] << ", closed form "
                              << 1.0 - kept);
      BOOST_TEST(cut.removed[i] == 1.0 - kept, boost::test_tools::tolerance(1e-4));
      // The scaled asymmetry: g = (1 - f) g* + (what the cut took, at cosines between mu_c and 1),
      // so (1 - f) g* + f mu_c <= g <= (1 - f) g* + f.
      const double f = cut.removed[i], g_star = cut.matrix->asymmetry(static_cast<int>(i));
      const double g_table = table.asymmetry(static_cast<int>(i));
      BOOST_TEST(g_table >= (1.0 - f) * g_star + f * mu_c - 1e-12);
      BOOST_TEST(g_table <= (1.0 - f) * g_star + f + 1e-12);
    }
  }
}

BOOST_AUTO_TEST_CASE(outside_the_cone_nothing_changes_and_inside_the_polarisation_stays) {
  const TabulatedScatteringMatrix table = henyey_greenstein_table({0.9}, 2001);
  const double cone = 10.0 * kPi / 180.0, mu_c = std::cos(cone);
  const TruncatedScatteringMatrix cut = truncate_forward_peak(table, cone);
  const double f = cut.removed[0];
  BOOST_TEST(f > 0.1);
  BOOST_TEST(f < 0.9);
  // The cone's edge is a node of the cut table.
  bool edge = false;
  for (double m : cut.matrix->mu()) edge = edge || m == mu_c;
  BOOST_TEST(edge);
  const SphereMatrixElements at_edge = table.elements(0, mu_c);
  for (int k = 0; k <= 400; ++k) {
    const double mu = -1.0 + 2.0 * k / 400.0;
    const SphereMatrixElements before = table.elements(0, mu), after = cut.matrix->elements(0, mu);
    if (mu <= mu_c) {
      // Renormalised by 1 / (1 - f): (1 - f) times the cut function is the function.
      BOOST_TEST((1.0 - f) * after.a1 == before.a1, boost::test_tools::tolerance(1e-9));
      BOOST_TEST((1.0 - f) * after.b1 == before.b1, boost::test_tools::tolerance(1e-9));
    } else {
      BOOST_TEST((1.0 - f) * after.a1 == at_edge.a1, boost::test_tools::tolerance(1e-9));
    }
    // Each element's ratio to a1 (the polarisation of scattered light) is the table's, to the
    // interpolation between nodes.
    BOOST_TEST(after.b1 / after.a1 == before.b1 / before.a1, boost::test_tools::tolerance(2e-3));
    BOOST_TEST(after.a3 / after.a1 == before.a3 / before.a1, boost::test_tools::tolerance(2e-3));
  }
  BOOST_CHECK_THROW(truncate_forward_peak(table, 0.0), std::invalid_argument);
  BOOST_CHECK_THROW(truncate_forward_peak(table, kPi), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(scaled_atmosphere_keeps_absorption_and_the_other_media) {
  const WavelengthGrid grid = WavelengthGrid::from_list({450.0, 650.0});
  AtmosphereSpec spec;
  const AtmosphereModel clear(spec, grid);
  // No tabulated matrix (the default scene's analytic aerosol): nothing to cut.
  BOOST_TEST(!clear.with_forward_peaks_truncated(0.1).has_value());
  AtmosphereModel foggy = clear;
  Medium fog;
  fog.name = "test_fog";
  fog.profile = make_profile(ProfileKind::Exponential, 100.0, spec.top_altitude_m);
  fog.scattering_per_m = SpectrumD::Constant(2, 1e-3);
  fog.extinction_per_m = SpectrumD::Constant(2, 1.2e-3);
  fog.phase.kind = MediumPhase::Kind::Tabulated;
  fog.phase.matrix = std::make_shared<const TabulatedScatteringMatrix>(henyey_greenstein_table({0.8, 0.9}, 4001));
  foggy.add_medium(fog);
  const std::optional<AtmosphereModel> scaled = foggy.with_forward_peaks_truncated(5.0 * kPi / 180.0);
  BOOST_REQUIRE(scaled.has_value());
  BOOST_REQUIRE(scaled->media().size() == foggy.media().size());
  for (size_t j = 0; j < foggy.media().size(); ++j) {
    const Medium &a = foggy.media()[j], &b = scaled->media()[j];
    if (a.name != "test_fog") {
      BOOST_TEST((a.scattering_per_m - b.scattering_per_m).abs().maxCoeff() == 0.0);
      BOOST_TEST((a.extinction_per_m - b.extinction_per_m).abs().maxCoeff() == 0.0);
      continue;
    }
    const TruncatedScatteringMatrix cut = truncate_forward_peak(*a.phase.matrix, 5.0 * kPi / 180.0);
    for (int i = 0; i < 2; ++i) {
      const double f = cut.removed[static_cast<size_t>(i)];
      BOOST_TEST(b.scattering_per_m[i] == (1.0 - f) * a.scattering_per_m[i], boost::test_tools::tolerance(1e-12));
      // Absorption is untouched: extinction less scattering is the same before and after.
      BOOST_TEST(b.extinction_per_m[i] - b.scattering_per_m[i] == a.extinction_per_m[i] - a.scattering_per_m[i],
                 boost::test_tools::tolerance(1e-9));
      BOOST_TEST(b.phase.g[i] == b.phase.matrix->asymmetry(i));
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
