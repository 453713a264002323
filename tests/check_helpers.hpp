// Small helpers the test suites share: relative differences and the setting an InputError names.
#pragma once

#include <cmath>
#include <functional>
#include <string>

#include "skyspec/error.hpp"

namespace skyspec::test {

/// |a - b| / |b|: the relative difference of a value from a reference.
inline double relative(double a, double b) { return std::abs(a - b) / std::abs(b); }

/// The setting (scene key or option) named by the InputError that f throws, or "(no error)".
inline std::string error_setting(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.setting();
  }
  return "(no error)";
}

/// The message of the InputError that f throws ("" if it throws none).
inline std::string input_error_message(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace skyspec::test
