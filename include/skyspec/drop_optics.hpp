// Rain drops by geometric optics: the rainbows (issue 39).
//
// A ray that meets a sphere of index n at incidence i is refracted at r (sin i = n sin r), and
// after k reflections inside leaves deviated by
//
//   D_k(i) = 2 (i - r) + k (pi - 2 r)                  (k = 0: straight through; a reflection off
//                                                        the outside: D = pi - 2 i)
//
// carrying the share (1 - R)^2 R^k of its light (R the Fresnel reflectance at i, for the s and p
// polarisations separately, then averaged). D_k has a stationary point where cos^2 i = (n^2 - 1) /
// (k (k + 2)) (Descartes): the light piles up there, the primary bow (k = 1, 137.9 degrees of
// scattering, 42.1 degrees from the antisolar point, at n = 1.333) and the secondary (k = 2, about
// 129 degrees, 51 from the antisolar point), with less light between them than on either side
// (Alexander's dark band). Rays fall on the drop uniformly over its disk, so the share scattered
// into an interval of angles is the integral of 2 b db over the impact parameters b = sin i whose
// rays end there: skyspec sums it over 400 000 impact parameters evenly spaced in b^2, for
// k = 0 to kMaxDropReflections (what is left inside after that, nearly all of it from rays at
// grazing incidence, is dropped: docs/bows-and-halos.md says how much). This is the
// Descartes-Fresnel model: no wave optics, so no supernumerary bows and a sharp (geometric) edge
// at the Descartes angle instead of Airy's maximum just inside it; for drops of 0.5 mm and larger
// (the bulk of a rain's light) the two differ by less than 0.3 degrees (van de Hulst 1957, 13.2;
// Lee 1998, Appl. Opt. 37, 1506). Diffraction (the other half of a drop's extinction, within
// lambda / D = a few thousandths of a degree of forward) is not part of it.
#pragma once

#include <vector>

namespace skyspec {

/// The scattering angle (radians) of the Descartes ray with k >= 1 internal reflections in a
/// sphere of index n: where the bow of order k is.
double descartes_scattering_angle(double n, int k);

/// The share of a drop's geometric-optics light scattered into each interval [mu[j], mu[j + 1]]
/// of scattering-angle cosines (mu strictly increasing from -1 to 1), unpolarised incident light.
std::vector<double> drop_geometric_scattering(double n, const std::vector<double>& mu);

/// The same with the scattering matrix: per interval, the shares of P11, P12 and P33 (Bohren &
/// Huffman's convention: P12 = (|S2|^2 - |S1|^2) / 2 < 0 where the light is polarised perpendicular
/// to the scattering plane, P33 = Re(S2 S1*)). A ray's amplitudes for the s and p polarisations are
/// the Fresnel amplitude coefficients r_s, r_p (reflected off the outside) or (1 - r^2) (-r)^k
/// (through, k reflections inside: the coefficient from inside is -r), real, so that P11 =
/// (a_s^2 + a_p^2) / 2, P12 = (a_p^2 - a_s^2) / 2, P33 = a_s a_p and P34 = 0 for each ray, summed
/// without interference between rays (geometric optics).
struct DropMatrixShares {
  std::vector<double> p11, p12, p33;
};
DropMatrixShares drop_geometric_matrix(double n, const std::vector<double>& mu);

/// The Fresnel-weighted rays with up to this many internal reflections are followed.
constexpr int kMaxDropReflections = 12;

}  // namespace skyspec
