// Small helpers the test suites share: relative differences and the setting an InputError names.
#pragma once

#include <cmath>
#include <functional>
#include <string>
#include <vector>

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

/// Cosines every 0.1 degree of scattering angle, ascending from -1 to 1: interval k from the
/// forward end is [k, k + 1] tenths of a degree.
inline std::vector<double> tenth_degree_cosines() {
  std::vector<double> mu;
  for (int k = 1800; k >= 0; --k) mu.push_back(std::cos(k * 0.1 * 3.14159265358979323846 / 180.0));
  mu.front() = -1.0;
  mu.back() = 1.0;
  return mu;
}

}  // namespace skyspec::test
