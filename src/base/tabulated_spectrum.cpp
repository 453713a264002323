// A published spectral table as a function of wavelength; exact integrals and bin means on a grid.
#include "base/tabulated_spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "base/text_format.hpp"
#include "skyspec/error.hpp"

namespace skyspec {

namespace {

void check_increasing(const std::string& name, const std::vector<double>& nm) {
  for (size_t i = 0; i < nm.size(); ++i) {
    if (!std::isfinite(nm[i])) throw Error(name + ": wavelength " + std::to_string(i) + " is not finite");
    if (i > 0 && !(nm[i] > nm[i - 1]))
      throw Error(name + ": wavelengths must increase (" + format_number(nm[i]) + " after " + format_number(nm[i - 1]) +
                  ")");
  }
}

void check_finite(const std::string& name, const std::vector<double>& values) {
  for (double v : values)
    if (!std::isfinite(v)) throw Error(name + ": a tabulated value is not finite");
}

}  // namespace

TabulatedSpectrum::TabulatedSpectrum(std::string name, Kind kind, std::vector<double> nm, std::vector<double> values)
    : name_(std::move(name)), kind_(kind), nm_(std::move(nm)), values_(std::move(values)) {
  // Running integral at every tabulated wavelength, so integral(lo, hi) = C(hi) - C(lo) costs two
  // binary searches. Samples: trapezoids, exact for the linear interpolant. Bins: value * width.
  cumulative_.assign(nm_.size(), 0.0);
  for (size_t i = 1; i < nm_.size(); ++i) {
    const double width_nm = nm_[i] - nm_[i - 1];
    const double piece =
        kind_ == Kind::Samples ? 0.5 * (values_[i - 1] + values_[i]) * width_nm : values_[i - 1] * width_nm;
    cumulative_[i] = cumulative_[i - 1] + piece;
  }
}

TabulatedSpectrum TabulatedSpectrum::samples(std::string name, std::vector<double> nm, std::vector<double> values) {
  if (nm.size() < 2 || values.size() != nm.size())
    throw Error(name + ": a sampled table needs at least 2 wavelengths and one value per wavelength");
  check_increasing(name, nm);
  check_finite(name, values);
  return TabulatedSpectrum(std::move(name), Kind::Samples, std::move(nm), std::move(values));
}

TabulatedSpectrum TabulatedSpectrum::bin_averages(std::string name, std::vector<double> edges_nm,
                                                  std::vector<double> values) {
  if (values.empty() || edges_nm.size() != values.size() + 1)
    throw Error(name + ": a binned table needs at least one bin and one more edge than values");
  check_increasing(name, edges_nm);
  check_finite(name, values);
  return TabulatedSpectrum(std::move(name), Kind::BinAverages, std::move(edges_nm), std::move(values));
}

std::string TabulatedSpectrum::range_text() const {
  return name_ + ", " + format_number(min_nm()) + "-" + format_number(max_nm()) + " nm";
}

double TabulatedSpectrum::value_at(double lambda_nm, const std::string& setting) const {
  if (!(lambda_nm >= min_nm() && lambda_nm <= max_nm()))
    throw InputError(setting, format_number(lambda_nm), "a wavelength within " + range_text());
  // Index of the interval [nm_[i], nm_[i + 1]] that holds lambda (the last one for max_nm).
  size_t i = static_cast<size_t>(std::upper_bound(nm_.begin(), nm_.end(), lambda_nm) - nm_.begin());
  i = std::min(i, nm_.size() - 1) - 1;
  if (kind_ == Kind::BinAverages) return values_[i];
  const double t = (lambda_nm - nm_[i]) / (nm_[i + 1] - nm_[i]);
  return values_[i] + t * (values_[i + 1] - values_[i]);
}

double TabulatedSpectrum::cumulative(double x_nm) const {
  size_t i = static_cast<size_t>(std::upper_bound(nm_.begin(), nm_.end(), x_nm) - nm_.begin());
  i = std::min(i, nm_.size() - 1) - 1;
  const double dx_nm = x_nm - nm_[i];
  if (kind_ == Kind::BinAverages) return cumulative_[i] + values_[i] * dx_nm;
  // Trapezoid from nm_[i] to x under the linear interpolant: dx * (f(nm_i) + f(x)) / 2.
  const double slope = (values_[i + 1] - values_[i]) / (nm_[i + 1] - nm_[i]);
  return cumulative_[i] + dx_nm * (values_[i] + 0.5 * slope * dx_nm);
}

double TabulatedSpectrum::integral(double lo_nm, double hi_nm, const std::string& setting) const {
  if (!(lo_nm >= min_nm() && hi_nm <= max_nm() && lo_nm <= hi_nm))
    throw InputError(setting, format_number(lo_nm) + "-" + format_number(hi_nm) + " nm",
                     "an increasing range within " + range_text());
  return cumulative(hi_nm) - cumulative(lo_nm);
}

double TabulatedSpectrum::mean(double lo_nm, double hi_nm, const std::string& setting) const {
  const double total = integral(lo_nm, hi_nm, setting);
  return hi_nm > lo_nm ? total / (hi_nm - lo_nm) : value_at(lo_nm, setting);
}

std::vector<TabulatedSpectrum::Bin> TabulatedSpectrum::grid_bins(const WavelengthGrid& grid) {
  std::vector<Bin> bins(static_cast<size_t>(grid.size()));
  const double half = 0.5 * grid.bandwidth_nm();
  for (int k = 0; k < grid.size(); ++k) bins[static_cast<size_t>(k)] = {grid.nm(k) - half, grid.nm(k) + half};
  return bins;
}

SpectrumD TabulatedSpectrum::mean_on_grid(const WavelengthGrid& grid, const std::string& setting) const {
  if (grid.min_nm() < min_nm() || grid.max_nm() > max_nm())
    throw InputError(setting, grid.describe(), "wavelengths within " + range_text());
  const std::vector<Bin> bins = grid_bins(grid);
  SpectrumD out(grid.size());
  for (int k = 0; k < grid.size(); ++k) {
    const Bin& bin = bins[static_cast<size_t>(k)];
    out[k] = mean(std::max(bin.lo_nm, min_nm()), std::min(bin.hi_nm, max_nm()), setting);
  }
  return out;
}

}  // namespace skyspec
