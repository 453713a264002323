// The gas bands skyspec does not model; see unmodelled_absorption.hpp.
#include "physics/unmodelled_absorption.hpp"

#include "base/text_format.hpp"

namespace skyspec {

// Band positions: the oxygen B (687 nm) and A (762 nm) bands and the water vapour bands at 720,
// 820 and 940 nm, as in the absorption coefficients of Bird & Riordan's SPECTRL2 model (1986;
// after Leckner 1978), whose table is zero outside them in this range. Edges are approximate.
const std::vector<UnmodelledBand>& unmodelled_bands() {
  static const std::vector<UnmodelledBand> bands{
      {"oxygen B band", 686.0, 697.0},
      {"water vapour (720 nm band)", 690.0, 740.0},
      {"oxygen A band", 759.0, 771.0},
      {"water vapour (820 nm band)", 800.0, 840.0},
      {"water vapour (940 nm band)", 880.0, 1000.0},
  };
  return bands;
}

std::string unmodelled_absorption_note(const WavelengthGrid& grid) {
  const double half = 0.5 * grid.bandwidth_nm();
  std::string listed;
  for (const UnmodelledBand& band : unmodelled_bands()) {
    bool touched = false;
    for (int k = 0; k < grid.size() && !touched; ++k)
      touched = grid.nm(k) + half >= band.min_nm && grid.nm(k) - half <= band.max_nm;
    // A band between two samples is not seen by the samples but is part of the range they stand for.
    touched = touched || (grid.min_nm() <= band.min_nm && grid.max_nm() >= band.max_nm);
    if (touched)
      listed += std::string(listed.empty() ? "" : "; ") + band.absorber + " " + format_number(band.min_nm) + "-" +
                format_number(band.max_nm) + " nm";
  }
  const std::string range = format_number(grid.min_nm()) + "-" + format_number(grid.max_nm()) + " nm";
  if (listed.empty())
    return "no band of the Earth's oxygen or water vapour in " + range +
           " (absorption modelled: ozone and the aerosols' extinction/scattering ratio)";
  return "absorption by the Earth's gases not modelled in " + range + ": " + listed +
         " (radiances there are too high; absorption modelled: ozone and the aerosols' extinction/scattering ratio)";
}

}  // namespace skyspec
