// Rendering a scene: cameras x single scattering -> spectral image -> files.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "skyspec/camera.hpp"
#include "skyspec/display.hpp"
#include "skyspec/scene.hpp"
#include "skyspec/spectrum.hpp"

namespace skyspec {

/// The neutral id of the setting that renders anyway although the render budget refuses (a
/// render's, a time-lapse's or an export's files exceed the free disk, a frame the memory, the
/// time a day): the CLI's --force, Python's force=. Refusals name it.
inline constexpr const char* kForceSetting = "budget.force";

/// Called after each band of rows with (rows done, rows in total).
using ProgressFn = std::function<void(int rows_done, int rows_total)>;

/// The camera a scene describes (world-space, planet-centred).
std::unique_ptr<Camera> make_camera(const Scene& scene);
/// Whether the camera makes a whole-sphere latitude-longitude panorama (equirectangular,
/// min_elevation_deg = -90): its EXRs carry OpenEXR's envmap = latlong attribute.
bool is_latlong_envmap(const CameraSpec& camera);

/// e1 of the Stokes frame of the image point (x, y) (pixels) whose ray is dir (unit): the direction
/// in which image x grows there, perpendicular to dir. e2 = k x e1 with k = -dir, the light's
/// direction: the image's up for the perspective and equirectangular cameras, its down for the
/// fisheye (a view from above). The frames of polarised renders (SkyRenderer::render_window_stokes).
Vec3 stokes_frame_axis_of_pixel(const Camera& camera, double x, double y, const Vec3& dir);

/// Everything needed to render one scene, built once: atmosphere on the grid, the sun's column
/// table, the integrator, the camera, and the colour conversion.
class SkyRenderer {
 public:
  explicit SkyRenderer(const Scene& scene);
  ~SkyRenderer();
  const Scene& scene() const;
  const WavelengthGrid& grid() const;
  int width() const;
  int height() const;
  /// The threads its work may use (render.threads; 0 there means all cores).
  int threads() const;

  /// Renders rows [y0, y0 + rows): spectral radiance ([row][x][lambda]) and linear Rec.709
  /// preview RGB ([row][x][c]); uses all threads allowed by render.threads. Results do not depend
  /// on the number of threads. Throws Error if any value is not finite.
  void render_rows(int y0, int rows, float* spectral, float* rgb) const;
  /// The same for the columns [x0, x1) of those rows only (a tile of the image): rows x (x1 - x0)
  /// pixels, each the value render_rows gives it. Throws Error for a window outside the image.
  void render_window(int x0, int x1, int y0, int rows, float* spectral, float* rgb) const;
  /// render_window for a scene with output.polarisation (Error otherwise): each pixel's Stokes
  /// vector per wavelength, [row][x][S0, S1, S2, S3][lambda] in `stokes`, and the RGB of S0. The
  /// sky-view table, built with the higher orders' Q and U for such a scene, serves the pixels it
  /// covers (S0 is then render_window's radiance); the others are marched. The Stokes frame of a pixel
  /// (stokes_frame_axis_of_pixel): e1 = the image's x axis at that pixel, carried onto the sky,
  /// e2 = k x e1 with k = -dir the light's direction (the spectral EXR's polarisationHandedness =
  /// "right"). S1 > 0: polarised along e1; S2 > 0: along e1 + e2. S3 (V) is 0.
  void render_window_stokes(int x0, int x1, int y0, int rows, float* stokes, float* rgb) const;
  /// skyspec::stokes_frame_axis_of_pixel for this renderer's camera.
  Vec3 stokes_frame_axis_of_pixel(double x, double y, const Vec3& dir) const;

  /// Spectral radiance of the sky (one value per grid wavelength, W m^-2 sr^-1 nm^-1), without
  /// the sun's disk, seen from the scene's camera position looking along the world-space direction
  /// dir, and the same as linear Rec.709. Where the image is interpolated from a sky-view table,
  /// so is this.
  Spectrum radiance(const Vec3& dir) const;
  Rgb radiance_rgb(const Vec3& dir) const;
  /// The sky's Stokes vector in that direction, in the frame (e1, k x e1) of the light arriving
  /// along k = -dir, e1 a unit vector perpendicular to dir; V = 0. i is radiance(dir), integrated
  /// along the ray (not read from the sky-view table). With output.polarisation the higher orders
  /// carry polarisation (vector tables: the air scatters it by Rayleigh's matrix, particles by
  /// their unit matrix or a sphere's matrix through its spin-2 harmonics, docs/polarisation.md);
  /// without it only single scattering is polarised. The ground depolarises. docs/validation.md
  /// measures both against the vector Monte Carlo.
  void stokes(const Vec3& dir, const Vec3& e1, Spectrum& i, Spectrum& q, Spectrum& u) const;

  /// Aerial perspective for rows [y0, y0 + rows): for each pixel, the spectral transmittance from
  /// the camera to a surface at distance_m[pixel] along the pixel's ray, and the light the air
  /// scatters into that stretch of ray (all orders the scene asks for). Infinite distances give
  /// the sky (transmittance to space, 0 where the ground is in the way). Buffers: distance
  /// [row][x], transmittance and inscatter [row][x][lambda].
  void aerial_rows(int y0, int rows, const float* distance_m, float* transmittance, float* inscatter) const;

  /// Transmittance from the camera along dir to space, per grid wavelength (0 where the ground or
  /// the scene's terrain is in the way).
  Spectrum transmittance(const Vec3& dir) const;
  /// The sun: spectral irradiance at the top of the atmosphere (W m^-2 nm^-1, or the flat
  /// spectrum's units), direction (world space, unit) and angular radius.
  const Spectrum& sun_irradiance() const;
  const Vec3& sun_direction() const;
  double sun_angular_radius_rad() const;
  const Vec3& camera_origin_m() const;
  /// Seconds spent building the sky-view table (0 without one).
  double sky_view_table_seconds() const;
  /// Seconds the constructor took: the atmosphere on the grid and every table it built or loaded
  /// (optical depth, scattering orders, sky view).
  double build_seconds() const;

  /// Linear Rec.709 from a spectrum: through CIE XYZ (spectral path, Y in cd m^-2 for radiance in
  /// W m^-2 sr^-1 nm^-1) or directly from the 680/550/440 nm values (RGB-fast path).
  /// The spectrum has one value per grid wavelength (a Spectrum, or a Map over a row buffer).
  Rgb spectrum_to_rgb(const Eigen::Ref<const Spectrum>& spectrum) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// A whole image in memory (tests, Python, small renders), with what it shows.
struct SpectralImageBuffer {
  int width = 0, height = 0;
  std::vector<double> wavelengths_nm;
  std::vector<float> spectral;  ///< [y][x][lambda]
  std::vector<float> rgb;       ///< [y][x][c]
  /// [y][x][S1, S2, S3][lambda] with output.polarisation (else empty): the Stokes vector's
  /// polarised components in the units of spectral, in each pixel's frame
  /// (SkyRenderer::render_window_stokes); spectral is then S0.
  std::vector<float> stokes;
  Scene scene;  ///< the effective scene it is a render of
  /// [y][x][3]: the unit view direction through each pixel's centre, in the east-north-up frame of
  /// the scene's reference point (x east, y north, z up; camera.hpp); (0, 0, 0) where the camera
  /// has none (outside the fisheye's circle).
  std::vector<double> directions;
  Vec3 sun_direction = Vec3::Zero();  ///< unit, towards the sun's centre, the same frame
  Rgb sun_rgb = Rgb::Zero();          ///< the sun's top-of-atmosphere irradiance in the image's RGB
  /// The automatic exposure's reading: the scale that takes the log-average luminance of the sky
  /// (without the sun's disk) at the metered pixels to 0.18 (exposure.hpp). The exposure the files
  /// record and apply is this unless the scene (output.exposure_ev) or the display settings fix one.
  double metered_exposure_scale = 1.0;

  /// Pixel (x, y)'s spectral radiance: wavelengths_nm.size() values (W m^-2 sr^-1 nm^-1), row 0 at
  /// the top as in the files. Error for a pixel outside the image.
  const float* spectrum(int x, int y) const;
  /// Pixel (x, y)'s linear Rec.709 (the spectrum through CIE XYZ, Y in cd m^-2).
  Rgb pixel_rgb(int x, int y) const;
  /// Pixel (x, y)'s view direction (as `directions`).
  Vec3 direction(int x, int y) const;
};
SpectralImageBuffer render_to_memory(const Scene& scene, const ProgressFn& progress = {});

/// The exposure the files of an image record and apply (render_scene_to_files' rule): the display
/// settings' manual or camera exposure; else output.exposure_ev when the scene sets it; else the
/// automatic one (metered_exposure_scale). With how it was chosen, in words.
struct PreviewExposure {
  double scale = 1.0;
  std::string description;
};
PreviewExposure preview_exposure(const SpectralImageBuffer& image);
PreviewExposure preview_exposure(const SpectralImageBuffer& image, const DisplaySettings& display);

/// The spectral EXR of an image in memory, as render_scene_to_files writes it for the same scene
/// and display settings: the same channels, values and header (provenance, exposure, units,
/// envmap), written atomically. Throws Error for a buffer render_to_memory did not make (size,
/// channels and scene disagree) and IoError for a value that is not finite or a failed write.
void write_spectral_exr(const SpectralImageBuffer& image, const std::filesystem::path& path);
void write_spectral_exr(const SpectralImageBuffer& image, const std::filesystem::path& path,
                        const DisplaySettings& display);
/// The image through a display pipeline as a PNG, as render_scene_to_files writes its preview (the
/// same code values and text chunks), atomically; returns the exposure's scale.
double write_display_png(const SpectralImageBuffer& image, const std::filesystem::path& path);
double write_display_png(const SpectralImageBuffer& image, const std::filesystem::path& path,
                         const DisplaySettings& display);

/// The PNG write_display_png writes for the image and settings, as bytes in memory (the same code
/// values and text chunks, no file), compressed as `compression` says: the viewer's frames.
std::string display_png_bytes(const SpectralImageBuffer& image, const DisplaySettings& display = {},
                              PngCompression compression = PngCompression::Smallest);
/// The picture of a polarised image's polarisation (scene output.polarisation; InputError
/// otherwise) as PNG bytes: the colours of <name>-polarisation.png (hue: the angle of linear
/// polarisation of the luminance-weighted Stokes vector, brightness: its degree).
std::string polarisation_png_bytes(const SpectralImageBuffer& image,
                                   PngCompression compression = PngCompression::Smallest);

struct RenderOutputs {
  std::filesystem::path exr, png;     ///< empty when not written
  std::filesystem::path working_exr;  ///< the RGB EXR in DisplaySettings::exr_space, if asked for
  /// output.polarisation: <name>-polarisation.exr (Y, DoLP, AoLP; not for a tile) and, with
  /// output.polarisation_png, <name>-polarisation.png.
  std::filesystem::path polarisation_exr, polarisation_png;
  std::filesystem::path surface_exr;  ///< output.surface: distance and masks (render/surface_pass.hpp)
  double preview_scale = 1.0;         ///< the exposure: factor applied to linear RGB before display
  double preview_ev = 0.0;            ///< log2(preview_scale)
  std::string exposure;               ///< how the exposure was chosen (also in the files' headers)
  std::string display;                ///< the display pipeline used for the PNG
  double seconds = 0.0;               ///< wall time of the whole call
  // Where it went (wall time; the rest is what `prepared` does, such as the render-budget sample):
  double tables_seconds = 0.0;  ///< set-up: atmosphere, optical-depth, scattering-order and sky-view tables
  double image_seconds = 0.0;   ///< exposure metering and the image's rows (with the EXR's bands, written meanwhile)
  double output_seconds = 0.0;  ///< completing the files: the EXR's offset table, fsync and rename; PNG
  /// Every file written (or, from render_output_paths, to be written), in a fixed order: the
  /// spectral EXR, the PNG, the working-space EXR, the polarisation EXR and PNG.
  std::vector<std::filesystem::path> files() const;
};

/// A tile of the image, as pbrt's pixel bounds: columns [x0, x1) and rows [y0, y1) of the camera's
/// image. Tiles rendered separately and merged (merge_spectral_exr_tiles) give the bytes of the
/// whole render.
struct PixelBounds {
  int x0 = 0, x1 = 0, y0 = 0, y1 = 0;
};
/// "x0,x1,y0,y1" (pbrt's order) -> PixelBounds; InputError naming `setting` for other text.
PixelBounds parse_pixel_bounds(const std::string& text, const std::string& setting);
/// Throws InputError naming `setting` unless 0 <= x0 < x1 <= width and 0 <= y0 < y1 <= height.
void check_pixel_bounds(const PixelBounds& bounds, const CameraSpec& camera, const std::string& setting);

/// Renders the scene and writes its outputs (spectral EXR streamed in bands, PNG preview), each
/// atomically: on any error no output file is left behind.
RenderOutputs render_scene_to_files(const Scene& scene, const ProgressFn& progress = {});
/// The same with a display pipeline for the PNG (display_pipeline.hpp: OCIO display, view, look,
/// exposure, bit depth) and optionally a scene-linear RGB EXR in a working space. The exposure is
/// chosen before rendering (automatic exposure meters the sky first, see exposure.hpp) and
/// recorded in both EXRs' headers ("skyspec:exposure", "skyspec:exposureScale"); the EXR values
/// stay scene-linear. scene.output.exposure_ev, when set, is a manual exposure unless the settings
/// ask for a camera exposure. Without settings: sRGB, Un-tone-mapped, skyspec's built-in config.
/// `prepared`, when given, is called with the renderer once it is built, before the exposure is
/// metered and before any file is created: it may throw to refuse the render (render_budget.hpp).
using PreparedFn = std::function<void(const SkyRenderer& renderer)>;
/// With `tile`, only those pixels are rendered, into a spectral EXR whose data window is the tile
/// and whose header is the whole render's (the same exposure, metered on the whole image); the
/// scene must ask for the spectral EXR alone (InputError otherwise).
RenderOutputs render_scene_to_files(const Scene& scene, const DisplaySettings& display, const ProgressFn& progress = {},
                                    const PreparedFn& prepared = {},
                                    const std::optional<PixelBounds>& tile = std::nullopt);
/// The files render_scene_to_files writes for these settings: exr, png and working_exr set (empty
/// where not asked for), nothing rendered. Unknown working spaces, and no output at all
/// (output.exr and output.png false and no working space), throw InputError.
RenderOutputs render_output_paths(const Scene& scene, const DisplaySettings& display);

}  // namespace skyspec
