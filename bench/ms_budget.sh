#!/usr/bin/env bash
# The multiple-scattering figures of docs/physics.md (section "Beyond single scattering"): how much
# stopping at 6 orders and the default 16 x 72 tables change the default scene, per wavelength,
# and what the higher orders add at the zenith. About a minute on 2 cores.
#
#   bench/ms_budget.sh [--skyspec PATH] [--out DIR]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"; root="$(dirname "$here")"
skyspec="$root/build/skyspec"; out=/tmp/skyspec-ms-budget
while [[ $# -gt 0 ]]; do
  case "$1" in
    --skyspec) skyspec="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    -h|--help) sed -n 2,6p "$0"; exit 0 ;;
    *) echo "ms_budget.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
[[ -x "$skyspec" ]] || { echo "ms_budget.sh: no skyspec binary at $skyspec (build it first)" >&2; exit 2; }
mkdir -p "$out"
export SKYSPEC_CACHE_DIR="$out/cache"; rm -rf "$SKYSPEC_CACHE_DIR"
common=(render -q --no-png --out "$out" --width 128 --height 128)
"$skyspec" "${common[@]}" --name orders6
"$skyspec" "${common[@]}" --name orders12 --set render.scattering_orders=12
"$skyspec" "${common[@]}" --name tables32x144 --set render.ms_altitude_samples=32 --set render.ms_sun_samples=144
"$skyspec" "${common[@]}" --name zenith6 --width 33 --height 33
"$skyspec" "${common[@]}" --name zenith1 --width 33 --height 33 --set render.scattering_orders=1
/usr/bin/python3 "$here/ms_budget.py" "$out"
