// Bradford chromatic adaptation (linear form, as in CIE 160:2004 and ICC.1:2010 Annex E).
#include "colour/chromatic_adaptation.hpp"

#include <Eigen/LU>

namespace skyspec {

Eigen::Matrix3d bradford_matrix() {
  Eigen::Matrix3d m;
  m << 0.8951, 0.2664, -0.1614,  //
      -0.7502, 1.7135, 0.0367,   //
      0.0389, -0.0685, 1.0296;
  return m;
}

Eigen::Matrix3d bradford_adaptation(const Eigen::Vector3d& source_white_xyz,
                                    const Eigen::Vector3d& destination_white_xyz) {
  const Eigen::Matrix3d m = bradford_matrix();
  const Eigen::Vector3d source_cone = m * source_white_xyz;
  const Eigen::Vector3d destination_cone = m * destination_white_xyz;
  const Eigen::Matrix3d von_kries = (destination_cone.array() / source_cone.array()).matrix().asDiagonal();
  return m.inverse() * von_kries * m;
}

Eigen::Vector3d xyz_from_xy(double x, double y, double Y) {
  return Eigen::Vector3d(x * Y / y, Y, (1.0 - x - y) * Y / y);
}

}  // namespace skyspec
