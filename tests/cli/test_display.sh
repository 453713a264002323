#!/usr/bin/env bash
# The display pipeline and the comparison on the command line: unknown display/view/look names
# are rejected with the valid ones listed (exit 2, no files); renders and conversions write PNGs
# of the asked bit depth and working-space EXRs with the right chromaticities; the shipped OCIO
# config passes ociocheck; `skyspec compare` writes its report, map and plot, and reports zero
# for a render compared with itself. Usage: test_display.sh PATH_TO_SKYSPEC
set -u
skyspec=$1
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
config="$here/../../data/ocio/config.ocio"
unset OCIO
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

# expect_error NAME EXIT_CODE 'text that must appear in stderr' COMMAND ARGS... (output in $work/out-NAME)
expect_error() {
  local name=$1 code=$2 text=$3 command=$4
  shift 4
  run_expecting_error "$name" "$code" "$text" "$work/out-$name" "$skyspec" "$command" -q --out "$work/out-$name" "$@"
}

small=(--width 8 --height 8 --set render.scattering_orders=1)
expect_error unknown_display 2 '--display = "P3" is not allowed: one of the displays of skyspec built-in config (data/ocio/config.ocio): "sRGB", "Display P3", "Rec.1886 Rec.709", "Rec.2100-PQ"' render "${small[@]}" --display P3
expect_error unknown_view 2 '--view = "Filmic" is not allowed: one of the views of display "sRGB": "Un-tone-mapped", "ACES 1.0 - SDR Video", "Raw"' render "${small[@]}" --view Filmic
expect_error hdr_view_on_sdr 2 '--view' render "${small[@]}" --view "ACES 1.1 - HDR Video (1000 nits & Rec.2020 lim)"
expect_error unknown_look 2 '"reinhard-extended", "reinhard-luminance", "uncharted2-filmic", "aces-approx"' render "${small[@]}" --look hable
expect_error png_bits 2 '--png-bits = 12 is not allowed: 8 or 16' render "${small[@]}" --png-bits 12
expect_error exr_space 2 '--exr-space = "sRGB" is not allowed: one of "ACEScg", "ACES2065-1", "Linear Rec.709"' render "${small[@]}" --exr-space sRGB
expect_error missing_config 2 "--ocio = '$work/none.ocio' is not allowed" render "${small[@]}" --ocio "$work/none.ocio"
expect_error camera_incomplete 2 '--f-number' render "${small[@]}" --shutter 1/250
expect_error camera_and_ev 2 'a manual and a camera exposure exclude each other' render "${small[@]}" --shutter 1/250 --f-number 8 --exposure 2
expect_error bad_shutter 2 '--shutter = "fast"' render "${small[@]}" --shutter fast --f-number 8
OCIO="$work/none.ocio" expect_error env_config 2 "OCIO environment variable" render "${small[@]}"
expect_error convert_missing 2 "INPUT = '$work/nope.exr' is not allowed" convert "$work/nope.exr"
expect_error compare_one_exr 2 "none (render the scene twice) or two" compare "$work/nope.exr"
expect_error compare_bad_sweep 2 '--sweep = "0:x:5"' compare --preset seed "${small[@]}" --sweep 0:x:5

# The shipped config passes OpenColorIO's own check, and --list-displays shows it.
ociocheck --iconfig "$config" >"$work/ociocheck" 2>&1 && ok || { bad "ociocheck failed"; cat "$work/ociocheck"; }
grep -qi "warning" "$work/ociocheck" && bad "ociocheck warns: $(grep -i warning "$work/ociocheck")" || ok

# Other tools with the shipped config: OpenImageIO labels our EXR "Linear", which the config
# knows (an alias of Linear Rec.709, also the scene_linear role and the default file rule), so
# oiiotool converts it to the sRGB display without being told its colour space; with the
# recorded exposure it gives skyspec's own PNG, code value for code value.
out="$work/oiio"
"$skyspec" render -q --out "$out" "${small[@]}" --width 32 || bad "render for oiiotool failed"
scale=$(/usr/bin/python3 -c "import OpenImageIO as o, sys
print(repr(o.ImageInput.open(sys.argv[1]).spec().getattribute('skyspec:exposureScale')))" "$out/sky.exr")
oiiotool --colorconfig "$config" "$out/sky.exr" --ch R,G,B --mulc "$scale" \
  --ociodisplay sRGB Un-tone-mapped -d uint8 -o "$out/oiio.png" 2>"$work/stderr" && ok || { bad "oiiotool --ociodisplay failed"; cat "$work/stderr"; }
[ "$(oiiotool "$out/oiio.png" "$out/sky.png" --diff 2>&1 | grep -c 'PASS')" = 1 ] && ok \
  || bad "oiiotool's sRGB image differs from skyspec's: $(oiiotool "$out/oiio.png" "$out/sky.png" --diff 2>&1 | tail -3)"
for name in Linear lin_rec709 "scene-linear Rec.709-sRGB"; do
  oiiotool --colorconfig "$config" "$out/sky.exr" --ch R,G,B --iscolorspace "$name" --ociodisplay sRGB Un-tone-mapped \
    -o "$out/named.png" 2>/dev/null && ok || bad "the config does not know \"$name\""
done
"$skyspec" render --list-displays | grep -q "ACES 1.1 - HDR Video (1000 nits & Rec.2020 lim)" && ok || bad "--list-displays"

# A render through Display P3 at 16 bits with an ACEScg EXR beside it.
out="$work/p3"
if "$skyspec" render -q --out "$out" "${small[@]}" --width 16 --display "Display P3" --png-bits 16 --exr-space ACEScg; then
  [ "$(ls "$out" | tr '\n' ' ')" = "sky-acescg.exr sky.exr sky.png " ] && ok || bad "p3 render files: $(ls "$out")"
  oiiotool --info -v "$out/sky.png" | grep -q "uint16 png" && ok || bad "PNG is not 16-bit"
  exrheader "$out/sky-acescg.exr" | grep -q "red   (0.713 0.293)" && ok || bad "ACEScg chromaticities missing"
  exrheader "$out/sky-acescg.exr" | grep -q "white (0.32168 0.33767)" && ok || bad "ACES white missing"
  exrheader "$out/sky.exr" | grep -q "skyspec:exposureScale (type double)" && ok || bad "spectral EXR lacks the exposure"
  exrheader "$out/sky.exr" | grep -q 'skyspec:exposure (type string): "automatic' && ok || bad "exposure rule not recorded"
  # Each file's metadata, read back with OpenImageIO: units that describe that file's channels,
  # the exposure scale as a number (also in a converted file).
  "$skyspec" convert "$out/sky.exr" --out "$out" --name conv --exr-space "Linear Rec.709" --no-png -q || bad "convert failed"
  /usr/bin/python3 - "$out" >"$work/meta" 2>&1 <<'PY' && ok || { bad "metadata"; cat "$work/meta"; }
import sys
import OpenImageIO as oiio
folder = sys.argv[1]
def spec(name):
    return oiio.ImageInput.open(folder + "/" + name).spec()
for name, units in [("sky.exr", "S0 channels: spectral radiance"), ("sky-acescg.exr", "R,G,B: scene-linear ACEScg"),
                    ("conv-linear-rec709.exr", "R,G,B: scene-linear Linear Rec.709")]:
    s = spec(name)
    u = s.getattribute("skyspec:units")
    assert u.startswith(units), (name, u)
    assert "S0" not in u or name == "sky.exr", (name, u)
    scale = s.getattribute("skyspec:exposureScale")
    assert isinstance(scale, float) and scale > 0, (name, scale)
    sun = s.getattribute("skyspec:sunRGB")  # Rec.709: only in the file whose R, G, B are Rec.709
    assert (sun is not None and len(sun) == 3 and all(isinstance(v, float) and v > 0 for v in sun)) == (name == "sky.exr"), (name, sun)
PY
  # A file of before sunRGB was a v3d attribute (text "r g b") still compares.
  oiiotool "$out/sky.exr" --attrib "skyspec:sunRGB" "1.5 1.5 1.5" -o "$out/old-text.exr" \
    && "$skyspec" compare -q "$out/old-text.exr" "$out/sky.exr" --out "$out/cmp-old" && [ -s "$out/cmp-old/compare.md" ] && ok \
    || bad "compare refused a file with the text form of skyspec:sunRGB"
else
  bad "p3 render failed"; cat "$work/stderr"
fi

# A whole-sphere panorama says so in OpenEXR's envmap attribute (OpenImageIO: "LatLong
# Environment", up +Y), in the spectral EXR, the RGB-only working-space EXR and a conversion of
# it; a hemisphere panorama does not; maketx makes a lat-long environment texture of the RGB file.
pano=(--camera equirectangular --width 16 --height 8 --set render.scattering_orders=1 --set spectrum.count=4)
if "$skyspec" render -q --out "$work/pano" "${pano[@]}" --panorama-convention blender --exr-space "Linear Rec.709" \
   && "$skyspec" convert "$work/pano/sky.exr" --out "$work/pano" --name conv --exr-space ACEScg --no-png -q \
   && "$skyspec" render -q --out "$work/dome" "${pano[@]}" --set camera.min_elevation_deg=0 --exr-space "Linear Rec.709"; then
  /usr/bin/python3 - "$work" >"$work/meta" 2>&1 <<'PY' && ok || { bad "panorama metadata"; cat "$work/meta"; }
import sys
import OpenImageIO as oiio
work = sys.argv[1]
for name in ["pano/sky.exr", "pano/sky-linear-rec709.exr", "pano/conv-acescg.exr"]:
    s = oiio.ImageInput.open(work + "/" + name).spec()
    assert s.getattribute("textureformat") == "LatLong Environment", (name, s.getattribute("textureformat"))
    assert s.getattribute("oiio:updirection") == "y", name
for name in ["dome/sky.exr", "dome/sky-linear-rec709.exr"]:
    s = oiio.ImageInput.open(work + "/" + name).spec()
    assert s.getattribute("textureformat") is None, (name, s.getattribute("textureformat"))
scene = oiio.ImageInput.open(work + "/pano/sky.exr").spec().getattribute("skyspec:scene")
assert 'panorama_convention = "blender"' in scene and "albedo = 0.25" in scene, scene
PY
  maketx --envlatl "$work/pano/sky-linear-rec709.exr" -o "$work/pano/sky.tx" >"$work/maketx" 2>&1 && ok \
    || { bad "maketx --envlatl refused the panorama"; cat "$work/maketx"; }
else
  bad "panorama render failed"
fi

# Half spectral channels (opt-in): OpenImageIO reads S0 as half and R, G, B as float; convert reads
# the file back.
if "$skyspec" render -q --out "$work/half" "${small[@]}" --set output.exr_spectral_type=half --no-png; then
  /usr/bin/python3 -c '
import sys, OpenImageIO as oiio
s = oiio.ImageInput.open(sys.argv[1]).spec()
types = {n: str(s.channelformat(i)) for i, n in enumerate(s.channelnames)}
assert types["S0.550,000000nm"] == "half" and types["R"] == "float", types' "$work/half/sky.exr" && ok || bad "half channel types"
  "$skyspec" convert "$work/half/sky.exr" --out "$work/half" --name conv -q && [ -s "$work/half/conv.png" ] && ok || bad "convert of a half file"
else
  bad "half render failed"
fi

# The config named through $OCIO gives the same image as the built-in one.
OCIO="$config" "$skyspec" render -q --out "$work/env" "${small[@]}" --no-exr && ok || bad "render with OCIO=config failed"
"$skyspec" render -q --out "$work/builtin" "${small[@]}"
oiiotool "$work/env/sky.png" "$work/builtin/sky.png" --diff >"$work/diff" 2>&1 && grep -q PASS "$work/diff" && ok || { bad "OCIO=config differs from the built-in config"; cat "$work/diff"; }
oiiotool --info -v "$work/env/sky.png" | grep -q "from OCIO environment variable" && ok || bad "the PNG does not say which config made it"

# A camera exposure is recorded with OpenEXR's standard camera attributes.
"$skyspec" render -q --out "$work/cam" "${small[@]}" --shutter 1/125 --f-number 16 --iso 100 --exr-space "Linear Rec.709"
exrheader "$work/cam/sky-linear-rec709.exr" | grep -q "aperture (type float): 16" && ok || bad "aperture attribute"
exrheader "$work/cam/sky.exr" | grep -q "EV100" && ok || bad "camera exposure not recorded"

# convert: the recorded exposure by default, PQ at 16 bits, and the pipeline without rendering.
if "$skyspec" convert "$work/p3/sky.exr" --out "$work/conv" --display Rec.2100-PQ --png-bits 16 --name pq >"$work/stdout"; then
  grep -q "exposure: recorded in the file" "$work/stdout" && ok || bad "convert did not use the recorded exposure"
  oiiotool --info -v "$work/conv/pq.png" | grep -q "uint16 png" && ok || bad "converted PQ PNG is not 16-bit"
else
  bad "convert failed"
fi
# Converting a render with the same settings reproduces its PNG exactly (the exposure is recorded).
"$skyspec" convert "$work/builtin/sky.exr" --out "$work/conv" --name again -q
oiiotool "$work/conv/again.png" "$work/builtin/sky.png" --diff >"$work/diff" 2>&1 && grep -q PASS "$work/diff" && ok || { bad "convert does not reproduce the render's PNG"; cat "$work/diff"; }
"$skyspec" convert "$work/p3/sky.exr" --out "$work/conv" --look uncharted2-filmic --name u2 -q && [ -s "$work/conv/u2.png" ] && ok || bad "convert with a skyspec look"

# compare: a render with itself reports zero; two renders of the same scene too.
"$skyspec" render -q --out "$work/same" --width 12 --height 12 --preset seed
"$skyspec" compare -q "$work/same/seed.exr" "$work/same/seed.exr" --out "$work/cmp-self"
grep -q '| \*\*all\*\* | [0-9]* | 0.00 | 0.00 | 0.00 | 0.00 | 0.0 % |' "$work/cmp-self/compare.md" && ok || { bad "self comparison is not zero"; cat "$work/cmp-self/compare.md"; }

# compare: the seed preset against its spectral twin, with a short sweep: all outputs, valid JSON.
if "$skyspec" compare -q --preset seed --width 16 --height 16 --sun-elevation 2 --sweep 0,30 --out "$work/cmp"; then
  for f in compare.md compare.json compare-delta-e.png compare-side-by-side.png compare-sweep.svg; do
    [ -s "$work/cmp/$f" ] && ok || bad "compare did not write $f"
  done
  grep -q "## Sweep over sun elevation" "$work/cmp/compare.md" && ok || bad "no sweep table"
  grep -q "<svg" "$work/cmp/compare-sweep.svg" && ok || bad "sweep plot is not SVG"
  if [ -x /usr/bin/python3 ]; then
    /usr/bin/python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); assert d["result"]["all"]["delta_e_2000"]["mean"] > 0; assert len(d["sweep"]) == 2' "$work/cmp/compare.json" && ok || bad "compare.json"
  fi
else
  bad "compare failed"
fi

finish cli_display
