#!/usr/bin/env bash
# Provenance: every output carries skyspec:version, skyspec:scene and skyspec:data, and
# `skyspec render --from FILE.exr` renders the recorded scene again, to the same spectral pixels;
# flags given with --from override the recorded scene. Errors name --from and the file.
# Usage: test_reproduce.sh SKYSPEC
set -u
skyspec=$1
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
export SKYSPEC_CACHE_DIR="${SKYSPEC_CACHE_DIR:-$work/cache}"
python=/usr/bin/python3

# Non-default keys, some with more digits than a person types (the header must keep them all).
"$skyspec" render -q --out "$work/first" --camera equirectangular --width 48 --height 24 \
  --sun-elevation 12.3456789012345 --sun-azimuth 101.5 --lambda-step 20 \
  --set atmosphere.mie.g=0.8123456789012 --set render.scattering_orders=2 --set ground.albedo=0.3 \
  2>"$work/stderr" && ok || { bad "first render failed"; cat "$work/stderr"; }

# Again from the file, elsewhere and under another name (flags override the recorded scene).
"$skyspec" render -q --from "$work/first/sky.exr" --out "$work/again" --name copy 2>"$work/stderr" \
  && ok || { bad "render --from failed"; cat "$work/stderr"; }
[ -s "$work/again/copy.exr" ] && [ -s "$work/again/copy.png" ] && ok || bad "render --from wrote: $(ls "$work/again")"
[ -s "$work/stderr" ] && bad "render --from of this version printed: $(cat "$work/stderr")" || ok

# Same channels, same spectral pixels bit for bit; the recorded scenes differ only in the output
# folder and name; the data tables are listed with their hashes in both files and in the PNG.
"$python" - "$work/first/sky.exr" "$work/again/copy.exr" "$work/again/copy.png" <<'PY' && ok || bad "reproduction differs"
import sys, OpenImageIO as oiio
def read(path):
    f = oiio.ImageInput.open(path)
    spec = f.spec()
    pixels = f.read_image(oiio.FLOAT)
    f.close()
    return spec, pixels
a, pa = read(sys.argv[1])
b, pb = read(sys.argv[2])
assert list(a.channelnames) == list(b.channelnames), (a.channelnames, b.channelnames)
assert any(c.startswith("S0.") for c in a.channelnames)
assert pa.tobytes() == pb.tobytes(), "spectral pixels differ"
for spec in (a, b):
    data = spec.getattribute("skyspec:data")
    assert data and "cie/cie1931_2deg_5nm.csv  fnv1a64=" in data and "solar/astm_g173_etr.csv" in data, data
    assert spec.getattribute("skyspec:version")
def scene(spec):
    return [l for l in spec.getattribute("skyspec:scene").splitlines() if not l.startswith(("directory", "name"))]
assert scene(a) == scene(b)
assert "elevation_deg = 12.3456789012345" in a.getattribute("skyspec:scene")
assert a.getattribute("skyspec:data") == b.getattribute("skyspec:data")
png = oiio.ImageInput.open(sys.argv[3])
for key in ("skyspec:version", "skyspec:scene", "skyspec:data"):
    assert png.spec().getattribute(key), key
png.close()
PY

# Flags override the recorded scene: another size.
"$skyspec" render -q --from "$work/first/sky.exr" --out "$work/wide" --width 64 --no-png 2>"$work/stderr" \
  && ok || { bad "render --from --width failed"; cat "$work/stderr"; }
"$skyspec" render --from "$work/first/sky.exr" --out "$work/wide" --width 64 --print-scene >"$work/scene.toml"
grep -q "^width = 64$" "$work/scene.toml" && grep -q "^height = 24$" "$work/scene.toml" && ok \
  || bad "--width with --from: $(grep -E '^(width|height)' "$work/scene.toml")"

# Another version's file is rendered, with a warning.
if oiiotool "$work/first/sky.exr" --attrib skyspec:version 0.0.1 -o "$work/old.exr" 2>/dev/null; then
  "$skyspec" render -q --from "$work/old.exr" --out "$work/old" --no-png 2>"$work/stderr" && ok || bad "old version refused"
  grep -q "warning: --from .*old.exr was written by skyspec 0.0.1" "$work/stderr" && ok || { bad "no version warning"; cat "$work/stderr"; }
fi

# Errors: not an EXR (cannot be read: 3), an EXR without a scene (bad input: 2), --from with --scene.
printf 'not an image\n' >"$work/text.exr"
run_expecting_error from_not_exr 3 "--from: cannot read $work/text.exr as OpenEXR" "$work/e1" \
  "$skyspec" render -q --from "$work/text.exr" --out "$work/e1"
run_expecting_error from_missing 3 "--from: cannot read $work/missing.exr" "$work/e2" \
  "$skyspec" render -q --from "$work/missing.exr" --out "$work/e2"
"$skyspec" aerial -q --distance 100 --image "$work/first/sky.exr" --out "$work/ap" --lambda-step 20 >/dev/null 2>&1
oiiotool --create 4x4 3 -d float -o "$work/plain.exr" 2>/dev/null
run_expecting_error from_no_scene 2 "--from = \"$work/plain.exr\" is not allowed" "$work/e3" \
  "$skyspec" render -q --from "$work/plain.exr" --out "$work/e3"
run_expecting_error from_and_scene 2 "excludes" "$work/e4" \
  "$skyspec" render -q --from "$work/first/sky.exr" --scene "$work/scene.toml" --out "$work/e4"

# The other commands' EXRs carry the provenance too.
"$skyspec" timelapse -q --out "$work/tl" --width 16 --height 16 --lambda-step 20 --set render.scattering_orders=1 \
  --latitude 48 --longitude 11 --start 2026-06-21T12:00:00+02:00 --end 2026-06-21T12:30:00+02:00 --step-minutes 30 \
  2>"$work/stderr" || { bad "timelapse failed"; cat "$work/stderr"; }
for f in "$work/tl/sky_0000.exr" "$work/tl/sky_0001.exr" "$work/ap/sky_inscatter.exr" "$work/ap/sky_composite.exr"; do
  header=$(exrheader "$f" 2>&1)
  for key in skyspec:version skyspec:scene skyspec:data; do
    grep -q "^$key " <<<"$header" && ok || bad "$f has no $key"
  done
done
grep -q "solar_position/spa_nutation_terms.csv" <<<"$(exrheader "$work/tl/sky_0000.exr")" && ok \
  || bad "a timelapse frame does not list the solar position tables"

finish reproduce
