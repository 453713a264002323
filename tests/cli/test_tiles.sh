#!/usr/bin/env bash
# Tiles (issue 22): `render --pixel-bounds` tiles merged with `skyspec merge` are byte for byte the
# whole render's EXR (a fisheye in an uneven grid; a half-float panorama in strips); bad bounds and
# tiles that overlap or leave a gap are refused, naming the flag or the tile, with no file left;
# the merge's peak memory stays flat as the image grows (measured at two heights).
# Usage: test_tiles.sh path/to/skyspec
skyspec=$1
source "$(dirname "$0")/lib.sh"

# render_tiles OUT ARGS... -- BOUNDS...: the whole render into OUT/whole, each tile into OUT/tile-K.
render_tiles() {
  local out=$1
  shift
  local args=()
  while [ "$1" != "--" ]; do args+=("$1"); shift; done
  shift
  "$skyspec" render "${args[@]}" --no-png --quiet --out "$out/whole" || bad "whole render failed"
  local k=0
  for b in "$@"; do
    "$skyspec" render "${args[@]}" --quiet --out "$out/tile-$k" --pixel-bounds "$b" || bad "tile $b failed"
    k=$((k + 1))
  done
}

render_tiles "$work/f" --quality lean --width 70 --height 53 --sun-elevation 50 -- \
  0,30,0,20 30,70,0,20 0,51,20,53 51,70,20,53
"$skyspec" merge "$work"/f/tile-*/sky.exr --out "$work/f/merged.exr" --quiet || bad "merge failed"
cmp -s "$work/f/merged.exr" "$work/f/whole/sky.exr" && ok || bad "merged fisheye tiles differ from the whole render"
ls "$work"/f/tile-0 | grep -q png && bad "a tile wrote a PNG" || ok
exrheader "$work/f/tile-3/sky.exr" | grep -q "dataWindow (type box2i): (51 20) - (69 52)" && ok || bad "tile data window"

render_tiles "$work/p" --quality draft --camera equirectangular --width 96 --height 48 --set output.exr_spectral_type=half -- \
  0,96,0,7 0,96,7,31 0,96,31,48
"$skyspec" merge "$work"/p/tile-*/sky.exr --out "$work/p/merged.exr" --quiet || bad "panorama merge failed"
cmp -s "$work/p/merged.exr" "$work/p/whole/sky.exr" && ok || bad "merged panorama strips differ from the whole render"
# The merged file is a usable EXR for other tools: the PNG from it, and OpenImageIO reads it.
"$skyspec" convert "$work/p/merged.exr" --out "$work/p/png" --quiet && [ -s "$work/p/png/merged.png" ] && ok || bad "convert of the merged file"

run_expecting_error "bounds outside the image" 2 "--pixel-bounds" "$work/none" \
  "$skyspec" render --quality draft --width 64 --height 32 --pixel-bounds 0,65,0,32 --out "$work/none"
run_expecting_error "bounds text" 2 "--pixel-bounds" "$work/none" \
  "$skyspec" render --quality draft --pixel-bounds 0,10,5 --out "$work/none"
mkdir -p "$work/m"
run_expecting_error "overlapping tiles" 2 "tile-1/sky.exr" "$work/m" \
  "$skyspec" merge "$work/f/tile-0/sky.exr" "$work/f/tile-1/sky.exr" "$work/f/tile-1/sky.exr" --out "$work/m/x.exr"
run_expecting_error "a missing tile" 2 "pixel(s) are in no tile" "$work/m" \
  "$skyspec" merge "$work/f/tile-0/sky.exr" "$work/f/tile-1/sky.exr" --out "$work/m/x.exr"
run_expecting_error "tiles of two renders" 2 "differs" "$work/m" \
  "$skyspec" merge "$work/f/tile-0/sky.exr" "$work/p/tile-1/sky.exr" --out "$work/m/x.exr"

# Peak memory of the merge at 512 x 512 and 512 x 2048 (44 float channels: 46 MB and 185 MB of
# pixels): bounded by a band of rows (and OpenEXR's line buffers, all in use from a few blocks
# on), it may not grow by more than 16 MB.
rss() {  # rss HEIGHT: max RSS in kB of merging two strips of a HEIGHT-row image
  local h=$1 half=$(($1 / 2))
  "$skyspec" render --quality draft --camera equirectangular --width 512 --height "$h" --set render.scattering_orders=1 \
    --quiet --out "$work/r$h/a" --pixel-bounds 0,512,0,$half
  "$skyspec" render --quality draft --camera equirectangular --width 512 --height "$h" --set render.scattering_orders=1 \
    --quiet --out "$work/r$h/b" --pixel-bounds 0,512,$half,"$h"
  /usr/bin/time -f %M -o "$work/r$h/rss" "$skyspec" merge "$work/r$h/a/sky.exr" "$work/r$h/b/sky.exr" \
    --out "$work/r$h/merged.exr" --quiet
  cat "$work/r$h/rss"
}
# Not under the sanitizers (scripts/test.sh sets SKYSPEC_SANITIZER_STAGE): AddressSanitizer keeps
# freed memory in quarantine, so its RSS says nothing about what the merge holds.
if [ -z "${SKYSPEC_SANITIZER_STAGE:-}" ]; then
  small=$(rss 512)
  big=$(rss 2048)
  echo "merge peak RSS: 512x512 $small kB, 512x2048 $big kB"
  [ -n "$small" ] && [ -n "$big" ] && [ $((big - small)) -lt 16384 ] && ok || bad "merge memory grows with the image: $small kB -> $big kB"
fi
finish cli_tiles
