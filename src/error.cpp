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

}  // namespace skyspec
