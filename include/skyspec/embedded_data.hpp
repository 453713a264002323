// Data files compiled into the library (see cmake/EmbedData.cmake and data/README.md).
#pragma once
#include <string_view>
#include <utility>
#include <vector>

namespace skyspec {
/// All embedded files as (path below data/, content) pairs, e.g. ("scenes/default.toml", "...").
const std::vector<std::pair<std::string_view, std::string_view>>& embedded_files();
/// The content of one embedded file; throws skyspec::Error if there is none by that name.
std::string_view embedded_file(std::string_view path_below_data);
}  // namespace skyspec
