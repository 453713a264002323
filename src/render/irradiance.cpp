#include "render/irradiance.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "base/cancellation.hpp"
#include "base/quadrature.hpp"
#include "base/text_format.hpp"
#include "skyspec/colour.hpp"
#include "skyspec/error.hpp"
#include "skyspec/units.hpp"
#include "transport/multiple_scattering.hpp"

namespace skyspec {

namespace {
// Trapezoid integral of a sampled spectrum over its grid.
double integrate_over_grid(const WavelengthGrid& grid, const SpectrumD& v) {
  return trapezoid(grid.nanometres().data(), v.data(), grid.nanometres().size());
}
}  // namespace

IrradianceReport irradiance_at_camera(const SkyRenderer& r, int zenith_nodes, int azimuth_nodes) {
  const WavelengthGrid& grid = r.grid();
  const int n = grid.size();
  if (grid.size() < 2) throw InputError("spectrum", grid.describe(), "at least 2 wavelengths for irradiance");
  const Vec3 up = r.camera_origin_m().normalized();
  // A tangent frame at the camera.
  const Vec3 east = (std::abs(up.z()) < 0.9 ? Vec3(0, 0, 1).cross(up) : Vec3(0, 1, 0).cross(up)).normalized();
  const Vec3 north = up.cross(east);

  IrradianceReport rep;
  rep.wavelengths_nm = grid.nanometres();
  // Direct.
  const Spectrum t = r.transmittance(r.sun_direction());
  rep.direct_normal.resize(n);
  for (int i = 0; i < n; ++i) rep.direct_normal[i] = static_cast<double>(r.sun_irradiance()[i]) * t[i];
  const double cos_sun = std::max(0.0, r.sun_direction().dot(up));
  rep.direct_horizontal = rep.direct_normal * cos_sun;

  // Diffuse: hemisphere quadrature, rows of zenith nodes in parallel (on the renderer's threads).
  std::vector<double> mu, w;
  gauss_legendre(zenith_nodes, 0.0, 1.0, mu, w);
  std::vector<SpectrumD> rows(static_cast<size_t>(zenith_nodes), SpectrumD::Zero(n));
  tbb::task_arena arena(r.threads());
  arena.execute([&] {
    tbb::parallel_for(0, zenith_nodes, [&](int i) {
      const double m = mu[static_cast<size_t>(i)], sin_t = std::sqrt(1 - m * m);
      for (int j = 0; j < azimuth_nodes; ++j) {
        const double phi = 2 * kPi * (j + 0.5) / azimuth_nodes;
        const Vec3 d = (sin_t * std::cos(phi)) * east + (sin_t * std::sin(phi)) * north + m * up;
        const Spectrum L = r.radiance(d);
        for (int l = 0; l < n; ++l)
          rows[static_cast<size_t>(i)][l] += w[static_cast<size_t>(i)] * m * (2 * kPi / azimuth_nodes) * L[l];
      }
    });
  });
  rep.diffuse_horizontal = SpectrumD::Zero(n);
  for (const auto& row : rows) rep.diffuse_horizontal += row;

  rep.direct_normal_W_m2 = integrate_over_grid(grid, rep.direct_normal);
  rep.direct_horizontal_W_m2 = integrate_over_grid(grid, rep.direct_horizontal);
  rep.diffuse_horizontal_W_m2 = integrate_over_grid(grid, rep.diffuse_horizontal);
  const SpectrumToXyz xyz(grid, constants::kMaxLuminousEfficacy_lm_per_W);
  rep.direct_normal_lux = xyz(rep.direct_normal)[1];
  rep.direct_horizontal_lux = xyz(rep.direct_horizontal)[1];
  rep.diffuse_horizontal_lux = xyz(rep.diffuse_horizontal)[1];
  const SpectrumD global_horizontal = rep.direct_horizontal + rep.diffuse_horizontal;
  rep.global_horizontal_cct = correlated_colour_temperature(xyz(global_horizontal));
  rep.diffuse_horizontal_cct = correlated_colour_temperature(xyz(rep.diffuse_horizontal));
  return rep;
}

IrradianceReport irradiance_report(const Scene& scene, const SkyRenderer& renderer) {
  IrradianceReport rep = irradiance_at_camera(renderer);
  if (scene.irradiance.broadband) rep.broadband = broadband_irradiance(scene);
  return rep;
}

std::vector<IrradianceReport> irradiance_reports(const Scene& scene, const std::vector<double>& sun_elevations_deg,
                                                 const ProgressFn& progress) {
  if (scene.render.path != RenderSpec::Path::Spectral)
    throw InputError("render.path", "\"rgb-fast\"", "\"spectral\" (illuminance needs the colour-matching functions)");
  for (double el : sun_elevations_deg)
    if (!(el >= -90.0 && el <= 90.0))
      throw InputError("sun_elevations_deg", format_number(el), "angles in degrees from -90 to 90");
  if (scene.irradiance.broadband) broadband_run_scenes(scene);  // its refusals, before any work
  const std::vector<double> elevations =
      sun_elevations_deg.empty() ? std::vector<double>{scene.sun.elevation_deg} : sun_elevations_deg;
  Scene s = scene;
  s.camera.width = s.camera.height = 1;  // only the camera's position matters: a cheap set-up
  std::vector<IrradianceReport> reports;
  for (size_t k = 0; k < elevations.size(); ++k) {
    throw_if_cancelled();
    s.sun.elevation_deg = elevations[k];
    const SkyRenderer r(s);
    reports.push_back(irradiance_report(s, r));
    if (progress) progress(static_cast<int>(k + 1), static_cast<int>(elevations.size()));
  }
  return reports;
}

std::vector<CameraIrradiance> camera_irradiance(const Scene& scene, const std::vector<double>& sun_elevations_deg,
                                                const ProgressFn& progress) {
  const std::vector<IrradianceReport> reports = irradiance_reports(scene, sun_elevations_deg, progress);
  std::vector<CameraIrradiance> out;
  for (size_t k = 0; k < reports.size(); ++k) {
    const IrradianceReport& rep = reports[k];
    CameraIrradiance c;
    c.sun_elevation_deg = sun_elevations_deg.empty() ? scene.sun.elevation_deg : sun_elevations_deg[k];
    c.wavelengths_nm = rep.wavelengths_nm;
    for (const IrradianceQuantity& q : irradiance_quantities()) {
      if (!q.present_in(rep)) continue;
      if (q.spectral()) {
        const SpectrumD v = q.spectrum(rep);
        c.spectra.emplace_back(q.key, std::vector<double>(v.data(), v.data() + v.size()));
      } else {
        c.values.emplace_back(q.key, q.value(rep));
      }
    }
    if (rep.global_horizontal_cct)
      c.global_cct_K = rep.global_horizontal_cct->cct_K, c.global_duv = rep.global_horizontal_cct->duv;
    if (rep.diffuse_horizontal_cct)
      c.diffuse_cct_K = rep.diffuse_horizontal_cct->cct_K, c.diffuse_duv = rep.diffuse_horizontal_cct->duv;
    out.push_back(std::move(c));
  }
  return out;
}

bool IrradianceQuantity::band_limited() const { return !spectral() && !of_broadband && std::string(units) == "W m-2"; }

const std::vector<IrradianceQuantity>& irradiance_quantities() {
  using R = IrradianceReport;
  static const std::vector<IrradianceQuantity> list = {
      {"direct_normal_W_m2", "direct_normal_irradiance", "direct normal irradiance over the band", "W m-2", 4,
       [](const R& r) { return r.direct_normal_W_m2; }, nullptr},
      {"direct_horizontal_W_m2", "direct_horizontal_irradiance",
       "direct irradiance on a horizontal surface over the band", "W m-2", 4,
       [](const R& r) { return r.direct_horizontal_W_m2; }, nullptr},
      {"diffuse_horizontal_W_m2", "diffuse_horizontal_irradiance",
       "diffuse irradiance on a horizontal surface over the band", "W m-2", 4,
       [](const R& r) { return r.diffuse_horizontal_W_m2; }, nullptr},
      {"global_horizontal_W_m2", "global_horizontal_irradiance",
       "global (direct + diffuse) irradiance on a horizontal surface over the band", "W m-2", 4,
       [](const R& r) { return r.global_horizontal_W_m2(); }, nullptr},
      {"direct_normal_lux", "direct_normal_illuminance", "direct normal illuminance", "lx", 2,
       [](const R& r) { return r.direct_normal_lux; }, nullptr},
      {"direct_horizontal_lux", "direct_horizontal_illuminance", "direct illuminance on a horizontal surface", "lx", 2,
       [](const R& r) { return r.direct_horizontal_lux; }, nullptr},
      {"diffuse_horizontal_lux", "diffuse_horizontal_illuminance", "diffuse illuminance on a horizontal surface", "lx",
       2, [](const R& r) { return r.diffuse_horizontal_lux; }, nullptr},
      {"global_horizontal_lux", "global_horizontal_illuminance", "global illuminance on a horizontal surface", "lx", 2,
       [](const R& r) { return r.global_horizontal_lux(); }, nullptr},
      {"global_horizontal_W_m2_nm", "spectral_global_horizontal_irradiance",
       "spectral global irradiance on a horizontal surface", "W m-2 nm-1", 6, nullptr,
       [](const R& r) { return r.global_horizontal(); }},
      {"diffuse_horizontal_W_m2_nm", "spectral_diffuse_horizontal_irradiance",
       "spectral diffuse irradiance on a horizontal surface", "W m-2 nm-1", 6, nullptr,
       [](const R& r) { return r.diffuse_horizontal; }},
      {"direct_normal_W_m2_nm", "spectral_direct_normal_irradiance", "spectral direct normal irradiance", "W m-2 nm-1",
       6, nullptr, [](const R& r) { return r.direct_normal; }},
      {"broadband_direct_normal_W_m2", "broadband_direct_normal_irradiance",
       "direct normal irradiance, 300-4000 nm, with the gases' bands", "W m-2", 4,
       [](const R& r) { return r.broadband->direct_normal_W_m2; }, nullptr, true, nullptr},
      {"broadband_direct_horizontal_W_m2", "broadband_direct_horizontal_irradiance",
       "direct irradiance on a horizontal surface, 300-4000 nm, with the gases' bands", "W m-2", 4,
       [](const R& r) { return r.broadband->direct_horizontal_W_m2; }, nullptr, true,
       "surface_direct_downwelling_shortwave_flux_in_air"},
      {"broadband_diffuse_horizontal_W_m2", "broadband_diffuse_horizontal_irradiance",
       "diffuse irradiance on a horizontal surface, 300-4000 nm, with the gases' bands", "W m-2", 4,
       [](const R& r) { return r.broadband->diffuse_horizontal_W_m2; }, nullptr, true,
       "surface_diffuse_downwelling_shortwave_flux_in_air"},
      {"broadband_global_horizontal_W_m2", "broadband_global_horizontal_irradiance",
       "global irradiance on a horizontal surface, 300-4000 nm, with the gases' bands (what a pyranometer measures)",
       "W m-2", 4, [](const R& r) { return r.broadband->global_horizontal_W_m2(); }, nullptr, true,
       "surface_downwelling_shortwave_flux_in_air"},
  };
  return list;
}

std::string IrradianceReport::describe() const {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "irradiance at the camera (%g-%g nm): direct normal %.1f W/m2 (%.0f lx), direct horizontal %.1f W/m2 "
                "(%.0f lx), diffuse horizontal %.1f W/m2 (%.0f lx), global horizontal %.0f lx",
                wavelengths_nm.front(), wavelengths_nm.back(), direct_normal_W_m2, direct_normal_lux,
                direct_horizontal_W_m2, direct_horizontal_lux, diffuse_horizontal_W_m2, diffuse_horizontal_lux,
                global_horizontal_lux());
  return buf;
}

}  // namespace skyspec
