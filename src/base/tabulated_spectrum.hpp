// A published spectral table (solar irradiance, absorption cross-sections, ...) as a function of
// wavelength, and its transfer onto a simulation's wavelength grid.
//
// Published tables come in two shapes, and the function they define differs:
//   - samples:      f(lambda_i) = v_i, read as the piecewise-linear interpolant between samples
//                   (e.g. ASTM G-173, tabulated at 0.5-5 nm);
//   - bin averages: v_i is the mean of f over [e_i, e_i+1), read as piecewise constant
//                   (e.g. the 10 nm resamplings of laboratory cross-sections).
// Either way the integral of the table over any interval is exact and closed form.
//
// Onto a grid, each sample lambda_k stands for the band of the grid's bandwidth w centred on it,
// [lambda_k - w/2, lambda_k + w/2], whatever the other samples are: the value at 680 nm is the
// same on the grid 440, 550, 680 nm as on a 1 nm grid (with the same w). The grid value is the
// table's exact mean over the band, (1 / w) integral_band f(lambda) dlambda, not f(lambda_k): a
// sample then carries the energy of the fine structure (Fraunhofer lines, absorption bands) within
// its band, and on a uniform grid whose step is w the bands tile the range, so sum_k w value_k
// equals the table's integral over them. A band much narrower than the table's own steps gives the
// point value (exactly, for a table that is linear across the band). A band that reaches past the
// end of the table is cut at the table's end (the table says nothing beyond it); a grid sample
// outside the table is an error.
#pragma once

#include <string>
#include <vector>

#include "skyspec/spectrum.hpp"

namespace skyspec {

class TabulatedSpectrum {
 public:
  enum class Kind { Samples, BinAverages };

  /// f(nm[i]) = values[i], linear in between; at least 2 samples, nm strictly increasing.
  /// `name` appears in error messages (e.g. "the ASTM G-173 extraterrestrial table").
  /// Throws Error on malformed input.
  static TabulatedSpectrum samples(std::string name, std::vector<double> nm, std::vector<double> values);
  /// f = values[i] on [edges_nm[i], edges_nm[i + 1]); edges strictly increasing,
  /// values.size() + 1 == edges_nm.size(). Throws Error on malformed input.
  static TabulatedSpectrum bin_averages(std::string name, std::vector<double> edges_nm, std::vector<double> values);

  const std::string& name() const { return name_; }
  Kind kind() const { return kind_; }
  /// Sample wavelengths (Samples) or bin edges (BinAverages), nm.
  const std::vector<double>& nanometres() const { return nm_; }
  const std::vector<double>& values() const { return values_; }
  double min_nm() const { return nm_.front(); }
  double max_nm() const { return nm_.back(); }

  /// f(lambda_nm). Throws InputError(setting, ...) outside [min_nm, max_nm]. For bin averages, a
  /// wavelength on an inner edge takes the bin above it, and max_nm the last bin.
  double value_at(double lambda_nm, const std::string& setting = "wavelength_nm") const;
  /// Exact integral_lo^hi f(lambda) dlambda (table units times nm). Throws InputError(setting, ...)
  /// unless min_nm <= lo_nm <= hi_nm <= max_nm.
  double integral(double lo_nm, double hi_nm, const std::string& setting = "wavelength range") const;
  /// integral(lo, hi) / (hi - lo); value_at(lo) when lo == hi.
  double mean(double lo_nm, double hi_nm, const std::string& setting = "wavelength range") const;

  /// The band of every grid sample (see the file comment), before cutting at the table's ends.
  struct Bin {
    double lo_nm, hi_nm;
  };
  static std::vector<Bin> grid_bins(const WavelengthGrid& grid);

  /// The table's mean over each grid sample's band (cut at the table's ends). Throws
  /// InputError(setting, grid description, allowed range) if a grid wavelength lies outside the
  /// table.
  SpectrumD mean_on_grid(const WavelengthGrid& grid, const std::string& setting = "spectrum") const;

 private:
  TabulatedSpectrum(std::string name, Kind kind, std::vector<double> nm, std::vector<double> values);
  /// Integral from min_nm to x (x inside the table), exact.
  double cumulative(double x_nm) const;
  std::string range_text() const;

  std::string name_;
  Kind kind_;
  std::vector<double> nm_, values_;
  std::vector<double> cumulative_;  ///< integral from min_nm to nm_[i]
};

}  // namespace skyspec
