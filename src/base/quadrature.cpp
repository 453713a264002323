#include "base/quadrature.hpp"

#include <cmath>

#include "skyspec/units.hpp"

namespace skyspec {

void gauss_legendre(int n, double a, double b, std::vector<double>& nodes, std::vector<double>& weights) {
  // Roots of the Legendre polynomial P_n by Newton's method from Tricomi's initial guesses; weights
  // 2 / ((1 - x^2) P_n'(x)^2), mapped from [-1, 1] to [a, b].
  nodes.assign(static_cast<size_t>(n), 0.0);
  weights.assign(static_cast<size_t>(n), 0.0);
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
    nodes[static_cast<size_t>(i)] = 0.5 * (b - a) * x + 0.5 * (b + a);
    weights[static_cast<size_t>(i)] = (b - a) / ((1.0 - x * x) * dp * dp);
  }
}

}  // namespace skyspec
