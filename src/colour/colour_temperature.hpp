// Correlated colour temperature (CCT) and the distance from the Planckian locus (Duv).
//
// CIE 015:2004 defines the CCT of a stimulus as the temperature of the Planckian (black-body)
// radiator whose chromaticity is nearest to the stimulus's in the CIE 1960 UCS diagram,
//   u = 4X / (X + 15Y + 3Z),  v = 6Y / (X + 15Y + 3Z).
// skyspec computes it from that definition, not from an approximation of the locus: the locus is
// Planck's law, M(lambda, T) ~ lambda^-5 / (exp(c2 / (lambda T)) - 1) with c2 = 1.4388e-2 m K,
// summed against the CIE 1931 colour-matching functions at their 5 nm table points, and the
// nearest point is found over the reciprocal temperature (a coarse scan, then golden-section
// refinement). Duv is the distance, positive above the locus (greener), negative below.
// Daylight spans about 3000-30000 K; a blue zenith sky can exceed 20000 K.
#pragma once

#include <optional>

#include <Eigen/Core>

namespace skyspec {

struct ColourTemperature {
  double cct_K = 0.0;
  double duv = 0.0;
};

/// The CIE 1960 UCS chromaticity (u, v) of XYZ.
Eigen::Vector2d uv_1960(const Eigen::Vector3d& xyz);

/// The chromaticity (u, v) of a Planckian radiator at temperature_K, from the CIE 1931 table.
Eigen::Vector2d planckian_uv_1960(double temperature_K);

/// CCT and Duv of XYZ over 1000 K - 1e6 K; nothing when the stimulus has no colour (X + 15Y + 3Z
/// not positive, or not finite) or lies farther than 0.05 from the locus (CIE 015: the CCT is
/// not meaningful there).
std::optional<ColourTemperature> correlated_colour_temperature(const Eigen::Vector3d& xyz);

}  // namespace skyspec
