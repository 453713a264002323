// The outputs of an RGB-fast vs spectral comparison (`skyspec compare`): a Markdown report for
// people, a JSON report for programs, a false-colour Delta E map with a colour bar, a side-by-side
// preview and, for a sweep over sun elevations, a plot. Everything is drawn by skyspec itself.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "colour/display_pipeline.hpp"
#include "skyspec/sky_comparison.hpp"

namespace skyspec {

/// Everything a report says.
struct ComparisonRun {
  std::string command;        ///< how to make it again
  std::string scene_summary;  ///< e.g. "preset seed, fisheye 64 x 64, sun 2 deg"
  std::string reference_label, test_label;
  double sun_elevation_deg = 0;
  RegionSettings regions;
  std::vector<std::string> notes;  ///< twin construction, sun disk, ...
  SkyComparison comparison;        ///< at the scene's sun elevation
  std::vector<SweepPoint> sweep;   ///< empty: no sweep
  double delta_e_max = 10;         ///< top of the map's colour bar
  /// Names of the figures beside the report (empty: not written).
  std::string delta_e_map_file, side_by_side_file, sweep_plot_file;
};

std::string comparison_markdown(const ComparisonRun& run);
std::string comparison_json(const ComparisonRun& run);
/// Mean and 95th percentile Delta E_00 of all compared pixels and the mean of each region against
/// sun elevation, as a standalone SVG file.
std::string sweep_plot_svg(const std::vector<SweepPoint>& sweep);

/// The neutral id of delta_e_max, as InputErrors name it (the CLI's --delta-e-max).
inline constexpr const char* kDeltaEMaxSetting = "comparison.delta_e_max";

/// The Delta E_00 map (cubehelix colour map from 0 to delta_e_max, a colour bar with ticks, pixels
/// not compared drawn as a grey checkerboard) as an 8-bit sRGB PNG, enlarged to at least 256
/// pixels (nearest neighbour).
void write_delta_e_map(const std::filesystem::path& path, const SkyComparison& comparison, double delta_e_max);
/// The reference and the test image side by side, on the comparison's common white and exposure,
/// through the display pipeline (its exposure is not used: white is already 1).
void write_side_by_side(const std::filesystem::path& path, const SkyComparison& comparison,
                        const DisplayPipeline& pipeline, const std::string& reference_label,
                        const std::string& test_label);
/// A text file written atomically.
void write_text_file(const std::filesystem::path& path, const std::string& text);

}  // namespace skyspec
