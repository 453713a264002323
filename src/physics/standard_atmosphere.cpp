// U.S. Standard Atmosphere 1976 (NOAA/NASA/USAF, Washington DC, 1976), lower atmosphere, computed
// from its defining layer table rather than read from its printed tables.
//
// Below 86 km the standard defines temperature as piecewise linear in geopotential altitude H
// (m'), with base altitudes H_b and lapse rates L_b (Table 4 of the standard). Pressure follows
// from the hydrostatic equation and the ideal gas law integrated layer by layer:
//
//   T(H) = T_b + L_b (H - H_b)
//   P(H) = P_b [T_b / T(H)]^(g0 M0 / (R* L_b))      if L_b != 0
//   P(H) = P_b exp(-g0 M0 (H - H_b) / (R* T_b))      if L_b == 0
//
// Each layer's base temperature and pressure are those at the top of the layer below, starting
// from T0 = 288.15 K and P0 = 101325 Pa at H = 0.
//
// The temperature returned is the standard's molecular-scale temperature T_M. Below 80 km it is the
// kinetic temperature; from 80 to 86 km the standard multiplies it by a tabulated M/M0 that falls
// to 0.999579, so there T (and N = P / (k T)) differ from the printed tables by less than 5e-4.
#include "skyspec/standard_atmosphere.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <sstream>

#include "base/text_format.hpp"
#include "skyspec/error.hpp"
#include "skyspec/units.hpp"

namespace skyspec {
namespace {

constexpr double kMetresPerKilometre = 1000.0;

/// Effective Earth radius of the geopotential conversion, m (the standard's r0 = 6356.766 km).
constexpr double kEarthRadiusForGeopotential_m = 6356.766e3;
/// Standard gravity g0, m s^-2 (defines the geopotential metre).
constexpr double kStandardGravity_m_per_s2 = 9.80665;
/// Sea-level mean molecular weight of air M0, kg mol^-1 (the standard's 28.9644 g/mol).
constexpr double kSeaLevelMolarMass_kg_per_mol = 28.9644e-3;
/// Gas constant R* as adopted by the standard, J mol^-1 K^-1 (not the CODATA value).
constexpr double kStandardGasConstant_J_per_mol_K = 8.31432;
/// Sea-level temperature T0, K, and pressure P0, Pa.
constexpr double kSeaLevelTemperature_K = 288.15;
constexpr double kSeaLevelPressure_Pa = 101325.0;

/// g0 M0 / R*, K per geopotential metre: the hydrostatic constant of every layer.
constexpr double kHydrostaticConstant_K_per_m =
    kStandardGravity_m_per_s2 * kSeaLevelMolarMass_kg_per_mol / kStandardGasConstant_J_per_mol_K;

/// Validity range of this implementation (geometric altitude, m).
constexpr double kMinimumAltitude_m = -5000.0;
constexpr double kMaximumAltitude_m = 100000.0;

/// One layer of the standard's Table 4: base geopotential altitude (m') and lapse rate (K/m').
struct LayerDefinition {
  double base_geopotential_m;
  double lapse_rate_K_per_m;
};

/// The seven layers from 0 to 84.852 km'. The first layer also covers -5 km to 0 (the standard's
/// tables start at -5 km with the same lapse rate). The last layer, defined up to 84.852 km'
/// (86 km geometric), is continued upwards to 100 km geometric: the standard's upper atmosphere
/// (86-1000 km) is defined differently (diffusive separation, geometric altitude), but the air
/// there holds less than 1e-5 of the column, which is negligible for optical work.
constexpr std::array<LayerDefinition, 7> kLayers{{
    {0.0 * kMetresPerKilometre, -6.5 / kMetresPerKilometre},
    {11.0 * kMetresPerKilometre, 0.0 / kMetresPerKilometre},
    {20.0 * kMetresPerKilometre, +1.0 / kMetresPerKilometre},
    {32.0 * kMetresPerKilometre, +2.8 / kMetresPerKilometre},
    {47.0 * kMetresPerKilometre, 0.0 / kMetresPerKilometre},
    {51.0 * kMetresPerKilometre, -2.8 / kMetresPerKilometre},
    {71.0 * kMetresPerKilometre, -2.0 / kMetresPerKilometre},
}};

/// A layer's base state, derived by chaining the layers below it.
struct LayerBase {
  double geopotential_m;
  double lapse_rate_K_per_m;
  double temperature_K;
  double pressure_Pa;
};

/// T(H) = T_b + L_b (H - H_b).
double layer_temperature_K(const LayerBase& b, double geopotential_m) {
  return b.temperature_K + b.lapse_rate_K_per_m * (geopotential_m - b.geopotential_m);
}

/// Hydrostatic pressure within a layer (see the file comment for both forms).
double layer_pressure_Pa(const LayerBase& b, double geopotential_m) {
  if (b.lapse_rate_K_per_m == 0.0)
    return b.pressure_Pa *
           std::exp(-kHydrostaticConstant_K_per_m * (geopotential_m - b.geopotential_m) / b.temperature_K);
  const double temperature_K = layer_temperature_K(b, geopotential_m);
  return b.pressure_Pa * std::pow(b.temperature_K / temperature_K, kHydrostaticConstant_K_per_m / b.lapse_rate_K_per_m);
}

/// Base temperature and pressure of every layer, chained upwards from sea level.
std::array<LayerBase, kLayers.size()> chain_layer_bases() {
  std::array<LayerBase, kLayers.size()> bases{};
  bases[0] = {kLayers[0].base_geopotential_m, kLayers[0].lapse_rate_K_per_m, kSeaLevelTemperature_K,
              kSeaLevelPressure_Pa};
  for (std::size_t i = 1; i < kLayers.size(); ++i) {
    const LayerBase& below = bases[i - 1];
    const double top_m = kLayers[i].base_geopotential_m;
    bases[i] = {top_m, kLayers[i].lapse_rate_K_per_m, layer_temperature_K(below, top_m),
                layer_pressure_Pa(below, top_m)};
  }
  return bases;
}

const std::array<LayerBase, kLayers.size()>& layer_bases() {
  static const std::array<LayerBase, kLayers.size()> bases = chain_layer_bases();
  return bases;
}

/// The layer containing a geopotential altitude (the first layer for anything below sea level,
/// the last for anything above 71 km').
const LayerBase& layer_at(double geopotential_m) {
  const auto& bases = layer_bases();
  std::size_t i = 0;
  while (i + 1 < bases.size() && geopotential_m >= bases[i + 1].geopotential_m) ++i;
  return bases[i];
}

}  // namespace

// H = r0 z / (r0 + z), both in metres (r0 = 6356.766 km, the standard's effective Earth radius).
double geopotential_altitude_m(double geometric_altitude_m) {
  return kEarthRadiusForGeopotential_m * geometric_altitude_m / (kEarthRadiusForGeopotential_m + geometric_altitude_m);
}

AtmosphereState us_standard_atmosphere_1976(double geometric_altitude_m) {
  if (!std::isfinite(geometric_altitude_m) || geometric_altitude_m < kMinimumAltitude_m ||
      geometric_altitude_m > kMaximumAltitude_m)
    throw InputError("altitude_m", format_number(geometric_altitude_m), "-5000 to 100000 m");
  const double geopotential_m = geopotential_altitude_m(geometric_altitude_m);
  const LayerBase& layer = layer_at(geopotential_m);
  AtmosphereState state{};
  state.temperature_K = layer_temperature_K(layer, geopotential_m);
  state.pressure_Pa = layer_pressure_Pa(layer, geopotential_m);
  // Ideal gas: N = P / (k T).
  state.number_density_per_m3 = state.pressure_Pa / (constants::kBoltzmann_J_per_K * state.temperature_K);
  return state;
}

}  // namespace skyspec
