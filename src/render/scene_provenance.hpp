// What a render of a scene records about how it was made (io/provenance.hpp names the attributes
// and reads them back): the version, the effective scene as TOML and the embedded data tables the
// scene reads. Knowing which tables a scene reads needs the scene, so it lives here, above io.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "io/provenance.hpp"
#include "skyspec/scene.hpp"

namespace skyspec {

/// The embedded tables (paths below data/) a render of the scene reads: the CIE 1931 observer
/// (spectral path), the ASTM G173 sun (sun.spectrum = "solar"), the ozone cross-sections (ozone
/// on), the solar position tables (sun.date_time set) and, when builtin_display_config, skyspec's
/// OpenColorIO config (a PNG or a working-space EXR through the built-in config).
std::vector<std::string> data_tables_used(const Scene& scene, bool builtin_display_config);

/// The skyspec:data text: EmbeddedTableInfo::describe() of each table, one per line.
std::string data_tables_text(const Scene& scene, bool builtin_display_config);

/// skyspec:version, skyspec:scene and skyspec:data for a render of the scene.
std::map<std::string, std::string> provenance_attributes(const Scene& scene, bool builtin_display_config);

}  // namespace skyspec
