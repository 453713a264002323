// A precondition for test cases left to the release stage of scripts/test.sh: the sanitizer stage
// sets SKYSPEC_SANITIZER_STAGE, and a case whose code the other cases run under the sanitizers but
// which takes long there (converged tables, many Monte Carlo paths) is skipped, saying why; and one
// for the benchmarks' own cases.
#pragma once

#include <boost/test/unit_test.hpp>

#include <cstdlib>

namespace skyspec::test {

inline boost::test_tools::assertion_result not_in_sanitizer_stage(boost::unit_test::test_unit_id) {
  boost::test_tools::assertion_result result(std::getenv("SKYSPEC_SANITIZER_STAGE") == nullptr);
  result.message() << "left to the release stage (SKYSPEC_SANITIZER_STAGE is set)";
  return result;
}

/// A precondition for a benchmark's own test case (disabled by default): it runs when the benchmark
/// script sets `variable`, and says which script does otherwise.
inline auto asked_for_by(const char* variable, const char* script) {
  return [variable, script](boost::unit_test::test_unit_id) {
    boost::test_tools::assertion_result result(std::getenv(variable) != nullptr);
    result.message() << "run by " << script << " (" << variable << " is not set)";
    return result;
  };
}

}  // namespace skyspec::test
