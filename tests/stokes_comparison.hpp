// The polarised renderer against the vector Monte Carlo reference at a scene's standard probes:
// one record per probe and wavelength, for the tests that compare them.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "skyspec/camera.hpp"
#include "skyspec/monte_carlo_reference.hpp"
#include "skyspec/render.hpp"

namespace skyspec::test {

struct StokesAtProbe {
  std::string label;
  double nm = 0.0;
  Vec3 direction;
  Eigen::Index wavelength = 0;              ///< index in the scene's grid
  double i = 0.0, q = 0.0, u = 0.0;         ///< the renderer's (SkyRenderer::stokes, stokes_frame_axis)
  std::array<double, 3> reference{}, se{};  ///< the reference's I, Q, U and their standard errors
  double dolp = 0.0, dolp_reference = 0.0;
  /// The reference's DoLP's standard error from Q's, U's and I's, to first order (a bound: Q and I
  /// come from the same paths, so it overestimates).
  double dolp_se = 0.0;
};

inline std::vector<StokesAtProbe> compare_with_vector_reference(const Scene& scene, const SkyRenderer& renderer,
                                                                std::int64_t paths, std::uint64_t seed) {
  const std::vector<ReferenceProbe> probes = standard_reference_probes(scene);
  ReferenceSettings settings;
  settings.paths = paths;
  settings.seed = seed;
  settings.stokes = true;
  const ReferenceResult mc = monte_carlo_reference(scene, probes, settings);
  std::vector<StokesAtProbe> out;
  for (size_t k = 0; k < probes.size(); ++k) {
    const Vec3 dir = direction_from_angles(probes[k].azimuth_deg, probes[k].elevation_deg);
    Spectrum i, q, u;
    renderer.stokes(dir, stokes_frame_axis(dir), i, q, u);
    for (size_t w = 0; w < mc.wavelengths_nm.size(); ++w) {
      StokesAtProbe r;
      r.label = probes[k].label;
      r.nm = mc.wavelengths_nm[w];
      r.direction = dir;
      r.wavelength = static_cast<Eigen::Index>(w);
      r.i = i[r.wavelength];
      r.q = q[r.wavelength];
      r.u = u[r.wavelength];
      for (int c = 0; c < 3; ++c) {
        r.reference[static_cast<size_t>(c)] = mc.stokes[k][w][static_cast<size_t>(c)];
        r.se[static_cast<size_t>(c)] = mc.stokes_standard_error[k][w][static_cast<size_t>(c)];
      }
      r.dolp = std::hypot(r.q, r.u) / r.i;
      r.dolp_reference = std::hypot(r.reference[1], r.reference[2]) / r.reference[0];
      r.dolp_se = std::hypot(r.se[1], r.se[2]) / r.reference[0] + r.dolp_reference * r.se[0] / r.reference[0];
      out.push_back(r);
    }
  }
  return out;
}

}  // namespace skyspec::test
