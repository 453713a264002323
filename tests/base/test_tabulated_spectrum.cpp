#include <boost/test/unit_test.hpp>

// Spectral tables as functions of wavelength: exact integrals of the two readings (samples joined
// linearly, piecewise-constant bin means) and the transfer onto a wavelength grid by bin means.
// Synthetic tables with closed-form answers.

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "base/tabulated_spectrum.hpp"
#include "check_helpers.hpp"
#include "skyspec/error.hpp"

BOOST_AUTO_TEST_SUITE(test_tabulated_spectrum)

using namespace skyspec;
using test::error_setting;

namespace {

/// f(x) = 2 + 0.01 (x - 400): linear, so every reading and every bin mean has a closed form.
double linear(double x_nm) { return 2.0 + 0.01 * (x_nm - 400.0); }

TabulatedSpectrum linear_samples(double lo_nm, double hi_nm, double step_nm) {
  std::vector<double> nm, v;
  for (double x = lo_nm; x <= hi_nm + 1e-9; x += step_nm) {
    nm.push_back(x);
    v.push_back(linear(x));
  }
  return TabulatedSpectrum::samples("a linear test table", nm, v);
}

/// A zig-zag: 1, 3, 1, 3, ... at 10 nm steps from 400 nm.
TabulatedSpectrum zigzag() {
  std::vector<double> nm, v;
  for (int i = 0; i <= 20; ++i) {
    nm.push_back(400.0 + 10.0 * i);
    v.push_back(i % 2 == 0 ? 1.0 : 3.0);
  }
  return TabulatedSpectrum::samples("a zig-zag test table", nm, v);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(readings)

BOOST_AUTO_TEST_CASE(samples_are_joined_linearly) {
  const TabulatedSpectrum t = zigzag();
  BOOST_TEST((t.kind() == TabulatedSpectrum::Kind::Samples));
  BOOST_TEST(t.value_at(400.0) == 1.0);
  BOOST_TEST(t.value_at(405.0) == 2.0);
  BOOST_TEST(t.value_at(410.0) == 3.0);
  BOOST_TEST(t.value_at(600.0) == 1.0);
  // Each 10 nm interval holds a triangle's worth: mean 2, so 20 nm per 10 nm.
  BOOST_TEST(std::abs(t.integral(400.0, 600.0) - 400.0) < 1e-12);
  // A piece inside an interval: integral_400^405 (1 + 0.2 (x - 400)) dx = 5 + 2.5.
  BOOST_TEST(std::abs(t.integral(400.0, 405.0) - 7.5) < 1e-12);
  BOOST_TEST(std::abs(t.integral(403.0, 417.0) - (t.integral(400.0, 417.0) - t.integral(400.0, 403.0))) < 1e-12);
  BOOST_TEST(t.integral(450.0, 450.0) == 0.0);
  BOOST_TEST(t.mean(450.0, 450.0) == t.value_at(450.0));
}

BOOST_AUTO_TEST_CASE(bins_are_piecewise_constant) {
  const TabulatedSpectrum t =
      TabulatedSpectrum::bin_averages("a binned test table", {360.0, 370.0, 380.0, 390.0}, {1.0, 4.0, 2.0});
  BOOST_TEST((t.kind() == TabulatedSpectrum::Kind::BinAverages));
  BOOST_TEST(t.value_at(360.0) == 1.0);
  BOOST_TEST(t.value_at(369.9) == 1.0);
  BOOST_TEST(t.value_at(370.0) == 4.0);  // an inner edge belongs to the bin above
  BOOST_TEST(t.value_at(390.0) == 2.0);  // the last edge to the last bin
  BOOST_TEST(std::abs(t.integral(360.0, 390.0) - 70.0) < 1e-12);
  BOOST_TEST(std::abs(t.integral(365.0, 375.0) - (5.0 + 20.0)) < 1e-12);
  BOOST_TEST(std::abs(t.mean(370.0, 380.0) - 4.0) < 1e-12);
}

BOOST_AUTO_TEST_CASE(malformed_tables_are_rejected) {
  BOOST_CHECK_THROW(TabulatedSpectrum::samples("t", {400.0}, {1.0}), Error);
  BOOST_CHECK_THROW(TabulatedSpectrum::samples("t", {400.0, 400.0}, {1.0, 2.0}), Error);
  BOOST_CHECK_THROW(TabulatedSpectrum::samples("t", {400.0, 410.0}, {1.0}), Error);
  BOOST_CHECK_THROW(TabulatedSpectrum::samples("t", {400.0, 410.0}, {1.0, std::nan("")}), Error);
  BOOST_CHECK_THROW(TabulatedSpectrum::bin_averages("t", {400.0, 410.0}, {1.0, 2.0}), Error);
}

BOOST_AUTO_TEST_CASE(reading_outside_the_table_names_the_setting) {
  const TabulatedSpectrum t = zigzag();
  BOOST_TEST(error_setting([&] { t.value_at(399.0, "sun.wavelength_nm"); }) == "sun.wavelength_nm");
  BOOST_TEST(error_setting([&] { t.integral(390.0, 500.0); }) == "wavelength range");
  BOOST_TEST(error_setting([&] { t.integral(500.0, 450.0); }) == "wavelength range");
  BOOST_TEST(error_setting([&] { t.value_at(std::nan("")); }) == "wavelength_nm");
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(onto_a_grid)

BOOST_AUTO_TEST_CASE(bands_are_centred_on_their_samples) {
  const WavelengthGrid grid = WavelengthGrid::from_list({400.0, 410.0, 430.0});
  const auto bins = TabulatedSpectrum::grid_bins(grid);  // the default 10 nm
  BOOST_TEST(bins.size() == 3u);
  BOOST_TEST(bins[0].lo_nm == 395.0);
  BOOST_TEST(bins[0].hi_nm == 405.0);
  BOOST_TEST(bins[1].lo_nm == 405.0);
  BOOST_TEST(bins[1].hi_nm == 415.0);
  BOOST_TEST(bins[2].lo_nm == 425.0);
  BOOST_TEST(bins[2].hi_nm == 435.0);
  const auto wide = TabulatedSpectrum::grid_bins(grid.with_bandwidth(30.0));
  BOOST_TEST(wide[2].lo_nm == 415.0);
  BOOST_TEST(wide[2].hi_nm == 445.0);
  BOOST_CHECK_THROW(grid.with_bandwidth(-1.0), InputError);
  // Width 0: the point value.
  const TabulatedSpectrum z = zigzag();
  BOOST_TEST(z.mean_on_grid(WavelengthGrid::from_list({420.0, 425.0}).with_bandwidth(0.0))[1] == z.value_at(425.0));
}

BOOST_AUTO_TEST_CASE(a_linear_table_gives_its_point_values) {
  // The mean of a linear function over a band centred on a sample is its value there, on any grid
  // (uniform or not) whose bands lie inside the table.
  const TabulatedSpectrum t = linear_samples(300.0, 900.0, 10.0);
  for (const WavelengthGrid& grid :
       {WavelengthGrid::uniform(380.0, 780.0, 1.0), WavelengthGrid::uniform(380.0, 780.0, 40.0),
        WavelengthGrid::uniform(420.5, 650.5, 115.0),
        WavelengthGrid::from_list({400.0, 410.0, 430.0}).with_bandwidth(25.0)}) {
    const SpectrumD means = t.mean_on_grid(grid);
    for (int k = 0; k < grid.size(); ++k)
      BOOST_TEST(std::abs(means[k] - linear(grid.nm(k))) < 1e-12, grid.describe() << " at " << grid.nm(k));
  }
}

// The issue this answers: a sample's value was the mean over the cell between its neighbours, so
// it changed when other samples were added or removed. Now it is the mean over its own band.
BOOST_AUTO_TEST_CASE(a_sample_does_not_depend_on_the_others) {
  const TabulatedSpectrum t = zigzag();
  const SpectrumD sparse = t.mean_on_grid(WavelengthGrid::from_list({420.0, 447.0, 550.0}));
  const SpectrumD dense = t.mean_on_grid(WavelengthGrid::uniform(410.0, 590.0, 1.0));
  BOOST_TEST(sparse[1] == dense[447 - 410]);
  BOOST_TEST(sparse[1] == t.mean(442.0, 452.0));
  BOOST_TEST(sparse[2] == dense[550 - 410]);
}

BOOST_AUTO_TEST_CASE(a_coarse_grid_keeps_the_integral) {
  // Sampled at every other knot, the zig-zag reads 1, 1, 1, ...: point sampling loses the energy of
  // the peaks in between; band means keep it: with bands as wide as the step, sum w mean = the
  // integral over the bands.
  const TabulatedSpectrum t = zigzag();
  const WavelengthGrid grid = WavelengthGrid::uniform(420.0, 580.0, 20.0).with_bandwidth(20.0);
  const SpectrumD means = t.mean_on_grid(grid);
  double sum = 0.0;
  for (int k = 0; k < grid.size(); ++k) {
    BOOST_TEST(t.value_at(grid.nm(k)) == 1.0);
    BOOST_TEST(std::abs(means[k] - 2.0) < 1e-12);  // the zig-zag's true mean over 20 nm
    sum += grid.bandwidth_nm() * means[k];
  }
  BOOST_TEST(std::abs(sum - t.integral(410.0, 590.0)) < 1e-10);
}

BOOST_AUTO_TEST_CASE(end_bands_are_cut_at_the_table_ends) {
  // A grid sample on the table's first wavelength: its band [395, 405] is cut to [400, 405].
  const TabulatedSpectrum t = zigzag();
  const SpectrumD means = t.mean_on_grid(WavelengthGrid::uniform(400.0, 600.0, 10.0));
  BOOST_TEST(std::abs(means[0] - t.mean(400.0, 405.0)) < 1e-12);
  BOOST_TEST(std::abs(means[20] - t.mean(595.0, 600.0)) < 1e-12);
  // A one-sample grid takes the mean over its band too.
  BOOST_TEST(t.mean_on_grid(WavelengthGrid::from_list({405.0}))[0] == t.mean(400.0, 410.0));
}

BOOST_AUTO_TEST_CASE(a_grid_outside_the_table_is_an_input_error) {
  const TabulatedSpectrum t = zigzag();
  BOOST_TEST(error_setting([&] { t.mean_on_grid(WavelengthGrid::uniform(380.0, 500.0, 10.0)); }) == "spectrum");
  BOOST_TEST(error_setting([&] { t.mean_on_grid(WavelengthGrid::uniform(500.0, 700.0, 10.0), "spectrum.max_nm"); }) ==
             "spectrum.max_nm");
  try {
    t.mean_on_grid(WavelengthGrid::uniform(380.0, 500.0, 10.0));
  } catch (const InputError& e) {
    const std::string message = e.what();
    BOOST_TEST(message.find("380-500 nm") != std::string::npos);  // the grid
    BOOST_TEST(message.find("400-600 nm") != std::string::npos);  // the table's range
    BOOST_TEST(message.find("zig-zag") != std::string::npos);     // which table
  }
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE_END()  // test_tabulated_spectrum
