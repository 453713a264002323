// A time-lapse: one image per time step between a start and an end date-time at the scene's place
// (location.latitude_deg / longitude_deg), the sun placed by the NREL solar position algorithm,
// with one exposure for every frame.
//
// The frames are the tasks of a job (one site, a time axis; docs/jobs.md): each frame's files,
// <output.name>_NNNN.exr / .png in output.directory, are written atomically, then its record
// <output.name>_NNNN.json (scene digest, file sizes and SHA-256), and manifest.jsonl lists them all.
// A resumed run keeps the frames whose record, scene and files check out and renders the others:
// the job system's resume, the only one.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "skyspec/scene.hpp"

namespace skyspec {

/// The neutral ids of a time-lapse's settings, as InputError::setting() reports them (the CLI
/// spells them --start, --end, --step-minutes, --frames; Python start=, end=, ...).
namespace timelapse_setting {
inline constexpr const char* kStart = "timelapse.start";
inline constexpr const char* kEnd = "timelapse.end";
inline constexpr const char* kStepMinutes = "timelapse.step_minutes";
inline constexpr const char* kFrames = "timelapse.frames";
}  // namespace timelapse_setting

struct TimelapseSettings {
  std::string start, end;     ///< ISO 8601 with a UTC offset, e.g. "2026-06-21T19:00:00+02:00"
  double step_minutes = 0.0;  ///< > 0; frames at start, start + step, ... up to end
  /// "A-B" or "A" (inclusive, 0-based): only these frames, e.g. one machine's share; the exposure
  /// is still the whole sequence's, so shares match. Empty: every frame.
  std::string frames;
  /// Keep the frames an earlier run finished (record, scene and files checked); without it every
  /// frame is rendered again. Either way temporary files a killed run left are removed first.
  bool resume = false;
  /// Render even when the frames exceed the free disk, a frame the memory or the time a day
  /// (render_budget's refusals, InputError naming kForceSetting otherwise).
  bool force = false;
};

struct TimelapseResult {
  int frames = 0;           ///< in the whole sequence
  int first = 0, last = 0;  ///< the frames this call covered: [first, last)
  int written = 0, kept = 0, failed = 0;
  /// Frames an earlier run left that were rendered again, and why ("its record records another
  /// scene", "sky_0003.png does not have its recorded size", ...).
  std::vector<std::string> replaced;
  std::vector<std::string> failures;  ///< "sky_0004: <error>" of frames that failed
  int removed_temporaries = 0;        ///< temporary files a killed run left (removed first)
  double exposure_ev = 0.0;           ///< every frame's (output.exposure_ev)
  /// How it was chosen: "given" or "metered on frame K (sun S deg)".
  std::string exposure;
  /// The files of the covered frames, in frame order (EXR, PNG of each), and the manifest.
  std::vector<std::filesystem::path> files;
  std::filesystem::path manifest;
};

/// Called with (frames done, frames to do) after each frame of this call.
using TimelapseProgress = std::function<void(int done, int total)>;

/// Renders the time-lapse of `scene` (its output.directory, output.name, output.exr/png and, when
/// set, output.exposure_ev: otherwise the automatic exposure of the frame with the highest sun,
/// metered on a 64-pixel-wide render of it, clamped to -64..64 EV). InputError names the setting
/// (timelapse_setting ids, or scene keys) before anything is written; a frame that fails is
/// recorded and counted, and the others still run. Polls skyspec::cancellation.
TimelapseResult render_timelapse(const Scene& scene, const TimelapseSettings& settings,
                                 const TimelapseProgress& progress = {});

}  // namespace skyspec
