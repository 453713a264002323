#include "render/table_family.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <sstream>

#include "base/recent_values.hpp"
#include "render/scene_tables.hpp"
#include "skyspec/spectrum.hpp"
#include "transport/optical_depth.hpp"
#include "transport/scattering_tables_cache.hpp"
#include "transport/single_scattering.hpp"

namespace skyspec {

namespace {

constexpr int kAerosolNodes = static_cast<int>(std::size(kAerosolNodes_per_m));
constexpr int kStencil = 4;  // cubic Lagrange in the aerosol's coefficient

// The coordinate the aerosol's weights are cubic in: x = ln(beta + kAerosolOffset_per_m), in
// which the doubling amounts are nearly evenly spaced. The tables bend most with the amount at
// small amounts and near the terminator, where the sun's light crosses an air mass of 30 and more
// and dims as exp(-m tau): there a cubic in x errs far less than one in beta itself (docs/jobs.md,
// "Tables shared between atmospheres", has both).
double aerosol_coordinate(double beta_per_m) { return std::log(beta_per_m + kAerosolOffset_per_m); }

// The Lagrange weights of the kStencil nodes from `first` on at beta, in aerosol_coordinate: sum_k
// w_k f(x_k) is the cubic through them. At a node, its own weight is 1 and the others' 0 exactly
// (a factor x - x_k = 0).
std::array<double, kStencil> lagrange_weights(int first, double beta) {
  const double x = aerosol_coordinate(beta);
  std::array<double, kStencil> nodes{}, w{};
  for (int k = 0; k < kStencil; ++k) nodes[static_cast<size_t>(k)] = aerosol_coordinate(kAerosolNodes_per_m[first + k]);
  for (int j = 0; j < kStencil; ++j) {
    double p = 1.0;
    for (int k = 0; k < kStencil; ++k)
      if (k != j)
        p *= (x - nodes[static_cast<size_t>(k)]) / (nodes[static_cast<size_t>(j)] - nodes[static_cast<size_t>(k)]);
    w[static_cast<size_t>(j)] = p;
  }
  return w;
}

// The first node of the stencil about x: the two nodes each side of it where there are two.
int stencil_start(double x) {
  int i = 0;
  while (i + 2 < kAerosolNodes && kAerosolNodes_per_m[i + 1] <= x) ++i;
  return std::clamp(i - 1, 0, kAerosolNodes - kStencil);
}

std::string describe(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// The grid's atmosphere: the scene's with the aerosol at `aerosol` (exponent 0) and the ozone column
// at `ozone` (each where the scene has that medium and the axis exists).
Scene member_scene(const Scene& scene, int aerosol, int ozone) {
  Scene m = scene;
  m.render.ms_tables = RenderSpec::Tables::Exact;
  if (aerosol >= 0) {
    m.atmosphere.mie.scattering_per_m = kAerosolNodes_per_m[aerosol];
    m.atmosphere.mie.angstrom_exponent = 0.0;
  }
  if (ozone >= 0) m.atmosphere.ozone.column_DU = ozone * kOzoneStep_DU;
  return m;
}

// The members' tables and the blends of this process: at most 32 besides the newest, 768 MiB.
RecentValues<ScatteringOrders>& kept_tables() {
  static RecentValues<ScatteringOrders> kept(32, std::size_t{768} << 20,
                                             [](const ScatteringOrders& o) { return o.bytes(); });
  return kept;
}

// The name of a scene's blend among kept_tables().
std::string blend_key(const AtmosphereModel& atmosphere, const Scene& scene) {
  return "interpolated\n" +
         scattering_tables_key(atmosphere, sun_table_resolution(scene), multiple_scattering_settings(scene)).inputs;
}

}  // namespace

std::optional<TableFamily> table_family(const Scene& scene, std::string* why_not) {
  const auto refuse = [&](const std::string& why) -> std::optional<TableFamily> {
    if (why_not) *why_not = why;
    return std::nullopt;
  };
  if (scene.render.scattering_orders < 2) return refuse("single scattering has no tables");
  const MieSpec& mie = scene.atmosphere.mie;
  const bool aerosol = mie.enabled;
  const bool ozone = scene.atmosphere.ozone.enabled;
  if (aerosol && mie.model != MieSpec::Model::Angstrom)
    return refuse("atmosphere.mie.model is not \"angstrom\" (only the Angstrom aerosol's tables are interpolated)");
  if (aerosol && !mie.table_wavelengths_nm.empty())
    return refuse("atmosphere.mie.table_wavelengths_nm is set (spectral aerosol tables are not interpolated)");
  if (!aerosol && !ozone) return refuse("neither the aerosol nor the ozone is on: nothing to interpolate");
  const WavelengthGrid grid = make_wavelength_grid(scene);
  const int n = grid.size();
  // Per wavelength: the aerosol's weights over the nodes (all of them, mostly zero).
  std::vector<std::vector<double>> aerosol_w(aerosol ? kAerosolNodes : 1, std::vector<double>(n, aerosol ? 0.0 : 1.0));
  if (aerosol) {
    const double last = kAerosolNodes_per_m[kAerosolNodes - 1];
    for (int i = 0; i < n; ++i) {
      const double beta =
          mie.scattering_per_m * std::pow(grid.nm(i) / mie.reference_wavelength_nm, -mie.angstrom_exponent);
      if (!(beta <= last))
        return refuse("the aerosol's scattering coefficient at " + describe(grid.nm(i)) + " nm, " + describe(beta) +
                      " m^-1 (atmosphere.mie.scattering_per_m and angstrom_exponent), is beyond the grid's " +
                      describe(last) + " m^-1");
      const int first = stencil_start(beta);
      const auto w = lagrange_weights(first, beta);
      for (int k = 0; k < kStencil; ++k) aerosol_w[static_cast<size_t>(first + k)][static_cast<size_t>(i)] = w[k];
    }
  }
  // The ozone column: the two columns about it (one where it is on the grid).
  int ozone_node = -1;
  float ozone_t = 0.0f;
  if (ozone) {
    const double column = scene.atmosphere.ozone.column_DU;
    if (!(column <= kOzoneLast_DU))
      return refuse("atmosphere.ozone.column_DU = " + describe(column) + " is beyond the grid's " +
                    describe(kOzoneLast_DU) + " DU");
    ozone_node = std::min(static_cast<int>(column / kOzoneStep_DU), static_cast<int>(kOzoneLast_DU / kOzoneStep_DU));
    ozone_t = static_cast<float>(column / kOzoneStep_DU - ozone_node);
  }
  const auto group = [&](int o) {
    TableFamily::Group g;
    for (size_t a = 0; a < aerosol_w.size(); ++a) {
      if (std::all_of(aerosol_w[a].begin(), aerosol_w[a].end(), [](double w) { return w == 0.0; })) continue;
      g.members.push_back(member_scene(scene, aerosol ? static_cast<int>(a) : -1, o));
      std::vector<float>& w = g.weights.emplace_back(static_cast<size_t>(n));
      for (int i = 0; i < n; ++i) w[static_cast<size_t>(i)] = static_cast<float>(aerosol_w[a][static_cast<size_t>(i)]);
    }
    return g;
  };
  TableFamily family;
  family.lower = group(ozone_node);
  if (ozone_t > 0.0f) {
    family.upper = group(ozone_node + 1);
    family.ozone_t = ozone_t;
  }
  return family;
}

std::vector<Scene> TableFamily::members() const {
  std::vector<Scene> all = lower.members;
  all.insert(all.end(), upper.members.begin(), upper.members.end());
  return all;
}

std::shared_ptr<const ScatteringOrders> interpolated_scattering_orders(const Scene& scene,
                                                                       const AtmosphereModel& atmosphere,
                                                                       std::string* why_not) {
  const std::optional<TableFamily> family = table_family(scene, why_not);
  if (!family) return nullptr;
  const MultipleScatteringSettings settings = multiple_scattering_settings(scene);
  return kept_tables().get(blend_key(atmosphere, scene), [&] {
    std::vector<std::shared_ptr<const ScatteringOrders>> held;  // the members' tables, while they are blended
    const auto blend_of = [&](const TableFamily::Group& g) {
      ScatteringOrders::Blend b;
      for (const Scene& m : g.members) b.members.push_back(held.emplace_back(scene_scattering_orders(m)).get());
      b.weights = g.weights;
      return b;
    };
    const ScatteringOrders::Blend lower = blend_of(family->lower), upper = blend_of(family->upper);
    return std::shared_ptr<const ScatteringOrders>(
        ScatteringOrders::blended(lower, upper, family->ozone_t, atmosphere, settings));
  });
}

bool interpolated_tables_in_memory(const Scene& scene) {
  if (!table_family(scene)) return false;
  const AtmosphereModel atmosphere(scene.atmosphere, make_wavelength_grid(scene), scene.render.cache_tables);
  return kept_tables().find(blend_key(atmosphere, scene)) != nullptr;
}

std::shared_ptr<const ScatteringOrders> scene_scattering_orders(const Scene& m) {
  const AtmosphereModel atmosphere(m.atmosphere, make_wavelength_grid(m), m.render.cache_tables);
  const SunColumnTable::Resolution sun = sun_table_resolution(m);
  const MultipleScatteringSettings settings = multiple_scattering_settings(m);
  const ScatteringTablesKey key = scattering_tables_key(atmosphere, sun, settings);
  return kept_tables().get(key.inputs, [&] {
    return scattering_orders_for(atmosphere, sun, settings, m.render.cache_tables, [&] {
      const auto table = SunColumnTable::shared(atmosphere, sun, SunColumnTable::MuBand{});
      const TableSunColumns columns(*table);
      const SingleScattering integrator(atmosphere, columns, IntegratorSettings{m.render.view_segments});
      return std::make_shared<const ScatteringOrders>(integrator, settings);
    });
  });
}

std::vector<Scene> scenes_of_tables(const Scene& scene) {
  if (scene.render.scattering_orders < 2) return {};
  if (scene.render.ms_tables == RenderSpec::Tables::Interpolated)
    if (std::optional<TableFamily> family = table_family(scene)) return family->members();
  return {scene};
}

bool scene_tables_cached(const Scene& scene) {
  for (const Scene& s : scenes_of_tables(scene)) {
    const ScatteringTablesKey key = scattering_tables_key(s);
    if (!kept_tables().find(key.inputs) && !scattering_orders_cached(key, s.render.cache_tables)) return false;
  }
  return true;
}

}  // namespace skyspec
