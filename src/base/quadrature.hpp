// Gauss-Legendre quadrature: the nodes and weights of the n-point rule on [a, b], exact for
// polynomials of degree 2n - 1.
#pragma once

#include <cstddef>
#include <vector>

namespace skyspec {

/// The n Gauss-Legendre nodes on [a, b], in descending order (from b towards a), and their weights
/// (none for n <= 0). The roots on [-1, 1] are found once per n and process (thread-safe).
void gauss_legendre(int n, double a, double b, std::vector<double>& nodes, std::vector<double>& weights);

/// Which end of [a, b] a graded rule gathers nodes at.
enum class PanelEnd { lower, upper };

/// A composite Gauss-Legendre rule on [a, b] for integrands that vary fastest at one end: n_panel
/// nodes on the panel of the given width at that end and n nodes on the rest of the interval, in
/// descending order like gauss_legendre; exact to degree 2 min(n, n_panel) - 1. The panel is at most
/// half the interval; with n_panel <= 0 or width <= 0 it is gauss_legendre(n, a, b).
void graded_gauss_legendre(int n, int n_panel, double width, PanelEnd end, double a, double b,
                           std::vector<double>& nodes, std::vector<double>& weights);

/// The trapezoid rule's integral of the n samples y over the increasing abscissae x (0 for n < 2).
double trapezoid(const double* x, const double* y, std::size_t n);

}  // namespace skyspec
