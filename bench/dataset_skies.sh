#!/usr/bin/env bash
# Issue 37's target 4: a dataset of skies with random aerosol amount, Angstrom exponent and ozone
# column (128 x 128 fisheyes, 41 wavelengths, every scattering order, EXR), run as a job on 2 Dask
# workers from an empty table cache, at least 1 sky per second. Runs the job three times: with
# render.ms_tables = "interpolated" (the grid's tables built first, one Dask task per set, then
# every sky blends its own: render/table_family.hpp) from an empty table cache, the same again with
# the grid's tables cached (a second dataset of the same kind of air), and with exact tables (a set
# built per sky) for the first EXACT skies of the same design; prints skies per second with pass /
# FAIL. What the interpolation errs: bench/table_family.py (docs/jobs.md). Not a test: about 10
# minutes on 2 cores.
#
#   bench/dataset_skies.sh [--skyspec PATH] [--skies 200] [--exact-skies 12] [--out DIR]
set -euo pipefail
export LC_ALL=C
here="$(cd "$(dirname "$0")" && pwd)"; root="$(dirname "$here")"
skyspec="$root/build/skyspec"; out=/tmp/skyspec-dataset-bench; skies=200; exact=12
while [[ $# -gt 0 ]]; do
  case "$1" in
    --skyspec) skyspec="$2"; shift 2 ;;
    --skies) skies="$2"; shift 2 ;;
    --exact-skies) exact="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    -h|--help) sed -n 2,10p "$0"; exit 0 ;;
    *) echo "dataset_skies.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
skyspec="$(realpath "$skyspec")"
rm -rf "$out"; mkdir -p "$out"

job() {  # job NAME SAMPLES TABLES
  cat >"$out/$1.toml" <<TOML
[job]
name = "$1"
produce = ["exr"]
[scene]
camera.width = 128
camera.height = 128
render.ms_tables = "$3"
[random]
seed = 1
samples = $2
[random.axes]
"atmosphere.mie.scattering_per_m" = { min = 1e-5, max = 1.5e-4 }
"atmosphere.mie.angstrom_exponent" = { min = 0.5, max = 2.0 }
"atmosphere.ozone.column_DU" = { min = 250.0, max = 400.0 }
TOML
}
# timed JOB CACHE RUN: the job on 2 workers with the table cache CACHE, into a fresh output folder;
# prints seconds.
timed() {
  export SKYSPEC_CACHE_DIR="$out/cache-$2"
  local t0=$EPOCHREALTIME
  "$skyspec" job run "$out/$1.toml" --out "$out/$3" --workers 2 --quiet
  /usr/bin/python3 -c "print(f'{$EPOCHREALTIME - $t0:.1f}')"
}
job interpolated "$skies" interpolated
job exact "$exact" exact
SKYSPEC_CACHE_DIR="$out/cache-interpolated" "$skyspec" job plan "$out/interpolated.toml" --out "$out/run1" |
  grep "^tables:" | sed 's/^/interpolated, plan: /'
t_interp=$(timed interpolated interpolated run1)
sets=$(ls "$out/cache-interpolated" | grep -c '^orders-.*\.bin$' || true)
t_warm=$(timed interpolated interpolated run2)
t_exact=$(timed exact exact run3)
/usr/bin/python3 - "$skies" "$t_interp" "$sets" "$exact" "$t_exact" "$t_warm" <<'PY'
import sys
skies, t_i, sets, exact, t_e = int(sys.argv[1]), float(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), float(sys.argv[5])
t_w = float(sys.argv[6])
rate_i, rate_e, rate_w = skies / t_i, exact / t_e, skies / t_w
print(f"dataset of {skies} random skies (aerosol 1e-5..1.5e-4 m^-1, alpha 0.5..2, ozone 250..400 DU; 128 x 128, "
      f"41 wl, 6 orders), 2 Dask workers, empty table cache:")
print(f"  interpolated tables: {t_i:.1f} s, {sets} grid atmospheres' tables built: {rate_i:.2f} skies/s")
print(f"  interpolated tables, the grid's tables cached (the same job again): {t_w:.1f} s: {rate_w:.2f} skies/s")
print(f"  exact tables (first {exact} skies of the same design): {t_e:.1f} s: {rate_e:.3f} skies/s "
      f"({t_e / exact:.1f} s per sky)")
print(f"target 4, at least 1 sky per second from an empty cache: {rate_i:.2f}: {'pass' if rate_i >= 1.0 else 'FAIL'}; "
      f"with the grid's tables cached: {rate_w:.2f}: {'pass' if rate_w >= 1.0 else 'FAIL'}")
PY
