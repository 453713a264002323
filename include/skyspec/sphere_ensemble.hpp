// The optical properties of a population of homogeneous spheres at one wavelength: Lorenz-Mie
// theory (lorenz_mie.hpp) averaged over a size distribution (size_distribution.hpp),
//
//   <C_ext> = integral pi r^2 Q_ext(x(r)) dN/dr dr,  <C_sca> likewise,  x(r) = 2 pi r n_med / lambda,
//   g = integral g(r) C_sca(r) dN / <C_sca>,
//   P_ij(mu) = integral S_ij(mu; r) dN / (k^2 <C_sca>),  k = 2 pi n_med / lambda,
//
// per particle (multiply by the number concentration for volume coefficients). P_ij is the
// normalised scattering matrix: P_11 integrates to 1 over the sphere (sr^-1), the convention of
// skyspec's phase functions. The integrals are composite Gauss-Legendre rules in ln r whose panels
// are also at most `panel_size_parameter` wide in size parameter, so that the interference
// structure of Q(x) (period pi / (m - 1) in x) and of the side-scattered light is resolved; the
// narrow resonances are sampled, not resolved, which a broad distribution mostly averages out but
// which dominate the light scattered straight back. The error of the default settings is measured
// in docs/validation.md (test_sphere_ensemble: halving both steps). The cost is one series per
// node and one sum over its terms per node and angle: about x_max / panel_size_parameter * 8 nodes.
#pragma once

#include <complex>
#include <vector>

#include "skyspec/lorenz_mie.hpp"
#include "skyspec/size_distribution.hpp"

namespace skyspec {

struct SphereEnsembleSettings {
  double panel_ln_radius = 0.05;      ///< the widest quadrature panel in ln r
  double panel_size_parameter = 1.0;  ///< the widest panel in size parameter (8 nodes per panel)
};

struct SphereEnsembleOptics {
  double wavelength_m = 0.0;
  double extinction_cross_section_m2 = 0.0;          ///< <C_ext>, per particle
  double scattering_cross_section_m2 = 0.0;          ///< <C_sca>
  double geometric_cross_section_m2 = 0.0;           ///< pi <r^2>
  double asymmetry = 0.0;                            ///< g
  int radius_nodes = 0;                              ///< quadrature nodes used
  std::vector<double> mu;                            ///< cosines of the scattering angle asked for
  std::vector<SphereScatteringMatrix> phase_matrix;  ///< P_ij at each mu, sr^-1
  double single_scattering_albedo() const {
    return extinction_cross_section_m2 > 0.0 ? scattering_cross_section_m2 / extinction_cross_section_m2 : 0.0;
  }
};

/// m_relative: the spheres' refractive index over the medium's (imag >= 0); wavelength in vacuum.
/// Throws std::invalid_argument when the distribution reaches a size parameter above 2e4 (truncate
/// it: SizeDistribution::truncated) or an argument is out of range.
SphereEnsembleOptics sphere_ensemble_optics(const SizeDistribution& sizes, std::complex<double> m_relative,
                                            double wavelength_m, double medium_index, const std::vector<double>& mu,
                                            const SphereEnsembleSettings& settings = {});

}  // namespace skyspec
