// Spectral sampling: the wavelength grid and the spectral value types.
//
// A spectrum is a column of values, one per wavelength of a WavelengthGrid, held in an Eigen array
// so that arithmetic and exp() over all wavelengths are single vectorised expressions. The grid
// is chosen at run time (any number of samples from 1 to kMaxWavelengths), so the arrays are
// dynamically sized; hot loops allocate them once per thread and reuse them.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace skyspec {

/// Per-wavelength values in single precision (radiance, transmittance along the render path).
using Spectrum = Eigen::ArrayXf;
/// Per-wavelength values in double precision (coefficient derivation, tables).
using SpectrumD = Eigen::ArrayXd;
/// Linear RGB (R, G, B), e.g. Rec.709 as the renderer converts spectra.
using Rgb = Eigen::Array3f;

/// A set of sample wavelengths in nanometres, strictly increasing, each standing for a band of
/// the same width around it (bandwidth_nm): tabulated inputs finer than the sky's sampling (the
/// solar spectrum, ozone cross-sections) are averaged over [lambda - w/2, lambda + w/2] at every
/// sample, whatever the other samples are (tabulated_spectrum.hpp), as a spectrometer with a
/// rectangular slit of width w would see them.
class WavelengthGrid {
 public:
  static constexpr int kMaxWavelengths = 1024;
  /// The band each sample stands for unless a scene says otherwise (spectrum.bandwidth_nm): the
  /// default grid's 10 nm step, and the resolution of the embedded ozone table.
  static constexpr double kDefaultBandwidth_nm = 10.0;
  /// The widest band a sample may stand for.
  static constexpr double kMaxBandwidth_nm = 1000.0;

  /// Evenly spaced samples from min_nm to max_nm inclusive, step_nm apart. max_nm - min_nm must be a
  /// whole number of steps (to 1e-6 nm). Throws InputError (setting "spectrum.step_nm" etc.).
  static WavelengthGrid uniform(double min_nm, double max_nm, double step_nm);
  /// count samples evenly spread over [min_nm, max_nm] (count == 1 needs min_nm == max_nm).
  static WavelengthGrid with_count(double min_nm, double max_nm, int count);
  /// An explicit list (any order is accepted; stored sorted ascending; duplicates rejected).
  static WavelengthGrid from_list(std::vector<double> wavelengths_nm);

  int size() const { return static_cast<int>(nm_.size()); }
  double nm(int i) const { return nm_[static_cast<size_t>(i)]; }
  const std::vector<double>& nanometres() const { return nm_; }
  double min_nm() const { return nm_.front(); }
  double max_nm() const { return nm_.back(); }
  /// Index of the sample equal to lambda_nm (within 1e-6 nm), or -1.
  int index_of(double lambda_nm) const;
  /// A short description, e.g. "41 samples, 380-780 nm, 10 nm step".
  std::string describe() const;
  /// The width of the band each sample stands for, nm.
  double bandwidth_nm() const { return bandwidth_nm_; }
  /// The same samples standing for bands of another width; 0: every tabulated input is taken at
  /// the sample wavelength itself. Throws InputError ("spectrum.bandwidth_nm", ...) unless
  /// 0 <= width <= kMaxBandwidth_nm.
  WavelengthGrid with_bandwidth(double width_nm) const;

 private:
  explicit WavelengthGrid(std::vector<double> nm);
  std::vector<double> nm_;
  double bandwidth_nm_ = kDefaultBandwidth_nm;
};

}  // namespace skyspec
