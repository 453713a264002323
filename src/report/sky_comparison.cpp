// RGB-fast vs spectral comparison: common white and exposure, CIEDE2000 per pixel, regions.
#include "skyspec/sky_comparison.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "base/text_format.hpp"
#include "colour/chromatic_adaptation.hpp"
#include "colour/ciede2000.hpp"
#include "colour/exposure.hpp"
#include "io/provenance.hpp"
#include "io/rgb_exr.hpp"
#include "skyspec/colour.hpp"
#include "skyspec/error.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

std::string to_string(SkyRegion region) {
  switch (region) {
    case SkyRegion::NearSun:
      return "near the sun";
    case SkyRegion::Horizon:
      return "horizon band";
    case SkyRegion::Zenith:
      return "zenith";
    case SkyRegion::Rest:
      return "the rest";
  }
  return "?";
}

std::string region_key(SkyRegion region) {
  switch (region) {
    case SkyRegion::NearSun:
      return "near_sun";
    case SkyRegion::Horizon:
      return "horizon";
    case SkyRegion::Zenith:
      return "zenith";
    case SkyRegion::Rest:
      return "rest";
  }
  return "?";
}

PixelGeometry pixel_geometry(const Scene& scene, const RegionSettings& rs) {
  const auto camera = make_camera(scene);
  PixelGeometry g;
  g.width = camera->width();
  g.height = camera->height();
  const size_t n = static_cast<size_t>(g.width) * static_cast<size_t>(g.height);
  g.elevation_deg.assign(n, 0.0f);
  g.sun_angle_deg.assign(n, 0.0f);
  g.region.assign(n, kNotCompared);
  // Directions are world-space; "up" is the local vertical at the camera, and the sun direction
  // is given in the east-north-up frame of the reference point, as the renderer uses it.
  const Vec3 up = camera->origin_m().normalized();
  const Vec3 sun = sun_direction(scene).normalized();
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const size_t i = static_cast<size_t>(y) * static_cast<size_t>(g.width) + static_cast<size_t>(x);
      Vec3 dir;
      if (!camera->direction(x + 0.5, y + 0.5, dir)) continue;
      dir.normalize();
      const double elevation = radians_to_degrees(std::asin(std::clamp(dir.dot(up), -1.0, 1.0)));
      const double sun_angle = radians_to_degrees(std::acos(std::clamp(dir.dot(sun), -1.0, 1.0)));
      g.elevation_deg[i] = static_cast<float>(elevation);
      g.sun_angle_deg[i] = static_cast<float>(sun_angle);
      if (elevation < 0.0) continue;
      if (sun_angle < rs.near_sun_deg)
        g.region[i] = static_cast<uint8_t>(SkyRegion::NearSun);
      else if (elevation < rs.horizon_deg)
        g.region[i] = static_cast<uint8_t>(SkyRegion::Horizon);
      else if (90.0 - elevation < rs.zenith_deg)
        g.region[i] = static_cast<uint8_t>(SkyRegion::Zenith);
      else
        g.region[i] = static_cast<uint8_t>(SkyRegion::Rest);
    }
  return g;
}

// ---------------------------------------------------------------------------------------------
// Images
// ---------------------------------------------------------------------------------------------

SkyImage render_sky_image(const Scene& scene, const ProgressFn& progress) {
  SkyRenderer r(scene);
  SkyImage image;
  image.width = r.width();
  image.height = r.height();
  image.path = scene.render.path == RenderSpec::Path::RgbFast ? "rgb-fast" : "spectral";
  image.label = image.path + " (" + r.grid().describe() + ")";
  const size_t n = static_cast<size_t>(r.grid().size()), w = static_cast<size_t>(image.width);
  image.rgb.resize(w * static_cast<size_t>(image.height) * 3);
  const int band = 16;
  std::vector<float> spectral(static_cast<size_t>(band) * w * n);
  for (int y = 0; y < image.height; y += band) {
    const int rows = std::min(band, image.height - y);
    r.render_rows(y, rows, spectral.data(), image.rgb.data() + static_cast<size_t>(y) * w * 3);
    if (progress) progress(y + rows, image.height);
  }
  image.sun_rgb = r.spectrum_to_rgb(r.sun_irradiance()).cast<double>().matrix();
  return image;
}

SkyImage read_sky_image(const std::filesystem::path& path, Scene* scene) {
  if (!std::filesystem::is_regular_file(path))
    throw InputError("EXR", "'" + path.string() + "'", "an existing EXR file");
  const RgbExrImage exr = read_rgb_exr(path);
  const auto attribute = [&](const std::string& key) -> const std::string& {
    const auto it = exr.strings.find(key);
    if (it == exr.strings.end())
      throw InputError("EXR", "'" + path.string() + "'",
                       "a file written by `skyspec render` (it has no " + key + " attribute; render it again)");
    return it->second;
  };
  SkyImage image;
  image.width = exr.width;
  image.height = exr.height;
  image.rgb = exr.rgb;
  image.path = attribute("skyspec:renderPath");
  image.label = image.path + " (" + path.filename().string() + ")";
  if (const auto v = exr.vectors.find(kSunRgbAttribute); v != exr.vectors.end()) {
    for (int c = 0; c < 3; ++c) image.sun_rgb[c] = v->second[static_cast<size_t>(c)];
  } else {  // files before it was a v3d attribute
    std::istringstream sun(attribute(kSunRgbAttribute));
    sun.imbue(std::locale::classic());
    sun >> image.sun_rgb[0] >> image.sun_rgb[1] >> image.sun_rgb[2];
    if (!sun) throw IoError("EXR '" + path.string() + "': skyspec:sunRGB is not three numbers");
  }
  for (float v : image.rgb)
    if (!std::isfinite(v)) throw IoError("EXR '" + path.string() + "': non-finite R, G, B values");
  if (scene) {
    SceneLoader loader("default");
    loader.apply_toml(attribute("skyspec:scene"), path.string() + " (skyspec:scene)");
    *scene = loader.finish();
  }
  return image;
}

// ---------------------------------------------------------------------------------------------
// Twins
// ---------------------------------------------------------------------------------------------

Scene rgb_fast_twin(const Scene& scene) {
  Scene s = scene;
  s.render.path = RenderSpec::Path::RgbFast;
  s.spectrum = SpectrumSpec{};
  s.spectrum.wavelengths_nm = {440.0, 550.0, 680.0};
  auto& ray = s.atmosphere.rayleigh;
  if (ray.source == RayleighSpec::Source::Fixed) {
    std::vector<double> nm, beta;
    for (double wanted : s.spectrum.wavelengths_nm)
      for (size_t i = 0; i < ray.fixed_wavelengths_nm.size(); ++i)
        if (std::abs(ray.fixed_wavelengths_nm[i] - wanted) < 1e-6) {
          nm.push_back(wanted);
          beta.push_back(ray.fixed_beta_per_m[i]);
        }
    if (nm.size() != 3)
      throw InputError("atmosphere.rayleigh.wavelengths_nm", "a fixed list without 440, 550 and 680 nm",
                       "fixed coefficients at 440, 550 and 680 nm for the RGB-fast twin");
    ray.fixed_wavelengths_nm = nm;
    ray.fixed_beta_per_m = beta;
  }
  return s;
}

Scene spectral_twin(const Scene& scene, std::string* note) {
  Scene s = scene;
  s.render.path = RenderSpec::Path::Spectral;
  s.spectrum = SpectrumSpec{};  // 380-780 nm, 10 nm
  const WavelengthGrid grid = make_wavelength_grid(s);
  auto& ray = s.atmosphere.rayleigh;
  if (note) note->clear();
  if (ray.source == RayleighSpec::Source::Fixed) {
    // beta(lambda) = K lambda^-4 with log K the mean of log(beta_i) + 4 log(lambda_i).
    const size_t m = ray.fixed_wavelengths_nm.size();
    if (m == 0 || ray.fixed_beta_per_m.size() != m)
      throw InputError("atmosphere.rayleigh.beta_per_m", "an empty list", "fixed coefficients to extend");
    double sum = 0.0;
    for (size_t i = 0; i < m; ++i)
      sum += std::log(ray.fixed_beta_per_m[i]) + 4.0 * std::log(ray.fixed_wavelengths_nm[i] / 1000.0);
    const double K = std::exp(sum / static_cast<double>(m));  // m^-1 um^4
    double worst = 0.0;
    for (size_t i = 0; i < m; ++i)
      worst = std::max(
          worst, std::abs(K * std::pow(ray.fixed_wavelengths_nm[i] / 1000.0, -4.0) / ray.fixed_beta_per_m[i] - 1.0));
    ray.fixed_wavelengths_nm = grid.nanometres();
    ray.fixed_beta_per_m.clear();
    for (double nm : grid.nanometres()) ray.fixed_beta_per_m.push_back(K * std::pow(nm / 1000.0, -4.0));
    if (note) {
      char text[400];
      std::snprintf(text, sizeof text,
                    "The scene's Rayleigh coefficients are typed in at %zu wavelengths; the spectral twin extends them "
                    "with the lambda^-4 law fitted to them, beta = %.5g m^-1 um^4 / lambda^4, which reproduces the "
                    "typed-in values to %.2g %%.",
                    m, K, 100.0 * worst);
      *note = text;
    }
  }
  return s;
}

// ---------------------------------------------------------------------------------------------
// Statistics
// ---------------------------------------------------------------------------------------------

namespace {

/// Percentile p in [0, 1] of sorted values, by linear interpolation between order statistics.
double percentile(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return 0.0;
  const double position = p * static_cast<double>(sorted.size() - 1);
  const size_t below = static_cast<size_t>(std::floor(position));
  const size_t above = std::min(below + 1, sorted.size() - 1);
  return sorted[below] + (position - static_cast<double>(below)) * (sorted[above] - sorted[below]);
}

LuminanceErrorStats luminance_stats(const std::vector<double>& errors) {
  LuminanceErrorStats s;
  s.pixels = errors.size();
  if (errors.empty()) return s;
  std::vector<double> magnitude;
  double sum = 0.0;
  for (double e : errors) {
    sum += e;
    magnitude.push_back(std::abs(e));
  }
  std::sort(magnitude.begin(), magnitude.end());
  s.mean = sum / static_cast<double>(errors.size());
  s.median_abs = percentile(magnitude, 0.5);
  s.p95_abs = percentile(magnitude, 0.95);
  s.max_abs = magnitude.back();
  return s;
}

}  // namespace

DeltaEStats delta_e_stats(std::vector<double> values) {
  DeltaEStats s;
  s.pixels = values.size();
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  double sum = 0.0;
  size_t above1 = 0, above2 = 0, above5 = 0;
  for (double v : values) {
    sum += v;
    above1 += v > 1.0;
    above2 += v > 2.0;
    above5 += v > 5.0;
  }
  const double n = static_cast<double>(values.size());
  s.mean = sum / n;
  s.median = percentile(values, 0.5);
  s.p95 = percentile(values, 0.95);
  s.max = values.back();
  s.share_above_1 = static_cast<double>(above1) / n;
  s.share_above_2 = static_cast<double>(above2) / n;
  s.share_above_5 = static_cast<double>(above5) / n;
  return s;
}

// ---------------------------------------------------------------------------------------------
// The comparison
// ---------------------------------------------------------------------------------------------

namespace {

/// Rule 1: the matrix from an image's R, G, B to XYZ relative to its sun, adapted to D65.
Eigen::Matrix3d sun_relative_xyz(const SkyImage& image, const Eigen::Vector3d& d65_unit) {
  const Eigen::Vector3d sun_xyz = linear_rec709_to_xyz() * image.sun_rgb;
  if (!(sun_xyz.y() > 0.0) || !sun_xyz.allFinite() || (sun_xyz.array() <= 0.0).any())
    throw InputError("sun",
                     "XYZ (" + format_number(sun_xyz.x()) + ", " + format_number(sun_xyz.y()) + ", " +
                         format_number(sun_xyz.z()) + ") of the " + image.label + " image",
                     "a sun with positive X, Y and Z (the comparison's white)");
  // Bradford maps sun_xyz onto d65_unit exactly: adaptation and division by the sun's luminance.
  return bradford_adaptation(sun_xyz, d65_unit) * linear_rec709_to_xyz();
}

}  // namespace

SkyComparison compare_skies(const SkyImage& reference, const SkyImage& test, const PixelGeometry& geometry) {
  if (reference.width != test.width || reference.height != test.height || reference.width != geometry.width ||
      reference.height != geometry.height)
    throw InputError("images",
                     std::to_string(reference.width) + "x" + std::to_string(reference.height) + " and " +
                         std::to_string(test.width) + "x" + std::to_string(test.height),
                     "two images of the same size as the camera (" + std::to_string(geometry.width) + "x" +
                         std::to_string(geometry.height) + ")");
  const size_t n = static_cast<size_t>(reference.width) * static_cast<size_t>(reference.height);
  const Eigen::Vector3d d65_unit = linear_rec709_to_xyz() * Eigen::Vector3d::Ones();
  const Eigen::Matrix3d to_ref = sun_relative_xyz(reference, d65_unit);
  const Eigen::Matrix3d to_test = sun_relative_xyz(test, d65_unit);
  const auto xyz_of = [](const Eigen::Matrix3d& m, const std::vector<float>& rgb, size_t i) {
    return Eigen::Vector3d(m * Eigen::Vector3d(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]));
  };

  // Rule 2: the reference's automatic exposure over the compared pixels.
  std::vector<double> reference_luminance;
  for (size_t i = 0; i < n; ++i)
    if (geometry.region[i] != kNotCompared) reference_luminance.push_back(xyz_of(to_ref, reference.rgb, i).y());
  SkyComparison c;
  c.width = reference.width;
  c.height = reference.height;
  c.exposure_scale = key_exposure_scale(reference_luminance);
  const double k = c.exposure_scale;

  c.delta_e.assign(n, 0.0f);
  c.luminance_error.assign(n, 0.0f);
  c.region = geometry.region;
  c.reference_rgb.resize(3 * n);
  c.test_rgb.resize(3 * n);
  const Eigen::Matrix3d to_rec709 = xyz_to_linear_rec709();
  std::vector<double> all_de, all_lum;
  std::array<std::vector<double>, 4> region_de, region_lum;
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d a = k * xyz_of(to_ref, reference.rgb, i);
    const Eigen::Vector3d b = k * xyz_of(to_test, test.rgb, i);
    const Eigen::Vector3d ra = to_rec709 * a, rb = to_rec709 * b;
    for (size_t ch = 0; ch < 3; ++ch) {
      c.reference_rgb[3 * i + ch] = static_cast<float>(ra[static_cast<long>(ch)]);
      c.test_rgb[3 * i + ch] = static_cast<float>(rb[static_cast<long>(ch)]);
    }
    if (geometry.region[i] == kNotCompared) continue;
    const double de = ciede2000(xyz_to_lab(a, d65_unit), xyz_to_lab(b, d65_unit));
    c.delta_e[i] = static_cast<float>(de);
    all_de.push_back(de);
    region_de[geometry.region[i]].push_back(de);
    if (a.y() > 0.0) {
      const double err = (b.y() - a.y()) / a.y();
      c.luminance_error[i] = static_cast<float>(err);
      all_lum.push_back(err);
      region_lum[geometry.region[i]].push_back(err);
    }
  }
  c.all = {delta_e_stats(all_de), luminance_stats(all_lum)};
  for (size_t r = 0; r < 4; ++r) c.regions[r] = {delta_e_stats(region_de[r]), luminance_stats(region_lum[r])};
  return c;
}

std::string comparison_rules(const RegionSettings& rs) {
  std::ostringstream out;
  out << "- **Paths.** Reference: the spectral path (spectrum -> CIE 1931 XYZ -> linear Rec.709). Test: the RGB-fast "
         "path (radiance at 680, 550, 440 nm read directly as linear Rec.709 R, G, B).\n"
      << "- **Common white and luminance scale: the extraterrestrial sun.** Each image is divided by the luminance of "
         "its own sun (the sun's spectral irradiance through the same conversion as the pixels) and adapted (Bradford) "
         "from the sun's colour to D65, so both describe a sky lit by a D65-white sun of unit luminance. The RGB-fast "
         "path takes sunlight as RGB white; the sun's overall colour cast is therefore not counted as an error, its "
         "spectral shape is.\n"
      << "- **Common exposure.** Both images are multiplied by the automatic exposure of the reference image (its "
         "log-average luminance over the compared pixels -> 0.18, Reinhard et al. 2002); CIELAB uses the D65 white at "
         "luminance 1 after that (L* = 100 is the un-tone-mapped display white; brighter pixels have L* > 100).\n"
      << "- **Compared pixels.** View direction at or above the horizon, inside the image. Regions, first match wins: "
         "near the sun (< "
      << format_number(rs.near_sun_deg) << " deg from the sun's centre), horizon band (elevation < "
      << format_number(rs.horizon_deg) << " deg), zenith (zenith angle < " << format_number(rs.zenith_deg)
      << " deg), the rest.\n"
      << "- **Per pixel.** CIEDE2000 (Sharma, Wu & Dalal 2005; k_L = k_C = k_H = 1) and the relative luminance error "
         "(Y_RGB-fast - Y_spectral) / Y_spectral.\n"
      << "- **Statistics.** Mean, median and 95th percentile (linear interpolation between order statistics), maximum, "
         "and the share of pixels with Delta E_00 above 1, 2 and 5.\n";
  return out.str();
}

}  // namespace skyspec
