#include <boost/test/unit_test.hpp>

#include <csignal>
#include <vector>

#include "atmosphere_fixtures.hpp"
#include "base/cancellation.hpp"
#include "transport/multiple_scattering.hpp"

BOOST_AUTO_TEST_SUITE(test_cancellation)

using namespace skyspec;

namespace {
// Clears the request whatever the test does, so that no other test sees it.
struct ClearAfter {
  ~ClearAfter() { clear_cancellation_request(); }
};
}  // namespace

BOOST_AUTO_TEST_CASE(a_request_is_seen_by_the_next_check) {
  ClearAfter clear;
  BOOST_CHECK_NO_THROW(throw_if_cancelled());
  request_cancellation(SIGTERM);
  BOOST_TEST(cancellation_requested() == SIGTERM);
  try {
    throw_if_cancelled();
    BOOST_FAIL("no exception");
  } catch (const Cancelled& e) {
    BOOST_TEST(e.signal_number() == SIGTERM);
    BOOST_TEST(e.exit_code() == 143);
    BOOST_TEST(std::string(e.what()).find("SIGTERM") != std::string::npos);
  }
  clear_cancellation_request();
  BOOST_CHECK_NO_THROW(throw_if_cancelled());
}

// The scattering-order tables (the longest stage of a render) stop at the request, from inside
// TBB's parallel loop, and the exception reaches the caller.
BOOST_AUTO_TEST_CASE(the_scattering_tables_stop_when_cancelled) {
  ClearAfter clear;
  const AtmosphereSpec spec =
      test::simple_atmosphere(ProfileKind::Exponential, 60e3, test::kSeedNm, test::kSeedBetaRayleigh, 21e-6);
  const test::IntegratorChain chain(spec, test::kSeedNm, {32, 64, 64}, 16);
  MultipleScatteringSettings ms;
  ms.orders = 3;
  ms.altitude_samples = 8;
  ms.sun_samples = 8;
  BOOST_CHECK_NO_THROW(ScatteringOrders(chain.integrator, ms));
  request_cancellation(SIGINT);
  BOOST_CHECK_THROW(ScatteringOrders(chain.integrator, ms), Cancelled);
}

// The estimate of a table build: 0 for single scattering; finite, positive and growing with the
// orders otherwise (what it costs is measured, so only its shape is tested).
BOOST_AUTO_TEST_CASE(the_build_estimate_scales_with_the_orders) {
  const AtmosphereSpec spec =
      test::simple_atmosphere(ProfileKind::Exponential, 60e3, test::kSeedNm, test::kSeedBetaRayleigh, 21e-6);
  const test::IntegratorChain chain(spec, test::kSeedNm, {32, 64, 64}, 16);
  MultipleScatteringSettings ms;
  ms.orders = 1;
  BOOST_TEST(ScatteringOrders::estimate_build_seconds(chain.integrator, ms) == 0.0);
  ms.orders = 2;
  ms.altitude_samples = 256;
  ms.sun_samples = 512;
  const double two = ScatteringOrders::estimate_build_seconds(chain.integrator, ms);
  ms.orders = 50;
  const double fifty = ScatteringOrders::estimate_build_seconds(chain.integrator, ms);
  BOOST_TEST(std::isfinite(two));
  BOOST_TEST(two > 0.0);
  BOOST_TEST(fifty > 3 * two);  // 49 orders of a comparable cost each, not one
}

BOOST_AUTO_TEST_SUITE_END()
