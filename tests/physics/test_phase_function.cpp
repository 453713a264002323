#include <boost/test/unit_test.hpp>

#include <cmath>
#include <functional>

#include "skyspec/phase_function.hpp"
#include "skyspec/units.hpp"

BOOST_AUTO_TEST_SUITE(test_phase_function)

using namespace skyspec;

namespace {
// Integral over the sphere of f(mu) (azimuthally symmetric): 2 pi int_{-1}^{1} f dmu, by
// composite Simpson on 20000 intervals (phase functions are smooth for |g| <= 0.95).
double sphere_integral(const std::function<double(double)>& f) {
  const int n = 20000;
  const double h = 2.0 / n;
  double sum = f(-1) + f(1);
  for (int i = 1; i < n; ++i) sum += f(-1 + i * h) * (i % 2 ? 4 : 2);
  return 2 * kPi * sum * h / 3;
}
}  // namespace

BOOST_AUTO_TEST_CASE(rayleigh_integrates_to_one) {
  BOOST_TEST(sphere_integral(rayleigh_phase) == 1.0, boost::test_tools::tolerance(1e-9));
}

BOOST_AUTO_TEST_CASE(henyey_greenstein_integrates_to_one_and_has_mean_cosine_g) {
  for (double g : {-0.5, 0.0, 0.3, 0.76, 0.9}) {
    BOOST_TEST(sphere_integral([g](double mu) { return henyey_greenstein_phase(mu, g); }) == 1.0,
               boost::test_tools::tolerance(1e-7));
    // The asymmetry parameter is the mean cosine of the scattering angle.
    BOOST_TEST(sphere_integral([g](double mu) { return mu * henyey_greenstein_phase(mu, g); }) == g,
               boost::test_tools::tolerance(1e-6));
  }
  BOOST_TEST(henyey_greenstein_phase(0.3, 0.0) == 1 / (4 * kPi), boost::test_tools::tolerance(1e-14));
}

BOOST_AUTO_TEST_CASE(cornette_shanks_integrates_to_one) {
  for (double g : {-0.5, 0.0, 0.5, 0.76, 0.9}) {
    BOOST_TEST(sphere_integral([g](double mu) { return cornette_shanks_phase(mu, g); }) == 1.0,
               boost::test_tools::tolerance(1e-7));
  }
  // With g = 0 it reduces to the Rayleigh phase function.
  BOOST_TEST(cornette_shanks_phase(0.4, 0.0) == rayleigh_phase(0.4), boost::test_tools::tolerance(1e-14));
}

BOOST_AUTO_TEST_CASE(forward_peak_for_positive_g) {
  const AerosolPhase p{AerosolPhase::Model::CornetteShanks, 0.76};
  BOOST_TEST(p(1.0) > 100 * p(-1.0));
  const AerosolPhase hg{AerosolPhase::Model::HenyeyGreenstein, 0.76};
  BOOST_TEST(hg(1.0) == (1 + 0.76) / (4 * kPi * (1 - 0.76) * (1 - 0.76)), boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_SUITE_END()  // test_phase_function
