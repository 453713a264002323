// Applying the display pipeline to an existing EXR without rendering again (`skyspec convert`).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "colour/display_pipeline.hpp"
#include "colour/exposure.hpp"

namespace skyspec {

/// The neutral ids of convert_exr_for_display's arguments, as its InputErrors name them (each front
/// end respells them: the CLI's INPUT, --out, --name, --no-png).
namespace conversion_setting {
inline constexpr const char* kInput = "conversion.input";
inline constexpr const char* kDirectory = "conversion.directory";
inline constexpr const char* kName = "conversion.name";
inline constexpr const char* kPng = "conversion.png";
inline constexpr const char* kOutputs = "conversion.directory / conversion.name";
}  // namespace conversion_setting

struct ConversionOutputs {
  std::filesystem::path png, working_exr;  ///< empty when not written
  ResolvedExposure exposure;
  std::string display;  ///< the pipeline's description
};

/// Reads the R, G, B channels of `input` (a skyspec EXR, or any EXR whose R, G, B are linear
/// Rec.709: its chromaticities attribute must be absent or Rec.709/D65), chooses the exposure and
/// writes <directory>/<name>.png (when `png`) and, with settings.exr_space, the working-space EXR
/// <directory>/<name>-<suffix>.exr, atomically and all or nothing.
///
/// Exposure: manual_ev if given, else a camera exposure if the settings ask for one, else the
/// exposure recorded in the file's header ("skyspec:exposureScale", written by `skyspec render`),
/// else the automatic rule metered on the image (exposure.hpp).
ConversionOutputs convert_exr_for_display(const std::filesystem::path& input, const std::filesystem::path& directory,
                                          const std::string& name, const DisplaySettings& settings,
                                          std::optional<double> manual_ev = {}, bool png = true);

}  // namespace skyspec
