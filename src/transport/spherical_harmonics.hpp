// Real spherical harmonics of fields symmetric about a plane, and Legendre moments of phase
// functions: what the angular source of the higher scattering orders is made of.
//
// A radiance field at a point of the atmosphere, in the local frame (z up, x towards the sun's
// azimuth), is symmetric under phi -> -phi, so only the cosine harmonics appear:
//
//   Y_lm(mu, phi) = K_lm P_l^m(mu) cos(m phi) (x sqrt 2 for m > 0),
//   K_lm = sqrt((2 l + 1) / (4 pi) (l - m)! / (l + m)!),   0 <= m <= l <= degree,
//
// orthonormal over the sphere (P_l^m without the Condon-Shortley sign). For a phase function
// p(cos theta) = sum_l (2 l + 1) / (4 pi) chi_l P_l(cos theta) (chi_0 = 1) and a field
// L = sum a_lm Y_lm, the addition theorem gives the in-scattered source in direction w:
//
//   J(w) = integral p(w . w') L(w') dw' = sum_l chi_l sum_m a_lm Y_lm(w)
//
// (Chandrasekhar 1950, ch. I sections 15-17; the expansion DISORT and the spherical-harmonics
// methods of radiative transfer rest on).
#pragma once

#include <array>
#include <functional>
#include <vector>

#include <Eigen/Core>

namespace skyspec {

/// Number of harmonics up to `degree`: (degree + 1)(degree + 2) / 2.
constexpr int harmonic_count(int degree) { return (degree + 1) * (degree + 2) / 2; }
/// Index of (l, m): l (l + 1) / 2 + m.
constexpr int harmonic_index(int l, int m) { return l * (l + 1) / 2 + m; }

/// The highest degree symmetric_harmonics evaluates.
constexpr int kMaxHarmonicDegree = 16;
/// Y_lm(mu, phi) for all 0 <= m <= l <= degree (at most kMaxHarmonicDegree), at harmonic_index(l, m); cos_phi is
/// cos(phi).
void symmetric_harmonics(int degree, double mu, double cos_phi, double* out);

/// chi_l = 2 pi integral_{-1}^{1} p(mu) P_l(mu) dmu for l = 0..degree, by Gauss-Legendre quadrature
/// with `nodes` nodes (p normalised to 1 over the sphere, so chi_0 = 1).
std::vector<double> legendre_moments(const std::function<double(double)>& phase, int degree, int nodes = 512);
/// chi_l of a phase function linear in mu between ascending cosines mu[k] (values[k] there, from
/// -1 to 1), as tabulated scattering matrices are: exact for that interpolant (Gauss-Legendre on
/// each interval, with the nodes a polynomial of degree `degree` + 1 needs), so that a forward peak
/// narrower than the spacing of legendre_moments' nodes keeps its weight.
std::vector<double> piecewise_linear_legendre_moments(const std::vector<double>& mu, const std::vector<double>& values,
                                                      int degree);

/// The moments of the phase function over the directions a straight skyline hides: the great
/// circle that passes gamma above the forward direction (the view direction w) bounds a half of
/// the sphere, and of each ring at angle theta from w the share
///   f_gamma(theta) = 1 (theta <= gamma), 1 - arccos(tan gamma / tan theta) / pi (between), 0 (theta >= pi - gamma)
/// lies below it (f = 1/2 at theta = 90 degrees; gamma = 90 degrees hides the hemisphere about w).
/// chi_l(gamma) = 2 pi integral f_gamma(theta) p(cos theta) P_l(cos theta) sin theta dtheta, for
/// gamma_j = j step_rad, j = 0..count - 1 (step_rad dividing 90 degrees): out[j (degree + 1) + l].
/// By the addition theorem sum_l chi_l(gamma) sum_m a_lm Y_lm(w) is the part of J(w) that arrives
/// from below the skyline for a field taken as its mean over each ring about w. Gauss-Legendre in
/// theta over each step (nodes_per_step nodes), so that a forward peak is resolved where it lies.
double skyline_hidden_share(double gamma, double theta);
std::vector<double> skyline_legendre_moments(const std::function<double(double)>& phase, int degree, int count,
                                             double step_rad, int nodes_per_step = 16);

/// The same region's first-order correction for a field that is not uniform around each ring: on
/// the ring at theta about w (azimuth phi from the direction towards the skyline) the field's
/// cos(phi) component, A_1(theta) = sum_l 2 g_l / (l (l + 1)) sin(theta) P_l'(cos theta) with g_l the
/// derivative of the field's degree-l part at w towards the skyline, contributes
/// -2 A_1 sin(phi_0) of the hidden arc (cos phi_0 = tan gamma / tan theta), so that
///   integral below the skyline of p L = sum_l chi_l(gamma) F_l(w) + sum_l delta_l(gamma) g_l,
///   delta_l(gamma) = -4 / (l (l + 1)) integral sin(phi_0) p(cos theta) P_l'(cos theta) sin^2 theta dtheta
/// (delta_0 = 0), exact for fields of degree 1, the rings' higher Fourier terms left out above. Laid
/// out as skyline_legendre_moments.
std::vector<double> skyline_gradient_moments(const std::function<double(double)>& phase, int degree, int count,
                                             double step_rad, int nodes_per_step = 16);

/// The second moments of the degree-2 harmonics: K_m = integral over the sphere of Y_2m(w) w w^T dw
/// for m = 0, 1, 2 (local frame). A field L = sum a_lm Y_lm has the second-moment tensor
/// T = integral L(w) w w^T dw = (a_00 / sqrt(4 pi)) (4 pi / 3) I + sum_m a_2m K_m: only its mean and
/// its quadrupole reach T, which is all that Rayleigh scattering polarises
/// (SingleScattering, RadianceParts::polarised_q).
const std::array<Eigen::Matrix3d, 3>& quadrupole_tensors();

}  // namespace skyspec
