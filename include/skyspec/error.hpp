// Errors that skyspec reports to its users.
//
// InputError is for anything the user asked for that cannot be done: it names the setting (a scene
// key such as "atmosphere.rayleigh.scale_height_m", or a neutral id of another setting such as
// "display.view" that each front end respells as it names it: the CLI "--view", Python "view"), the
// offending value, what is allowed, and where the value came from (file:line:column or the flag).
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace skyspec {

/// Base class of every exception skyspec throws on purpose.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A user-supplied value is wrong. what() is a complete, human-readable sentence.
class InputError : public Error {
 public:
  InputError(std::string setting, std::string value, std::string allowed, std::string origin = {});
  /// A setting that does not exist: "<origin>: unknown key "<key>"<hint>".
  static InputError unknown_key(std::string key, std::string hint, std::string origin);
  /// A request refused as a whole (e.g. a render too big for the disk): what() is `message`.
  static InputError refused(std::string setting, std::string message);
  /// The same error as a front end words it: every neutral setting id of `spellings` (first: the
  /// library's id, e.g. "display.view"; second: the front end's word for it, e.g. "--view" or
  /// "view") is replaced wherever it stands as a whole word, in setting() and in what().
  InputError respelled(const std::vector<std::pair<std::string, std::string>>& spellings) const;
  const std::string& setting() const { return setting_; }
  const std::string& value() const { return value_; }
  const std::string& allowed() const { return allowed_; }
  const std::string& origin() const { return origin_; }

 private:
  struct Composed {};
  InputError(Composed, std::string message, std::string setting, std::string origin);
  std::string setting_, value_, allowed_, origin_;
};

/// Reading or writing a file failed (I/O, format).
class IoError : public Error {
 public:
  using Error::Error;
};

}  // namespace skyspec
