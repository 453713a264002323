// Quadrature rules (base/quadrature.hpp): Gauss-Legendre is exact to degree 2n - 1 on any
// interval and returns the same nodes however often it is asked (its roots are found once per n);
// the trapezoid rule is exact for straight lines.
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

BOOST_AUTO_TEST_CASE(trapezoid_is_exact_for_lines) {
  const std::vector<double> x{400.0, 410.0, 435.0, 500.0}, y{1.0, 1.5, 2.75, 6.0};  // y = 1 + (x - 400) / 20
  BOOST_TEST(trapezoid(x.data(), y.data(), x.size()) == 100.0 + (100.0 * 100.0 / 40.0),
             boost::test_tools::tolerance(1e-14));
  BOOST_TEST(trapezoid(x.data(), y.data(), 1) == 0.0);
  BOOST_TEST(trapezoid(x.data(), y.data(), 0) == 0.0);
}

BOOST_AUTO_TEST_SUITE_END()
