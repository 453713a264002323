// The kinds of scene key: a number with a unit and a range, a whole number, a switch, a choice of
// words, a text or file name, a 3-vector, a list of numbers, a TOML date-time. Each makes a KeyDef
// (key_registry.hpp) that checks what it is given, names the key, the value and what is allowed, and
// writes the value back as TOML text that reads back to the same stored value.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "base/text_format.hpp"
#include "scene/key_registry.hpp"

namespace skyspec::scene_keys {

/// A closed (or left-open) interval of allowed numbers.
struct Range {
  double lo, hi;
  bool lo_open = false;
  /// ">= lo and <= hi" (or "> lo ...").
  std::string bounds() const {
    std::ostringstream s;
    s << (lo_open ? "> " : ">= ") << format_number(lo) << " and <= " << format_number(hi);
    return s.str();
  }
  /// "a number in <unit>, >= lo and <= hi".
  std::string describe(const std::string& unit) const {
    return "a number" + (unit.empty() ? std::string() : " in " + unit) + ", " + bounds();
  }
  bool contains(double v) const { return std::isfinite(v) && (lo_open ? v > lo : v >= lo) && v <= hi; }
};

double get_number(const KeyDef& k, const toml::node& n, const std::string& origin, const std::string& allowed);
KeyDef number_key(std::string key, std::string unit, Range range, std::string help, std::function<double&(Scene&)> ref,
                  double scale = 1.0);
/// A number that may be absent (then the scene writes no value for it).
KeyDef optional_number_key(std::string key, std::string unit, Range range, std::string help,
                           std::function<std::optional<double>&(Scene&)> ref);
KeyDef integer_key(std::string key, long lo, long hi, std::string help, std::function<int&(Scene&)> ref);
KeyDef bool_key(std::string key, std::string help, std::function<bool&(Scene&)> ref);
KeyDef choice_key(std::string key, std::vector<std::string> choices, std::string help,
                  std::function<void(Scene&, const std::string&)> set_value,
                  std::function<std::string(const Scene&)> get_value);
KeyDef text_key(std::string key, std::string help, std::function<std::string&(Scene&)> ref, bool file_name_only);
KeyDef vec3_key(std::string key, std::string unit, double bound, std::string help, std::function<Vec3&(Scene&)> ref);
KeyDef list_key(std::string key, std::string unit, Range range, size_t max_count, std::string help,
                std::function<std::vector<double>&(Scene&)> ref);
std::string toml_date_time_text(const toml::date_time& t, const std::string& key, const std::string& value,
                                const std::string& origin);
std::string exact_number(double stored_value, double scale = 1.0);
size_t edit_distance(const std::string& a, const std::string& b);

}  // namespace skyspec::scene_keys
