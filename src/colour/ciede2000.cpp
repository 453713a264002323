// CIELAB and CIEDE2000 through Little CMS 2 (cmsXYZ2Lab, cmsCIE2000DeltaE); see ciede2000.hpp.
#include "colour/ciede2000.hpp"

#include <lcms2.h>

namespace skyspec {

Lab xyz_to_lab(const Eigen::Vector3d& xyz, const Eigen::Vector3d& white_xyz) {
  // Little CMS takes XYZ and the white in the same units; relative to the white's Y it is the CIE
  // formula for any scale.
  const cmsCIEXYZ white{white_xyz.x(), white_xyz.y(), white_xyz.z()};
  const cmsCIEXYZ colour{xyz.x(), xyz.y(), xyz.z()};
  cmsCIELab lab;
  cmsXYZ2Lab(&white, &lab, &colour);
  return {lab.L, lab.a, lab.b};
}

double ciede2000(const Lab& lab1, const Lab& lab2, double k_L, double k_C, double k_H) {
  const cmsCIELab a{lab1.L, lab1.a, lab1.b}, b{lab2.L, lab2.a, lab2.b};
  return cmsCIE2000DeltaE(&a, &b, k_L, k_C, k_H);
}

}  // namespace skyspec
