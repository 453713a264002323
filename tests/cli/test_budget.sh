#!/usr/bin/env bash
# Absurd but legal requests are refused up front, with the estimate, unless --force: outputs
# bigger than the free disk (a 1 MiB tmpfs; needs root, else skipped), a render estimated at more
# than a day. A normal render is not refused, --dry-run prints the estimate and writes nothing.
# Usage: test_budget.sh SKYSPEC
set -u
skyspec=$1
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
export SKYSPEC_CACHE_DIR="${SKYSPEC_CACHE_DIR:-$work/cache}"
small="--set render.scattering_orders=1"

# --- the disk ----------------------------------------------------------------------------------
disk="$work/disk"
mkdir -p "$disk"
if mount -t tmpfs -o size=1m skyspec-test-budget "$disk" 2>/dev/null; then
  trap 'umount "$disk" 2>/dev/null; rm -rf "$work"' EXIT
  # 512 x 512 x 44 floats: up to 46 MB of EXR for 1 MiB.
  run_expecting_error disk_refused 2 "this render would write up to 47 MB (a 46 MB EXR) but $disk/out has 1.0 MB free" \
    "$disk/out" "$skyspec" render -q --out "$disk/out" $small
  grep -qF "(use --force to render anyway)" "$work/stderr" && ok || bad "disk refusal does not name --force"
  # --force really bypasses the check: the render runs into the full disk (exit 3, no file left).
  run_expecting_error disk_forced 3 "No space left on device" "$disk/forced" \
    "$skyspec" render -q --out "$disk/forced" --force $small
  # A time-lapse counts all its frames: 3 x 16 x 16 frames fit in 1 MiB, 300 do not.
  run_expecting_error timelapse_disk 2 "(300 frames of up to" "$disk/tl" \
    "$skyspec" timelapse -q --out "$disk/tl" --width 16 --height 16 $small --latitude 48 --longitude 11 \
    --start 2026-06-21T00:00:00Z --end 2026-06-21T04:59:00Z --step-minutes 1
  umount "$disk" && ok || bad "could not unmount the test tmpfs"
  trap 'rm -rf "$work"' EXIT
else
  echo "SKIP disk: cannot mount a tmpfs here (needs root)"
fi

# --- the time ----------------------------------------------------------------------------------
# Every pixel marched with 4096 view segments, 268 Mpixels, one thread: days (PNG only, 805 MB).
slow=(--camera equirectangular --width 16384 --height 16384 --view-segments 4096 --threads 1 --no-exr
      --set render.sky_view_table=false $small)
run_expecting_error too_slow 2 "would take about" "$work/slow" \
  "$skyspec" render -q --out "$work/slow" "${slow[@]}"
grep -qF "at these settings (41 wavelengths, 4096 view segments, 16384x16384, 1 thread)" "$work/stderr" && ok \
  || { bad "time refusal lacks the settings"; cat "$work/stderr"; }
grep -qF "use --force" "$work/stderr" && ok || bad "time refusal does not name --force"
# The estimate is cheap: refused within seconds, not after rendering.
start=$(date +%s)
"$skyspec" render -q --dry-run --out "$work/slow" "${slow[@]}" >/dev/null 2>&1
[ $(( $(date +%s) - start )) -lt 20 ] && ok || bad "the estimate took $(( $(date +%s) - start )) s"

# --- a normal render -----------------------------------------------------------------------------
"$skyspec" render --out "$work/normal" --width 32 --height 32 $small >"$work/stdout" 2>"$work/stderr" \
  && ok || { bad "a small render was refused"; cat "$work/stderr"; }
grep -q "^estimate: outputs up to .* free), peak memory about .* available), about .* of rendering$" "$work/stdout" \
  && ok || { bad "no estimate in the summary"; cat "$work/stdout"; }
# --dry-run: the estimate and nothing else.
"$skyspec" render --dry-run --out "$work/dry" --width 32 --height 32 $small >"$work/stdout" 2>"$work/stderr" \
  && ok || { bad "--dry-run failed"; cat "$work/stderr"; }
grep -q "^estimate: outputs up to [0-9.]* kB .* (41 wavelengths, 64 view segments, 32x32," "$work/stdout" && ok \
  || { bad "--dry-run printed: $(cat "$work/stdout")"; }
[ ! -e "$work/dry" ] && ok || bad "--dry-run wrote $(ls -A "$work/dry")"

finish budget
