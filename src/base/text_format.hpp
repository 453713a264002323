// Number formatting for messages and reports (internal).
#pragma once

#include <cstdio>
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
