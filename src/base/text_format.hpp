// Number formatting for messages and reports (internal).
#pragma once

#include <cstdio>
#include <cstdlib>
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

/// A number with every digit it needs to read back as the same double ("%.17g"): values that
/// travel as text (job parameters, TOML written for the scene loader).
inline std::string format_exact(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

/// A number as format_number writes it when that reads back as the same double, else with the
/// fewest more digits that do (0.1, not 0.10000000000000001; 6360000, not 6.36e+06): a value
/// echoed to the person who typed it. "nan" and "inf" as such.
inline std::string format_shortest(double v) {
  std::string text;
  for (int digits = 10; digits <= 17; ++digits) {
    std::ostringstream s;
    s << std::setprecision(digits) << v;
    text = s.str();
    if (!(v == v) || std::strtod(text.c_str(), nullptr) == v) break;
  }
  return text;
}

/// A number with a fixed number of decimals ("%.*f").
inline std::string format_fixed(double v, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, v);
  return text;
}

/// Text for a cell of a Markdown table: '|' escaped as "\\|".
inline std::string markdown_cell(std::string text) {
  for (std::size_t at = text.find('|'); at != std::string::npos; at = text.find('|', at + 2))
    text.replace(at, 1, "\\|");
  return text;
}

}  // namespace skyspec
