#include "physics/scattering_matrix.hpp"

#include "skyspec/units.hpp"

namespace skyspec {

MuellerMatrix ScatteringMatrix::matrix() const {
  MuellerMatrix m;
  m << a1, b1, 0.0, 0.0,  //
      b1, a2, 0.0, 0.0,   //
      0.0, 0.0, a3, b2,   //
      0.0, 0.0, -b2, a4;
  return m;
}

ScatteringMatrix& ScatteringMatrix::operator+=(const ScatteringMatrix& o) {
  a1 += o.a1;
  a2 += o.a2;
  a3 += o.a3;
  a4 += o.a4;
  b1 += o.b1;
  b2 += o.b2;
  return *this;
}

ScatteringMatrix& ScatteringMatrix::operator*=(double s) {
  a1 *= s;
  a2 *= s;
  a3 *= s;
  a4 *= s;
  b1 *= s;
  b2 *= s;
  return *this;
}

ScatteringMatrix rayleigh_scattering_matrix(double mu, double gamma) {
  const double delta = (1.0 - gamma) / (1.0 + 2.0 * gamma);
  const double delta_delta_prime = (1.0 - 3.0 * gamma) / (1.0 + 2.0 * gamma);
  const double k = 1.0 / (4.0 * kPi);
  ScatteringMatrix f;
  f.a2 = k * 0.75 * delta * (1.0 + mu * mu);
  f.a1 = f.a2 + k * (1.0 - delta);
  f.b1 = -k * 0.75 * delta * (1.0 - mu * mu);
  f.a3 = k * 1.5 * delta * mu;
  f.a4 = k * 1.5 * delta_delta_prime * mu;
  return f;
}

ScatteringMatrix non_polarising_scattering_matrix(double phase) {
  ScatteringMatrix f;
  f.a1 = f.a2 = f.a3 = f.a4 = phase;
  return f;
}

MuellerMatrix stokes_rotation(double c, double s) {
  const double c2 = c * c - s * s, s2 = 2.0 * c * s;
  MuellerMatrix r = MuellerMatrix::Identity();
  r(1, 1) = c2;
  r(1, 2) = s2;
  r(2, 1) = -s2;
  r(2, 2) = c2;
  return r;
}

}  // namespace skyspec
