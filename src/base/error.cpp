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

bool id_char(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'; }

// Every whole-word occurrence of an id replaced by its spelling (the longest id first where one
// is a prefix of another: "display.exposure.ev" before a hypothetical "display.exposure").
std::string respell(const std::string& text, const std::vector<std::pair<std::string, std::string>>& spellings) {
  std::string out;
  size_t i = 0;
  while (i < text.size()) {
    const std::pair<std::string, std::string>* best = nullptr;
    const bool starts_word = i == 0 || (!id_char(text[i - 1]) && text[i - 1] != '.' && text[i - 1] != '-');
    if (starts_word) {
      for (const auto& s : spellings) {
        const std::string& id = s.first;
        if (id.empty() || text.compare(i, id.size(), id) != 0) continue;
        const size_t end = i + id.size();
        const bool ends_word =
            end == text.size() ||
            (!id_char(text[end]) && !(text[end] == '.' && end + 1 < text.size() && id_char(text[end + 1])));
        if (ends_word && (!best || id.size() > best->first.size())) best = &s;
      }
    }
    if (best) {
      out += best->second;
      i += best->first.size();
    } else {
      out += text[i++];
    }
  }
  return out;
}
}  // namespace

InputError InputError::respelled(const std::vector<std::pair<std::string, std::string>>& spellings) const {
  if (!allowed_.empty() || !value_.empty())
    return InputError(respell(setting_, spellings), value_, respell(allowed_, spellings), origin_);
  return InputError(Composed{}, respell(what(), spellings), respell(setting_, spellings), origin_);
}

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
