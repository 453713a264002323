#include "skyspec/embedded_data.hpp"

#include <string>

#include "skyspec/error.hpp"

namespace skyspec {
std::string_view embedded_file(std::string_view path_below_data) {
  for (const auto& [name, content] : embedded_files())
    if (name == path_below_data) return content;
  throw Error("no embedded data file named '" + std::string(path_below_data) + "'");
}
}  // namespace skyspec
