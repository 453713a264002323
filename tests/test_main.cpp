// The one Boost.Test module of skyspec's C++ tests: every tests/<layer>/test_<name>.cpp is a test
// suite of it (BOOST_AUTO_TEST_SUITE(<name>)), registered with CTest as test_<name>
// (skyspec_tests --run_test=<name>).
#define BOOST_TEST_MODULE skyspec
#include <boost/test/unit_test.hpp>
