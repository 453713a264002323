// Scattering matrices: how one scattering event turns the Stokes vector [I, Q, U, V] of the light
// arriving into that of the light leaving, for scattering angle Theta (mu = cos Theta; mu = 1 is
// forward scattering, the phase functions' convention).
//
// The Stokes vectors are taken in the scattering plane's frames: for light travelling along k
// and the plane's normal n (k_in x k_out, normalised), e1 = n x k lies in the plane and e2 = n,
// so that (e1, e2, k) is right-handed; Q = I(e1) - I(e2), U = I((e1 + e2)/sqrt 2) - I((e1 - e2)/sqrt 2),
// V > 0 for light whose field turns from e1 towards e2. With that choice every matrix here has
// the block form of scattering by randomly oriented particles with a plane of symmetry
// (van de Hulst 1957, section 5.22; Hovenier, van der Mee & Domke 2004, eq. 2.17):
//
//        | a1  b1   0   0 |
//   F =  | b1  a2   0   0 |      F11 = a1 is the phase function (sr^-1, integral 1 over the sphere)
//        |  0   0  a3  b2 |
//        |  0   0 -b2  a4 |
#pragma once

#include <Eigen/Core>

namespace skyspec {

using Stokes = Eigen::Vector4d;
using MuellerMatrix = Eigen::Matrix4d;

struct ScatteringMatrix {
  double a1 = 0.0, a2 = 0.0, a3 = 0.0, a4 = 0.0, b1 = 0.0, b2 = 0.0;
  MuellerMatrix matrix() const;
  ScatteringMatrix& operator+=(const ScatteringMatrix& o);
  ScatteringMatrix& operator*=(double s);
};

/// Rayleigh scattering by anisotropic molecules (Chandrasekhar 1950, Radiative Transfer, ch. I
/// section 18; Hansen & Travis 1974, Space Sci. Rev. 16, eq. 2.15), with gamma = rho / (2 - rho)
/// as in rayleigh_phase(mu, gamma): with Delta = (1 - gamma) / (1 + 2 gamma) and
/// Delta Delta' = (1 - 3 gamma) / (1 + 2 gamma),
///   a1 = [3/4 Delta (1 + mu^2) + 1 - Delta] / 4 pi      (= rayleigh_phase(mu, gamma))
///   b1 = -3/4 Delta (1 - mu^2) / 4 pi,   a2 = 3/4 Delta (1 + mu^2) / 4 pi,
///   a3 = 3/2 Delta mu / 4 pi,            a4 = 3/2 Delta Delta' mu / 4 pi,   b2 = 0.
/// The degree of linear polarisation of unpolarised light scattered once, -b1 / a1, is
/// (1 - mu^2) / (1 + mu^2 + 2 rho / (1 - rho)).
ScatteringMatrix rayleigh_scattering_matrix(double mu, double gamma);

/// An aerosol phase function p(mu) as a scattering matrix that neither polarises nor depolarises:
/// p(mu) times the unit matrix. An approximation (the aerosol models here give a phase function
/// only, not a Mie matrix); real particles polarise weakly and depolarise.
ScatteringMatrix non_polarising_scattering_matrix(double phase);

/// The Stokes vector in the frame (e1', e2') = (cos psi e1 + sin psi e2, -sin psi e1 + cos psi e2)
/// from the one in (e1, e2): Q' = Q cos 2psi + U sin 2psi, U' = -Q sin 2psi + U cos 2psi; I and V
/// unchanged. Given cos psi and sin psi.
MuellerMatrix stokes_rotation(double cos_psi, double sin_psi);

}  // namespace skyspec
