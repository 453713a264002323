#include "skyspec/sphere_ensemble.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "base/cancellation.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

namespace {
// The sums of one block of radius nodes; blocks are added in order, so that the result does not
// depend on how many threads computed them.
struct PartialSums {
  double ext = 0.0, sca = 0.0, g_sca = 0.0, geometric = 0.0;
  std::vector<SphereScatteringMatrix> s;
};
constexpr size_t kBlock = 16;
}  // namespace

SphereEnsembleOptics sphere_ensemble_optics(const SizeDistribution& sizes, std::complex<double> m_relative,
                                            double wavelength_m, double medium_index, const std::vector<double>& mu,
                                            const SphereEnsembleSettings& settings) {
  if (!(wavelength_m > 0.0) || !std::isfinite(wavelength_m))
    throw std::invalid_argument("sphere ensemble: wavelength must be a positive length");
  if (!(medium_index >= 1.0 && medium_index < 10.0))
    throw std::invalid_argument("sphere ensemble: the medium's refractive index must be in [1, 10)");
  for (double c : mu)
    if (!(c >= -1.0 && c <= 1.0)) throw std::invalid_argument("sphere ensemble: a scattering cosine outside [-1, 1]");
  const double k = 2.0 * kPi * medium_index / wavelength_m;
  const double x_max = k * sizes.max_radius_m();
  if (x_max > kMaxMieSizeParameter) {
    std::ostringstream s;
    s << "sphere ensemble: " << sizes.description() << " reaches radius " << sizes.max_radius_m() * 1e6
      << " um, size parameter " << x_max << " at " << wavelength_m * 1e9 << " nm; Lorenz-Mie here goes to 2e4 (radius "
      << kMaxMieSizeParameter / k * 1e6 << " um): truncate the distribution";
    throw std::invalid_argument(s.str());
  }
  const std::vector<RadiusNode> nodes = sizes.quadrature(settings.panel_ln_radius, settings.panel_size_parameter / k);
  const size_t blocks = (nodes.size() + kBlock - 1) / kBlock;
  std::vector<PartialSums> partial(blocks);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, blocks), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t b = range.begin(); b != range.end(); ++b) {
      throw_if_cancelled();
      PartialSums& p = partial[b];
      p.s.assign(mu.size(), SphereScatteringMatrix{});
      for (size_t i = b * kBlock; i < std::min(nodes.size(), (b + 1) * kBlock); ++i) {
        const double r = nodes[i].radius_m, w = nodes[i].weight;
        const MieSeries series = lorenz_mie(m_relative, k * r);
        const MieEfficiencies q = mie_efficiencies(series);
        const double area = kPi * r * r;
        p.ext += w * area * q.extinction;
        p.sca += w * area * q.scattering;
        p.g_sca += w * area * q.scattering * q.asymmetry;
        p.geometric += w * area;
        const std::vector<MieAmplitudes> amp = mie_amplitudes(series, mu);
        for (size_t j = 0; j < mu.size(); ++j) {
          const SphereScatteringMatrix m = sphere_scattering_matrix(amp[j]);
          p.s[j].s11 += w * m.s11;
          p.s[j].s12 += w * m.s12;
          p.s[j].s33 += w * m.s33;
          p.s[j].s34 += w * m.s34;
        }
      }
    }
  });
  SphereEnsembleOptics out;
  out.wavelength_m = wavelength_m;
  out.radius_nodes = static_cast<int>(nodes.size());
  out.mu = mu;
  out.phase_matrix.assign(mu.size(), SphereScatteringMatrix{});
  for (const PartialSums& p : partial) {
    out.extinction_cross_section_m2 += p.ext;
    out.scattering_cross_section_m2 += p.sca;
    out.asymmetry += p.g_sca;
    out.geometric_cross_section_m2 += p.geometric;
    for (size_t j = 0; j < mu.size(); ++j) {
      out.phase_matrix[j].s11 += p.s[j].s11;
      out.phase_matrix[j].s12 += p.s[j].s12;
      out.phase_matrix[j].s33 += p.s[j].s33;
      out.phase_matrix[j].s34 += p.s[j].s34;
    }
  }
  const double sca = out.scattering_cross_section_m2;
  out.asymmetry = sca > 0.0 ? out.asymmetry / sca : 0.0;
  const double scale = sca > 0.0 ? 1.0 / (k * k * sca) : 0.0;
  for (SphereScatteringMatrix& m : out.phase_matrix) {
    m.s11 *= scale;
    m.s12 *= scale;
    m.s33 *= scale;
    m.s34 *= scale;
  }
  return out;
}

}  // namespace skyspec
