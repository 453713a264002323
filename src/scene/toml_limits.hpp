// Limits on TOML text, checked before any text reaches the parser.
//
// toml++ parses nested arrays, inline tables and dotted keys recursively, so a key of 70 000 dotted
// parts or a header 40 000 tables deep overflows the stack (a crash, not an error). Every TOML
// text skyspec reads (scene files, --set values, the skyspec:scene header of an EXR, Python's
// scene_toml) passes check_toml_limits() first: a lexical scan, linear in the text, that knows
// strings and comments and measures the size, the bracket nesting and the parts of dotted keys.
// A scene needs far less than the limits (its deepest key has 3 parts, its deepest value 2
// brackets).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace skyspec {

/// Largest TOML text accepted (bytes). The default scene is about 10 kB.
inline constexpr std::size_t kMaxTomlBytes = 1u << 20;
/// Deepest nesting of arrays, inline tables and table headers ("[[a]]" counts 2).
inline constexpr int kMaxTomlNesting = 32;
/// Most parts of one dotted key ("a.b.c" has 3).
inline constexpr int kMaxTomlKeyParts = 32;

/// Throws InputError naming `setting` and `origin` (with line:column) if `text` is larger, nests
/// deeper or has longer dotted keys than the limits above. Text that is not valid TOML is left to
/// the parser.
void check_toml_limits(std::string_view text, const std::string& setting, const std::string& origin);

}  // namespace skyspec
