#!/usr/bin/env bash
# How the multiple-scattering tables' ray quadrature sets the sky: the default and hazy presets'
# 256 x 128 panoramas (suns 30, 10, 2 and -4 degrees, 41 wavelengths) rendered with the tables'
# segments per ray for order 2 and for orders 3 and up (render.ms_view_segments,
# render.ms_higher_order_segments) at the defaults (24, 16), at (24, 24) and at (48, 48), each set
# of tables built in its own cache folder; prints per preset and sun the median and largest
# relative difference of the spectral radiance (every S0 channel of every pixel whose radiance
# exceeds 1e-6 of the image's largest) against (48, 48), and the seconds each render took (the
# first sun's builds the tables, the others read them from the cache). About a minute on 2 cores. Usage (from the repository root):
#
#   bench/ms_segments.sh [SKYSPEC]     (default: build/skyspec)
set -euo pipefail
export LC_ALL=C  # EPOCHREALTIME with a decimal point
skyspec=${1:-build/skyspec}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
settings=("24 16" "24 24" "48 48")
echo "| preset | sun (deg) | segments (order 2, orders >= 3) | seconds (the first sun's render builds the tables) | median difference vs (48, 48) | largest |"
echo "| --- | ---: | --- | ---: | ---: | ---: |"
for preset in default hazy; do
  for sun in 30 10 2 -4; do
    for s in "${settings[@]}"; do
      set -- $s
      name="$preset-$sun-$1-$2"
      start=$EPOCHREALTIME
      SKYSPEC_CACHE_DIR="$work/cache-$1-$2" "$skyspec" render -q --no-png --preset "$preset" --sun-elevation "$sun" \
        --camera equirectangular --width 256 --height 128 --set render.ms_view_segments="$1" \
        --set render.ms_higher_order_segments="$2" --out "$work" --name "$name"
      awk -v a="$start" -v b="$EPOCHREALTIME" -v n="$name" 'BEGIN { print n, b - a }' >>"$work/seconds"
    done
  done
done
/usr/bin/python3 - "$work" <<'PY'
import sys
import numpy as np
import OpenImageIO as oiio

work = sys.argv[1]
seconds = dict(line.split() for line in open(work + "/seconds"))


def spectral(name):
    inp = oiio.ImageInput.open(f"{work}/{name}.exr")
    spec = inp.spec()
    px = np.asarray(inp.read_image(0, 0, 0, spec.nchannels, oiio.FLOAT), dtype=np.float64)
    inp.close()
    idx = [k for k, n in enumerate(spec.channelnames) if n.startswith("S0.")]
    return px[:, :, idx]


for preset in ("default", "hazy"):
    for sun in ("30", "10", "2", "-4"):
        ref = spectral(f"{preset}-{sun}-48-48")
        lit = ref > 1e-6 * ref.max()
        for s in ("24-16", "24-24", "48-48"):
            img = spectral(f"{preset}-{sun}-{s}")
            rel = np.abs(img[lit] - ref[lit]) / ref[lit]
            a, b = s.split("-")
            print(f"| {preset} | {sun} | {a}, {b} | {float(seconds[f'{preset}-{sun}-{s}']):.1f} | "
                  f"{100 * np.median(rel):.4f} % | {100 * rel.max():.3f} % |")
PY
