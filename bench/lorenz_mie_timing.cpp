// How long Lorenz-Mie takes: one sphere at size parameters 10 .. 2e4, and size distributions at
// one wavelength (a water-soluble aerosol, a fog, drizzle) with the scattering matrix at 181 and
// 1801 angles (1 and 0.1 degree), on all cores; then the rain of atmosphere.rain.drops =
// "lognormal" (media/rain.cpp) with its coarser quadrature in size parameter against the default
// one: time and the largest difference of the phase function over the bows (120-150 degrees, every
// 0.1). Built and run by bench/lorenz_mie_timing.sh.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <vector>

#include "skyspec/lorenz_mie.hpp"
#include "skyspec/sphere_ensemble.hpp"
#include "skyspec/water.hpp"

using namespace skyspec;

namespace {
template <class F>
double seconds(F f) {
  const auto start = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::vector<double> angles(int n) {
  std::vector<double> mu;
  for (int k = 0; k < n; ++k) mu.push_back(std::cos(M_PI * k / (n - 1)));
  return mu;
}
}  // namespace

int main() {
  const double water = water_refractive_index(283.15, liquid_water_density_kg_per_m3(283.15), 550.0);
  std::printf("one sphere (m = %.4f, water at 10 degC and 550 nm): the series a_n, b_n, then S1, S2 at 1801 angles\n",
              water);
  std::printf("%10s %8s %14s %14s\n", "x", "terms", "series (ms)", "1801 angles (ms)");
  for (double x : {10.0, 100.0, 1000.0, 1e4, 2e4}) {
    MieSeries s;
    const double t_series = seconds([&] {
                              for (int i = 0; i < 10; ++i) s = lorenz_mie({water, 1e-9}, x);
                            }) /
                            10;
    const std::vector<double> mu = angles(1801);
    const double t_angles = seconds([&] { mie_amplitudes(s, mu); });
    std::printf("%10g %8d %14.3f %14.3f\n", x, s.terms(), 1e3 * t_series, 1e3 * t_angles);
  }
  struct Case {
    const char* name;
    SizeDistribution sizes;
    std::complex<double> m;
  };
  const Case cases[] = {
      {"water-soluble aerosol (OPAC waso, dry)", SizeDistribution::lognormal(0.0212e-6, 2.24), {1.53, 0.006}},
      {"fog (modified gamma, 8 um, alpha 3)", SizeDistribution::modified_gamma(8e-6, 3.0, 1.0), {water, 1e-9}},
      {"drizzle (Marshall-Palmer 2 mm/h, 50-150 um)",
       SizeDistribution::marshall_palmer(2.0).truncated(50e-6, 150e-6),
       {water, 1e-9}}};
  std::printf("\nsize distributions at 550 nm, default quadrature, all cores\n");
  std::printf("%-46s %8s %10s %16s %16s\n", "", "x_max", "nodes", "181 angles (s)", "1801 angles (s)");
  for (const Case& c : cases) {
    SphereEnsembleOptics o;
    const double t181 = seconds([&] { o = sphere_ensemble_optics(c.sizes, c.m, 550e-9, 1.0, angles(181)); });
    const double t1801 = seconds([&] { o = sphere_ensemble_optics(c.sizes, c.m, 550e-9, 1.0, angles(1801)); });
    std::printf("%-46s %8.0f %10d %16.3f %16.3f\n", c.name, 2 * M_PI * c.sizes.max_radius_m() / 550e-9, o.radius_nodes,
                t181, t1801);
  }
  std::printf("\nrain drops (lognormal, truncated at 3 spreads) at 550 nm, 120-150 degrees every 0.1, all cores\n");
  std::printf("%-28s %8s %18s %18s %20s\n", "", "x_max", "panel 1 (s, nodes)", "panel 4 (s, nodes)",
              "largest difference");
  std::vector<double> bows;
  for (int k = 300; k >= 0; --k) bows.push_back(std::cos((120.0 + 0.1 * k) * M_PI / 180.0));
  for (const auto& [median_mm, spread] : {std::pair{0.25, 1.1}, std::pair{0.5, 1.1}, std::pair{0.25, 1.2}}) {
    const double cut = std::pow(spread, 3.0), median_m = median_mm * 1e-3;
    const SizeDistribution drops =
        SizeDistribution::lognormal(median_m, spread).truncated(median_m / cut, median_m * cut);
    SphereEnsembleSettings coarse;
    coarse.panel_size_parameter = 4.0;
    SphereEnsembleOptics fine_o, coarse_o;
    const double t_fine = seconds([&] { fine_o = sphere_ensemble_optics(drops, {water, 0.0}, 550e-9, 1.0, bows); });
    const double t_coarse = seconds([&] {
      coarse_o = sphere_ensemble_optics(drops, {water, 0.0}, 550e-9, 1.0, bows, coarse);
    });
    double largest = 0.0;
    for (size_t j = 0; j < bows.size(); ++j)
      largest = std::max(largest, std::abs(coarse_o.phase_matrix[j].s11 / fine_o.phase_matrix[j].s11 - 1.0));
    char name[64];
    std::snprintf(name, sizeof name, "%.2f mm, spread %.1f", median_mm, spread);
    std::printf("%-28s %8.0f %10.2f %7d %10.2f %7d %19.2f%%\n", name, 2 * M_PI * drops.max_radius_m() / 550e-9, t_fine,
                fine_o.radius_nodes, t_coarse, coarse_o.radius_nodes, 100.0 * largest);
  }
  return 0;
}
