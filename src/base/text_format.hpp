// Number formatting for messages and reports (internal).
#pragma once

#include <iomanip>
#include <sstream>
#include <string>

namespace skyspec {

/// A number as a person would type it back: up to 10 significant digits, no trailing zeros.
inline std::string format_number(double v) {
  std::ostringstream s;
  s << std::setprecision(10) << v;
  return s.str();
}

}  // namespace skyspec
