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
for n in 8 24; do for chunk in 1 24; do job "o${n}_${chunk}" 660 "$chunk" $((n / 2)); done; done
"$skyspec" render --quality lean --width 8 --height 8 --quiet --no-png --out "$out/warm"  # tables into the cache
# timed NAME COMMAND...: runs it into a fresh folder and appends "NAME seconds" to $out/times.
timed() {
  local name=$1; shift
  rm -rf "$out/run"
  local t0; t0=$(now); "$@"; local t1; t1=$(now)
  echo "$name $(seconds "$t0" "$t1")" >>"$out/times"
}
# Each case runs $RUNS times (default 3), the cases interleaved, so that this VM's drift between
# minutes touches them alike; the report takes the medians.
for _ in $(seq "${RUNS:-3}"); do
  j=$out/throughput.toml
  timed one "$skyspec" job run "$j" --out "$out/run" --shard 1/1 --threads 1 --quiet
  timed two bash -c "'$skyspec' job run '$j' --out '$out/run' --shard 1/2 --threads 1 --quiet --no-collect &
                     '$skyspec' job run '$j' --out '$out/run' --shard 2/2 --threads 1 --quiet --no-collect & wait"
  timed dask1 "$skyspec" job run "$j" --out "$out/run" --workers 1 --quiet
  timed dask2 "$skyspec" job run "$j" --out "$out/run" --workers 2 --quiet
  # The engine's overhead for tasks of about a second (660 x 660, lean, one thread): jobs of 8 and
  # 24 tasks in one process and on a 1-worker LocalCluster, with chunks of 1 task and of 24.
  for n in 8 24; do
    timed "here_$n" "$skyspec" job run "$out/o${n}_1.toml" --out "$out/run" --shard 1/1 --threads 1 --quiet
    for chunk in 1 24; do
      timed "dask_${n}_${chunk}" "$skyspec" job run "$out/o${n}_${chunk}.toml" --out "$out/run" --workers 1 --quiet
    done
  done
done
/usr/bin/python3 - "$out/times" <<'PY'
import statistics, sys, collections
runs = collections.defaultdict(list)
for line in open(sys.argv[1]):
    name, t = line.split()
    runs[name].append(float(t))
m = {k: statistics.median(v) for k, v in runs.items()}
r = lambda k: f"{m[k]:6.2f} s (runs {', '.join(f'{x:.2f}' for x in runs[k])})"
ceiling, dask = m["one"] / m["two"], m["dask1"] / m["dask2"]
print(f"## Throughput: 200 tasks (64 x 64, lean, EXR), chunks of 10; medians of {len(runs['one'])} interleaved runs")
print(f"one process, one thread:           {r('one')}")
print(f"two one-thread processes at once:  {r('two')}   ceiling {ceiling:.2f}x")
print(f"Dask LocalCluster, 1 worker:       {r('dask1')}")
print(f"Dask LocalCluster, 2 workers:      {r('dask2')}   {dask:.2f}x = {100 * dask / ceiling:.0f} % of the ceiling (aim >= 90 %)")
task = (m["here_24"] - m["here_8"]) / 16
print(f"\n## Engine overhead for tasks of {task:.2f} s (660 x 660, lean, one thread; Dask: 1 worker)")
print(f"in one process: 8 tasks {r('here_8')}, 24 tasks {r('here_24')}")
for chunk, name in ((1, "a chunk per task"), (24, "chunks of 24")):
    d8, d24 = m[f"dask_8_{chunk}"], m[f"dask_24_{chunk}"]
    per = ((d24 - d8) - (m["here_24"] - m["here_8"])) / 16
    fixed = d8 - m["here_8"] - 8 * per
    print(f"Dask, {name}: 8 tasks {d8:.2f} s, 24 tasks {d24:.2f} s: per task {per:+.3f} s = {100 * per / task:+.1f} % "
          f"(aim < 3 %); fixed {fixed:.2f} s a job")
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
