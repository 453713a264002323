// Chromatic adaptation: re-expressing colours seen under one white as if seen under another.
//
// The Bradford transform (Lam 1985; as given in CIE 160:2004 / ICC.1 Annex E and used by the
// Academy's ACES matrices, which OpenColorIO's "_BFD" built-ins denote): XYZ -> "cone" responses
// with the Bradford matrix, von Kries scaling of each by the ratio of the two whites' responses,
// back to XYZ. The linear (von Kries) form is the one colour-management systems use.
#pragma once

#include <Eigen/Core>

namespace skyspec {

/// The Bradford cone-response matrix (XYZ -> RGB_bfd).
Eigen::Matrix3d bradford_matrix();

/// The 3 x 3 matrix that adapts XYZ from white source_white_xyz to destination_white_xyz: it maps
/// source_white_xyz exactly onto destination_white_xyz (both XYZ, any common scale).
Eigen::Matrix3d bradford_adaptation(const Eigen::Vector3d& source_white_xyz,
                                    const Eigen::Vector3d& destination_white_xyz);

/// XYZ of a chromaticity (x, y) with luminance Y.
Eigen::Vector3d xyz_from_xy(double x, double y, double Y = 1.0);

}  // namespace skyspec
