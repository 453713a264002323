#include "skyspec/error.hpp"

#include <utility>

namespace skyspec {
namespace {
std::string compose(const std::string& setting, const std::string& value, const std::string& allowed,
                    const std::string& origin) {
  std::string msg;
  if (!origin.empty()) msg += origin + ": ";
  msg += setting + " = " + value + " is not allowed: " + allowed;
  return msg;
}
}  // namespace

InputError::InputError(std::string setting, std::string value, std::string allowed, std::string origin)
    : Error(compose(setting, value, allowed, origin)),
      setting_(std::move(setting)),
      value_(std::move(value)),
      allowed_(std::move(allowed)),
      origin_(std::move(origin)) {}

InputError::InputError(Composed, std::string message, std::string setting, std::string origin)
    : Error(std::move(message)), setting_(std::move(setting)), origin_(std::move(origin)) {}

InputError InputError::unknown_key(std::string key, std::string hint, std::string origin) {
  std::string msg;
  if (!origin.empty()) msg += origin + ": ";
  msg += "unknown key \"" + key + "\"" + hint;
  return InputError(Composed{}, std::move(msg), std::move(key), std::move(origin));
}

InputError InputError::refused(std::string setting, std::string message) {
  return InputError(Composed{}, std::move(message), std::move(setting), {});
}

}  // namespace skyspec
