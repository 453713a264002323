// The display pipeline: scene-linear images to display code values through OpenColorIO.
//
//   R, G, B (linear Rec.709: skyspec's EXR channels, Y in cd m^-2 for spectral renders)
//     x exposure (exposure.hpp)
//     -> optional skyspec look (tone_mapping.hpp; C++, on linear Rec.709)
//     -> CIE XYZ (D65) with the engine's own matrix (colour.hpp)
//     -> OpenColorIO: the config's scene-referred "CIE-XYZ-D65" space (or, in a config without
//        it, ACES2065-1 reached with OCIO's built-in Bradford "UTILITY - ACES-AP0_to_CIE-XYZ-D65_BFD"
//        and the config's aces_interchange role), an optional OCIO look, then the display's view
//     -> display code values in [0, 1] -> PNG (8 or 16 bits)
//
// The config is skyspec's own (data/ocio/config.ocio, compiled in; OpenColorIO 2.1 built-in
// transforms only) unless a file is named (the CLI takes --ocio or the OCIO environment variable).
// Unknown display, view, look or working-space names are InputErrors that list the valid ones.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "colour/exposure.hpp"
#include "colour/png_colour_tag.hpp"
#include "skyspec/colour.hpp"
#include "skyspec/display.hpp"

namespace skyspec {

/// A loaded OpenColorIO config and the names a user can pick from it.
class OcioConfig {
 public:
  /// Throws InputError naming the origin when the file cannot be read or is not a valid config.
  explicit OcioConfig(const OcioConfigSource& source = {});
  ~OcioConfig();
  bool is_builtin() const;
  /// "skyspec built-in config" or "'<path>' (from --ocio)".
  std::string describe() const;
  std::vector<std::string> displays() const;
  std::string default_display() const;
  std::vector<std::string> views(const std::string& display) const;
  std::string default_view(const std::string& display) const;
  std::vector<std::string> looks() const;
  std::vector<std::string> colour_spaces() const;
  /// How skyspec's XYZ enters this config (the space name, and the route).
  std::string input_description() const;

  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  std::shared_ptr<const Impl> impl_;
};

class DisplayPipeline {
 public:
  /// Loads the config and checks every name; an InputError naming the setting (display.display,
  /// display.view, display.look, display.png_bit_depth, display.exr_space, ...) lists what is allowed.
  explicit DisplayPipeline(const DisplaySettings& settings);
  ~DisplayPipeline();
  DisplayPipeline(DisplayPipeline&&) noexcept;

  const OcioConfig& config() const;
  const DisplaySettings& settings() const;
  const std::string& display() const;
  const std::string& view() const;
  /// The look's name and kind: "" (none), "OCIO look" or "skyspec look (C++)".
  const std::string& look() const;
  std::string look_kind() const;
  /// One line: display, view, look and config.
  std::string describe() const;
  /// The PNG chunks for this display (only for skyspec's own config; None otherwise).
  PngColourTag png_tag() const;

  /// Linear Rec.709 scene values ([n][3]) times exposure_scale, through the look and the display
  /// transform: display code values, clamped to [0, 1]. Non-finite results become 0.
  std::vector<float> encode(std::vector<float> linear_rec709, double exposure_scale) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// A scene-linear working space for RGB EXR interchange, with its OpenEXR chromaticities.
struct WorkingSpace {
  std::string name;         ///< its colour-space name in the config
  std::string file_suffix;  ///< for file names: "acescg", "aces2065-1", "linear-rec709"
  Chromaticities chromaticities;
};
/// ACEScg (AP1 primaries, ACES white; S-2014-004), ACES2065-1 (AP0, ACES white; SMPTE ST
/// 2065-1) and Linear Rec.709 (ITU-R BT.709 primaries, D65).
const std::vector<WorkingSpace>& working_spaces();
/// Throws InputError(setting, name, the list) for an unknown name (case-insensitive match).
const WorkingSpace& find_working_space(const std::string& name,
                                       const std::string& setting = display_setting::kExrSpace);
/// The skyspec:units text of an RGB EXR in `space`: what its R, G, B are (scene-linear in that
/// space; luminance in cd/m^2 on the spectral path, the sun's units on the RGB-fast path).
std::string working_space_units(const WorkingSpace& space, bool rgb_fast);

/// skyspec's linear Rec.709 values ([n][3]) in a working space, converted by the config (the
/// config must have a colour space of that name).
std::vector<float> to_working_space(const OcioConfig& config, const std::vector<float>& linear_rec709,
                                    const WorkingSpace& space);

/// The displays with their views, and the looks (OCIO and skyspec), as text for --list-displays.
std::string describe_displays_and_looks(const OcioConfig& config);

}  // namespace skyspec
