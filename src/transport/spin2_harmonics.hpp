// Spin-2 spherical harmonics of a polarisation field symmetric about a plane, and the moments of a
// phase function that scatter it: the angular detail of the polarised light of the higher
// scattering orders (multiple_scattering.hpp).
//
// The linear polarisation of the light arriving from direction w (mu = cos theta, phi in the local
// frame: z up, x towards the sun's azimuth) is the complex field P = Q + i U, Q and U relative to
// the frame (e_theta, e_phi) of w. P is a spin-weight 2 function: it expands in the spin-weighted
// harmonics sY_lm = sqrt((2 l + 1) / (4 pi)) d^l_{m,-s}(theta) exp(i m phi), l >= 2, m = -l..l
// (Newman & Penrose 1966; Goldberg et al. 1967; d^l the Wigner functions), orthonormal over the
// sphere. A field symmetric about the sun's vertical plane (Q even, U odd in phi) has real
// coefficients c_lm = integral (Q cos m phi + U sin m phi) lambda_lm dw, lambda_lm the harmonic's
// theta part, and
//
//   Q(w) = sum c_lm lambda_lm(theta) cos(m phi),   U(w) = sum c_lm lambda_lm(theta) sin(m phi).
//
// A particle whose scattering matrix is its phase function times the unit matrix keeps Q and U
// relative to the scattering plane: it carries each arriving polarisation along the great circle
// from w' to w (a rotation about the plane's normal) and weights it by p(w . w'). That operator
// commutes with rotations, so it scales each degree alone (the addition theorem of the generalized
// spherical functions, Hovenier, van der Mee & Domke 2004, ch. 2; Siewert 1981):
//
//   c_lm -> beta_l c_lm,   beta_l = 2 pi integral_{-1}^{1} p(mu) d^l_22(mu) dmu,
//
// d^l_22 = P^l_22 the generalized spherical function (d^2_22 = (1 + mu)^2 / 4): the counterpart of
// the Legendre moments chi_l of the intensity (spherical_harmonics.hpp).
#pragma once

#include <functional>
#include <vector>

namespace skyspec {

/// Number of spin-2 harmonics with 2 <= l <= degree, -l <= m <= l: (degree + 1)^2 - 4 (0 below 2).
constexpr int spin2_harmonic_count(int degree) { return degree < 2 ? 0 : (degree + 1) * (degree + 1) - 4; }
/// Index of (l, m): l^2 - 4 + l + m, so that a lower degree's harmonics are a prefix.
constexpr int spin2_harmonic_index(int l, int m) { return l * l - 4 + l + m; }

/// The highest degree spin2_harmonics evaluates.
constexpr int kMaxSpin2Degree = 16;

/// The Wigner function d^l_{m1,m2}(theta) at cos theta = mu, |m1|, |m2| <= l <= kMaxSpin2Degree
/// (Wigner's sum; Varshalovich et al. 1988, 4.3.1 eq. 2).
double wigner_d(int l, int m1, int m2, double mu);

/// The harmonics' parts of Q and U at (mu, phi): q[i] = lambda_lm(mu) cos(m phi) and
/// u[i] = lambda_lm(mu) sin(m phi) at i = spin2_harmonic_index(l, m), 2 <= l <= degree.
void spin2_harmonics(int degree, double mu, double cos_phi, double sin_phi, double* q, double* u);

/// beta_l = 2 pi integral p(mu) d^l_22(mu) dmu for l = 0..degree (beta_0 = beta_1 = 0), by
/// Gauss-Legendre quadrature with `nodes` nodes (p normalised to 1 over the sphere).
std::vector<double> spin2_moments(const std::function<double(double)>& phase, int degree, int nodes = 512);

/// 2 pi integral f(mu) d^l_{m1,m2}(mu) dmu for l = 0..degree (0 where l < |m1| or |m2|), f linear
/// between ascending cosines mu[k] (values[k] there, from -1 to 1), as tabulated scattering
/// matrices are: exact for that interpolant (Gauss-Legendre on each interval), so that a forward
/// peak narrower than any fixed set of nodes keeps its weight.
std::vector<double> piecewise_linear_spin_moments(const std::vector<double>& mu, const std::vector<double>& values,
                                                  int degree, int m1, int m2);

// A sphere's matrix beyond the unit matrix. Relative to the scattering plane a particle with
// elements a1 = a2, a3, b1 (Hovenier et al. 2004, eq. 2.133; circular polarisation left out) turns
// the arriving I and P = Q + i U into
//   P_out = b1 I + alpha_+ P + alpha_- conj(P),   alpha_+- = (a2 +- a3) / 2,
// and each term is diagonal in the degree (the addition theorem again):
//  - alpha_+ P: c_lm -> beta_l c_lm with beta_l from alpha_+ (spin2_moments; alpha_+ = p for the
//    unit matrix);
//  - alpha_- conj(P) (the polarisation mirrored in the scattering plane, then carried to w):
//    c_l,-m -> (-1)^m beta-_l c_lm, beta-_l = 2 pi int alpha_- d^l_{2,-2} dmu;
//  - b1 I, from the field's real harmonics a_lm (spherical_harmonics.hpp, m >= 0):
//    c_l0 -> gamma_l a_l0 and, for m > 0, c_lm -> (-1)^m gamma_l a_lm / sqrt 2,
//    c_l,-m -> gamma_l a_lm / sqrt 2, with gamma_l = 2 pi int b1 d^l_{2,0} dmu.
// test_spin2_harmonics checks the three against brute-force integrals over the sphere.

}  // namespace skyspec
