// Aerial perspective: what the air between a camera and the surfaces it sees does to their light.
//
// For every pixel of a scene's camera and a distance along its ray (a depth pass, or one distance),
// the spectral transmittance T from the camera to the surface and the light L the air scatters into
// that stretch of ray (all the scattering orders the scene asks for); an image of the surfaces
// becomes image x T + L. Infinite distances are the sky. `skyspec aerial` is this plus files.
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "skyspec/render.hpp"
#include "skyspec/scene.hpp"

namespace skyspec {

/// Transmittance and inscattered light of every pixel, per wavelength and as linear Rec.709.
struct AerialPerspectiveImage {
  int width = 0, height = 0;
  std::vector<double> wavelengths_nm;
  std::vector<float> transmittance;  ///< [y][x][lambda], unitless
  std::vector<float> inscatter;      ///< [y][x][lambda], W m^-2 sr^-1 nm^-1
  /// [y][x][c]: the ratio of the sun's light after and before the path, per Rec.709 channel (what
  /// multiplies an RGB image lit by the sun).
  std::vector<float> transmittance_rgb;
  std::vector<float> inscatter_rgb;  ///< [y][x][c], linear Rec.709, Y in cd m^-2
  /// The scene's colour conversion: linear Rec.709 channel c of a spectrum s is (rgb_rows[c] * s).sum().
  std::array<Spectrum, 3> rgb_rows;
  Scene scene;  ///< the effective scene
};

/// Distances along each ray from a z depth (along the camera's view axis, the image centre's ray):
/// z / cos(ray, axis). Infinite values stay infinite. InputError naming `setting` for a NaN or a
/// negative value, with the pixel.
std::vector<float> ray_distances_from_z(const Scene& scene, const std::vector<float>& z_m,
                                        const std::string& setting = "depth");

/// The scene's own checks of aerial_perspective, without building anything (a front end calls it
/// before its budget's pilot): InputError for the RGB-fast path or output.polarisation.
void check_aerial_perspective_scene(const Scene& scene);

/// Aerial perspective for the scene's camera (its width x height) with distance_m[y][x] in metres
/// along each ray. InputError for the RGB-fast path or output.polarisation (not polarised), for a
/// distance buffer of another size, and for NaN or negative distances (naming `distance_setting`).
/// `prepared` is called with the renderer once its tables are built, before any pixel (it may
/// throw to refuse: render_budget.hpp).
AerialPerspectiveImage aerial_perspective(const Scene& scene, const std::vector<float>& distance_m,
                                          const ProgressFn& progress = {}, const PreparedFn& prepared = {},
                                          const std::string& distance_setting = "distance_m");

/// image x transmittance + inscatter: spectral ([y][x][lambda] on the same wavelengths) or linear
/// Rec.709 ([y][x][c], with the RGB transmittance). Error for a buffer of another size.
std::vector<float> composite_spectral(const AerialPerspectiveImage& ap, const std::vector<float>& spectral_image);
std::vector<float> composite_rgb(const AerialPerspectiveImage& ap, const std::vector<float>& rgb_image);

/// Writes <output.directory>/<output.name>_transmittance.exr and _inscatter.exr (spectral EXRs with
/// R, G, B), each atomically, with the scene's provenance; returns their paths.
std::vector<std::filesystem::path> write_aerial_perspective(const AerialPerspectiveImage& ap);
/// Writes <output.directory>/<output.name>_composite.exr, image x transmittance + inscatter:
/// spectral (S0 channels and R, G, B) for a spectral image, R, G, B for a linear Rec.709 one.
std::filesystem::path write_aerial_composite(const AerialPerspectiveImage& ap, const std::vector<float>& image,
                                             bool spectral);

}  // namespace skyspec
