// The command line's words for the library's neutral setting ids (display.view -> --view, ...):
// the library names what was wrong in its own terms (skyspec/display.hpp, skyspec/scene.hpp,
// render/render_budget.hpp, render/display_conversion.hpp, report/comparison_report.hpp) and the
// CLI words every error as its user typed it. Scene keys (camera.width) are the same everywhere
// and are not respelled.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "skyspec/error.hpp"

namespace skyspec::cli {

/// Neutral id -> flag (or argument name), one row per setting a command-line flag sets.
const std::vector<std::pair<std::string, std::string>>& cli_spellings();

/// The error as the command line words it.
inline InputError in_cli_words(const InputError& e) { return e.respelled(cli_spellings()); }

}  // namespace skyspec::cli
