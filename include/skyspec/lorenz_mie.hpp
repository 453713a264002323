// Scattering of light by a homogeneous sphere: Lorenz-Mie theory.
//
// A sphere of radius a in a medium of refractive index n_med, lit by light of vacuum wavelength
// lambda, is described by its size parameter x = 2 pi a n_med / lambda and its refractive index
// relative to the medium, m = n + i k (k >= 0 absorbs: the time dependence exp(-i omega t) of
// Bohren & Huffman 1983, "Absorption and Scattering of Light by Small Particles", ch. 4). The
// scattered field is the series of the coefficients a_n, b_n (Bohren & Huffman eq. 4.88)
//
//   a_n = [(D_n(mx)/m + n/x) psi_n(x) - psi_n-1(x)] / [(D_n(mx)/m + n/x) xi_n(x) - xi_n-1(x)]
//   b_n = [(m D_n(mx) + n/x) psi_n(x) - psi_n-1(x)] / [(m D_n(mx) + n/x) xi_n(x) - xi_n-1(x)]
//
// with psi_n, xi_n = psi_n - i chi_n the Riccati-Bessel functions and D_n = psi_n' / psi_n their
// logarithmic derivative, summed to Wiscombe's N_stop terms. The algorithm follows Wiscombe 1980,
// "Improved Mie scattering algorithms", Appl. Opt. 19, 1505-1509 (NCAR/TN-140+STR, rev. 1996):
//   - N_stop = x + 4 x^(1/3) + 1 (x <= 8), x + 4.05 x^(1/3) + 2 (8 < x < 4200), x + 4 x^(1/3) + 2;
//   - D_n(mx) by downward recurrence D_n-1 = n/z - 1 / (D_n + n/z), started at n = N_stop with
//     the exact value from Lentz's continued fraction (Lentz 1976, Appl. Opt. 15, 668), not from
//     zero: the zero start of Bohren & Huffman's BHMIE is wrong for large, nearly transparent
//     spheres (Wiscombe's water cases 10 and 11 show it);
//   - psi_n and chi_n by upward recurrence, stable to N_stop.
// The amplitude functions S1 (perpendicular to the scattering plane) and S2 (parallel) follow from
// the angular functions pi_n, tau_n by their upward recurrences (Bohren & Huffman eqs. 4.74, 4.47).
// Valid, and checked against Wiscombe's published test cases (tests/physics/test_lorenz_mie.cpp),
// for 10^-3 <= x <= 2 10^4 and |m| up to 14; a perfectly conducting sphere (m -> infinity) is
// lorenz_mie_conducting.
#pragma once

#include <complex>
#include <vector>

namespace skyspec {

/// The series of one sphere: a_n and b_n for n = 1 .. N (index n - 1).
struct MieSeries {
  double size_parameter = 0.0;
  std::vector<std::complex<double>> a, b;
  int terms() const { return static_cast<int>(a.size()); }
};

/// Wiscombe's number of terms for size parameter x.
int mie_term_count(double x);

/// The largest size parameter the series here are computed for (Wiscombe 1980's tested range).
constexpr double kMaxMieSizeParameter = 2e4;

/// The coefficients of a sphere of relative refractive index m (imag(m) >= 0) and size parameter
/// x (> 0). Throws std::invalid_argument for x <= 0, x > 2e4, real(m) <= 0 or imag(m) < 0.
MieSeries lorenz_mie(std::complex<double> m, double x);

/// A perfectly conducting sphere: a_n = psi_n'(x) / xi_n'(x), b_n = psi_n(x) / xi_n(x).
MieSeries lorenz_mie_conducting(double x);

/// Efficiencies (cross-sections over pi a^2) and the asymmetry parameter (Bohren & Huffman
/// eqs. 4.61, 4.62, p. 120):
///   Q_ext = 2/x^2 sum (2n+1) Re(a_n + b_n),  Q_sca = 2/x^2 sum (2n+1) (|a_n|^2 + |b_n|^2),
///   g Q_sca = 4/x^2 [sum n(n+2)/(n+1) Re(a_n a*_n+1 + b_n b*_n+1) + sum (2n+1)/(n(n+1)) Re(a_n b*_n)],
///   Q_back = |sum (2n+1) (-1)^n (a_n - b_n)|^2 / x^2 (= 4 |S1(180 deg)|^2 / x^2; not the radar
///   convention, which has another factor 4 pi).
struct MieEfficiencies {
  double extinction = 0.0, scattering = 0.0, backscatter = 0.0, asymmetry = 0.0;
  double absorption() const { return extinction - scattering; }
  double single_scattering_albedo() const { return extinction > 0.0 ? scattering / extinction : 0.0; }
};
MieEfficiencies mie_efficiencies(const MieSeries& s);

/// The amplitude functions at the cosine mu of the scattering angle (Bohren & Huffman eq. 4.74):
///   S1 = sum (2n+1)/(n(n+1)) (a_n pi_n + b_n tau_n),  S2 = sum (2n+1)/(n(n+1)) (a_n tau_n + b_n pi_n).
/// S1(0 deg) = S2(0 deg) and Q_ext = 4/x^2 Re S(0 deg) (the optical theorem).
struct MieAmplitudes {
  std::complex<double> s1, s2;
};
std::vector<MieAmplitudes> mie_amplitudes(const MieSeries& s, const std::vector<double>& mu);

/// The scattering (Mueller) matrix of a sphere from its amplitudes, Bohren & Huffman eq. 3.16, in
/// the frame of the scattering plane (Stokes I, Q, U, V with Q > 0 parallel to it):
///   [S11 S12 0 0; S12 S11 0 0; 0 0 S33 S34; 0 0 -S34 S33],
///   S11 = (|S2|^2 + |S1|^2) / 2, S12 = (|S2|^2 - |S1|^2) / 2, S33 = Re(S2 S1*), S34 = Im(S2 S1*).
/// Units: the scattered Stokes vector at distance r is (1 / (k^2 r^2)) S times the incident one,
/// k = 2 pi n_med / lambda. The phase function is 4 pi S11 / (x^2 Q_sca), normalised to 1 over 4 pi sr.
struct SphereScatteringMatrix {
  double s11 = 0.0, s12 = 0.0, s33 = 0.0, s34 = 0.0;
  /// The degree of linear polarisation of scattered unpolarised light, -S12 / S11 (positive when
  /// the light is polarised perpendicular to the scattering plane, as Rayleigh's is).
  double degree_of_polarisation() const { return s11 > 0.0 ? -s12 / s11 : 0.0; }
};
SphereScatteringMatrix sphere_scattering_matrix(const MieAmplitudes& s);

}  // namespace skyspec
