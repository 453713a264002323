// Quadrature rules (base/quadrature.hpp): Gauss-Legendre is exact to degree 2n - 1 on any
// interval and returns the same nodes however often it is asked (its roots are found once per n);
// the graded rule (a panel at one end) is a Gauss-Legendre rule on each of its two intervals and
// beats the plain rule of as many nodes where the integrand is steep at that end; the trapezoid
// rule is exact for straight lines.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <vector>

#include "base/quadrature.hpp"

BOOST_AUTO_TEST_SUITE(test_quadrature)

using namespace skyspec;

BOOST_AUTO_TEST_CASE(gauss_legendre_is_exact_to_degree_2n_minus_1) {
  for (int n : {1, 2, 5, 16, 64}) {
    std::vector<double> x, w;
    gauss_legendre(n, -0.5, 2.0, x, w);
    BOOST_TEST(x.size() == static_cast<size_t>(n));
    for (int degree : {0, 1, 2 * n - 1}) {
      double sum = 0.0;
      for (int i = 0; i < n; ++i) sum += w[static_cast<size_t>(i)] * std::pow(x[static_cast<size_t>(i)], degree);
      const double exact = (std::pow(2.0, degree + 1) - std::pow(-0.5, degree + 1)) / (degree + 1);
      BOOST_TEST(sum == exact, boost::test_tools::tolerance(1e-12));
    }
    std::vector<double> again_x, again_w;
    gauss_legendre(n, -0.5, 2.0, again_x, again_w);
    BOOST_TEST(again_x == x);
    BOOST_TEST(again_w == w);
  }
  std::vector<double> x{1.0}, w{1.0};
  gauss_legendre(0, 0.0, 1.0, x, w);
  BOOST_TEST(x.empty());
  BOOST_TEST(w.empty());
}

BOOST_AUTO_TEST_CASE(graded_gauss_legendre_is_two_rules_and_wins_at_its_steep_end) {
  const double a = -0.2, b = 1.0;
  for (PanelEnd end : {PanelEnd::lower, PanelEnd::upper}) {
    std::vector<double> x, w;
    graded_gauss_legendre(12, 4, 0.05, end, a, b, x, w);
    BOOST_TEST_REQUIRE(x.size() == 16u);
    for (size_t i = 0; i < x.size(); ++i) {
      BOOST_TEST((x[i] > a && x[i] < b));
      if (i > 0) BOOST_TEST(x[i] < x[i - 1]);
    }
    // Four nodes in the panel, whichever end it is at.
    const double split = end == PanelEnd::lower ? a + 0.05 : b - 0.05;
    int in_panel = 0;
    for (double xi : x) in_panel += end == PanelEnd::lower ? xi < split : xi > split;
    BOOST_TEST(in_panel == 4);
    // Exact to degree 2 min(12, 4) - 1 = 7.
    for (int degree : {0, 1, 7}) {
      double sum = 0.0;
      for (size_t i = 0; i < x.size(); ++i) sum += w[i] * std::pow(x[i], degree);
      BOOST_TEST(sum == (std::pow(b, degree + 1) - std::pow(a, degree + 1)) / (degree + 1),
                 boost::test_tools::tolerance(1e-12));
    }
    // The light of a layer of optical thickness 0.02 seen at a distance t = |x - end| from the
    // steep end, 1 - exp(-0.02 / t) (a line of sight at zenith cosine t crosses 0.02 / t); its
    // integral over [0, L] is L (1 - E2(0.02 / L)), E2(z) = exp(-z) - z E1(z), E1(z) = -Ei(-z).
    const double e = end == PanelEnd::lower ? a : b, tau = 0.02, z = tau / (b - a);
    const auto f = [&](double xi) { return 1.0 - std::exp(-tau / std::abs(xi - e)); };
    const double exact = (b - a) * (1.0 - (std::exp(-z) + z * std::expint(-z)));
    std::vector<double> px, pw;
    gauss_legendre(16, a, b, px, pw);
    double graded = 0.0, plain = 0.0;
    for (size_t i = 0; i < x.size(); ++i) {
      graded += w[i] * f(x[i]);
      plain += pw[i] * f(px[i]);
    }
    BOOST_TEST_MESSAGE("graded " << graded / exact - 1 << ", plain " << plain / exact - 1);
    BOOST_TEST(std::abs(graded / exact - 1) < 0.2 * std::abs(plain / exact - 1));
  }
  // No panel: the plain rule.
  std::vector<double> x, w, px, pw;
  graded_gauss_legendre(8, 0, 0.1, PanelEnd::lower, a, b, x, w);
  gauss_legendre(8, a, b, px, pw);
  BOOST_TEST(x == px);
  BOOST_TEST(w == pw);
}

BOOST_AUTO_TEST_CASE(trapezoid_is_exact_for_lines) {
  const std::vector<double> x{400.0, 410.0, 435.0, 500.0}, y{1.0, 1.5, 2.75, 6.0};  // y = 1 + (x - 400) / 20
  BOOST_TEST(trapezoid(x.data(), y.data(), x.size()) == 100.0 + (100.0 * 100.0 / 40.0),
             boost::test_tools::tolerance(1e-14));
  BOOST_TEST(trapezoid(x.data(), y.data(), 1) == 0.0);
  BOOST_TEST(trapezoid(x.data(), y.data(), 0) == 0.0);
}

BOOST_AUTO_TEST_SUITE_END()
