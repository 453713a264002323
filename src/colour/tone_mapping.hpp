// Tone-mapping operators of the real-time sky literature, as skyspec "looks".
//
// The five operators of the CS 184 student report "Sky, and Rainbow (or Halo?)" (Tang, Cheng, He &
// Lin 2023), each from its original source. They act on exposed scene-linear Rec.709 values, the
// way the games literature applies them, and their output goes to the display pipeline's
// "Un-tone-mapped" view (sRGB curve and clipping; any other view would tone-map twice). Negative
// (out-of-gamut) components are set to 0 first: the operators are defined for values >= 0.
//
//   reinhard            c / (1 + c) per channel (Reinhard et al. 2002, eq. 3). Also in skyspec's
//                       OpenColorIO config as the exact OCIO look "reinhard".
//   reinhard-extended   c (1 + c / W^2) / (1 + c) per channel (Reinhard et al. 2002, eq. 4), so a
//                       value W maps to 1. The report prints c / (1 + c / W^2), which is not eq. 4.
//   reinhard-luminance  eq. 4 on luminance Y only, colours scaled by Y_out / Y_in so that
//                       chromaticity is kept. The report prints the ratio upside down.
//   uncharted2-filmic   Hable 2010 ("Filmic tonemapping operators" and the GDC 2010 talk
//                       "Uncharted 2: HDR lighting"): f(x) = (x(Ax + CB) + DE) / (x(Ax + B) + DF)
//                       - E/F with A..F = 0.15, 0.50, 0.10, 0.20, 0.02, 0.30, applied as
//                       f(2 c) / f(11.2) (his exposure bias 2 and linear white 11.2).
//   aces-approx         Narkowicz 2016, "ACES filmic tone mapping curve": c' = 0.6 c, then
//                       c'(2.51 c' + 0.03) / (c'(2.43 c' + 0.59) + 0.14), clamped to [0, 1]; a fit
//                       of the ACES RRT + sRGB ODT curve, not the ACES transform itself (the
//                       "ACES 1.0 - SDR Video" view is).
//
// Why only reinhard is an OCIO look: OpenColorIO 2.1 transforms (matrix, log, exponent, range,
// fixed functions, grading curves) compose per-channel functions but cannot add or multiply two
// functions of the same value, which the rational curves above need (and the luminance version
// couples the channels); grading curves or LUTs would only approximate them. So skyspec applies
// them in C++ before the OCIO display transform.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace skyspec {

enum class ToneOperator { Reinhard, ReinhardExtended, ReinhardLuminance, Uncharted2Filmic, AcesApprox };

/// The look names: "reinhard", "reinhard-extended", "reinhard-luminance", "uncharted2-filmic",
/// "aces-approx", in that order.
const std::vector<std::string>& tone_operator_names();
std::optional<ToneOperator> tone_operator_from_name(const std::string& name);
std::string to_string(ToneOperator op);

double reinhard(double c);
double reinhard_extended(double c, double white);
double uncharted2_filmic(double c);
double aces_approx_narkowicz(double c);

/// Applies the operator in place to linear Rec.709 triples ([n][3]). white (extended and
/// luminance Reinhard): the value that maps to 1; when absent, the largest luminance of the image
/// (at least 1), the report's L_white. Returns the white used (0 for the other operators).
double apply_tone_operator(ToneOperator op, std::vector<float>& linear_rgb, std::optional<double> white = {});

}  // namespace skyspec
