// Vec3: a point or direction in three dimensions, in double precision (Eigen).
//
// World space is planet-centred, in metres (geometry.hpp says why doubles); the east-north-up
// frame of a scene's reference point uses the same type. Base layer: every layer may use it.
#pragma once

#include <Eigen/Core>

namespace skyspec {

using Vec3 = Eigen::Vector3d;

}  // namespace skyspec
