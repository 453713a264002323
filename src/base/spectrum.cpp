#include "skyspec/spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "base/text_format.hpp"
#include "skyspec/error.hpp"

namespace skyspec {
namespace {
void check_range(const std::string& setting, double v) {
  if (!std::isfinite(v) || v <= 0.0 || v > 1.0e5)
    throw InputError(setting, format_number(v), "a wavelength in nm, > 0 and <= 100000");
}
}  // namespace

WavelengthGrid::WavelengthGrid(std::vector<double> nm) : nm_(std::move(nm)) {}

WavelengthGrid WavelengthGrid::uniform(double min_nm, double max_nm, double step_nm) {
  check_range("spectrum.min_nm", min_nm);
  check_range("spectrum.max_nm", max_nm);
  if (max_nm < min_nm)
    throw InputError("spectrum.max_nm", format_number(max_nm), ">= spectrum.min_nm (" + format_number(min_nm) + ")");
  if (!std::isfinite(step_nm) || step_nm < 1.0)
    throw InputError("spectrum.step_nm", format_number(step_nm), "a step of at least 1 nm");
  const double steps = (max_nm - min_nm) / step_nm;
  const double whole = std::round(steps);
  if (std::abs(steps - whole) * step_nm > 1e-6)
    throw InputError("spectrum.step_nm", format_number(step_nm),
                     "a step that divides max_nm - min_nm (" + format_number(max_nm - min_nm) + " nm) evenly");
  if (whole + 1 > kMaxWavelengths)
    throw InputError(
        "spectrum.step_nm", format_number(step_nm),
        "at most " + std::to_string(kMaxWavelengths) + " samples (this gives " + format_number(whole + 1) + ")");
  std::vector<double> nm(static_cast<size_t>(whole) + 1);
  for (size_t i = 0; i < nm.size(); ++i) nm[i] = min_nm + step_nm * static_cast<double>(i);
  nm.back() = max_nm;
  return WavelengthGrid(std::move(nm));
}

WavelengthGrid WavelengthGrid::with_count(double min_nm, double max_nm, int count) {
  check_range("spectrum.min_nm", min_nm);
  check_range("spectrum.max_nm", max_nm);
  if (count < 1 || count > kMaxWavelengths)
    throw InputError("spectrum.count", std::to_string(count), "1 to " + std::to_string(kMaxWavelengths) + " samples");
  if (max_nm < min_nm)
    throw InputError("spectrum.max_nm", format_number(max_nm), ">= spectrum.min_nm (" + format_number(min_nm) + ")");
  if (count == 1) {
    if (max_nm != min_nm) throw InputError("spectrum.count", "1", "at least 2 when spectrum.max_nm > spectrum.min_nm");
    return WavelengthGrid({min_nm});
  }
  if (max_nm == min_nm)
    throw InputError("spectrum.count", std::to_string(count), "1 when spectrum.max_nm == spectrum.min_nm");
  const double step = (max_nm - min_nm) / (count - 1);
  if (step < 1.0 - 1e-9)
    throw InputError("spectrum.count", std::to_string(count),
                     "a count that keeps samples at least 1 nm apart (at most " +
                         format_number(std::floor(max_nm - min_nm) + 1) + " here)");
  std::vector<double> nm(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) nm[static_cast<size_t>(i)] = min_nm + step * i;
  nm.back() = max_nm;
  return WavelengthGrid(std::move(nm));
}

WavelengthGrid WavelengthGrid::from_list(std::vector<double> nm) {
  if (nm.empty()) throw InputError("spectrum.wavelengths_nm", "[]", "at least one wavelength");
  if (nm.size() > static_cast<size_t>(kMaxWavelengths))
    throw InputError("spectrum.wavelengths_nm", std::to_string(nm.size()) + " values",
                     "at most " + std::to_string(kMaxWavelengths));
  for (double v : nm) check_range("spectrum.wavelengths_nm", v);
  std::sort(nm.begin(), nm.end());
  for (size_t i = 1; i < nm.size(); ++i)
    if (nm[i] - nm[i - 1] < 1.0 - 1e-9)
      throw InputError("spectrum.wavelengths_nm", format_number(nm[i]),
                       "distinct wavelengths at least 1 nm apart (" + format_number(nm[i - 1]) + " is too close)");
  return WavelengthGrid(std::move(nm));
}

int WavelengthGrid::index_of(double lambda_nm) const {
  for (int i = 0; i < size(); ++i)
    if (std::abs(nm_[static_cast<size_t>(i)] - lambda_nm) < 1e-6) return i;
  return -1;
}

WavelengthGrid WavelengthGrid::with_bandwidth(double width_nm) const {
  if (!(width_nm >= 0.0 && width_nm <= kMaxBandwidth_nm))
    throw InputError("spectrum.bandwidth_nm", format_number(width_nm),
                     "a width from 0 (point values) to " + format_number(kMaxBandwidth_nm) + " nm");
  WavelengthGrid g = *this;
  g.bandwidth_nm_ = width_nm;
  return g;
}

std::string WavelengthGrid::describe() const {
  std::ostringstream s;
  s << size() << (size() == 1 ? " sample, " : " samples, ") << min_nm();
  if (size() > 1) s << "-" << max_nm();
  s << " nm";
  if (size() > 2) {
    const double step = (max_nm() - min_nm()) / (size() - 1);
    bool uniform = true;
    for (int i = 1; i < size(); ++i)
      if (std::abs(nm(i) - nm(i - 1) - step) > 1e-6) uniform = false;
    if (uniform) s << ", " << step << " nm step";
  }
  return s.str();
}

}  // namespace skyspec
