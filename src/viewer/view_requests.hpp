// What the viewer's page asks for, without the HTTP: a query (the page's controls as scene keys
// and a few viewer words) -> the scene and display settings it means -> a frame (PNG bytes), the
// spectrum under a pixel, or an export of full-quality files. The server (viewer_server.hpp) only
// routes requests here; tests call these directly.
//
// A query's names are scene keys (any key of docs/scene-keys.md but the ones the viewer owns,
// kViewerOwnedKeys) whose values are TOML value text as `skyspec render --set` takes it
// ("10.5", "\"fisheye\"", "[0, 0, 2]"), and these words:
//   preset  start from this preset instead of the viewer's scene
//   view    the display's view (OpenColorIO), e.g. "Un-tone-mapped"
//   mode    colour (the display image) or polarisation (angle as hue, degree as brightness)
//   x, y    the pixel of a spectrum request (image pixels, 0 at the top-left)
//   preview 1: a quick frame while a control is being dragged (a coarser sky-view table)
//
// Previews: a frame is exact (the scene as asked) unless the query asks for a preview or the
// scene's scattering-order tables are not at hand yet; then it is a preview, and says which:
//   coarse sky-view table   the sky-view table at kPreviewZenithSamples x kPreviewAzimuthSamples,
//                           its rays marched in kPreviewViewSegments segments (everything else as
//                           asked; docs/viewer.md measures the difference)
//   small scattering tables the scene's tables are being built (the server starts that) and the
//                           preview's are at hand: all orders from tables of kPreviewTableAltitudes
//                           x kPreviewTableSuns entries, harmonics to kPreviewTableDegree and
//                           kPreviewTableOrders orders (with_preview_tables), which the server builds
//                           first, in a fraction of the scene's time; the coarse sky-view table too
//   single scattering       neither is at hand yet: the orders above the first are missing
// and, with a rain shower (atmosphere.rain.extent = "shower") and tables, kShowerPreview appended:
// its own multiple scattering (render.shower_passes) left out, the tables' source alone.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "skyspec/display.hpp"
#include "skyspec/scene.hpp"

namespace skyspec::viewer {

/// The server's settings, as errors name them (a front end respells them: the CLI's --host,
/// --port, --allow-remote, --out; src/cli/setting_spellings.cpp).
namespace viewer_setting {
inline constexpr const char* kHost = "viewer.host";
inline constexpr const char* kPort = "viewer.port";
inline constexpr const char* kAllowRemote = "viewer.allow_remote";
inline constexpr const char* kExportFolder = "viewer.export_folder";
}  // namespace viewer_setting

/// (name, value) pairs in the order the page sent them.
using Query = std::vector<std::pair<std::string, std::string>>;

/// Scene keys a query may not set: where and under which name files go is the server's choice
/// (its export folder), threads and the disk cache its command line's.
inline const std::vector<std::string> kViewerOwnedKeys = {"output.directory", "output.name",    "output.exr",
                                                          "output.png",       "render.threads", "render.cache_tables"};
/// The sky-view table of a preview: rows from the horizon to the zenith, azimuths, and the
/// segments of its rays (render.view_segments).
constexpr int kPreviewZenithSamples = 32, kPreviewAzimuthSamples = 16, kPreviewViewSegments = 32;
/// What a preview of a shower adds to its description.
constexpr const char* kShowerPreview = "; the shower's own multiple scattering left out";
/// The scattering-order tables of a preview while the scene's are built (with_preview_tables):
/// altitudes, sun angles, the harmonics' degree and the highest order, each at most these.
constexpr int kPreviewTableAltitudes = 12, kPreviewTableSuns = 24, kPreviewTableDegree = 6, kPreviewTableOrders = 4;
/// The largest frame the page may ask for, in pixels (an export is held to the render budget).
constexpr std::int64_t kMaxFramePixels = std::int64_t{2048} * 2048;

/// The viewer's starting point: the scene (its TOML, every key), the display settings of its
/// command line (config, display, look; the view is the page's), and the render threads.
struct ViewerBase {
  std::string scene_toml;
  DisplaySettings display;
  int threads = 0;
};

struct ViewRequest {
  enum class Mode { Colour, Polarisation };
  Scene scene;
  DisplaySettings display;
  Mode mode = Mode::Colour;
  bool preview = false;  ///< the query's preview=1
};

/// The scene and settings a query means. InputError names the query's name (a scene key, "view",
/// "mode", "preset"), its value and what is allowed; unknown names and owned keys are refused.
ViewRequest parse_view_request(const ViewerBase& base, const Query& query);

/// A frame as PNG bytes: the display image (the PNG `skyspec render` writes for the same scene and
/// view) or the polarisation picture.
struct Frame {
  std::string png;
  int width = 0, height = 0;
  double render_seconds = 0.0, encode_seconds = 0.0;
  std::string exposure;  ///< how the exposure was chosen, in words
  std::string preview;   ///< "" for an exact frame, else what the preview leaves out (see above)
};
/// Which of a scene's scattering-order tables are in memory or in the disk cache: its own, the
/// preview's (with_preview_tables) or none (a single-scattering scene's are always at hand).
enum class TablesAtHand { exact, preview, none };
TablesAtHand tables_at_hand(const Scene& scene);
/// The frame of a request with the tables at hand: exact with the scene's own, else a preview
/// (see above).
Frame render_frame(const ViewRequest& request, TablesAtHand tables = TablesAtHand::exact);

/// Whether the scene's scattering-order tables are in memory or in the disk cache (true for single
/// scattering), or, with render.ms_tables = "interpolated", blended in this process already: a frame
/// of it is then exact without a table build or blend.
bool scattering_tables_ready(const Scene& scene);
/// The scene with the preview's smaller scattering-order tables (its render.ms_altitude_samples,
/// ms_sun_samples, ms_angular_degree and scattering_orders at most kPreviewTable*).
Scene with_preview_tables(const Scene& scene);
/// Builds (and caches) the preview's tables and then the scene's; what the server runs in the
/// background while previews are shown.
void build_scattering_tables(const Scene& scene);

/// The sky's spectral radiance through the centre of pixel (x, y), all the orders the scene asks
/// for and single scattering alone, both integrated along the ray (not read from the sky-view
/// table): {"x", "y", "azimuth_deg", "elevation_deg", "wavelengths_nm", "radiance",
/// "single_scattering", "orders", "units", "preview"}. With the preview's tables at hand (not the
/// scene's: TablesAtHand::preview) the orders come from them and "preview" says so; it is "" for
/// the scene's own. InputError naming "x" or "y" for a pixel outside the image or one the camera
/// has no ray for; Error for TablesAtHand::none (a spectrum waits for tables).
nlohmann::json spectrum_at(const ViewRequest& request, const Query& query, TablesAtHand tables = TablesAtHand::exact);

/// Writes the request's scene as `<folder>/view-NNNN.toml` and renders it to view-NNNN.exr and
/// .png with render_scene_to_files (the files `skyspec render --scene view-NNNN.toml` writes),
/// NNNN the first number none of whose files exist. Returns {"scene", "files", "command"}.
nlohmann::json export_view(const ViewRequest& request, const std::filesystem::path& folder);

/// Every scene key's current value in the base scene (TOML value text) and its help, the presets,
/// the camera types and the display's views: what the page builds its controls from.
nlohmann::json viewer_state(const ViewerBase& base);

}  // namespace skyspec::viewer
