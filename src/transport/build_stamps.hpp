// When the translation units that the multiple-scattering tables depend on were compiled, so that
// tables cached on disk by an older build are not reused (internal).
#pragma once

namespace skyspec {
const char* build_stamp_single_scattering();
const char* build_stamp_multiple_scattering();
const char* build_stamp_optical_depth();
const char* build_stamp_density_profile();
}  // namespace skyspec
