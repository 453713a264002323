// Ice crystals: the refractive index of ice and how a randomly oriented hexagonal prism scatters
// light by geometric optics, which gives the 22 and 46 degree halos (issue 39).
//
// A hexagonal prism (a column when its length exceeds its width, a plate when it is shorter) of
// ice refracts light through faces that meet at 60 degrees (alternate side faces) and at 90
// degrees (a side face and a basal face). Through a prism of apex A light is deviated by at least
//
//   D_min = 2 asin(n sin(A / 2)) - A                                   (minimum deviation)
//
// and piles up there: 21.9 degrees (A = 60, n = 1.311 at 550 nm), the 22 degree halo, and 45.9
// degrees (A = 90), the 46 degree halo; red inside, where n is smallest. The scattering function is
// computed by tracing rays through the prism (Greenler 1980, "Rainbows, Halos, and Glories"; Tape
// 1994, "Atmospheric Halos"; Macke, Mueller & Raschke 1996, J. Atmos. Sci. 53, 2813, for the
// method): each ray enters the prism at a point drawn uniformly over its projected area, for an
// orientation drawn uniformly over all orientations, and at each face is reflected with the
// Fresnel reflectance of unpolarised light (the mean of the s and p reflectances) or refracted by
// Snell's law, chosen at random with those probabilities (totally reflected inside beyond the
// critical angle), until it leaves. What leaves is the geometric-optics share of the light the
// prism removes from a beam; diffraction by its outline removes as much again (extinction
// efficiency 2), into a forward peak about lambda / D wide (0.4 degrees for crystals 50 um across),
// which is not part of this function. Absorption inside is neglected (k < 1e-8 in the visible:
// less than 1e-5 of the light over a 100 um path).
#pragma once

#include <cstdint>
#include <vector>

namespace skyspec {

/// Real part of the refractive index of ice Ih: Warren & Brandt 2008 (J. Geophys. Res. 113,
/// D14220), their table at 300-1100 nm (data/ice/warren_brandt2008.csv), interpolated linearly.
/// Throws InputError naming `setting` outside that range.
double ice_refractive_index(double wavelength_nm, const char* setting = "spectrum");

/// The minimum deviation of light through a prism of apex angle apex_rad and index n, radians.
double prism_minimum_deviation(double n, double apex_rad);

/// A hexagonal ice prism's shape: its length along the c axis over its width across corners
/// (2 x the side). Columns > 1, plates < 1; the scattering function of geometric optics does not
/// depend on the size.
struct HexagonalPrism {
  double aspect_ratio = 2.0;
};

/// What ray tracing gives: the share of the rays leaving with a scattering-angle cosine in each
/// interval [mu[k], mu[k + 1]] of the cosines given (summing to 1 - lost share), how many rays
/// were traced and how many were stopped after kMaxInteractions faces.
struct PrismScattering {
  std::vector<double> share;
  long long rays = 0, lost = 0;
  static constexpr int kMaxInteractions = 60;
};

/// Traces `rays` rays (all hitting the prism) through randomly oriented prisms of index n;
/// deterministic for a seed. mu: strictly increasing from -1 to 1.
PrismScattering hexagonal_prism_scattering(const HexagonalPrism& prism, double n, const std::vector<double>& mu,
                                           long long rays, std::uint64_t seed);

}  // namespace skyspec
