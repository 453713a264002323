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

# --- estimates against reality (issue 42, item 7: memory was 2.6x too low for a large PNG) --------
# A 2500 x 2500 render, PNG only, then EXR only: the measured peak memory (GNU time's maximum
# resident set) within 1.5x of the estimate either way; the time within 3x: the wall time, or, on a
# machine busy with other work (which stretches the wall time, not the CPU time the estimate
# samples), the render's CPU time over its threads (as many as cores).
if [ -n "${SKYSPEC_SANITIZER_STAGE:-}" ]; then
  echo "SKIP estimates: under AddressSanitizer memory and time are not the release build's (release stage only)"
elif [ -x /usr/bin/time ]; then
  for outputs in --no-exr --no-png; do
    args=(--width 2500 --height 2500 --quality draft $small "$outputs")
    "$skyspec" render --dry-run --out "$work/real" "${args[@]}" >"$work/stdout" 2>&1
    est_mb=$(sed -n 's/.*peak memory about \([0-9.]*\) MB.*/\1/p' "$work/stdout")
    est_s=$(sed -n 's/.*about \([0-9.]*\) s of rendering.*/\1/p' "$work/stdout")
    /usr/bin/time -f "%M %e %U %S" -o "$work/time" "$skyspec" render -q --out "$work/real" "${args[@]}" 2>/dev/null
    read -r peak_kb wall_s user_s sys_s <"$work/time"
    cpu_s=$(awk -v u="$user_s" -v s="$sys_s" -v n="$(nproc)" 'BEGIN { printf "%.2f", (u + s) / n }')
    awk -v e="$est_mb" -v m="$peak_kb" 'BEGIN { r = e * 1e6 / (m * 1024); exit !(r > 1 / 1.5 && r < 1.5) }' && ok \
      || bad "memory $outputs: estimated $est_mb MB, measured $((peak_kb / 1024)) MB"
    awk -v e="$est_s" -v m="$wall_s" -v c="$cpu_s" 'BEGIN {
          if (e == "" || m <= 0) exit 1
          r = e / m; q = c > 0 ? e / c : 0
          exit !((r > 1 / 3 && r < 3) || (q > 1 / 3 && q < 3)) }' && ok \
      || bad "time $outputs: estimated ${est_s:-?} s, measured $wall_s s (CPU time over the threads $cpu_s s)"
    echo "estimate $outputs: memory $est_mb MB against $((peak_kb / 1024)) MB measured, time $est_s s against" \
      "$wall_s s ($cpu_s s of CPU time per thread)"
    rm -rf "$work/real"
  done
else
  echo "SKIP estimates: no /usr/bin/time (GNU time)"
fi

# --- a job's table builds (issue 42, item 8: 100 random albedos were "about 0.1 s") ----------------
# Three random ground albedos are three atmospheres, each with its own scattering-order tables:
# `job plan` counts the builds, their time and the bytes the cache gains; the run then adds those
# bytes (within 10 %) and takes that time (within 3x); a second plan finds them cached. Release stage
# only: the builds take minutes under the sanitizers.
# A swept sun azimuth shares one set; without the disk cache each chunk (process) builds its own.
tables='camera.width = 8
camera.height = 8
render.ms_altitude_samples = 8
render.ms_sun_samples = 16
render.scattering_orders = 2'
if [ -n "${SKYSPEC_SANITIZER_STAGE:-}" ]; then
  echo "SKIP job tables: they build tables, left to the release stage"
else
printf '[job]\nname = "albedos"\nproduce = ["exr"]\n[scene]\n%s\n[random]\nsamples = 3\nseed = 1\n[random.axes]\n"ground.albedo" = { min = 0.0, max = 1.0 }\n' \
  "$tables" >"$work/albedos.toml"
export SKYSPEC_CACHE_DIR="$work/job-cache"
"$skyspec" job plan "$work/albedos.toml" --out "$work/albedos" >"$work/plan.txt" 2>&1
grep -q "^tables: 3 distinct sets of scattering-order tables (0 cached): 3 builds, about .*, .* added to $work/job-cache$" \
  "$work/plan.txt" && ok || bad "job plan does not count the table builds: $(cat "$work/plan.txt")"
bytes_of() { awk '{ v = $1; u = $2; m = (u == "kB") ? 1e3 : (u == "MB") ? 1e6 : (u == "GB") ? 1e9 : 1; printf "%.0f", v * m }'; }
planned=$(sed -n 's/^tables: .*, \([0-9.]* [kMG]*B\) added to .*/\1/p' "$work/plan.txt" | bytes_of)
plan_s=$(sed -n 's/.*about \([0-9.]*\) s of rendering, tables about \([0-9.]*\) s .*/\1 \2/p' "$work/plan.txt")
start=$(date +%s.%N)
"$skyspec" job run "$work/albedos.toml" --out "$work/albedos" --shard 1/1 -q || bad "the albedo job failed"
wall=$(echo "$(date +%s.%N) - $start" | bc)
cached=$(du -sb "$work/job-cache" | cut -f1)
awk -v p="$planned" -v c="$cached" 'BEGIN { exit !(p > 0 && c / p > 0.9 && c / p < 1.1) }' && ok \
  || bad "the plan said ${planned:-?} bytes for the cache, the run added $cached"
awk -v e="$plan_s" -v m="$wall" 'BEGIN { split(e, t, " "); r = (t[1] + t[2]) / m; exit !(r > 1 / 3 && r < 3) }' && ok \
  || bad "the plan said ${plan_s:-?} s (rendering, tables), the job took $wall s"
echo "job tables: planned ${plan_s:-?} s (rendering, tables) and $planned bytes; measured $wall s and $cached bytes"
"$skyspec" job plan "$work/albedos.toml" --out "$work/albedos" >"$work/plan.txt" 2>&1
grep -q "^tables: 3 distinct sets of scattering-order tables (3 cached): nothing to build$" "$work/plan.txt" && ok \
  || bad "a second plan does not find the tables cached: $(cat "$work/plan.txt")"
printf '[job]\nname = "suns"\nproduce = ["exr"]\ntasks_per_chunk = 1\n[scene]\n%s\nrender.cache_tables = false\n[axes]\n"sun.azimuth_deg" = [0, 90, 180]\n' \
  "$tables" >"$work/suns.toml"
"$skyspec" job plan "$work/suns.toml" --out "$work/suns" >"$work/plan.txt" 2>&1
grep -q "^tables: 1 distinct set of scattering-order tables (0 cached): 3 builds, about .*, not kept (render.cache_tables = false)$" \
  "$work/plan.txt" && ok || bad "a sun sweep without the cache: $(cat "$work/plan.txt")"

# Interpolated tables (render.ms_tables, render/table_family.hpp): two random aerosol amounts read
# the tables of the grid's atmospheres about them, which the plan counts and lists (--json) and
# `job run --table-set K` builds, one set per call (the Dask driver's tasks); then nothing is left
# to build, and the job renders from them.
printf '[job]\nname = "grid"\nproduce = ["exr"]\n[scene]\n%s\nrender.ms_tables = "interpolated"\n[random]\nsamples = 2\nseed = 1\n[random.axes]\n"atmosphere.mie.scattering_per_m" = { min = 1e-5, max = 1e-4 }\n' \
  "$tables" >"$work/grid.toml"
export SKYSPEC_CACHE_DIR="$work/grid-cache"
"$skyspec" job plan "$work/grid.toml" --out "$work/grid" >"$work/plan.txt" 2>&1
sets=$("$skyspec" job plan "$work/grid.toml" --out "$work/grid" --json | /usr/bin/python3 -c 'import json, sys; print(" ".join(map(str, json.load(sys.stdin)["table_sets"])))')
count=$(echo "$sets" | wc -w)
[ "$count" -ge 4 ] && grep -q "^tables: $count distinct sets of scattering-order tables (0 cached): $count builds" "$work/plan.txt" \
  && ok || bad "interpolated tables: the plan lists '$sets': $(cat "$work/plan.txt")"
for k in $sets; do "$skyspec" job run "$work/grid.toml" --out "$work/grid" --table-set "$k" --threads 2 -q || bad "--table-set $k failed"; done
"$skyspec" job plan "$work/grid.toml" --out "$work/grid" >"$work/plan.txt" 2>&1
grep -q "^tables: $count distinct sets of scattering-order tables ($count cached): nothing to build$" "$work/plan.txt" && ok \
  || bad "after --table-set, sets left to build: $(cat "$work/plan.txt")"
"$skyspec" job run "$work/grid.toml" --out "$work/grid" --shard 1/1 -q 2>"$work/stderr" && [ "$(ls "$work/grid-cache" | grep -c '^orders-')" = "$count" ] \
  && ! grep -q "warning" "$work/stderr" && ok || bad "the interpolated job built more tables or warned: $(cat "$work/stderr")"
run_expecting_error table_set_range 2 "--table-set = 99 is not allowed: a set from 0 to $((count - 1))" "$work/none" \
  "$skyspec" job run "$work/grid.toml" --out "$work/grid" --table-set 99
run_expecting_error table_set_shard 2 "--table-set = 0 is not allowed: no --shard or --tasks" "$work/none" \
  "$skyspec" job run "$work/grid.toml" --out "$work/grid" --table-set 0 --shard 1/1
fi

finish budget
