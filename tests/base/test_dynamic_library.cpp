// Libraries opened on first use (src/base/dynamic_library.hpp): a missing one is an error naming it
// and what needs it; a present one gives its functions, the same handle each time.
#include <boost/test/unit_test.hpp>

#include <string>

#include "base/dynamic_library.hpp"
#include "skyspec/error.hpp"

BOOST_AUTO_TEST_SUITE(test_dynamic_library)

using namespace skyspec;

BOOST_AUTO_TEST_CASE(a_missing_library_names_itself_and_its_purpose) {
  try {
    open_shared_library("libskyspec-no-such-library.so.7", "testing the loader");
    BOOST_FAIL("no error");
  } catch (const Error& e) {
    const std::string what = e.what();
    BOOST_TEST(what.find("libskyspec-no-such-library.so.7") != std::string::npos);
    BOOST_TEST(what.find("testing the loader") != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(a_present_library_gives_its_functions) {
  void* libm = open_shared_library("libm.so.6", "testing the loader");
  BOOST_TEST(libm == open_shared_library("libm.so.6", "testing the loader"));
  using Floor = double (*)(double);
  const auto floor_of = reinterpret_cast<Floor>(shared_library_symbol(libm, "libm.so.6", "floor"));
  BOOST_TEST(floor_of(2.75) == 2.0);
  BOOST_CHECK_THROW(shared_library_symbol(libm, "libm.so.6", "skyspec_no_such_function"), Error);
}

BOOST_AUTO_TEST_SUITE_END()
