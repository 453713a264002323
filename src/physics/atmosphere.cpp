#include "skyspec/atmosphere.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "physics/media/media.hpp"
#include "skyspec/error.hpp"
#include "skyspec/phase_function.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

std::string to_string(ProfileKind k) {
  switch (k) {
    case ProfileKind::Exponential:
      return "exponential";
    case ProfileKind::UsStandard1976:
      return "us1976";
    case ProfileKind::Constant:
      return "constant";
  }
  return "?";
}

DensityProfile make_profile(ProfileKind kind, double scale_height_m, double top_altitude_m) {
  switch (kind) {
    case ProfileKind::Exponential:
      return DensityProfile::exponential(scale_height_m);
    case ProfileKind::UsStandard1976:
      return DensityProfile::us_standard_1976(top_altitude_m);
    case ProfileKind::Constant:
      return DensityProfile::constant();
  }
  return DensityProfile::constant();
}

AtmosphereModel::AtmosphereModel(const AtmosphereSpec& spec, const WavelengthGrid& grid, bool cache_on_disk)
    : spec_(spec), grid_(grid) {
  const MediumContext context{spec_, grid_, cache_on_disk};
  for (const MediumEntry& entry : medium_registry())
    if (std::optional<Medium> m = entry.build(context)) add_medium(std::move(*m));

  // What the Rayleigh derivation report shows.
  const AirNumberDensity n0 = air_number_density(spec.rayleigh);
  rayleigh_n0_per_m3_ = n0.per_m3;
  rayleigh_n0_origin_ = n0.origin;
  if (spec.rayleigh.source == RayleighSpec::Source::Derived && spec.gas_band_term < 0)
    derivation_ = derive_rayleigh(grid.nanometres(), spec.rayleigh.derivation);
  ozone_peak_per_m3_ = skyspec::ozone_peak_number_density_per_m3(spec.ozone);

  // --- Ground -----------------------------------------------------------------------------
  ground_albedo_ = albedo_on_grid(spec.ground, grid);
}

SpectrumD albedo_on_grid(const GroundSpec& g, const WavelengthGrid& grid) {
  SpectrumD albedo(grid.size());
  for (int i = 0; i < grid.size(); ++i)
    albedo[i] =
        g.albedo_values.empty() ? g.albedo : interpolate_linear(g.albedo_wavelengths_nm, g.albedo_values, grid.nm(i));
  return albedo;
}

const Medium* AtmosphereModel::medium(const std::string& name) const {
  for (const Medium& m : media_)
    if (m.name == name) return &m;
  return nullptr;
}

namespace {
std::string format_value(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}
// Every value finite and >= 0, one per wavelength.
void check_spectrum(const std::string& key, const SpectrumD& v, int n) {
  if (v.size() != n)
    throw InputError(key, std::to_string(v.size()) + " values",
                     "one value per wavelength of the grid (" + std::to_string(n) + ")");
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(v[i]) || v[i] < 0.0)
      throw InputError(key, format_value(v[i]), "finite values >= 0 (wavelength " + std::to_string(i) + ")");
}
}  // namespace

std::optional<AtmosphereModel> AtmosphereModel::with_forward_peaks_truncated(double cone_rad) const {
  std::optional<AtmosphereModel> out;
  for (size_t j = 0; j < media_.size(); ++j) {
    const Medium& m = media_[j];
    if (m.phase.kind != MediumPhase::Kind::Tabulated || !m.scatters()) continue;
    if (!out) out = *this;
    Medium& cut = out->media_[j];
    TruncatedScatteringMatrix t = truncate_forward_peak(*m.phase.matrix, cone_rad);
    for (int i = 0; i < grid_.size(); ++i) {
      const double f = t.removed[static_cast<size_t>(i)];
      cut.extinction_per_m[i] = m.extinction_per_m[i] - f * m.scattering_per_m[i];
      cut.scattering_per_m[i] = (1.0 - f) * m.scattering_per_m[i];
      cut.phase.g[i] = t.matrix->asymmetry(i);
    }
    cut.phase.matrix = std::move(t.matrix);
  }
  return out;
}

bool AtmosphereModel::has_regional_media() const {
  for (const Medium& m : media_)
    if (m.region) return true;
  return false;
}

std::optional<AtmosphereModel> AtmosphereModel::with_regional_media_as_probes() const {
  if (!has_regional_media()) return std::nullopt;
  AtmosphereModel out = *this;
  for (Medium& m : out.media_) {
    if (!m.region) continue;
    m.region.reset();
    m.scattering_per_m *= kProbeDensity;
    m.extinction_per_m *= kProbeDensity;
  }
  return out;
}

void AtmosphereModel::add_medium(Medium m) {
  const int n = grid_.size();
  const std::string key = "medium." + (m.name.empty() ? std::string("?") : m.name);
  if (m.name.empty()) throw InputError("medium.name", "\"\"", "a name of the medium");
  if (medium(m.name)) throw InputError(key + ".name", m.name, "a name no other medium of the atmosphere has");
  if (media_.size() >= static_cast<size_t>(kMaxMedia))
    throw InputError(key, m.name, "at most " + std::to_string(kMaxMedia) + " media in one atmosphere (kMaxMedia)");
  check_spectrum(key + ".scattering_per_m", m.scattering_per_m, n);
  check_spectrum(key + ".extinction_per_m", m.extinction_per_m, n);
  for (int i = 0; i < n; ++i)
    if (m.extinction_per_m[i] < m.scattering_per_m[i] * (1.0 - 1e-12))
      throw InputError(key + ".extinction_per_m", format_value(m.extinction_per_m[i]),
                       "at least the scattering coefficient (" + format_value(m.scattering_per_m[i]) +
                           " at wavelength " + std::to_string(i) + ")");
  MediumPhase& p = m.phase;
  switch (p.kind) {
    case MediumPhase::Kind::None:
      if (m.scattering_per_m.size() > 0 && m.scattering_per_m.maxCoeff() > 0.0)
        throw InputError(key + ".phase", "none", "a phase function for a medium that scatters");
      break;
    case MediumPhase::Kind::Rayleigh:
      check_spectrum(key + ".phase.rayleigh_gamma", p.rayleigh_gamma, n);
      break;
    case MediumPhase::Kind::Analytic:
      if (p.g.size() != n)
        throw InputError(key + ".phase.g", std::to_string(p.g.size()) + " values",
                         "one asymmetry parameter per wavelength of the grid (" + std::to_string(n) + ")");
      for (int i = 0; i < n; ++i)
        if (!(std::abs(p.g[i]) < 1.0)) throw InputError(key + ".phase.g", format_value(p.g[i]), "-1 < g < 1");
      break;
    case MediumPhase::Kind::Tabulated:
      if (!p.matrix || p.matrix->wavelengths() != n)
        throw InputError(key + ".phase.matrix",
                         p.matrix ? std::to_string(p.matrix->wavelengths()) + " wavelengths" : "none",
                         "a scattering matrix with one row per wavelength of the grid (" + std::to_string(n) + ")");
      if (p.g.size() != n) {  // the table's own asymmetry, for reports and the Monte Carlo
        p.g.resize(n);
        for (int i = 0; i < n; ++i) p.g[i] = p.matrix->asymmetry(i);
      }
      break;
  }
  // The integrator's log-mean rule needs a scatterer's density to be positive everywhere.
  if (m.scatters() && !m.profile.positive_everywhere())
    throw InputError(key + ".profile", m.profile.describe(),
                     "a density profile that is positive everywhere for a medium that scatters (exponential, "
                     "us1976, constant); a layer (tent) only for an absorber");
  if (m.region) {
    if (!(m.region->radius_m > 0.0) || !std::isfinite(m.region->radius_m))
      throw InputError(key + ".region.radius_m", format_value(m.region->radius_m), "a positive radius in metres");
    if (!(std::abs(m.region->axis.norm() - 1.0) < 1e-9))
      throw InputError(key + ".region.axis", format_value(m.region->axis.norm()), "a unit vector (its length)");
  }
  media_.push_back(std::move(m));
}

double MediumPhase::at(int i, double mu) const {
  switch (kind) {
    case Kind::None:
      return 0.0;
    case Kind::Rayleigh:
      return rayleigh_phase(mu, rayleigh_gamma[i]);
    case Kind::Analytic:
      return analytic(i)(mu);
    case Kind::Tabulated:
      return matrix->phase(i, mu);
  }
  return 0.0;
}

bool MediumPhase::varies_with_wavelength() const {
  return kind == Kind::Tabulated || (kind == Kind::Analytic && g.size() > 0 && g.maxCoeff() != g.minCoeff());
}

double interpolate_linear(const std::vector<double>& x, const std::vector<double>& y, double x0) {
  if (x.empty()) return 0.0;
  if (x0 <= x.front()) return y.front();
  if (x0 >= x.back()) return y.back();
  const auto it = std::upper_bound(x.begin(), x.end(), x0);
  const size_t i = static_cast<size_t>(it - x.begin());
  const double f = (x0 - x[i - 1]) / (x[i] - x[i - 1]);
  return y[i - 1] + f * (y[i] - y[i - 1]);
}

}  // namespace skyspec
