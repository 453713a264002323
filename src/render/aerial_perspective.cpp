// Aerial perspective (skyspec/aerial_perspective.hpp): SkyRenderer::aerial_rows over the image,
// the RGB of both spectra, composites and files.
#include "skyspec/aerial_perspective.hpp"

#include <cmath>
#include <string>

#include "base/atomic_file.hpp"
#include "io/exr_channels.hpp"
#include "io/spectral_exr.hpp"
#include "physics/unmodelled_absorption.hpp"
#include "render/scene_provenance.hpp"
#include "skyspec/colour.hpp"
#include "skyspec/error.hpp"

namespace skyspec {

namespace {

void check_distances(const std::vector<float>& d, int width, const std::string& setting) {
  for (size_t i = 0; i < d.size(); ++i)
    if (std::isnan(d[i]) || d[i] < 0.0f)
      throw InputError(setting,
                       "pixel (" + std::to_string(i % static_cast<size_t>(width)) + ", " +
                           std::to_string(i / static_cast<size_t>(width)) + ") = " + std::to_string(d[i]),
                       "distances >= 0 (infinity for the sky)");
}

}  // namespace

std::vector<float> ray_distances_from_z(const Scene& scene, const std::vector<float>& z_m, const std::string& setting) {
  const int width = scene.camera.width, height = scene.camera.height;
  if (z_m.size() != static_cast<size_t>(width) * height)
    throw InputError(setting, std::to_string(z_m.size()) + " values",
                     std::to_string(width) + " x " + std::to_string(height) + " (the camera's pixels)");
  check_distances(z_m, width, setting);
  const auto camera = make_camera(scene);
  Vec3 forward;
  camera->direction(0.5 * width, 0.5 * height, forward);
  std::vector<float> dist(z_m.size());
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t i = static_cast<size_t>(y) * width + x;
      float d = z_m[i];
      if (std::isfinite(d)) {
        Vec3 dir;
        camera->direction(x + 0.5, y + 0.5, dir);
        d = static_cast<float>(d / std::max(1e-6, dir.dot(forward)));
      }
      dist[i] = d;
    }
  return dist;
}

void check_aerial_perspective_scene(const Scene& scene) {
  if (scene.render.path != RenderSpec::Path::Spectral)
    throw InputError("render.path", "\"rgb-fast\"", "\"spectral\" for aerial perspective");
  if (scene.output.polarisation)
    throw InputError("output.polarisation", "true",
                     "false for aerial perspective (its transmittance and inscatter are not polarised; render the sky "
                     "with skyspec render)");
}

AerialPerspectiveImage aerial_perspective(const Scene& scene, const std::vector<float>& distance_m,
                                          const ProgressFn& progress, const PreparedFn& prepared,
                                          const std::string& distance_setting) {
  check_aerial_perspective_scene(scene);
  const int width = scene.camera.width, height = scene.camera.height;
  if (distance_m.size() != static_cast<size_t>(width) * height)
    throw InputError(distance_setting, std::to_string(distance_m.size()) + " values",
                     std::to_string(width) + " x " + std::to_string(height) + " (the camera's pixels)");
  check_distances(distance_m, width, distance_setting);
  const SkyRenderer r(scene);
  if (prepared) prepared(r);
  const int n = r.grid().size();
  AerialPerspectiveImage s;
  s.width = width;
  s.height = height;
  s.wavelengths_nm = r.grid().nanometres();
  s.scene = scene;
  s.transmittance.resize(static_cast<size_t>(width) * height * n);
  s.inscatter.resize(s.transmittance.size());
  const int band = 16;
  for (int y = 0; y < height; y += band) {
    const int rows = std::min(band, height - y);
    const size_t off = static_cast<size_t>(y) * width;
    r.aerial_rows(y, rows, distance_m.data() + off, s.transmittance.data() + off * n, s.inscatter.data() + off * n);
    if (progress) progress(y + rows, height);
  }
  s.transmittance_rgb.resize(static_cast<size_t>(width) * height * 3);
  s.inscatter_rgb.resize(s.transmittance_rgb.size());
  for (int c = 0; c < 3; ++c) s.rgb_rows[c] = Spectrum::Zero(n);
  for (int i = 0; i < n; ++i) {
    Spectrum unit = Spectrum::Zero(n);
    unit[i] = 1.0f;
    const Rgb column = r.spectrum_to_rgb(unit);
    for (int c = 0; c < 3; ++c) s.rgb_rows[c][i] = column[c];
  }
  const Rgb sun_rgb = r.spectrum_to_rgb(r.sun_irradiance());
  for (size_t i = 0; i < distance_m.size(); ++i) {
    const Eigen::Map<const Spectrum> inscatter(s.inscatter.data() + i * n, n),
        transmittance(s.transmittance.data() + i * n, n);
    Eigen::Map<Rgb>(s.inscatter_rgb.data() + i * 3) = r.spectrum_to_rgb(inscatter);
    const Rgb t_rgb = r.spectrum_to_rgb(transmittance * r.sun_irradiance());
    for (int c = 0; c < 3; ++c) s.transmittance_rgb[i * 3 + c] = sun_rgb[c] > 0 ? t_rgb[c] / sun_rgb[c] : 0.0f;
  }
  return s;
}

namespace {
// image x t + l, value by value, for buffers of one size.
std::vector<float> composite(const char* what, const std::vector<float>& image, const std::vector<float>& t,
                             const std::vector<float>& l) {
  if (image.size() != t.size())
    throw Error(std::string(what) + ": the image has " + std::to_string(image.size()) + " values, not " +
                std::to_string(t.size()));
  std::vector<float> comp(image.size());
  for (size_t i = 0; i < comp.size(); ++i) comp[i] = image[i] * t[i] + l[i];
  return comp;
}
}  // namespace

std::vector<float> composite_spectral(const AerialPerspectiveImage& ap, const std::vector<float>& spectral_image) {
  return composite("composite_spectral", spectral_image, ap.transmittance, ap.inscatter);
}

std::vector<float> composite_rgb(const AerialPerspectiveImage& ap, const std::vector<float>& rgb_image) {
  return composite("composite_rgb", rgb_image, ap.transmittance_rgb, ap.inscatter_rgb);
}

namespace {

// The files' header: version, scene, data tables, what is not modelled; envmap for the depth of a
// whole-sphere panorama.
SpectralExrMetadata aerial_metadata(const Scene& scene) {
  SpectralExrMetadata meta;
  meta.strings = provenance_attributes(scene, false);
  meta.strings["skyspec:notModelled"] = unmodelled_absorption_note(make_wavelength_grid(scene));
  meta.latlong_envmap = is_latlong_envmap(scene.camera);
  return meta;
}

std::filesystem::path write_spectral(const AerialPerspectiveImage& ap, const std::string& suffix,
                                     const std::vector<float>& spectral, const std::vector<float>& rgb,
                                     const std::string& what) {
  SpectralExrMetadata m = aerial_metadata(ap.scene);
  m.strings["skyspec:content"] = what;
  const auto path = std::filesystem::path(ap.scene.output.directory) / (ap.scene.output.name + suffix);
  SpectralExrWriter w(path, ap.width, ap.height, ap.wavelengths_nm, m);
  w.write_rows(ap.height, spectral.data(), rgb.data());
  w.finish();
  return path;
}

}  // namespace

std::vector<std::filesystem::path> write_aerial_perspective(const AerialPerspectiveImage& ap) {
  ensure_writable_directory(ap.scene.output.directory, "output.directory");
  std::vector<std::filesystem::path> written;
  written.push_back(write_spectral(
      ap, "_transmittance.exr", ap.transmittance, ap.transmittance_rgb,
      "aerial perspective: transmittance camera -> surface (S0 channels: unitless, per wavelength; R,G,B: "
      "ratio of sunlight after/before the path per Rec.709 channel)"));
  written.push_back(write_spectral(ap, "_inscatter.exr", ap.inscatter, ap.inscatter_rgb,
                                   "aerial perspective: light scattered into the path (S0: W m^-2 sr^-1 nm^-1; R,G,B: "
                                   "linear Rec.709, Y in cd m^-2)"));
  return written;
}

std::filesystem::path write_aerial_composite(const AerialPerspectiveImage& ap, const std::vector<float>& image,
                                             bool spectral) {
  ensure_writable_directory(ap.scene.output.directory, "output.directory");
  if (spectral) {
    const std::vector<float> comp = composite_spectral(ap, image);
    const int n = static_cast<int>(ap.wavelengths_nm.size());
    std::vector<float> comp_rgb(ap.transmittance_rgb.size());
    for (size_t i = 0; i < comp_rgb.size() / 3; ++i)
      for (int c = 0; c < 3; ++c)
        comp_rgb[i * 3 + c] = (ap.rgb_rows[c] * Eigen::Map<const Spectrum>(comp.data() + i * n, n)).sum();
    return write_spectral(ap, "_composite.exr", comp, comp_rgb,
                          "aerial perspective: image x transmittance + inscatter");
  }
  const std::vector<float> comp = composite_rgb(ap, image);
  std::vector<float> ch[3];
  for (int c = 0; c < 3; ++c) {
    ch[c].resize(comp.size() / 3);
    for (size_t i = 0; i < ch[c].size(); ++i) ch[c][i] = comp[i * 3 + c];
  }
  const SpectralExrMetadata meta = aerial_metadata(ap.scene);
  const auto path = std::filesystem::path(ap.scene.output.directory) / (ap.scene.output.name + "_composite.exr");
  write_exr_channels(path, ap.width, ap.height, {{"R", &ch[0]}, {"G", &ch[1]}, {"B", &ch[2]}},
                     {{"skyspec:content", "aerial perspective: image x transmittance + inscatter (linear Rec.709)"},
                      {kVersionAttribute, meta.strings.at(kVersionAttribute)},
                      {kSceneAttribute, meta.strings.at(kSceneAttribute)},
                      {kDataAttribute, meta.strings.at(kDataAttribute)}});
  return path;
}

}  // namespace skyspec
