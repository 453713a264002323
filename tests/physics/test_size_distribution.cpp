// Size distributions against their closed forms: the moments <r^k> of the lognormal, the modified
// gamma and Marshall-Palmer's exponential, Marshall-Palmer's concentration and liquid water
// content, truncation, and bad parameters.

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <stdexcept>

#include "skyspec/size_distribution.hpp"
#include "skyspec/units.hpp"

BOOST_AUTO_TEST_SUITE(test_size_distribution)

using namespace skyspec;

namespace {
double relative(double ours, double theirs) { return std::abs(ours / theirs - 1.0); }
}  // namespace

// <r^k> = r_m^k exp(k^2 s^2 / 2), s = ln sigma; OPAC's water-soluble and mineral (coarse) modes.
BOOST_AUTO_TEST_CASE(lognormal_moments) {
  for (const auto& [r_m, sigma] : {std::pair{0.0212e-6, 2.24}, {1.9e-6, 2.0}, {0.5e-6, 1.05}}) {
    const SizeDistribution d = SizeDistribution::lognormal(r_m, sigma);
    const double s = std::log(sigma);
    for (int k = 0; k <= 3; ++k)
      BOOST_TEST(relative(d.moment(k), std::pow(r_m, k) * std::exp(0.5 * k * k * s * s)) < 1e-8,
                 "r_m " << r_m << ", sigma " << sigma << ", k " << k);
    // The density is the formula's (normalised over the range, which holds all but 1e-10).
    const double r = 1.3 * r_m;
    const double formula = std::exp(-0.5 * std::pow(std::log(r / r_m) / s, 2)) / (std::sqrt(2.0 * kPi) * r * s);
    BOOST_TEST(relative(d.density_per_m(r), formula) < 1e-8);
    BOOST_TEST(d.number_per_m3() == 0.0);
  }
}

// <r^k> = B^(-k/gamma) Gamma((alpha + k + 1) / gamma) / Gamma((alpha + 1) / gamma), and the
// density's maximum at the mode radius; Deirmendjian's cloud C.1 (r_c = 4 um, alpha 6, gamma 1)
// and haze M (0.05 um, 1, 0.5).
BOOST_AUTO_TEST_CASE(modified_gamma_moments_and_mode) {
  for (const auto& [r_c, alpha, gamma] : {std::tuple{4e-6, 6.0, 1.0}, {0.05e-6, 1.0, 0.5}, {10e-6, 3.0, 2.0}}) {
    const SizeDistribution d = SizeDistribution::modified_gamma(r_c, alpha, gamma);
    const double b = alpha / (gamma * std::pow(r_c, gamma));
    for (int k = 0; k <= 3; ++k) {
      const double closed = std::pow(b, -k / gamma) *
                            std::exp(std::lgamma((alpha + k + 1.0) / gamma) - std::lgamma((alpha + 1.0) / gamma));
      BOOST_TEST(relative(d.moment(k), closed) < 1e-8, "r_c " << r_c << ", k " << k);
    }
    BOOST_TEST(d.density_per_m(r_c) > d.density_per_m(r_c * 1.01));
    BOOST_TEST(d.density_per_m(r_c) > d.density_per_m(r_c * 0.99));
  }
}

// Marshall & Palmer: N0 / Lambda drops per m^3, <r^k> = k! / (2 Lambda)^k, and the liquid water
// content pi rho_w N0 / Lambda^4 = 0.0889 R^0.84 g m^-3 (from N0 = 8000 m^-3 mm^-1, Lambda = 4.1 R^-0.21 mm^-1).
BOOST_AUTO_TEST_CASE(marshall_palmer_rain) {
  for (double rate : {1.0, 5.0, 25.0}) {
    const SizeDistribution d = SizeDistribution::marshall_palmer(rate);
    const double lambda = 4.1e3 * std::pow(rate, -0.21);
    BOOST_TEST(relative(d.number_per_m3(), 8e6 / lambda) < 1e-12);
    double factorial = 1.0;
    for (int k = 0; k <= 3; ++k) {
      if (k > 0) factorial *= k;
      BOOST_TEST(relative(d.moment(k), factorial / std::pow(2.0 * lambda, k)) < 1e-8, "R " << rate << ", k " << k);
    }
    const double water_g_per_m3 = 1e6 * 4.0 / 3.0 * kPi * d.moment(3) * d.number_per_m3();
    BOOST_TEST(relative(water_g_per_m3, 0.08894 * std::pow(rate, 0.84)) < 1e-3);
  }
}

// A truncated distribution holds one particle in its range and, for rain, only the drops there.
BOOST_AUTO_TEST_CASE(truncation) {
  const SizeDistribution rain = SizeDistribution::marshall_palmer(5.0);
  const SizeDistribution cut = rain.truncated(0.05e-3, 1e-3);
  BOOST_TEST(relative(cut.moment(0), 1.0) < 1e-10);
  const double c = 2.0 * 4.1e3 * std::pow(5.0, -0.21);  // dN/dr ~ exp(-c r)
  const double inside = std::exp(-c * 0.05e-3) - std::exp(-c * 1e-3);
  BOOST_TEST(relative(cut.number_per_m3(), rain.number_per_m3() * inside) < 1e-8);
  BOOST_TEST(cut.density_per_m(2e-3) == 0.0);
  BOOST_TEST(cut.description().find("radii") != std::string::npos);
}

// A lognormal population without its far tails: cut at median * s^(+-k), renormalised.
BOOST_AUTO_TEST_CASE(lognormal_within_spreads) {
  const double median = 1e-5, s = 1.5;
  const SizeDistribution cut = SizeDistribution::lognormal_within(median, s, 3.0);
  BOOST_TEST(relative(cut.min_radius_m(), median / (s * s * s)) < 1e-12);
  BOOST_TEST(relative(cut.max_radius_m(), median * s * s * s) < 1e-12);
  BOOST_TEST(relative(cut.moment(0), 1.0) < 1e-10);
  // Within the cut the density is the whole distribution's over its share inside, erf(3 / sqrt 2).
  const SizeDistribution whole = SizeDistribution::lognormal(median, s);
  const double inside = std::erf(3.0 / std::sqrt(2.0));
  for (double r : {median / 2.0, median, median * 2.5})
    BOOST_TEST(relative(cut.density_per_m(r), whole.density_per_m(r) / inside) < 1e-6);
  BOOST_TEST(cut.density_per_m(median * 4.0) == 0.0);
  BOOST_CHECK_THROW(SizeDistribution::lognormal_within(median, s, 0.0), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(bad_parameters_are_refused) {
  BOOST_CHECK_THROW(SizeDistribution::lognormal(0.0, 2.0), std::invalid_argument);
  BOOST_CHECK_THROW(SizeDistribution::lognormal(1e-6, 1.0), std::invalid_argument);
  BOOST_CHECK_THROW(SizeDistribution::lognormal(std::nan(""), 2.0), std::invalid_argument);
  BOOST_CHECK_THROW(SizeDistribution::modified_gamma(1e-6, 0.0, 1.0), std::invalid_argument);
  BOOST_CHECK_THROW(SizeDistribution::modified_gamma(1e-6, 2.0, -1.0), std::invalid_argument);
  BOOST_CHECK_THROW(SizeDistribution::marshall_palmer(0.0), std::invalid_argument);
  BOOST_CHECK_THROW(SizeDistribution::marshall_palmer(1e4), std::invalid_argument);
  BOOST_CHECK_THROW(SizeDistribution::marshall_palmer(5.0).truncated(1e-3, 1e-4), std::invalid_argument);
  try {
    SizeDistribution::lognormal(1e-6, 0.5);
    BOOST_FAIL("no error");
  } catch (const std::invalid_argument& e) {
    BOOST_TEST(std::string(e.what()).find("geometric standard deviation = 0.5") != std::string::npos);
  }
}

BOOST_AUTO_TEST_SUITE_END()
