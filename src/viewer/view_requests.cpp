#include "viewer/view_requests.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <system_error>

#include "base/atomic_file.hpp"
#include "colour/display_pipeline.hpp"
#include "render/render_budget.hpp"
#include "render/scene_tables.hpp"
#include "render/table_family.hpp"
#include "scene/key_registry.hpp"
#include "skyspec/camera.hpp"
#include "skyspec/error.hpp"
#include "skyspec/render.hpp"
#include "skyspec/units.hpp"

namespace skyspec::viewer {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

const char* const kSmallTablesPreview = "small scattering tables (the scene's are being built)";

const std::string kWords = "a scene key (skyspec render --help-keys), preset, view, mode, preview, x or y";

bool viewer_word(const std::string& name) {
  return name == "preset" || name == "view" || name == "mode" || name == "x" || name == "y" || name == "preview";
}

// The last value of a viewer word in the query, or null.
const std::string* word(const Query& query, const std::string& name) {
  const std::string* found = nullptr;
  for (const auto& [k, v] : query)
    if (k == name) found = &v;
  return found;
}

int pixel_coordinate(const Query& query, const std::string& name, int size) {
  const std::string* text = word(query, name);
  if (!text) throw InputError(name, "(missing)", "a pixel index from 0 to " + std::to_string(size - 1));
  std::size_t used = 0;
  long value = -1;
  try {
    value = std::stol(*text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text->size() || value < 0 || value >= size)
    throw InputError(name, "\"" + *text + "\"", "a pixel index from 0 to " + std::to_string(size - 1));
  return static_cast<int>(value);
}

std::vector<double> to_vector(const Spectrum& s) { return std::vector<double>(s.data(), s.data() + s.size()); }

}  // namespace

ViewRequest parse_view_request(const ViewerBase& base, const Query& query) {
  ViewRequest request;
  request.display = base.display;
  const std::string* preset = word(query, "preset");
  SceneLoader loader(preset ? *preset : std::string("default"));
  if (!preset) loader.apply_toml(base.scene_toml, "the viewer's scene");
  for (const auto& [name, value] : query) {
    if (viewer_word(name)) continue;
    if (std::find(kViewerOwnedKeys.begin(), kViewerOwnedKeys.end(), name) != kViewerOwnedKeys.end())
      throw InputError(name, value, "not set by the page: the viewer chooses it (" + name + " is its own)");
    if (!scene_keys::find_key(name)) throw InputError(name, value, kWords);
    loader.apply_override(name, value, "the page's query");
  }
  if (const std::string* view = word(query, "view")) request.display.view = *view;
  if (const std::string* mode = word(query, "mode")) {
    if (*mode == "polarisation")
      request.mode = ViewRequest::Mode::Polarisation;
    else if (*mode != "colour")
      throw InputError("mode", "\"" + *mode + "\"", "colour or polarisation");
  }
  if (const std::string* preview = word(query, "preview")) {
    if (*preview != "0" && *preview != "1") throw InputError("preview", "\"" + *preview + "\"", "0 or 1");
    request.preview = *preview == "1";
  }
  if (request.mode == ViewRequest::Mode::Polarisation) loader.set("output.polarisation", true, "mode");
  request.scene = loader.finish();
  request.scene.render.threads = base.threads;
  DisplayPipeline check(request.display);  // names checked now: InputError naming display.view
  return request;
}

bool scattering_tables_ready(const Scene& scene) {
  // Interpolated tables are blended in the background like a build (a frame does not wait for the
  // grid's tables to be read and blended): ready once this process holds the blend.
  if (scene.render.ms_tables == RenderSpec::Tables::Interpolated && table_family(scene))
    return interpolated_tables_in_memory(scene);
  return scene_tables_cached(scene);
}

Scene with_preview_tables(const Scene& scene) {
  Scene s = scene;
  RenderSpec& r = s.render;
  r.ms_altitude_samples = std::min(r.ms_altitude_samples, kPreviewTableAltitudes);
  r.ms_sun_samples = std::min(r.ms_sun_samples, kPreviewTableSuns);
  r.ms_angular_degree = std::min(r.ms_angular_degree, kPreviewTableDegree);
  r.scattering_orders = std::min(r.scattering_orders, kPreviewTableOrders);
  r.ms_tables = RenderSpec::Tables::Exact;  // one small build, not a grid of them
  return s;
}

TablesAtHand tables_at_hand(const Scene& scene) {
  if (scattering_tables_ready(scene)) return TablesAtHand::exact;
  return scattering_tables_ready(with_preview_tables(scene)) ? TablesAtHand::preview : TablesAtHand::none;
}

void build_scattering_tables(const Scene& scene) {
  // A renderer of one pixel without a sky-view table: its construction is the tables' build (a
  // polarised scene's are vector tables, so output.polarisation stays as asked; a shower's passes,
  // which are not in the tables, left out). The preview's small tables first, for the frames shown
  // while the scene's own are built.
  const auto build = [](Scene s) {
    s.camera.width = s.camera.height = 1;
    s.render.sky_view_table = false;
    s.render.shower_passes = 0;
    const SkyRenderer renderer(s);
  };
  const Scene preview = with_preview_tables(scene);
  // Not where the scene's own tables are only to be read or blended: that is quicker.
  if (!scattering_tables_ready(preview) && !scene_tables_cached(scene)) build(preview);
  if (!scattering_tables_ready(scene)) build(scene);
}

Frame render_frame(const ViewRequest& request, TablesAtHand tables) {
  const CameraSpec& camera = request.scene.camera;
  if (static_cast<std::int64_t>(camera.width) * camera.height > kMaxFramePixels)
    throw InputError("camera.width", std::to_string(camera.width) + " x " + std::to_string(camera.height),
                     "a frame of at most " + std::to_string(kMaxFramePixels) + " pixels (Export renders any size)");
  Frame frame;
  Scene scene = request.scene;
  if (request.preview || tables != TablesAtHand::exact) {
    scene.render.sky_view_zenith_samples = std::min(scene.render.sky_view_zenith_samples, kPreviewZenithSamples);
    scene.render.sky_view_azimuth_samples = std::min(scene.render.sky_view_azimuth_samples, kPreviewAzimuthSamples);
    scene.render.view_segments = std::min(scene.render.view_segments, kPreviewViewSegments);
    frame.preview = "coarse sky-view table";
  }
  if (tables == TablesAtHand::preview) {
    scene = with_preview_tables(scene);
    frame.preview = kSmallTablesPreview;
  } else if (tables == TablesAtHand::none) {
    scene.render.scattering_orders = 1;
    frame.preview = "single scattering (the scattering tables are being built)";
  }
  // A shower's own multiple scattering takes seconds per camera position and sun: previews leave
  // it out (the tables' source alone).
  if (!frame.preview.empty() && scene.render.scattering_orders >= 2 && scene.atmosphere.rain.enabled &&
      scene.atmosphere.rain.extent == RainSpec::Extent::Shower && scene.render.shower_passes > 0) {
    scene.render.shower_passes = 0;
    frame.preview += kShowerPreview;
  }
  const auto start = std::chrono::steady_clock::now();
  const SpectralImageBuffer image = render_to_memory(scene);
  frame.render_seconds = seconds_since(start);
  const auto encode = std::chrono::steady_clock::now();
  // Frames go out at once: compressed for speed (the pixels are those of the exported PNG).
  frame.png = request.mode == ViewRequest::Mode::Polarisation
                  ? polarisation_png_bytes(image, PngCompression::Fastest)
                  : display_png_bytes(image, request.display, PngCompression::Fastest);
  frame.encode_seconds = seconds_since(encode);
  frame.width = image.width;
  frame.height = image.height;
  frame.exposure = preview_exposure(image, request.display).description;
  return frame;
}

nlohmann::json spectrum_at(const ViewRequest& request, const Query& query, TablesAtHand tables) {
  if (tables == TablesAtHand::none) throw Error("a spectrum needs the scene's scattering tables or the preview's");
  const int x = pixel_coordinate(query, "x", request.scene.camera.width);
  const int y = pixel_coordinate(query, "y", request.scene.camera.height);
  const std::unique_ptr<Camera> camera = make_camera(request.scene);
  Vec3 dir;
  if (!camera->direction(x + 0.5, y + 0.5, dir))
    throw InputError("x", std::to_string(x) + ", y = " + std::to_string(y), "a pixel the camera has a ray for");
  // Both integrated along the ray: no sky-view table to build or read. The scene's own tables (a
  // polarised scene's vector tables: the ones scattering_tables_ready speaks of).
  Scene all = tables == TablesAtHand::preview ? with_preview_tables(request.scene) : request.scene;
  all.render.sky_view_table = false;
  Scene single = all;
  single.render.scattering_orders = 1;
  const Spectrum radiance = SkyRenderer(all).radiance(dir);
  const Spectrum first = SkyRenderer(single).radiance(dir);
  // World directions are east-north-up at the scene's reference point (camera.hpp).
  const double azimuth = std::fmod(std::atan2(dir.x(), dir.y()) * 180.0 / kPi + 360.0, 360.0);
  const double elevation = std::asin(std::clamp(dir.z(), -1.0, 1.0)) * 180.0 / kPi;
  const WavelengthGrid grid = make_wavelength_grid(request.scene);
  const std::vector<double>& wavelengths = grid.nanometres();
  return {{"x", x},
          {"y", y},
          {"azimuth_deg", azimuth},
          {"elevation_deg", elevation},
          {"wavelengths_nm", wavelengths},
          {"radiance", to_vector(radiance)},
          {"single_scattering", to_vector(first)},
          {"orders", all.render.scattering_orders},
          {"units", "W m^-2 sr^-1 nm^-1"},
          {"preview", tables == TablesAtHand::preview ? kSmallTablesPreview : ""}};
}

nlohmann::json export_view(const ViewRequest& request, const std::filesystem::path& folder) {
  ensure_writable_directory(folder, viewer_setting::kExportFolder);
  Scene scene = request.scene;
  scene.output.directory = folder.string();
  scene.output.exr = scene.output.png = true;
  // The first number none of whose files exist: an export never replaces a file.
  for (int k = 1;; ++k) {
    if (k > 9999) throw IoError("'" + folder.string() + "': view-0001 .. view-9999 are all taken");
    char name[32];
    std::snprintf(name, sizeof name, "view-%04d", k);
    scene.output.name = name;
    bool taken = false;
    std::error_code ec;
    for (const auto& p : render_output_paths(scene, request.display).files())
      taken = taken || std::filesystem::exists(std::filesystem::symlink_status(p, ec));
    if (!taken && !std::filesystem::exists(std::filesystem::symlink_status(folder / (scene.output.name + ".toml"), ec)))
      break;
  }
  // The render budget's limits, without its --force: the viewer has none (the command line does).
  const std::vector<std::string> problems = estimate_render(RenderPlan::for_scene(scene, request.display)).problems();
  if (!problems.empty()) {
    std::string message = "this export";
    for (size_t i = 0; i < problems.size(); ++i) message += (i ? ", and " : " ") + problems[i];
    throw InputError::refused("export", message +
                                            " (make the frame smaller, or render the exported scene with skyspec "
                                            "render, which can be told to go beyond the budget)");
  }
  const std::filesystem::path toml_path = folder / (scene.output.name + ".toml");
  Scene recorded = scene;
  recorded.render.threads = 0;  // the machine's choice, as a scene file's default
  const std::string toml_text = "# Exported by skyspec view: skyspec render --scene " + toml_path.filename().string() +
                                " renders these files again.\n" + scene_to_toml(recorded);
  const RenderOutputs out = render_scene_to_files(scene, request.display);
  try {
    write_file_atomically(toml_path, toml_text);  // last: no scene file without its images
  } catch (...) {
    std::error_code ec;
    for (const auto& p : out.files()) std::filesystem::remove(p, ec);
    throw;
  }
  nlohmann::json files = nlohmann::json::array();
  for (const auto& p : out.files()) files.push_back(p.string());
  std::string command = "skyspec render --scene " + toml_path.string();
  if (!request.display.view.empty()) command += " --view \"" + request.display.view + "\"";
  return {{"scene", toml_path.string()}, {"files", files}, {"command", command}, {"seconds", out.seconds}};
}

nlohmann::json viewer_state(const ViewerBase& base) {
  SceneLoader loader("default");
  loader.apply_toml(base.scene_toml, "the viewer's scene");
  const Scene scene = loader.finish();
  nlohmann::json values = nlohmann::json::object(), help = nlohmann::json::object();
  for (const scene_keys::KeyDef& key : scene_keys::registry()) {
    values[key.key] = key.get(scene);
    help[key.key] = key.doc;
  }
  nlohmann::json cameras = nlohmann::json::array();
  for (const auto& c : camera_types()) cameras.push_back(c.name);
  const OcioConfig config(base.display.config);
  const std::string display = base.display.display.empty() ? config.default_display() : base.display.display;
  return {{"values", values},
          {"help", help},
          {"presets", preset_names()},
          {"cameras", cameras},
          {"display", display},
          {"views", config.views(display)},
          {"view", base.display.view.empty() ? config.default_view(display) : base.display.view},
          {"owned_keys", kViewerOwnedKeys}};
}

}  // namespace skyspec::viewer
