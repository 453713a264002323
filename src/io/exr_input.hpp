// Opening OpenEXR files that skyspec did not necessarily write (render --from, convert, compare,
// aerial): the header is checked against the file before OpenEXR allocates anything for it.
//
// OpenEXR believes the sizes a header declares: a 49 kB file that declares a 2 GB string
// attribute gets 2 GB allocated before it fails, one that declares 8000 x 8000 pixels gets our
// whole-image buffers. check_exr_declared_sizes() walks the header itself (magic, version flags,
// every attribute's declared size against the bytes that follow it) and bounds the pixel data a
// part declares by what its chunks can hold: for a scan-line file every entry of the offset table
// must point inside the file (an unfinished file, with entries 0, is refused rather than rebuilt
// by OpenEXR from the chunks' own sizes) and every chunk's declared data size must fit in it, and
// the decoded size may not exceed the file's size times the largest ratio the part's compression
// can reach. The readers in io/ open files through
// io/exr_open.hpp, which applies this check (this header stays free of OpenEXR's).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace skyspec {

/// Largest decoded / stored size ratio of each OpenEXR compression, an upper bound (deflate's
/// limit is about 1032:1; RLE's 64:1; PIZ's run-length Huffman codes stay below a few hundred).
double exr_max_compression_ratio(int compression);

/// Throws IoError naming the file when it is not a regular file, not OpenEXR, or its header
/// declares more than the file holds (see above). Reads only the header and the offset table.
void check_exr_declared_sizes(const std::filesystem::path& path);

/// Reads every pixel of every channel of the file, 16 rows at a time into one small buffer, and
/// throws IoError naming the file if any chunk cannot be read or decoded (truncated, damaged).
/// Memory: 16 rows x width x channels floats, whatever the image's size.
void verify_exr_pixels(const std::filesystem::path& path);

}  // namespace skyspec
