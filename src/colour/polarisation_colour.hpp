// Linear polarisation as numbers and as colour: the degree and angle of a Stokes vector, and the
// usual picture of them (polarisation imaging's HSV map): the angle as hue on a colour wheel that
// goes round once over 180 degrees (the angle is an axis: 0 and 180 degrees are the same), the
// degree as brightness.
#pragma once

#include <array>

namespace skyspec {

struct LinearPolarisation {
  double degree = 0.0;     ///< sqrt(S1^2 + S2^2) / S0, 0 where S0 <= 0
  double angle_deg = 0.0;  ///< 1/2 atan2(S2, S1), in (-90, 90]: from e1 towards e2
};
LinearPolarisation linear_polarisation(double s0, double s1, double s2);

/// sRGB code values in [0, 1] for a polarisation: hue = (angle + 90) / 180 of the way round the
/// wheel (red at -90 and 90 degrees, then yellow, green, cyan, blue, magenta), full saturation,
/// value = the degree (clamped to [0, 1]). A picture, not a colorimetric quantity.
std::array<float, 3> polarisation_colour(const LinearPolarisation& p);

}  // namespace skyspec
