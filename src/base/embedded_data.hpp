// Data files compiled into the library (see cmake/EmbedData.cmake and data/README.md).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace skyspec {
/// All embedded files as (path below data/, content) pairs, e.g. ("scenes/default.toml", "...").
const std::vector<std::pair<std::string_view, std::string_view>>& embedded_files();
/// The content of one embedded file; throws skyspec::Error if there is none by that name.
std::string_view embedded_file(std::string_view path_below_data);

/// The FNV-1a 64 offset basis: the hash of no bytes.
inline constexpr std::uint64_t kFnv1a64Basis = 0xcbf29ce484222325ull;
/// FNV-1a, 64 bit, of bytes (a content fingerprint, not a cryptographic hash). Bytes hashed in
/// pieces give the same result when each piece starts from the hash of the ones before.
std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t hash = kFnv1a64Basis);

/// What an output file says about one embedded data table: its path below data/, where its
/// numbers come from (the source and version data/README.md states for it), and the size and
/// FNV-1a 64 hash of the bytes actually compiled in.
struct EmbeddedTableInfo {
  std::string path;
  std::string source;
  std::size_t bytes = 0;
  std::uint64_t fnv1a64 = 0;
  /// "cie/cie1931_2deg_5nm.csv  fnv1a64=0123456789abcdef  bytes=4052  <source>"
  std::string describe() const;
};
/// The entry of one embedded file; throws skyspec::Error if there is none by that name.
EmbeddedTableInfo embedded_table_info(std::string_view path_below_data);
}  // namespace skyspec
