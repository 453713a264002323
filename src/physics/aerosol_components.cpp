#include "skyspec/aerosol_components.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <sstream>

#include "base/csv_table.hpp"
#include "base/embedded_data.hpp"
#include "base/preparation_progress.hpp"
#include "physics/particle_optics_cache.hpp"
#include "skyspec/error.hpp"
#include "skyspec/size_distribution.hpp"
#include "skyspec/sphere_ensemble.hpp"
#include "skyspec/units.hpp"

namespace skyspec {

namespace {
constexpr const char* kFile = "aerosols/opac_components.csv";
constexpr int kAerosolCacheFormat = 1;
constexpr std::array<const char*, kAerosolComponentCount> kNames = {"inso", "waso", "soot", "ssam", "sscm",
                                                                    "minm", "miam", "micm", "mitr", "suso"};
constexpr std::array<const char*, kAerosolComponentCount> kDescriptions = {"insoluble",
                                                                           "water-soluble",
                                                                           "soot",
                                                                           "sea salt (accumulation mode)",
                                                                           "sea salt (coarse mode)",
                                                                           "mineral (nucleation mode)",
                                                                           "mineral (accumulation mode)",
                                                                           "mineral (coarse mode)",
                                                                           "mineral (transported)",
                                                                           "sulfate droplets"};

struct Row {
  double wavelength_nm, m_re, m_im, ext_per_km, ssa, g;
};
struct Humidity {
  int rh_percent;
  double r_min_um, r_max_um, sigma, r_mod_wet_um;
  std::vector<Row> rows;  // ascending wavelength
};
struct Component {
  std::vector<Humidity> humidities;  // ascending; one (0 %) for components that take up no water
};

const std::array<Component, kAerosolComponentCount>& table() {
  static const std::array<Component, kAerosolComponentCount> t = [] {
    std::array<Component, kAerosolComponentCount> c;
    const auto rows =
        parse_csv(kFile, embedded_file(kFile),
                  {"component", "rh_percent", "r_min_um", "r_max_um", "sigma", "r_mod_wet_um", "r_mod_dry_um",
                   "wavelength_um", "m_re", "m_im", "ext_per_km", "single_scattering_albedo", "asymmetry"});
    for (const CsvRow& r : rows) {
      const auto it = std::find(kNames.begin(), kNames.end(), r.fields[0]);
      if (it == kNames.end()) throw Error(std::string(kFile) + ": unknown component " + r.fields[0]);
      Component& comp = c[static_cast<size_t>(it - kNames.begin())];
      const int rh = static_cast<int>(csv_number(kFile, r, 1));
      if (comp.humidities.empty() || comp.humidities.back().rh_percent != rh)
        comp.humidities.push_back({rh,
                                   csv_number(kFile, r, 2),
                                   csv_number(kFile, r, 3),
                                   csv_number(kFile, r, 4),
                                   csv_number(kFile, r, 5),
                                   {}});
      comp.humidities.back().rows.push_back({csv_number(kFile, r, 7) * 1e3, csv_number(kFile, r, 8),
                                             csv_number(kFile, r, 9), csv_number(kFile, r, 10),
                                             csv_number(kFile, r, 11), csv_number(kFile, r, 12)});
    }
    for (size_t k = 0; k < c.size(); ++k)
      if (c[k].humidities.empty()) throw Error(std::string(kFile) + ": no rows for " + kNames[k]);
    return c;
  }();
  return t;
}

// The refractive index of one humidity's table at a wavelength, linear between its rows.
std::complex<double> index_at(const Humidity& h, double nm) {
  const auto& r = h.rows;
  auto it = std::upper_bound(r.begin(), r.end(), nm, [](double x, const Row& row) { return x < row.wavelength_nm; });
  size_t k =
      static_cast<size_t>(std::clamp<long>(static_cast<long>(it - r.begin()) - 1, 0, static_cast<long>(r.size()) - 2));
  const double f = (nm - r[k].wavelength_nm) / (r[k + 1].wavelength_nm - r[k].wavelength_nm);
  return {r[k].m_re + f * (r[k + 1].m_re - r[k].m_re), r[k].m_im + f * (r[k + 1].m_im - r[k].m_im)};
}

// The tabulated scattering angles: fine near the forward peak, where aerosols scatter most.
std::vector<double> make_cosines() {
  std::vector<double> deg;
  for (int k = 0; k < 40; ++k) deg.push_back(0.05 * k);          // 0 - 1.95
  for (int k = 0; k < 32; ++k) deg.push_back(2.0 + 0.25 * k);    // 2 - 9.75
  for (int k = 0; k <= 340; ++k) deg.push_back(10.0 + 0.5 * k);  // 10 - 180
  return cosines_of_degrees(deg);
}
}  // namespace

const std::array<const char*, kAerosolComponentCount>& aerosol_component_names() { return kNames; }
std::string aerosol_component_description(int c) { return kDescriptions[static_cast<size_t>(c)]; }

AerosolComponentWavelengths aerosol_component_wavelengths() {
  const auto& rows = table()[0].humidities.front().rows;
  return {rows.front().wavelength_nm, rows.back().wavelength_nm};
}

const std::vector<double>& aerosol_scattering_cosines() {
  static const std::vector<double> mu = make_cosines();
  return mu;
}

AerosolComponentState aerosol_component_state(int component, double rh, double nm, const std::string& setting) {
  const Component& c = table()[static_cast<size_t>(component)];
  const auto& rows = c.humidities.front().rows;
  if (!(nm >= rows.front().wavelength_nm && nm <= rows.back().wavelength_nm)) {
    std::ostringstream v, a;
    v << nm << " nm";
    a << "wavelengths from " << rows.front().wavelength_nm << " to " << rows.back().wavelength_nm
      << " nm (OPAC's refractive indices as skyspec carries them) for the microphysical aerosol";
    throw InputError("spectrum", v.str(), a.str());
  }
  if (!(rh >= 0.0 && rh <= 99.0)) {
    std::ostringstream v;
    v << rh;
    throw InputError(setting, v.str(), "a relative humidity in percent, >= 0 and <= 99 (OPAC's range)");
  }
  const auto& hs = c.humidities;
  size_t k = 0;
  while (k + 2 < hs.size() && rh > hs[k + 1].rh_percent) ++k;
  const Humidity& lo = hs[k];
  const Humidity& hi = hs.size() > 1 ? hs[k + 1] : hs[k];
  const double f = hs.size() > 1 ? std::clamp((rh - lo.rh_percent) / (hi.rh_percent - lo.rh_percent), 0.0, 1.0) : 0.0;
  const std::complex<double> m = (1.0 - f) * index_at(lo, nm) + f * index_at(hi, nm);
  AerosolComponentState s;
  s.median_radius_m = ((1.0 - f) * lo.r_mod_wet_um + f * hi.r_mod_wet_um) * 1e-6;
  s.geometric_standard_deviation = lo.sigma;
  s.min_radius_m = ((1.0 - f) * lo.r_min_um + f * hi.r_min_um) * 1e-6;
  s.max_radius_m = ((1.0 - f) * lo.r_max_um + f * hi.r_max_um) * 1e-6;
  s.m_real = m.real();
  s.m_imag = m.imag();
  return s;
}

double aerosol_component_fraction_in_range(const AerosolComponentState& s) {
  const double ln_s = std::log(s.geometric_standard_deviation) * std::sqrt(2.0);
  auto below = [&](double r) { return 0.5 * std::erfc(-std::log(r / s.median_radius_m) / ln_s); };
  return below(s.max_radius_m) - below(s.min_radius_m);
}

bool opac_published_optics(int component, int rh, double nm, OpacPublishedOptics& out) {
  for (const Humidity& h : table()[static_cast<size_t>(component)].humidities) {
    if (h.rh_percent != rh) continue;
    for (const Row& r : h.rows)
      if (std::abs(r.wavelength_nm - nm) < 1e-6) {
        out = {r.ext_per_km, r.ssa, r.g};
        return true;
      }
  }
  return false;
}

AerosolMixture AerosolMixture::continental_average() {
  AerosolMixture m;
  m.number_per_cm3[0] = 0.4;     // inso
  m.number_per_cm3[1] = 7000.0;  // waso
  m.number_per_cm3[2] = 8300.0;  // soot
  return m;
}

namespace {
RawParticleOptics compute(const AerosolMixture& mix, const WavelengthGrid& grid, const std::string& setting) {
  const std::vector<double>& mu = aerosol_scattering_cosines();
  const int n = grid.size();
  const size_t nm = mu.size();
  RawParticleOptics o;
  o.sca.assign(static_cast<size_t>(n), 0.0);
  o.ext.assign(static_cast<size_t>(n), 0.0);
  o.a1.assign(static_cast<size_t>(n), std::vector<double>(nm, 0.0));
  o.b1 = o.a3 = o.b2 = o.a1;
  long long pairs = 0;
  for (double number : mix.number_per_cm3) pairs += number > 0.0 ? n : 0;
  if (pairs == 0)
    throw InputError(setting + ".*_per_cm3", "0 for every component",
                     "at least one component with a number concentration > 0");
  plan_preparation(pairs, "computing the aerosol's optics (Lorenz-Mie)");
  for (int c = 0; c < kAerosolComponentCount; ++c) {
    const double per_m3 = mix.number_per_cm3[static_cast<size_t>(c)] * 1e6;
    if (!(per_m3 > 0.0)) continue;
    for (int i = 0; i < n; ++i) {
      const size_t w = static_cast<size_t>(i);
      const AerosolComponentState s =
          aerosol_component_state(c, mix.relative_humidity_percent, grid.nm(i), setting + ".relative_humidity_percent");
      const SizeDistribution sizes = SizeDistribution::lognormal(s.median_radius_m, s.geometric_standard_deviation)
                                         .truncated(s.min_radius_m, s.max_radius_m);
      const SphereEnsembleOptics e = sphere_ensemble_optics(sizes, {s.m_real, s.m_imag}, grid.nm(i) * 1e-9, 1.0, mu);
      const double in_range = per_m3 * aerosol_component_fraction_in_range(s);
      const double sca = in_range * e.scattering_cross_section_m2;
      o.sca[w] += sca;
      o.ext[w] += in_range * e.extinction_cross_section_m2;
      for (size_t k = 0; k < nm; ++k) {
        const SphereScatteringMatrix& p = e.phase_matrix[k];
        o.a1[w][k] += sca * p.s11;
        o.b1[w][k] += sca * p.s12;
        o.a3[w][k] += sca * p.s33;
        o.b2[w][k] += sca * p.s34;
      }
      finish_preparation(1);
    }
  }
  return o;
}

// What the optics depend on, as text: the mixture, the grid, the angles, the quadrature and the
// component table's bytes (a changed table is a new key).
std::string optics_key(const AerosolMixture& mix, const WavelengthGrid& grid) {
  std::ostringstream key;
  key.precision(17);
  key << "skyspec aerosol optics, format " << kAerosolCacheFormat << "\nnumber_per_cm3";
  for (double v : mix.number_per_cm3) key << ' ' << v;
  key << "\nrelative_humidity_percent " << mix.relative_humidity_percent << "\nwavelengths_nm";
  for (double v : grid.nanometres()) key << ' ' << v;
  const SphereEnsembleSettings quadrature;
  key << "\ncosines " << aerosol_scattering_cosines().size() << "\nquadrature " << quadrature.panel_ln_radius << ' '
      << quadrature.panel_size_parameter << "\ntable " << std::hex << fnv1a64(embedded_file(kFile)) << '\n';
  return key.str();
}

}  // namespace

AerosolMixtureOptics aerosol_mixture_optics(const AerosolMixture& mix, const WavelengthGrid& grid,
                                            const std::string& setting, bool use_disk_cache) {
  return cached_particle_optics(optics_key(mix, grid), grid.size(), aerosol_scattering_cosines(), use_disk_cache,
                                [&] { return compute(mix, grid, setting); });
}

}  // namespace skyspec
