// What a user picks for a displayed image: the OpenColorIO config, display, view and look, the
// exposure, the PNG's bit depth and an optional scene-linear RGB EXR in a working space.
//
// The render functions that write a PNG or an RGB EXR take these settings (render.hpp); names are
// checked when a display pipeline is built from them, and a wrong one is an InputError whose
// setting() is the neutral id of the field below ("display.view", "display.exposure.iso", ...),
// which each front end spells its own way (the CLI as --view, Python as display_view=...).
#pragma once

#include <optional>
#include <string>

namespace skyspec {

/// How the exposure (the factor from scene-linear values to the display's input) is chosen:
///   Automatic: the log-average luminance of the sky is mapped to 0.18 (Reinhard et al. 2002);
///   Manual: scale = 2^ev (ev = 0 makes 1 cd m^-2 white on the spectral path);
///   Camera: ISO 12232 saturation-based sensitivity, scale = 1 / (1.2 * 2^EV100) with
///           EV100 = log2(N^2 / t * 100 / S) (Lagarde & de Rousiers 2014).
struct ExposureSettings {
  enum class Mode { Automatic, Manual, Camera };
  Mode mode = Mode::Automatic;
  double ev = 0.0;          ///< Manual
  double f_number = 8.0;    ///< Camera: N
  double shutter_s = 0.01;  ///< Camera: t, seconds
  double iso = 100.0;       ///< Camera: S
};

/// Where the OpenColorIO config comes from.
struct OcioConfigSource {
  std::string path;    ///< empty: skyspec's built-in config
  std::string origin;  ///< what named the path, for messages, e.g. "--ocio" or "$OCIO"
};

/// Everything a user picks for a displayed image.
struct DisplaySettings {
  OcioConfigSource config;
  std::string display;               ///< empty: the config's default display (sRGB in skyspec's config)
  std::string view;                  ///< empty: the display's default view (Un-tone-mapped in skyspec's config)
  std::string look;                  ///< empty: none; an OCIO look of the config, else a skyspec look
  std::optional<double> look_white;  ///< reinhard-extended / -luminance white (after exposure)
  ExposureSettings exposure;
  int png_bit_depth = 8;
  std::string exr_space;  ///< non-empty: also write a scene-linear RGB EXR in this working space
};

/// How hard a PNG is compressed: Smallest as files are written (zlib's default level, libpng's
/// adaptive row filters), Fastest for frames sent at once (zlib's level 1 and the Sub filter, which
/// suits smooth skies: docs/viewer.md measures both). The pixels are the same.
enum class PngCompression { Smallest, Fastest };

/// The neutral ids of the settings above, as InputError::setting() reports them.
namespace display_setting {
inline constexpr const char* kOcio = "display.ocio";
inline constexpr const char* kDisplay = "display.display";
inline constexpr const char* kView = "display.view";
inline constexpr const char* kLook = "display.look";
inline constexpr const char* kLookWhite = "display.look_white";
inline constexpr const char* kExposureEv = "display.exposure.ev";
inline constexpr const char* kFNumber = "display.exposure.f_number";
inline constexpr const char* kShutter = "display.exposure.shutter_s";
inline constexpr const char* kIso = "display.exposure.iso";
inline constexpr const char* kPngBits = "display.png_bit_depth";
inline constexpr const char* kExrSpace = "display.exr_space";
}  // namespace display_setting

}  // namespace skyspec
