// The extraterrestrial solar spectral irradiance (ASTM G173-03 ETR column); see solar_spectrum.hpp.
#include "physics/solar_spectrum.hpp"

#include <cmath>
#include <string_view>

#include "base/csv_table.hpp"
#include "base/embedded_data.hpp"
#include "base/text_format.hpp"
#include "skyspec/error.hpp"

namespace skyspec {
namespace {

constexpr std::string_view kSolarFile = "solar/astm_g173_etr.csv";

TabulatedSpectrum load_solar_table() {
  const std::vector<CsvRow> rows = parse_csv(kSolarFile, embedded_file(kSolarFile), {"nm", "irradiance_W_m2_nm"});
  std::vector<double> nm, irradiance_W_m2_nm;
  for (const CsvRow& row : rows) {
    nm.push_back(csv_number(kSolarFile, row, 0));
    irradiance_W_m2_nm.push_back(csv_number(kSolarFile, row, 1));
  }
  return TabulatedSpectrum::samples("the ASTM G173-03 extraterrestrial solar table", std::move(nm),
                                    std::move(irradiance_W_m2_nm));
}

}  // namespace

const TabulatedSpectrum& solar_irradiance_table() {
  static const TabulatedSpectrum table = load_solar_table();
  return table;
}

SpectrumD solar_irradiance_on_grid(const WavelengthGrid& grid, const std::string& setting) {
  return solar_irradiance_table().mean_on_grid(grid, setting);
}

double solar_irradiance_integral_W_m2(double lo_nm, double hi_nm, const std::string& setting) {
  return solar_irradiance_table().integral(lo_nm, hi_nm, setting);
}

double inverse_square_distance_factor(double earth_sun_distance_au) {
  // The Earth's orbit keeps d within 0.983-1.017 AU; a wider window only catches unit mistakes.
  if (!(earth_sun_distance_au >= 0.9 && earth_sun_distance_au <= 1.1))
    throw InputError("earth_sun_distance_au", format_number(earth_sun_distance_au),
                     "a distance in astronomical units from 0.9 to 1.1 (the Earth's orbit spans 0.983-1.017)");
  return 1.0 / (earth_sun_distance_au * earth_sun_distance_au);
}

}  // namespace skyspec
