// Which colour chunks tell a reader how to decode a display-encoded PNG: a property of the
// display encoding (colour layer), written by io/png_image.hpp.
#pragma once

namespace skyspec {

/// How the code values of a display-encoded PNG are to be read: which chunks say so.
///   Srgb: the sRGB chunk with its recommended gAMA and cHRM (PNG specification 11.3.3.5);
///   DisplayP3, Rec709, Rec2100Pq: a cICP chunk (PNG 3rd edition; ITU-T H.273 code points
///     12/13/0/1, 1/1/0/1 and 9/16/0/1), plus cHRM and gAMA for decoders without cICP
///     (gAMA 1/2.2 for Display P3's sRGB curve, 1/2.4 for Rec.1886; none for PQ);
///   None: no colour chunk (the encoding is not known, e.g. a display of a user's OCIO config).
enum class PngColourTag { None, Srgb, DisplayP3, Rec709, Rec2100Pq };

}  // namespace skyspec
