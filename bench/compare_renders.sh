#!/usr/bin/env bash
# Are this tree's renders byte-identical to another revision's? For refactors that must not change a
# pixel. Builds REV's program in a scratch worktree (release, the CLI only), renders the same six
# scenes (seven where REV has terrain: a ridge at sunset) with both programs (each with its own, empty table cache, so the tables are built by each),
# and compares every EXR and PNG byte for byte; where the bytes differ, their pixels (every
# channel, exactly: OpenImageIO's idiff -fail 0 -warn 0 -a), since a new scene key changes the
# scene text in the files' headers but no pixel.
#   bench/compare_renders.sh REV [THIS_PROGRAM]      (default: build/skyspec)
# Prints "same FILE", "same pixels FILE (headers differ)" or "DIFF FILE" per file; exits 1 if any
# pixel differs. About 4 minutes on 2 cores
# plus REV's build.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
rev=${1:?usage: bench/compare_renders.sh REV [PROGRAM]}
this=$(realpath "${2:-build/skyspec}")
work=$(mktemp -d)
trap 'git worktree remove --force "$work/src" >/dev/null 2>&1 || true; rm -rf "$work"' EXIT
git worktree add --detach "$work/src" "$rev" >/dev/null
cmake -S "$work/src" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DSKYSPEC_BUILD_TESTS=OFF -DSKYSPEC_BUILD_PYTHON=OFF >/dev/null
cmake --build "$work/build" -j"$(nproc)" --target skyspec_cli >/dev/null
renders() {  # renders PROGRAM DIR: the default, hazy, polarised, panorama, seed and OPAC (tabulated) scenes
  local s=$1 o=$2
  export SKYSPEC_CACHE_DIR=$o/cache
  "$s" render --quiet --width 128 --height 128 --out "$o/default"
  "$s" render --quiet --preset hazy --width 128 --height 128 --out "$o/hazy"
  "$s" render --quiet --width 96 --height 48 --camera equirectangular --set output.polarisation=true \
    --set output.polarisation_png=true --out "$o/polarised"
  "$s" render --quiet --camera equirectangular --width 256 --height 128 --sun-elevation 10 --sun-azimuth 90 --out "$o/panorama"
  "$s" render --quiet --preset seed --width 64 --height 64 --out "$o/seed"
  "$s" render --quiet --width 48 --height 48 --set 'atmosphere.mie.model="opac"' --set output.polarisation=true \
    --out "$o/opac"
  if [ "$terrain" = yes ]; then  # the notched ridge at sunset, all orders (the light shafts' picture, small)
    "$s" render --quiet --scene docs/images/terrain-light-shafts.toml --width 96 --height 54 --out "$o/terrain"
  fi
}
# The terrain scene where REV has the picture's scene (terrain exists there).
terrain=no
[ -f "$work/src/docs/images/terrain-light-shafts.toml" ] && terrain=yes
renders "$work/build/skyspec" "$work/theirs"
renders "$this" "$work/ours"
status=0
for f in $(cd "$work/theirs" && find . -name '*.exr' -o -name '*.png' | grep -v '^./cache' | sort); do
  if cmp -s "$work/theirs/$f" "$work/ours/$f"; then
    echo "same ${f#./}"
  elif idiff -fail 0 -warn 0 -a "$work/theirs/$f" "$work/ours/$f" >/dev/null 2>&1; then
    echo "same pixels ${f#./} (headers differ)"
  else
    echo "DIFF ${f#./}"
    status=1
  fi
done
exit $status
