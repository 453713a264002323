#include "base/quadrature.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>

#include "skyspec/units.hpp"

namespace skyspec {
namespace {

// The roots x of the Legendre polynomial P_n and P_n'(x) there, [node][x, P_n'(x)].
using LegendreRoots = std::vector<std::pair<double, double>>;

// Roots of P_n by Newton's method from Tricomi's initial guesses.
LegendreRoots legendre_roots(int n) {
  LegendreRoots roots(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      const double pn = n == 1 ? x : p1, pn1 = n == 1 ? 1.0 : p0;
      dp = n * (x * pn - pn1) / (x * x - 1.0);
      const double dx = pn / dp;
      x -= dx;
      if (std::abs(dx) < 1e-15) break;
    }
    roots[static_cast<size_t>(i)] = {x, dp};
  }
  return roots;
}

// Each n's roots once per process: finding them costs O(n^2) and renders ask for the same few
// rules every time they are built (the integrator's 512-node rule, the tables' directions).
const LegendreRoots& cached_legendre_roots(int n) {
  static std::mutex mutex;
  static std::map<int, std::unique_ptr<const LegendreRoots>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto& roots = cache[n];
  if (!roots) roots = std::make_unique<const LegendreRoots>(legendre_roots(n));
  return *roots;
}

}  // namespace

void gauss_legendre(int n, double a, double b, std::vector<double>& nodes, std::vector<double>& weights) {
  // Weights 2 / ((1 - x^2) P_n'(x)^2), mapped from [-1, 1] to [a, b].
  nodes.assign(static_cast<size_t>(std::max(n, 0)), 0.0);
  weights.assign(nodes.size(), 0.0);
  if (n <= 0) return;
  const LegendreRoots& roots = cached_legendre_roots(n);
  for (size_t i = 0; i < roots.size(); ++i) {
    const auto [x, dp] = roots[i];
    nodes[i] = 0.5 * (b - a) * x + 0.5 * (b + a);
    weights[i] = (b - a) / ((1.0 - x * x) * dp * dp);
  }
}

void graded_gauss_legendre(int n, int n_panel, double width, PanelEnd end, double a, double b,
                           std::vector<double>& nodes, std::vector<double>& weights) {
  if (n_panel <= 0 || width <= 0.0) {
    gauss_legendre(n, a, b, nodes, weights);
    return;
  }
  const double w = std::min(width, 0.5 * (b - a));
  // The upper interval's nodes first (each rule is descending): together they descend from b.
  const double split = end == PanelEnd::lower ? a + w : b - w;
  const int n_upper = end == PanelEnd::lower ? n : n_panel, n_lower = end == PanelEnd::lower ? n_panel : n;
  std::vector<double> lower_x, lower_w;
  gauss_legendre(n_upper, split, b, nodes, weights);
  gauss_legendre(n_lower, a, split, lower_x, lower_w);
  nodes.insert(nodes.end(), lower_x.begin(), lower_x.end());
  weights.insert(weights.end(), lower_w.begin(), lower_w.end());
}

double trapezoid(const double* x, const double* y, std::size_t n) {
  double sum = 0.0;
  for (std::size_t i = 1; i < n; ++i) sum += 0.5 * (x[i] - x[i - 1]) * (y[i] + y[i - 1]);
  return sum;
}

}  // namespace skyspec
