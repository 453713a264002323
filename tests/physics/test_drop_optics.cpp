// Rain drops by geometric optics (issue 39): the bows at Descartes' angles, red outside in the
// primary and inside in the secondary, Alexander's dark band, and every share of the light.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <numeric>
#include <vector>

#include "check_helpers.hpp"
#include "skyspec/drop_optics.hpp"
#include "skyspec/units.hpp"
#include "skyspec/water.hpp"

BOOST_AUTO_TEST_SUITE(test_drop_optics)

using namespace skyspec;

namespace {
// The share of the interval [t, t + 1] tenths of a degree of scattering angle.
double share_at(const std::vector<double>& s, int tenths) { return s[static_cast<size_t>(1800 - tenths - 1)]; }
double water_index(double nm) { return water_refractive_index(283.15, liquid_water_density_kg_per_m3(283.15), nm); }
}  // namespace

// Descartes' angles from the closed form: 137.9 and 129.1 degrees at n = 1.333 (the reference's
// 42.1 and about 51 degrees from the antisolar point).
BOOST_AUTO_TEST_CASE(descartes_angles) {
  BOOST_TEST(radians_to_degrees(descartes_scattering_angle(1.333, 1)) == 137.92, boost::test_tools::tolerance(2e-4));
  BOOST_TEST(180.0 - radians_to_degrees(descartes_scattering_angle(1.333, 2)) == 50.9,
             boost::test_tools::tolerance(2e-3));
}

// The primary bow's bright side ends at Descartes' angle (the function is brightest in the 0.1
// degree interval that holds it, or the next, and drops by 10 times on its other side), the
// secondary's likewise from the other side; red deviates less (primary: red outside); Alexander's
// band between them darker than either side; all but 1e-4 of the light accounted for.
BOOST_AUTO_TEST_CASE(bows_at_descartes_angles) {
  const std::vector<double> mu = test::tenth_degree_cosines();
  double primary_previous = 0.0;
  for (double nm : {400.0, 550.0, 700.0}) {
    const double n = water_index(nm);
    const std::vector<double> s = drop_geometric_scattering(n, mu);
    const double p = radians_to_degrees(descartes_scattering_angle(n, 1));
    const double q = radians_to_degrees(descartes_scattering_angle(n, 2));
    const int tp = static_cast<int>(std::floor(10.0 * p)), tq = static_cast<int>(std::floor(10.0 * q));
    BOOST_TEST_MESSAGE(nm << " nm: n " << n << ", primary at " << p << ", secondary at " << q << " degrees");
    // Primary: brightest in the interval that holds D_1 or the next one above it (inside the bow,
    // towards the antisolar point: the caustic's light lies beyond the Descartes angle), none below.
    double brightest = 0.0;
    int at = 0;
    for (int t = tp - 20; t <= tp + 20; ++t)
      if (share_at(s, t) > brightest) {
        brightest = share_at(s, t);
        at = t;
      }
    BOOST_TEST((at == tp || at == tp + 1), "brightest at " << 0.1 * at << " degrees");
    BOOST_TEST(share_at(s, tp) > 10.0 * share_at(s, tp - 2));
    // Secondary: light at angles below D_2 (outside it), little above.
    BOOST_TEST(share_at(s, tq) > 10.0 * share_at(s, tq + 2));
    // Alexander's band: between the bows less light than just inside the primary and just outside the secondary.
    const double band = share_at(s, (tp + tq) / 2);
    BOOST_TEST(band < 0.2 * share_at(s, tp + 5));
    BOOST_TEST(band < 0.5 * share_at(s, tq - 5));
    if (primary_previous > 0.0) BOOST_TEST(p < primary_previous);  // blue deviates more: red outside
    primary_previous = p;
    const double total = std::accumulate(s.begin(), s.end(), 0.0);
    BOOST_TEST(total <= 1.0);
    BOOST_TEST(total > 1.0 - 1e-4);  // what stays inside after kMaxDropReflections
  }
}

// The bows' polarisation: the primary bow's light (its brightest 0.1-degree interval) more than 90 %
// polarised perpendicular to the scattering plane (tangentially to the bow; the reference's
// "above 90 %"), the secondary's too; every interval a valid matrix, P12^2 + P33^2 <= P11^2 (each
// ray's light is fully polarised, a sum of them no more); P33 near -P11 straight back (a sphere's
// backscatter: exactly -P11 for the rays at normal incidence).
BOOST_AUTO_TEST_CASE(bows_are_polarised) {
  const std::vector<double> mu = test::tenth_degree_cosines();
  const double n = water_index(550.0);
  const DropMatrixShares m = drop_geometric_matrix(n, mu);
  const int tp = static_cast<int>(std::floor(10.0 * radians_to_degrees(descartes_scattering_angle(n, 1))));
  const int tq = static_cast<int>(std::floor(10.0 * radians_to_degrees(descartes_scattering_angle(n, 2))));
  const auto dolp = [&](int t) { return -share_at(m.p12, t) / share_at(m.p11, t); };
  const int brightest = share_at(m.p11, tp) > share_at(m.p11, tp + 1) ? tp : tp + 1;
  BOOST_TEST_MESSAGE("degree of polarisation: primary " << dolp(brightest) << ", secondary " << dolp(tq));
  BOOST_TEST(dolp(brightest) > 0.9);
  BOOST_TEST(dolp(tq) > 0.7);
  for (size_t j = 0; j < m.p11.size(); ++j)
    BOOST_TEST(m.p12[j] * m.p12[j] + m.p33[j] * m.p33[j] <= m.p11[j] * m.p11[j] * (1.0 + 1e-12));
  BOOST_TEST(m.p33.front() < 0.0);                    // the interval next to 180 degrees
  BOOST_TEST(-m.p33.front() / m.p11.front() > 0.85);  // rays of several orders end there
}

BOOST_AUTO_TEST_SUITE_END()
