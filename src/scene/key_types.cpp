// The kinds of scene key (key_types.hpp) and the value formatting they share.
#include "scene/key_types.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include <toml++/toml.h>

#include "base/embedded_data.hpp"
#include "base/text_format.hpp"
#include "physics/date_time.hpp"
#include "physics/ozone.hpp"
#include "physics/solar_position.hpp"
#include "physics/solar_spectrum.hpp"
#include "scene/toml_limits.hpp"
#include "skyspec/error.hpp"
#include "skyspec/refractive_index.hpp"
#include "skyspec/units.hpp"

namespace skyspec::scene_keys {

// ---------------------------------------------------------------------------------------------
// Value formatting
// ---------------------------------------------------------------------------------------------
// Value formatting

std::string node_text(const toml::node& n) {
  std::ostringstream s;
  if (auto str = n.as_string()) {
    s << '"' << str->get() << '"';
  } else if (auto arr = n.as_array()) {
    s << *arr;
  } else if (n.is_table()) {
    s << "(a table)";
  } else if (auto f = n.as_floating_point()) {
    s << format_shortest(f->get());
  } else {
    n.visit([&](auto&& v) { s << v; });
  }
  return s.str();
}

std::string origin_of(const toml::node& n, const std::string& fallback) {
  const auto& src = n.source();
  if (src.begin.line == 0) return fallback;
  std::ostringstream s;
  s << (src.path ? *src.path : fallback) << ":" << src.begin.line << ":" << src.begin.column;
  return s.str();
}

std::string origin_of_key(const toml::key& k, const std::string& fallback) {
  const auto& src = k.source();
  if (src.begin.line == 0) return fallback;
  std::ostringstream s;
  s << (src.path ? *src.path : fallback) << ":" << src.begin.line << ":" << src.begin.column;
  return s.str();
}

// A number for scene_to_toml that reads back as exactly the stored value: the shortest of 10 to 17
// significant digits whose value times scale is stored_value (so a scene written into a file's
// header and loaded again is the same scene, bit for bit).
std::string exact_number(double stored_value, double scale) {
  std::string text;
  for (int digits = 10; digits <= 17; ++digits) {
    std::ostringstream s;
    s << std::setprecision(digits) << stored_value / scale;
    text = s.str();
    if (std::strtod(text.c_str(), nullptr) * scale == stored_value) break;
  }
  return text;
}

// Levenshtein distance, for "did you mean".
size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

// ---------------------------------------------------------------------------------------------
// The key registry: one entry per scene key, with its unit, range, setter and getter.

double get_number(const KeyDef& k, const toml::node& n, const std::string& origin, const std::string& allowed) {
  if (auto i = n.as_integer()) return static_cast<double>(i->get());
  if (auto f = n.as_floating_point()) return f->get();
  throw InputError(k.key, node_text(n), allowed, origin);
}

// scale: the stored value is the entered value times scale (e.g. ppm -> parts per volume).
KeyDef number_key(std::string key, std::string unit, Range range, std::string help, std::function<double&(Scene&)> ref,
                  double scale) {
  KeyDef k;
  k.key = std::move(key);
  k.unit = unit;
  const std::string allowed = range.describe(unit);
  k.doc = "(" + allowed + ") " + help;
  k.set = [k, allowed, range, ref, scale](Scene& s, const toml::node& n, const std::string& origin) {
    const double v = get_number(k, n, origin, allowed);
    if (!range.contains(v)) throw InputError(k.key, node_text(n), allowed, origin);
    ref(s) = v * scale;
  };
  k.get = [ref, scale](const Scene& s) { return exact_number(ref(const_cast<Scene&>(s)), scale); };
  return k;
}

KeyDef optional_number_key(std::string key, std::string unit, Range range, std::string help,
                           std::function<std::optional<double>&(Scene&)> ref) {
  KeyDef k;
  k.key = std::move(key);
  k.unit = unit;
  const std::string allowed = range.describe(unit);
  k.doc = "(" + allowed + ") " + help;
  k.set = [k, allowed, range, ref](Scene& s, const toml::node& n, const std::string& origin) {
    const double v = get_number(k, n, origin, allowed);
    if (!range.contains(v)) throw InputError(k.key, node_text(n), allowed, origin);
    ref(s) = v;
  };
  k.get = [ref](const Scene& s) {
    const std::optional<double>& v = ref(const_cast<Scene&>(s));
    return v ? exact_number(*v) : std::string();
  };
  return k;
}

KeyDef integer_key(std::string key, long lo, long hi, std::string help, std::function<int&(Scene&)> ref) {
  KeyDef k;
  k.key = std::move(key);
  const std::string allowed = "a whole number from " + std::to_string(lo) + " to " + std::to_string(hi);
  k.doc = "(" + allowed + ") " + help;
  k.set = [k, allowed, lo, hi, ref](Scene& s, const toml::node& n, const std::string& origin) {
    auto i = n.as_integer();
    if (!i || i->get() < lo || i->get() > hi) throw InputError(k.key, node_text(n), allowed, origin);
    ref(s) = static_cast<int>(i->get());
  };
  k.get = [ref](const Scene& s) { return std::to_string(ref(const_cast<Scene&>(s))); };
  return k;
}

KeyDef bool_key(std::string key, std::string help, std::function<bool&(Scene&)> ref) {
  KeyDef k;
  k.key = std::move(key);
  k.doc = "(true or false) " + help;
  k.set = [k, ref](Scene& s, const toml::node& n, const std::string& origin) {
    auto b = n.as_boolean();
    if (!b) throw InputError(k.key, node_text(n), "true or false", origin);
    ref(s) = b->get();
  };
  k.get = [ref](const Scene& s) { return ref(const_cast<Scene&>(s)) ? std::string("true") : std::string("false"); };
  return k;
}

std::string join(const std::vector<std::string>& v, const std::string& sep) {
  std::string out;
  for (size_t i = 0; i < v.size(); ++i) out += (i ? sep : "") + v[i];
  return out;
}

// A string chosen from a list; conversion to the scene's type is done by the callbacks.
KeyDef choice_key(std::string key, std::vector<std::string> choices, std::string help,
                  std::function<void(Scene&, const std::string&)> set_value,
                  std::function<std::string(const Scene&)> get_value) {
  KeyDef k;
  k.key = std::move(key);
  k.text = true;
  const std::string allowed = "one of: " + join(choices, ", ");
  k.doc = "(" + allowed + ") " + help;
  k.set = [k, allowed, choices, set_value](Scene& s, const toml::node& n, const std::string& origin) {
    auto str = n.as_string();
    if (!str || std::find(choices.begin(), choices.end(), str->get()) == choices.end())
      throw InputError(k.key, node_text(n), allowed, origin);
    set_value(s, str->get());
  };
  k.get = [get_value](const Scene& s) { return "\"" + get_value(s) + "\""; };
  return k;
}

KeyDef text_key(std::string key, std::string help, std::function<std::string&(Scene&)> ref, bool file_name_only) {
  KeyDef k;
  k.key = std::move(key);
  k.text = true;
  // A file name leaves room for what is added to it: "-polarisation.exr" and a temporary's
  // ".tmp-<pid>-<64 bits in hex>" within the 255 bytes most file systems allow.
  constexpr std::size_t kMaxFileName = 200;
  const std::string allowed = file_name_only ? "a non-empty file name of at most " + std::to_string(kMaxFileName) +
                                                   " characters without '/' (letters, digits, '-', '_', '.')"
                                             : "a non-empty path";
  k.doc = "(" + allowed + ") " + help;
  k.set = [k, allowed, ref, file_name_only](Scene& s, const toml::node& n, const std::string& origin) {
    auto str = n.as_string();
    if (!str || str->get().empty()) throw InputError(k.key, node_text(n), allowed, origin);
    if (file_name_only) {
      const std::string& v = str->get();
      const bool ok = v != "." && v != ".." && v.size() <= kMaxFileName && std::all_of(v.begin(), v.end(), [](char c) {
                        return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
                      });
      if (!ok) throw InputError(k.key, node_text(n), allowed, origin);
    }
    ref(s) = str->get();
  };
  k.get = [ref](const Scene& s) {
    std::ostringstream o;
    o << toml::value<std::string>(ref(const_cast<Scene&>(s)));
    return o.str();
  };
  return k;
}

KeyDef vec3_key(std::string key, std::string unit, double bound, std::string help, std::function<Vec3&(Scene&)> ref) {
  KeyDef k;
  k.key = std::move(key);
  k.unit = unit;
  const std::string allowed = "an array of 3 numbers in " + unit + ", each within +-" + format_number(bound);
  k.doc = "(" + allowed + ") " + help;
  k.set = [k, allowed, bound, ref](Scene& s, const toml::node& n, const std::string& origin) {
    auto arr = n.as_array();
    if (!arr || arr->size() != 3) throw InputError(k.key, node_text(n), allowed, origin);
    Vec3 v;
    for (size_t i = 0; i < 3; ++i) {
      const double x = get_number(k, *arr->get(i), origin, allowed);
      if (!std::isfinite(x) || std::abs(x) > bound) throw InputError(k.key, node_text(n), allowed, origin);
      v[static_cast<int>(i)] = x;
    }
    ref(s) = v;
  };
  k.get = [ref](const Scene& s) {
    const Vec3& v = ref(const_cast<Scene&>(s));
    return "[" + exact_number(v[0]) + ", " + exact_number(v[1]) + ", " + exact_number(v[2]) + "]";
  };
  return k;
}

KeyDef list_key(std::string key, std::string unit, Range range, size_t max_count, std::string help,
                std::function<std::vector<double>&(Scene&)> ref) {
  KeyDef k;
  k.key = std::move(key);
  k.unit = unit;
  const std::string allowed = "an array of up to " + std::to_string(max_count) + " numbers, each " +
                              (unit.empty() ? std::string() : "in " + unit + ", ") + range.bounds();
  k.doc = "(" + allowed + ") " + help;
  k.set = [k, allowed, range, max_count, ref](Scene& s, const toml::node& n, const std::string& origin) {
    auto arr = n.as_array();
    if (!arr || arr->size() > max_count) throw InputError(k.key, node_text(n), allowed, origin);
    std::vector<double> v;
    for (size_t i = 0; i < arr->size(); ++i) {
      const double x = get_number(k, *arr->get(i), origin, allowed);
      if (!range.contains(x)) throw InputError(k.key, node_text(n), allowed, origin);
      v.push_back(x);
    }
    ref(s) = v;
  };
  k.get = [ref](const Scene& s) {
    const auto& v = ref(const_cast<Scene&>(s));
    std::string out = "[";
    for (size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + exact_number(v[i]);
    return out + "]";
  };
  return k;
}

// A TOML date-time (RFC 3339, unquoted in a scene file or after --set) as ISO 8601 text. It must
// carry its UTC offset: a local date-time, a date or a time alone names no instant.
std::string toml_date_time_text(const toml::date_time& t, const std::string& key, const std::string& value,
                                const std::string& origin) {
  if (!t.offset)
    throw InputError(key, value,
                     "a date-time with its UTC offset: add Z for UTC or the zone's offset such as +02:00 (a bare "
                     "local time is ambiguous)",
                     origin);
  DateTime d;
  d.year = t.date.year;
  d.month = t.date.month;
  d.day = t.date.day;
  d.hour = t.time.hour;
  d.minute = t.time.minute;
  d.second = t.time.second + t.time.nanosecond * 1e-9;
  d.utc_offset_hours = t.offset->minutes / 60.0;
  try {
    validate(d, key);
  } catch (const InputError& e) {
    throw InputError(key, value, e.allowed(), origin);
  }
  return to_iso8601(d);
}

}  // namespace skyspec::scene_keys
