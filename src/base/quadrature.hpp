// Gauss-Legendre quadrature: the nodes and weights of the n-point rule on [a, b], exact for
// polynomials of degree 2n - 1.
#pragma once

#include <cstddef>
#include <vector>

namespace skyspec {

/// The n Gauss-Legendre nodes on [a, b], in descending order (from b towards a), and their weights
/// (none for n <= 0). The roots on [-1, 1] are found once per n and process (thread-safe).
void gauss_legendre(int n, double a, double b, std::vector<double>& nodes, std::vector<double>& weights);

/// The trapezoid rule's integral of the n samples y over the increasing abscissae x (0 for n < 2).
double trapezoid(const double* x, const double* y, std::size_t n);

}  // namespace skyspec
