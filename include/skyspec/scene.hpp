// A scene: atmosphere, sun, camera, spectral grid, quality and outputs.
//
// Scenes are TOML files (see data/scenes/default.toml, which documents every key). Loading
// starts from a built-in preset ("default" or "seed"), applies the keys of a scene file, then
// command-line overrides; every key is checked with its unit and range, and an error names the
// key, the value, what is allowed and where the value came from (file:line:column or the flag).
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "skyspec/atmosphere.hpp"
#include "skyspec/camera_spec.hpp"
#include "skyspec/geometry.hpp"
#include "skyspec/terrain.hpp"

namespace skyspec {

struct SunSpec {
  double elevation_deg = 30.0;
  double azimuth_deg = 0.0;  ///< clockwise from north
  /// "solar": the measured extraterrestrial spectrum (ASTM G173-03, data/solar/) scaled by
  /// (1 au / d)^2; "flat": spectral_irradiance_W_m2_nm at every wavelength.
  enum class Spectrum { Solar, Flat };
  Spectrum spectrum = Spectrum::Solar;
  /// The flat spectrum's value, W m^-2 nm^-1.
  double spectral_irradiance_W_m2_nm = 1.0;
  double distance_au = 1.0;  ///< planet-sun distance
  bool disk = true;          ///< draw the limb-darkened sun disk
  /// When not empty, an ISO 8601 date-time with UTC offset ("2026-06-21T20:30:00+02:00"): the
  /// sun's elevation, azimuth and distance are computed for it at the location (NREL SPA),
  /// replacing elevation_deg, azimuth_deg and distance_au (the Earth-Sun distance: Earth only).
  std::string date_time;
  bool refraction = true;  ///< with date_time: use the apparent (refracted) elevation
};

/// Where on the planet the scene's reference point is (used with sun.date_time).
struct LocationSpec {
  double latitude_deg = 0.0;   ///< north positive
  double longitude_deg = 0.0;  ///< east positive
};

/// The ground albedo a panorama that sees below the horizon (equirectangular, min_elevation_deg <
/// 0) gets when no preset, scene file or flag sets one (SceneLoader::finish): a black lower
/// hemisphere lights nothing from below in image-based lighting. 0.25 is pvlib's default ground
/// albedo ("typically 0.1-0.4 for bare or vegetated ground", pvlib.irradiance.get_ground_diffuse);
/// fresh grass is about 0.26 in its SURFACE_ALBEDOS table. Set ground.albedo = 0 for a black ground.
inline constexpr double kPanoramaGroundAlbedo = 0.25;

/// Terrain (terrain.hpp, docs/terrain.md): mountains that hide what lies behind them, shadow the
/// air and reflect light. Its albedo is the ground's (atmosphere.ground).
/// A height map's scale (terrain.model = heightmap): an image without georeferencing, centred on
/// the reference point, top row north, pixel centres pixel_m apart on the ground; height =
/// value x height_scale_m + height_offset_m, the value a PNG's (or another unsigned 8/16-bit
/// image's) code over its largest (0 to 1), an EXR's or a float image's value as stored.
struct HeightMapSpec {
  std::optional<double> pixel_m;  ///< required with model = heightmap
  double height_scale_m = 1.0;
  double height_offset_m = 0.0;
};

struct TerrainSpec {
  enum class Model { None, Ridge, File, HeightMap };
  Model model = Model::None;
  RidgeSpec ridge;  ///< model = ridge: the synthetic ridge
  /// model = file: an elevation raster GDAL opens (GeoTIFF and the others), georeferenced, heights
  /// in metres above sea level; read over the square of half-size extent_m around the reference
  /// point (location.latitude_deg / longitude_deg). model = heightmap: a height map (EXR, PNG or
  /// another image GDAL reads) whose scale `heightmap` states.
  std::string file;
  HeightMapSpec heightmap;
  /// The surface's own Lambertian albedo: albedo_values at albedo_wavelengths_nm (linearly
  /// interpolated) or a constant `albedo`; neither: the ground's (ground.albedo, ...).
  std::optional<double> albedo;
  std::vector<double> albedo_wavelengths_nm, albedo_values;
  /// An albedo map (model = file: a georeferenced raster read as the heights are; heightmap: an
  /// image over the height map's ground): a factor in [0, 1] on the albedo at each point. Empty: none.
  std::string albedo_map;
  double extent_m = 30000.0;
  double spacing_m = 100.0;  ///< the spacing of the map grid the heights are sampled on
};

/// Every terrain model by its name in scene files: none, ridge, file, heightmap
/// (scene/scene_terrain.cpp builds each).
const std::vector<NamedValue<TerrainSpec::Model>>& terrain_models();
/// "none", "ridge", "file" or "heightmap".
const char* terrain_model_name(TerrainSpec::Model model);

struct SpectrumSpec {
  double min_nm = 380.0, max_nm = 780.0, step_nm = 10.0;
  int count = 0;                       ///< when > 0: this many samples evenly over [min_nm, max_nm] (replaces step_nm)
  std::vector<double> wavelengths_nm;  ///< explicit list; overrides min/max/step when non-empty
  /// The band each sample stands for (WavelengthGrid::bandwidth_nm).
  double bandwidth_nm = WavelengthGrid::kDefaultBandwidth_nm;
};

struct RenderSpec {
  enum class Path { Spectral, RgbFast };
  Path path = Path::Spectral;
  int view_segments = 64;
  int table_altitude_samples = 128;
  int table_zenith_samples = 256;
  int threads = 0;  ///< 0: all cores
  /// Highest scattering order (1: single scattering); orders >= 2 come from precomputed tables.
  int scattering_orders = 6;
  int ms_altitude_samples = 16;
  int ms_sun_samples = 72;
  /// Spherical-harmonic degree of the multiple-scattering tables' radiance fields: 0 treats light
  /// scattered more than once as isotropic (the draft quality); 2 makes Rayleigh exact; more
  /// resolves the aerosol's forward scattering (multiple_scattering.hpp).
  int ms_angular_degree = 10;
  /// Quadrature segments along each ray of the multiple-scattering tables: order 2's (its source,
  /// the light scattered once, has the sun's shadow and the aerosol's peak) and the orders after it
  /// (smoother sources, fewer segments).
  int ms_view_segments = 24;
  int ms_higher_order_segments = 16;
  /// The tables cut a tabulated scattering matrix's forward peak within this angle (degrees) and
  /// carry its light with the unscattered light (delta-M); 0: nothing cut.
  double ms_forward_cone_deg = 5.0;
  /// A shower's own multiple scattering (RegionalSecondOrder's passes; 0: the tables' source alone).
  int shower_passes = 3;
  /// Where the multiple-scattering tables come from: built for this atmosphere, or blended from
  /// those of atmospheres on a grid of aerosol amounts and ozone columns (render/table_family.hpp).
  enum class Tables { Exact, Interpolated };
  Tables ms_tables = Tables::Exact;
  /// Keep the multiple-scattering tables on disk and reuse them for the same atmosphere.
  bool cache_tables = true;
  /// Interpolate images from a table of the sky over view directions (sky_view_table.hpp) rather
  /// than march a ray per pixel; used where it applies (a camera inside the atmosphere).
  bool sky_view_table = true;
  int sky_view_zenith_samples = 128;  ///< rows from the horizon to the zenith (half as many below)
  int sky_view_azimuth_samples = 64;  ///< columns from towards the sun to away from it
  /// The higher orders' light in the sky-view table from a coarser table of this many rows and
  /// columns, interpolated (the light scattered once keeps the table's own); at or above the
  /// table's own: its own rays (docs/physics.md, "Numerics", has what the default errs).
  int sky_view_higher_zenith_samples = 32;
  int sky_view_higher_azimuth_samples = 64;
};

struct OutputSpec {
  std::string directory = "skyspec-out";
  std::string name = "sky";
  bool exr = true;
  bool png = true;
  /// Lossless compression of the spectral EXR: none, rle, zips, zip or piz.
  std::string exr_compression = "piz";
  /// Pixel type of the spectral channels: "float" or "half" (R, G, B are always float).
  std::string exr_spectral_type = "float";
  std::optional<double> exposure_ev;  ///< preview exposure; automatic when absent
  /// Vector transport for the air: the scattering-order tables carry linear polarisation, the
  /// spectral EXR gets S1-S3 beside S0, and <name>-polarisation.exr holds the luminance-weighted
  /// Y, DoLP and AoLP (docs/polarisation.md).
  bool polarisation = false;
  /// With polarisation and png: also <name>-polarisation.png, the angle of linear polarisation as
  /// hue and its degree as brightness (colour/polarisation_colour.hpp).
  bool polarisation_png = false;
  /// Also <name>-surface.exr: per pixel the distance to the surface its ray ends on (Z, metres)
  /// and masks of the terrain and the planet's ground (render/surface_pass.hpp).
  bool surface = false;
};

/// What the irradiance outputs (skyspec irradiance, a job's irradiance tables, the render summary)
/// hold beyond the render's band.
struct IrradianceSpec {
  /// Also the broadband irradiance, 300-4000 nm, with the gases' absorption bands
  /// (broadband_irradiance.hpp).
  bool broadband = false;
};

struct Scene {
  AtmosphereSpec atmosphere;
  SunSpec sun;
  LocationSpec location;
  TerrainSpec terrain;
  CameraSpec camera;
  SpectrumSpec spectrum;
  RenderSpec render;
  OutputSpec output;
  IrradianceSpec irradiance;
};

/// Names of the built-in presets ("default", "seed").
std::vector<std::string> preset_names();

/// What a scene is loaded for: a render (every table it uses must cover its wavelengths) or only
/// its atmosphere's coefficients (skyspec coefficients: the refractive index's range).
enum class SceneUse { Render, Atmosphere };

/// The neutral id of a scene file's path, as InputErrors about the file itself name it (the CLI
/// spells it --scene, Python scene_file).
inline constexpr const char* kSceneFileSetting = "scene_file";

/// Builds a Scene from a preset, scene files and overrides, validating as it goes.
class SceneLoader {
 public:
  /// Starts from a built-in preset; throws InputError("preset", ...) for an unknown name.
  explicit SceneLoader(const std::string& preset = "default");
  /// Applies every key of a TOML scene file (InputError with file:line:column on any problem).
  void apply_file(const std::string& path);
  /// Applies TOML text (origin names it in messages).
  void apply_toml(const std::string& text, const std::string& origin);
  /// Applies a quality level's sample counts (data/quality/<name>.toml; quality_names()); keys
  /// applied afterwards override them. A scene of single scattering (render.scattering_orders =
  /// 1, as the seed preset) stays one: the level sets how many orders multiple scattering takes,
  /// not whether there is any. InputError naming `origin` for an unknown name.
  void apply_quality(const std::string& name, const std::string& origin = "render.quality");
  /// Applies one key = value given as TOML value text, e.g. ("camera.width", "1024"); origin is
  /// the flag that supplied it, e.g. "--width". A key the scene's camera does not read (the field
  /// of view of a fisheye, the panorama convention of a perspective view) is refused by finish().
  void apply_override(const std::string& key, const std::string& toml_value, const std::string& origin);
  /// Typed overrides for C++ callers: loader.set("sun.elevation_deg", 10.0), set("camera.width",
  /// 512), set("output.png", false), set("camera.type", "equirectangular"), set("camera.position_m",
  /// {0, 0, 1500}). The same checks as apply_override (an integer key refuses 8.5; InputError names
  /// the key, or `origin` when given).
  void set(const std::string& key, double value, const std::string& origin = "");
  void set(const std::string& key, int value, const std::string& origin = "");
  void set(const std::string& key, bool value, const std::string& origin = "");
  void set(const std::string& key, const std::string& value, const std::string& origin = "");
  void set(const std::string& key, const char* value, const std::string& origin = "");
  void set(const std::string& key, const std::vector<double>& values, const std::string& origin = "");
  /// Checks relations between keys (top above ground, camera above ground, grid vs fixed
  /// coefficients, ...) and returns the scene. SceneUse::Atmosphere (the coefficient report) checks
  /// the wavelengths against the refractive index of air only (230-1690 nm), not the render's
  /// tables (check_spectral_range).
  Scene finish(SceneUse use = SceneUse::Render) const;

 private:
  Scene scene_;
  std::set<std::string> given_;  ///< keys set by a preset (not the default), a file, a quality level or a flag
  std::map<std::string, std::string> overridden_;  ///< keys set by apply_override, and the flag that set each
};

/// Text as a TOML basic string ("...", with \", \\ and control characters escaped): the value text
/// of a text key for SceneLoader::apply_override.
std::string toml_quoted(const std::string& text);

/// The quality levels, fastest first: draft, lean, default, high, reference.
std::vector<std::string> quality_names();

/// What scene_to_toml writes: every key, or what a file records of the scene it shows (Recorded):
/// every key but where the outputs go (output.directory, output.name) and how many threads made
/// them (render.threads), none of which changes a pixel. The same render written into another
/// folder, under another name or with other threads is the same file, byte for byte.
enum class SceneTomlKeys { All, Recorded };
/// The effective scene as TOML, for provenance and `--from` style reproduction.
std::string scene_to_toml(const Scene& scene, SceneTomlKeys keys = SceneTomlKeys::All);

/// All scene keys with their documentation ("key  (unit, range)  help"), for --help-keys.
std::vector<std::pair<std::string, std::string>> scene_key_help();

/// The key reference as a Markdown table (key, default, allowed values, meaning), generated from
/// the same registry as the reader: docs/scene-keys.md is this text.
std::string scene_keys_markdown();

/// The built-in default scene: data/scenes/default.toml, which equals Scene{} key by key.
Scene default_scene();

/// The wavelength grid a scene asks for (validated).
WavelengthGrid make_wavelength_grid(const Scene& scene);

/// Throws InputError("spectrum", ...) unless the grid has at least 2 wavelengths, all where every
/// built-in table the scene uses is defined (the refractive index of air 230-1690 nm, the solar
/// spectrum from 280 nm, the ozone cross-sections to 1060 nm); the message names the limiting
/// table on each side. Colour comes from the grid's overlap with the colour-matching functions.
void check_spectral_range(const Scene& scene, const WavelengthGrid& grid);
/// The sun direction (unit, east-north-up) of a scene.
Vec3 sun_direction(const Scene& scene);

}  // namespace skyspec
