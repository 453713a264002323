// Tiles of one image (spectral EXRs whose data windows are parts of a common display window, as
// `skyspec render --pixel-bounds` writes them) assembled into the whole image's EXR, streaming:
// a band of scanlines at a time is read from the tiles it crosses and written, so memory is
// bounded by one band of the image's width, not by the image. The result has the tiles' header
// with the whole display window as data window: for tiles of one render, the bytes of that
// render's own EXR.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace skyspec {

struct MergeSummary {
  int tiles = 0, width = 0, height = 0, channels = 0;
  int band_rows = 0;  ///< scanlines held in memory at a time
};

/// Merges `tiles` into `output` (atomically). InputError (setting "TILES") naming the tile when one
/// is not a tile of the same image as the first (display window, channels, compression or another
/// header attribute differ), when two overlap, or when they leave pixels uncovered; IoError when a
/// tile cannot be read, holds a value that is not finite, or the output cannot be written.
/// `progress` gets (rows done, rows in total).
MergeSummary merge_spectral_exr_tiles(const std::vector<std::filesystem::path>& tiles,
                                      const std::filesystem::path& output,
                                      const std::function<void(int, int)>& progress = {});

}  // namespace skyspec
