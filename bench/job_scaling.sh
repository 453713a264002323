#!/usr/bin/env bash
# Jobs on Dask (issue 22): throughput of a 200-task job with 2 workers against 1, next to the
# ceiling two independent one-thread processes reach on the same machine; the engine's overhead per
# task for tasks of about a second; the merge of a giant panorama from tiles (time, peak memory).
# Not a test: it takes several minutes. Usage (from the repository root):
#
#   bench/job_scaling.sh [--skyspec PATH] [--out DIR] [--merge WxH]
#
# --merge  the panorama the merge case renders in 8 strips and merges (default 16384x8192, 41
#          wavelengths, draft quality, single scattering: 24 GB of pixels; about 25 GB of disk)
#          or "none"
set -euo pipefail
export LC_ALL=C
here="$(cd "$(dirname "$0")" && pwd)"; root="$(dirname "$here")"
skyspec="$root/build/skyspec"; out=/tmp/skyspec-job-bench; merge=16384x8192
while [[ $# -gt 0 ]]; do
  case "$1" in
    --skyspec) skyspec="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --merge) merge="$2"; shift 2 ;;
    -h|--help) sed -n 2,12p "$0"; exit 0 ;;
    *) echo "job_scaling.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
skyspec="$(realpath "$skyspec")"
[[ -x /usr/bin/time ]] || { echo "job_scaling.sh: needs GNU time" >&2; exit 2; }
rm -rf "$out"; mkdir -p "$out"
export SKYSPEC_CACHE_DIR="$out/cache"  # the tables are built once, before anything is timed
now() { echo "$EPOCHREALTIME"; }
seconds() { /usr/bin/python3 -c "print(f'{$2 - $1:.2f}')"; }

# A job of 200 tasks: 2 sites x 100 hourly frames, 64 x 64 lean fisheyes (EXR only).
job() {  # job NAME SIZE TASKS_PER_CHUNK FRAMES
  cat >"$out/$1.toml" <<TOML
[job]
name = "$1"
quality = "lean"
produce = ["exr"]
tasks_per_chunk = $3
[scene]
camera.width = $2
camera.height = $2
[[time]]
start = 2026-06-15T06:00:00Z
end = $(/usr/bin/python3 -c "import datetime as d; print((d.datetime(2026,6,15,6)+d.timedelta(hours=$4-1)).strftime('%Y-%m-%dT%H:%M:%SZ'))")
step_minutes = 60
[[site]]
name = "a"
latitude_deg = 10
longitude_deg = 0
[[site]]
name = "b"
latitude_deg = 20
longitude_deg = 0
TOML
}
job throughput 64 10 100
"$skyspec" render --quality lean --width 8 --height 8 --quiet --no-png --out "$out/warm"  # tables into the cache
t0=$(now); "$skyspec" job run "$out/throughput.toml" --out "$out/one-process" --shard 1/1 --threads 1 --quiet; t1=$(now)
one=$(seconds "$t0" "$t1")
t0=$(now)
"$skyspec" job run "$out/throughput.toml" --out "$out/two-processes" --shard 1/2 --threads 1 --quiet --no-collect &
"$skyspec" job run "$out/throughput.toml" --out "$out/two-processes" --shard 2/2 --threads 1 --quiet --no-collect &
wait; t1=$(now)
two=$(seconds "$t0" "$t1")
t0=$(now); "$skyspec" job run "$out/throughput.toml" --out "$out/dask1" --workers 1 --quiet; t1=$(now)
dask1=$(seconds "$t0" "$t1")
t0=$(now); "$skyspec" job run "$out/throughput.toml" --out "$out/dask2" --workers 2 --quiet; t1=$(now)
dask2=$(seconds "$t0" "$t1")
/usr/bin/python3 - "$one" "$two" "$dask1" "$dask2" <<'PY'
import sys
one, two, d1, d2 = map(float, sys.argv[1:])
ceiling, dask = one / two, d1 / d2
print("## Throughput: 200 tasks (64 x 64, lean, EXR), chunks of 10")
print(f"one process, one thread:               {one:7.2f} s")
print(f"two one-thread processes at once:      {two:7.2f} s   ceiling {ceiling:.2f}x")
print(f"Dask LocalCluster, 1 worker:           {d1:7.2f} s")
print(f"Dask LocalCluster, 2 workers:          {d2:7.2f} s   {dask:.2f}x = {100 * dask / ceiling:.0f} % of the ceiling (aim >= 90 %)")
PY

# Overhead per task of about a second: Dask (1 worker, a chunk per task: the worst case, and
# chunks of 8) against the same tasks in one process.
job second 360 1 12
t0=$(now); "$skyspec" job run "$out/second.toml" --out "$out/second-here" --shard 1/1 --threads 1 --quiet; t1=$(now)
here_s=$(seconds "$t0" "$t1")
t0=$(now); "$skyspec" job run "$out/second.toml" --out "$out/second-dask" --workers 1 --quiet; t1=$(now)
dask_s=$(seconds "$t0" "$t1")
sed -i 's/tasks_per_chunk = 1$/tasks_per_chunk = 8/' "$out/second.toml"
t0=$(now); "$skyspec" job run "$out/second.toml" --out "$out/second-dask8" --workers 1 --quiet; t1=$(now)
dask8_s=$(seconds "$t0" "$t1")
/usr/bin/python3 - "$here_s" "$dask_s" "$dask8_s" <<'PY'
import sys
here, dask, dask8 = map(float, sys.argv[1:])
n = 24
print(f"\n## Engine overhead: {n} tasks of {here / n:.2f} s each (360 x 360, lean, one thread)")
print(f"one process:                           {here:7.2f} s")
print(f"Dask, 1 worker, a chunk per task:      {dask:7.2f} s   overhead {(dask - here) / n:.3f} s a task = {100 * (dask - here) / here:.1f} % (aim < 3 %)")
print(f"Dask, 1 worker, chunks of 8:           {dask8:7.2f} s   overhead {(dask8 - here) / n:.3f} s a task = {100 * (dask8 - here) / here:.1f} %")
PY

if [[ "$merge" != none ]]; then
  w=${merge%x*}; h=${merge#*x}; strip=$((h / 8))
  for k in $(seq 0 7); do
    "$skyspec" render --quality draft --camera equirectangular --width "$w" --height "$h" --set render.scattering_orders=1 \
      --pixel-bounds "0,$w,$((k * strip)),$(((k + 1) * strip))" --quiet --force --out "$out/strips/$k"
  done
  /usr/bin/time -f "%e %M" -o "$out/merge.time" "$skyspec" merge "$out"/strips/*/sky.exr --out "$out/merged.exr" --quiet
  read -r merge_s merge_kb <"$out/merge.time"
  bytes=$(stat -c %s "$out/merged.exr")
  echo
  echo "## Merge: ${w} x ${h} x 41 wavelengths from 8 strips (PIZ)"
  echo "merge: ${merge_s} s, peak RSS $((merge_kb / 1024)) MB, merged file $((bytes / 1000000)) MB"
  rm -rf "$out/strips" "$out/merged.exr"
fi
