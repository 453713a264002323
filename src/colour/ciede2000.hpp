// CIELAB and the CIEDE2000 colour difference, computed by Little CMS 2.
//
// CIELAB (CIE 015:2004, section 8.2.1) from XYZ relative to a reference white, and the CIEDE2000
// total colour difference Delta E_00 (CIE 142-2001; ISO/CIE 11664-6:2014), as Sharma, Wu & Dalal
// 2005 ("The CIEDE2000 color-difference formula: implementation notes, supplementary test data,
// and mathematical observations", Color Research & Application 30(1), 21-30) write it out. Little
// CMS's cmsXYZ2Lab and cmsCIE2000DeltaE do both (docs/architecture.md says why we use them rather
// than our own); tests/colour/test_ciede2000.cpp checks the 34 pairs of the paper's Table 1
// (tests/data/ciede2000_sharma2005.csv).
#pragma once

#include <Eigen/Core>

namespace skyspec {

struct Lab {
  double L = 0.0, a = 0.0, b = 0.0;
};

/// CIELAB of xyz relative to the reference white white_xyz (same units, white Y > 0). Values above
/// the white (L* > 100) follow the same formula, as CIE 015 allows for self-luminous colours.
Lab xyz_to_lab(const Eigen::Vector3d& xyz, const Eigen::Vector3d& white_xyz);

/// Delta E_00 between a reference (lab1) and a sample (lab2) with the parametric factors
/// k_L = k_C = k_H = 1 unless given. Symmetric in its two colours.
double ciede2000(const Lab& lab1, const Lab& lab2, double k_L = 1.0, double k_C = 1.0, double k_H = 1.0);

}  // namespace skyspec
