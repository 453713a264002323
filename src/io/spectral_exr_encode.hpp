// Internal: encoding rows as the spectral EXR writer does, without a file.
#pragma once

#include <cstdint>
#include <vector>

#include "io/spectral_exr.hpp"

namespace skyspec::detail {

/// Encodes `rows` rows (layout as SpectralExrWriter::write_rows) as a width x rows spectral EXR
/// with meta's compression and threads, into a stream that discards the bytes; returns how many
/// there were. What writing costs in CPU time, for the render-time estimate (render_budget.cpp),
/// without creating and removing a file.
std::uint64_t encode_spectral_rows(int width, int rows, const std::vector<double>& wavelengths_nm,
                                   const SpectralExrMetadata& meta, const float* spectral, const float* rgb);

}  // namespace skyspec::detail
