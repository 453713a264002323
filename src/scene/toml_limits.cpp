#include "scene/toml_limits.hpp"

#include "skyspec/error.hpp"

namespace skyspec {
namespace {

// Where a limit was exceeded, as "origin:line:column".
std::string position(const std::string& origin, std::string_view text, std::size_t at) {
  int line = 1, column = 1;
  for (std::size_t i = 0; i < at && i < text.size(); ++i) {
    if (text[i] == '\n')
      ++line, column = 1;
    else
      ++column;
  }
  return origin + ":" + std::to_string(line) + ":" + std::to_string(column);
}

}  // namespace

void check_toml_limits(std::string_view text, const std::string& setting, const std::string& origin) {
  if (text.size() > kMaxTomlBytes)
    throw InputError::refused(setting, origin + ": " + std::to_string(text.size()) +
                                           " bytes of TOML; skyspec reads at most " +
                                           std::to_string(kMaxTomlBytes >> 20) + " MiB");
  int depth = 0, dots = 0;
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n; ++i) {
    const char c = text[i];
    if (c == '#') {  // a comment, to the end of the line
      while (i < n && text[i] != '\n') ++i;
      dots = 0;
      continue;
    }
    if (c == '"' || c == '\'') {  // a string: basic or literal, single- or multi-line
      const bool multi = text.substr(i, 3) == std::string(3, c);
      const std::size_t open = multi ? 3 : 1;
      i += open;
      while (i < n) {
        if (c == '"' && text[i] == '\\') {
          i += 2;
          continue;
        }
        if (!multi && text[i] == '\n') break;  // unterminated: the parser says so
        if (text[i] == c && (!multi || text.substr(i, 3) == std::string(3, c))) {
          i += open - 1;
          break;
        }
        ++i;
      }
      continue;
    }
    switch (c) {
      case '[':
      case '{':
        if (++depth > kMaxTomlNesting)
          throw InputError::refused(setting, position(origin, text, i) + ": arrays, inline tables or table headers " +
                                                 "nested more than " + std::to_string(kMaxTomlNesting) +
                                                 " deep; skyspec reads TOML nested at most " +
                                                 std::to_string(kMaxTomlNesting) + " deep");
        dots = 0;
        break;
      case ']':
      case '}':
        if (depth > 0) --depth;
        dots = 0;
        break;
      case '.':
        if (++dots >= kMaxTomlKeyParts)
          throw InputError::refused(
              setting, position(origin, text, i) + ": a dotted key of more than " + std::to_string(kMaxTomlKeyParts) +
                           " parts; skyspec reads keys of at most " + std::to_string(kMaxTomlKeyParts) + " parts");
        break;
      case '=':
      case ',':
      case '\n':
        dots = 0;
        break;
      default:
        break;
    }
  }
}

}  // namespace skyspec
