// Broadband irradiance with the gases' bands; see broadband_irradiance.hpp.
#include "render/broadband_irradiance.hpp"

#include <string>

#include "base/quadrature.hpp"
#include "physics/gas_bands.hpp"
#include "physics/media/media.hpp"
#include "render/irradiance.hpp"
#include "skyspec/error.hpp"
#include "skyspec/render.hpp"
#include "skyspec/scene.hpp"

namespace skyspec {
namespace {

constexpr const char* kKey = "irradiance.broadband";

// The scene of one run: the term, its wavelengths (each standing for 10 nm, the solar spectrum's
// and the ozone table's mean over it), a 1x1 camera, no files.
Scene run_scene(const Scene& scene, int term, std::vector<double> wavelengths_nm) {
  Scene s = scene;
  s.atmosphere.gas_band_term = term;
  s.spectrum = SpectrumSpec{};
  s.spectrum.wavelengths_nm = std::move(wavelengths_nm);
  s.camera.width = s.camera.height = 1;
  s.irradiance.broadband = false;
  return s;
}

// The wavelengths term `term` is solved at, and their weights: every wavelength for term 0, those
// where a gas absorbs for the others.
struct RunWavelengths {
  std::vector<double> nm, weight;
  std::vector<int> node;
};
RunWavelengths run_wavelengths(const Scene& scene, int term) {
  const std::vector<double>& nodes = band_model_wavelengths_nm();
  const double water_cm = scene.atmosphere.water_vapour.column_cm;
  const double pressure = relative_surface_pressure(scene.atmosphere.rayleigh);
  RunWavelengths r;
  for (size_t j = 0; j < nodes.size(); ++j) {
    const GasTermCoefficients c = gas_term_coefficients(term, nodes[j], water_cm, pressure);
    if (term > 0 && !c.absorbs) continue;
    r.nm.push_back(nodes[j]);
    r.weight.push_back(c.weight);
    r.node.push_back(static_cast<int>(j));
  }
  return r;
}

// Throws InputError naming the key, with the reason a run's scene is refused.
[[noreturn]] void refuse(const InputError& e) {
  throw InputError(kKey, "true",
                   "false unless every medium of the scene is defined from 300 to 4000 nm: " + std::string(e.what()));
}

}  // namespace

std::vector<Scene> broadband_run_scenes(const Scene& scene) {
  if (scene.render.path != RenderSpec::Path::Spectral)
    throw InputError(kKey, "true", "false when render.path = \"rgb-fast\" (the broadband irradiance is spectral)");
  std::vector<Scene> scenes;
  for (int term = 0; term < exponential_term_count(); ++term) {
    RunWavelengths r = run_wavelengths(scene, term);
    if (r.nm.size() < 2) continue;
    scenes.push_back(run_scene(scene, term, std::move(r.nm)));
    try {
      check_spectral_range(scenes.back(), make_wavelength_grid(scenes.back()));
    } catch (const InputError& e) {
      refuse(e);
    }
  }
  return scenes;
}

BroadbandIrradiance broadband_irradiance(const Scene& scene, int zenith_nodes, int azimuth_nodes) {
  const std::vector<Scene> runs = broadband_run_scenes(scene);
  const std::vector<double>& nodes = band_model_wavelengths_nm();
  const int n = static_cast<int>(nodes.size());
  BroadbandIrradiance out;
  out.wavelengths_nm = nodes;
  out.direct_normal = SpectrumD::Zero(n);
  out.diffuse_horizontal = SpectrumD::Zero(n);
  for (const Scene& one : runs) {
    const RunWavelengths run = run_wavelengths(scene, one.atmosphere.gas_band_term);
    IrradianceReport rep;
    try {
      rep = irradiance_at_camera(SkyRenderer(one), zenith_nodes, azimuth_nodes);
    } catch (const InputError& e) {
      refuse(e);
    }
    for (size_t k = 0; k < run.node.size(); ++k) {
      const Eigen::Index i = static_cast<Eigen::Index>(k), j = run.node[k];
      out.direct_normal[j] += run.weight[k] * rep.direct_normal[i];
      out.diffuse_horizontal[j] += run.weight[k] * rep.diffuse_horizontal[i];
    }
    // The sun's cosine at the camera, where the most direct light is (a low sun leaves none at
    // 300 nm, under the ozone).
    Eigen::Index brightest = 0;
    rep.direct_normal.maxCoeff(&brightest);
    if (rep.direct_normal[brightest] > 0.0)
      out.cos_sun = rep.direct_horizontal[brightest] / rep.direct_normal[brightest];
    ++out.runs;
  }
  out.direct_normal_W_m2 = trapezoid(nodes.data(), out.direct_normal.data(), nodes.size());
  out.diffuse_horizontal_W_m2 = trapezoid(nodes.data(), out.diffuse_horizontal.data(), nodes.size());
  out.direct_horizontal_W_m2 = out.direct_normal_W_m2 * out.cos_sun;
  return out;
}

}  // namespace skyspec
