// A tabulated scattering matrix's means over ranges of the scattering cosine
// (TabulatedScatteringMatrix::add_mean_phases, add_mean_b1s): what a direction of the scattering-order
// tables' coarse quadrature takes for a sharp matrix (integrate_order). Against the interpolant
// integrated finely, over the whole sphere (the normalisation) and across a ring narrower than any
// coarse sampling would see.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <utility>
#include <vector>

#include "skyspec/tabulated_scattering.hpp"
#include "skyspec/units.hpp"

using namespace skyspec;

namespace {

// A flat function with a ring 0.2 wide in mu about mu = 0.3 that carries `ring` of the light
// (before normalisation), polarised b1 = -0.5 a1 on the ring and 0 elsewhere; two wavelengths,
// the second without the ring.
TabulatedScatteringMatrix ringed_table(double ring) {
  const std::vector<double> mu = {-1.0, 0.0, 0.199, 0.2, 0.3, 0.4, 0.401, 1.0};
  std::vector<double> with_ring, flat(mu.size(), 1.0), b1(mu.size(), 0.0), zero(mu.size(), 0.0);
  for (double m : mu) with_ring.push_back(m == 0.3 ? 1.0 + ring / 0.1 : 1.0);
  for (size_t k = 0; k < mu.size(); ++k) b1[k] = mu[k] == 0.3 ? -0.5 * with_ring[k] : 0.0;
  return TabulatedScatteringMatrix(mu, {with_ring, flat}, {b1, zero}, {zero, zero}, {zero, zero});
}

// The mean of the interpolant over [lo, hi] by the trapezoidal rule on 200 000 points.
double fine_mean(const TabulatedScatteringMatrix& m, int i, double lo, double hi, bool b1) {
  const int n = 200000;
  double sum = 0.0;
  for (int k = 0; k <= n; ++k) {
    const double mu = lo + (hi - lo) * k / n;
    const TabulatedScatteringMatrix::Position p = m.locate(mu);
    const double v = b1 ? m.b1(i, p) : m.phase(i, p);
    sum += (k == 0 || k == n) ? 0.5 * v : v;
  }
  return sum / n;
}

// Wavelength i's mean of a1 (or b1) over [lo, hi], as the quadrature takes it (single precision).
double mean(const TabulatedScatteringMatrix& m, int i, double lo, double hi, bool b1) {
  std::vector<float> out(static_cast<size_t>(m.wavelengths()), 0.0f);
  if (b1)
    m.add_mean_b1s(m.locate(lo), m.locate(hi), 1.0, out.data());
  else
    m.add_mean_phases(m.locate(lo), m.locate(hi), 1.0, out.data());
  return out[static_cast<size_t>(i)];
}

}  // namespace

BOOST_AUTO_TEST_SUITE(test_tabulated_scattering)

BOOST_AUTO_TEST_CASE(means_are_the_interpolants_integrals) {
  const TabulatedScatteringMatrix m = ringed_table(0.2);
  // Over the sphere: 2 pi integral a1 dmu = 1, a mean of 1 / (4 pi). The means are single precision.
  for (int i = 0; i < 2; ++i)
    BOOST_TEST(mean(m, i, -1.0, 1.0, false) == 1.0 / (4.0 * kPi), boost::test_tools::tolerance(1e-6));
  for (const auto& [lo, hi] : {std::pair{-0.7, 0.25}, std::pair{0.21, 0.39}, std::pair{0.25, 0.3}, std::pair{0.0, 1.0}})
    for (int i = 0; i < 2; ++i) {
      BOOST_TEST(mean(m, i, lo, hi, false) == fine_mean(m, i, lo, hi, false), boost::test_tools::tolerance(1e-6));
      BOOST_TEST(std::abs(mean(m, i, lo, hi, true) - fine_mean(m, i, lo, hi, true)) < 1e-8);
    }
  // A range of no width: the value there.
  BOOST_TEST(mean(m, 0, 0.25, 0.25, false) == m.phase(0, 0.25), boost::test_tools::tolerance(1e-6));
  // The weight scales what is added.
  std::vector<float> out(2, 1.0f);
  m.add_mean_phases(m.locate(-1.0), m.locate(1.0), 0.5, out.data());
  BOOST_TEST(out[0] == 1.0 + 0.5 / (4.0 * kPi), boost::test_tools::tolerance(1e-6));
}

// A coarse sampling at mu = -0.5, 0, 0.5 and 1 sees no ring; the means over the ranges about those
// cosines carry it whole: the ring's share of the normalised function, 0.2 / 2.2 of 1 / (2 pi).
BOOST_AUTO_TEST_CASE(a_ring_between_samples_counts_in_the_means) {
  const TabulatedScatteringMatrix m = ringed_table(0.2);
  const double samples[] = {-0.5, 0.0, 0.5, 1.0}, edges[] = {-1.0, -0.25, 0.25, 0.75, 1.0};
  double sampled = 0.0, averaged = 0.0, without = 0.0;
  for (int k = 0; k < 4; ++k) {
    const double width = edges[k + 1] - edges[k];
    sampled += width * m.phase(0, samples[k]);
    averaged += width * mean(m, 0, edges[k], edges[k + 1], false);
    without += width * mean(m, 1, edges[k], edges[k + 1], false);
  }
  BOOST_TEST(2.0 * kPi * averaged == 1.0, boost::test_tools::tolerance(1e-6));
  BOOST_TEST(2.0 * kPi * without == 1.0, boost::test_tools::tolerance(1e-6));
  BOOST_TEST(2.0 * kPi * sampled == 2.0 / 2.2, boost::test_tools::tolerance(1e-12));  // the ring missed
}

BOOST_AUTO_TEST_SUITE_END()
