#!/usr/bin/env bash
# skyspec benchmark against the seed tutorial's baseline program (the performance issue).
# Not a unit test: it takes several minutes. Usage (from the repository root):
#
#   bench/run_benchmarks.sh [--skyspec PATH] [--baseline SEED.cpp] [--out DIR]
#
# --skyspec   the skyspec binary (default: build-bench/skyspec, else build/skyspec)
# --baseline  the baseline source (default: ../shared/bench/seed_nishita.cpp); built with
#             g++ -O3 -march=native -std=c++17. When it does not exist the ratio columns are skipped.
# --out       working folder for renders and logs (default: /tmp/skyspec-bench)
#
# DATASET=0 leaves out the dataset of 200 skies (bench/dataset_skies.sh, about 10 minutes more).
#
# Times are process wall-clock times (bash's EPOCHREALTIME around the command, to the millisecond;
# peak memory is GNU time's maximum resident set size, /usr/bin/time -f %M), including start-up
# and writing the output (skyspec: the spectral EXR, no PNG; baseline: its PFM). The baseline and
# cases 1-4 run $RUNS times (default 5; this VM's timings vary 10-30 % from run to run) and the
# table shows the median with the range; each run writes a new file. Errors are computed
# by bench/bench_stats.py (/usr/bin/python3, numpy, OpenImageIO) against a reference render of
# the same scene and resolution (REF below).
set -euo pipefail
export LC_ALL=C  # EPOCHREALTIME with a decimal point
here="$(cd "$(dirname "$0")" && pwd)"; root="$(dirname "$here")"
skyspec=""; baseline_src="$(cd "$root/.." && pwd)/shared/bench/seed_nishita.cpp"; out=/tmp/skyspec-bench
while [[ $# -gt 0 ]]; do
  case "$1" in
    --skyspec) skyspec="$2"; shift 2 ;;
    --baseline) baseline_src="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    -h|--help) sed -n 2,17p "$0"; exit 0 ;;
    *) echo "run_benchmarks.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
if [[ -z "$skyspec" ]]; then
  if [[ -x "$root/build-bench/skyspec" ]]; then skyspec="$root/build-bench/skyspec"; else skyspec="$root/build/skyspec"; fi
fi
[[ -x "$skyspec" ]] || { echo "run_benchmarks.sh: no skyspec binary at $skyspec (build it first)" >&2; exit 2; }
[[ -x /usr/bin/time ]] || { echo "run_benchmarks.sh: needs GNU time (apt-get install time)" >&2; exit 2; }
mkdir -p "$out"; out="$(cd "$out" && pwd)"; manifest="$out/manifest.tsv"; : > "$manifest"
# Every render writes a new file: outputs of an earlier run are removed first (replacing a file
# adds the unlinking of the old one, about 0.02 s for 25 MB here, to the timing).
rm -f "$out"/*.exr "$out"/*.pfm "$out"/*.png
scene="$here/seed-spectral.toml"
# The converged reference: every pixel marched (no sky-view table) with 256 view segments and a
# 1024 x 2048 sun table; the run checks it against 512 segments (last line of the report).
REF=(--view-segments 256 --set render.table_altitude_samples=1024 --set render.table_zenith_samples=2048
     --set render.sky_view_table=false)
# The table cache lives in the output folder, emptied first, so that the multiple-scattering case
# measures a cold build and then a warm one.
export SKYSPEC_CACHE_DIR="$out/cache"; rm -rf "$SKYSPEC_CACHE_DIR"
echo "skyspec benchmark, $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "skyspec: $skyspec"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"

baseline=""
if [[ -f "$baseline_src" ]]; then
  baseline="$out/seed_nishita"
  g++ -O3 -march=native -std=c++17 "$baseline_src" -o "$baseline"
  echo "baseline: $baseline_src, built with g++ -O3 -march=native -std=c++17"
else
  echo "baseline: $baseline_src does not exist; the ratio and baseline columns are skipped"
fi

# run_once NAME CMD...: runs CMD once and appends a line "wall_s rss_kB" to $out/NAME.time and
# skyspec's "rendered ..." line (its own split of the time) to $out/NAME.stages. The outputs of the
# previous run are removed first (NAME.exr, NAME.png, NAME.*.exr and .png, the baseline's
# seed.pfm). The log is the last run's.
run_once() {
  local name="$1"; shift
  local t0 t1
  rm -f "$out/$name.exr" "$out/$name.png" "$out/$name".*.exr "$out/$name".*.png "$out/seed.pfm"
  t0=$EPOCHREALTIME
  /usr/bin/time -f '%M' -o "$out/$name.rss" "$@" > "$out/$name.log" 2>&1
  t1=$EPOCHREALTIME
  echo "$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.4f", b - a }') $(tail -n 1 "$out/$name.rss")" >> "$out/$name.time"
  grep '^rendered ' "$out/$name.log" >> "$out/$name.stages" || true
  rm -f "$out/$name.rss"
}
# timed NAME CMD...: run_once ${N:-1} times, the case's earlier runs forgotten.
timed() {
  local name="$1"; shift
  : > "$out/$name.time"; : > "$out/$name.stages"
  local i
  for ((i = 0; i < ${N:-1}; i++)); do run_once "$name" "$@"; done
}
# The cases whose times are compared with each other (a case and the baseline, one and two
# threads) run interleaved, run i of each before run i + 1 of any, so that the slow drifts of
# this VM's speed (a third within minutes) fall on all of them alike:
#   declare_case NAME CMD... declares a case (its command is kept in the array cmd_NAME);
#   interleave NAME... runs the declared cases RUNS times in turn.
declare_case() {
  local name="$1"; shift
  local var="cmd_${name//-/_}"
  eval "$var=(\"\$@\")"
}
interleave() {
  local name i
  for name in "$@"; do : > "$out/$name.time"; : > "$out/$name.stages"; done
  for ((i = 0; i < RUNS; i++)); do
    for name in "$@"; do
      local -n cmd="cmd_${name//-/_}"
      if [[ "$name" == base-* ]]; then
        ( cd "$out" && run_once "$name" "${cmd[@]}" && mv seed.pfm "$name.pfm" )
      else
        run_once "$name" "${cmd[@]}"
      fi
      unset -n cmd
    done
  done
}
RUNS="${RUNS:-5}"
# skyspec_cmd NAME SUN [ARGS...]: the command line of a skyspec render into $out/NAME.exr. Not
# -q: the log keeps the "rendered ... (tables, image, completing the files)" line (no progress
# bar: the output is not a terminal).
skyspec_cmd() {
  local name="$1" sun="$2"; shift 2
  local png=(--no-png); [[ "${WITH_PNG:-0}" == 1 ]] && png=()
  cmd_line=("$skyspec" render "${png[@]}" --out "$out" --name "$name" --sun-elevation "$sun" "$@")
}
# row KIND NAME LABEL SUN: a row of the table. Kinds: main (with the error against the reference
# $out/ref-NAME.exr), time (no error), base (the baseline).
row() { printf '%s\t%s\t%s\t%s\n' "$1" "$2" "$3" "$4" >> "$manifest"; }
# sky KIND NAME LABEL SUN [ARGS...]: a render timed once, and its row.
sky() {
  local kind="$1" name="$2" label="$3" sun="$4"; shift 4
  skyspec_cmd "$name" "$sun" "$@"
  timed "$name" "${cmd_line[@]}"
  row "$kind" "$name" "$label" "$sun"
}
# later KIND NAME LABEL SUN [ARGS...]: a render declared (and its row written) to run interleaved.
later() {
  local kind="$1" name="$2" label="$3" sun="$4"; shift 4
  skyspec_cmd "$name" "$sun" "$@"
  declare_case "$name" "${cmd_line[@]}"
  row "$kind" "$name" "$label" "$sun"
}
ref() {  # ref NAME SUN ARGS...: the converged reference (not timed in the table)
  local name="$1" sun="$2"; shift 2
  timed "ref-$name" "$skyspec" render -q --no-png --out "$out" --name "ref-$name" --sun-elevation "$sun" "$@" "${REF[@]}"
}

NONE=(--set output.exr_compression=none)
# The codec alone (bench/exr_codecs.cpp; --same: a render's own pixels written again with PIZ on 2
# threads by both OpenEXR libraries, only the writing timed), for issue 37's target 6.
g++ -O2 -std=c++17 "$here/exr_codecs.cpp" -o "$out/exr_codecs" $(pkg-config --cflags --libs OpenEXR) -lpthread
for sun in 30 10 2; do
  echo "sun $sun: case 1 (spectral, 41 wavelengths), case 2 (seed preset, RGB-fast)${baseline:+ and the baseline}, interleaved ..."
  names=()
  if [[ -n "$baseline" ]]; then
    declare_case "base-$sun" "$baseline" "$sun"
    row base "base-$sun" "baseline (RGB 3 wl, 16/8 samples, 1 thread)" "$sun"
    names+=("base-$sun")
  fi
  later main "c1-$sun" "1: spectral 41 wl, 512 fisheye, 2 threads, EXR (PIZ)" "$sun" --scene "$scene"
  later main "c1n-$sun" "1: the same, EXR uncompressed" "$sun" --scene "$scene" "${NONE[@]}"
  later main "c2-$sun" "2: seed preset RGB-fast, 512 fisheye, 2 threads, EXR (PIZ)" "$sun" --preset seed
  later main "c2n-$sun" "2: the same, EXR uncompressed" "$sun" --preset seed "${NONE[@]}"
  # The same two at --quality lean (the default's march, coarser tables: data/quality/lean.toml).
  later main "c1ln-$sun" "1: the same at --quality lean, EXR uncompressed" "$sun" --scene "$scene" --quality lean "${NONE[@]}"
  later main "c2ln-$sun" "2: the same at --quality lean, EXR uncompressed" "$sun" --preset seed --quality lean "${NONE[@]}"
  interleave "${names[@]}" "c1-$sun" "c1n-$sun" "c2-$sun" "c2n-$sun" "c1ln-$sun" "c2ln-$sun"
  if [[ "$sun" == 30 ]]; then  # case 1's last file written again by the codec alone, RUNS times
    : > "$out/c1-codec.tsv"
    for ((i = 0; i < RUNS; i++)); do "$out/exr_codecs" --same "$out/c1-30.exr" "$out" 2 >> "$out/c1-codec.tsv"; done
  fi
  if [[ -n "$baseline" ]]; then
    ref "base511-$sun" "$sun" --preset seed --width 511 --height 511   # the baseline's directions
  fi
  ref "c1-$sun" "$sun" --scene "$scene"
  cp "$out/ref-c1-$sun.exr" "$out/ref-c1n-$sun.exr"
  ref "c2-$sun" "$sun" --preset seed
  cp "$out/ref-c2-$sun.exr" "$out/ref-c2n-$sun.exr"
  cp "$out/ref-c1-$sun.exr" "$out/ref-c1ln-$sun.exr"
  cp "$out/ref-c2-$sun.exr" "$out/ref-c2ln-$sun.exr"
done
echo "case 3 (threads, interleaved) ..."
later time "c3-1t" "3: case 1, 1 thread" 30 --scene "$scene" --threads 1
later time "c3-2t" "3: case 1, 2 threads" 30 --scene "$scene" --threads 2
later time "c3n-1t" "3: case 1 uncompressed, 1 thread" 30 --scene "$scene" --threads 1 "${NONE[@]}"
later time "c3n-2t" "3: case 1 uncompressed, 2 threads" 30 --scene "$scene" --threads 2 "${NONE[@]}"
# What two cores give this work at best: two case-1 renders on one thread each at the same time
# (outputs c3x-1t.a.exr and .b.exr), no sharing between them. 2 x (one alone) / (both at once) is
# the speed-up two independent renders get (a loop of pure arithmetic got 2.00x on this VM).
skyspec_cmd "c3x-1t.a" 30 --scene "$scene" --threads 1; pair_a=("${cmd_line[@]}")
skyspec_cmd "c3x-1t.b" 30 --scene "$scene" --threads 1; pair_b=("${cmd_line[@]}")
declare_case "c3x-1t" bash -c 'n=$(( $# / 2 )); "${@:1:n}" & a=$!; "${@:n+1}"; b=$?; wait "$a" && exit "$b"' _ \
  "${pair_a[@]}" "${pair_b[@]}"
row time "c3x-1t" "ceiling: two case-1 renders on 1 thread each, at once" 30
interleave c3-1t c3-2t c3n-1t c3n-2t c3x-1t
echo "case 4 (equirectangular upper hemisphere, interleaved) ..."
HEMI=(--camera equirectangular --width 512 --height 256 --set camera.min_elevation_deg=0)
later main "c4-10" "4: spectral 41 wl, 512x256 equirect upper hemisphere, 2 threads, EXR (PIZ)" 10 --scene "$scene" "${HEMI[@]}"
later main "c4n-10" "4: the same, EXR uncompressed" 10 --scene "$scene" "${HEMI[@]}" "${NONE[@]}"
later main "c4n1-10" "4: the same, EXR uncompressed, 1 thread" 10 --scene "$scene" "${HEMI[@]}" "${NONE[@]}" --threads 1
interleave c4-10 c4n-10 c4n1-10
ref "c4-10" 10 --scene "$scene" "${HEMI[@]}"
cp "$out/ref-c4-10.exr" "$out/ref-c4n-10.exr"
cp "$out/ref-c4-10.exr" "$out/ref-c4n1-10.exr"
echo "case 5 (large EXR) ..."
# Twice, each render followed by the codec alone on its file (a minute and a half each: the file,
# 3.9 GB, is read back and written twice more), so that the VM's drifts fall on both alike.
skyspec_cmd "c5-10" 10 --scene "$scene" --camera equirectangular --width 8192 --height 4096 --lambda-step 5
: > "$out/c5-10.time"; : > "$out/c5-10.stages"; : > "$out/c5-codec.tsv"
for ((i = 0; i < 2; i++)); do
  run_once "c5-10" "${cmd_line[@]}"
  "$out/exr_codecs" --same "$out/c5-10.exr" "$out" 2 >> "$out/c5-codec.tsv"
done
row time "c5-10" "5: spectral 81 wl, 8192x4096 equirect EXR" 10
rm -f "$out/c5-10.exr"
# What OpenEXR's lossless codecs can do with case 5's pixels: its scene and view at 1024 x 512 (a
# 64th of the pixels), uncompressed, then written again with each codec on 1 and 2 threads
# (bench/exr_codecs.cpp, the fastest of 2 writes each, into /dev/shm so the disk does not count).
echo "codecs (case 5's panorama at 1024 x 512, each lossless codec) ..."
"$skyspec" render -q --no-png --out "$out" --name "codec-sample" --sun-elevation 10 --scene "$scene" \
  --camera equirectangular --width 1024 --height 512 --lambda-step 5 --set output.exr_compression=none
"$out/exr_codecs" "$out/codec-sample.exr" /dev/shm 2 > "$out/codecs.tsv"
rm -f "$out/codec-sample.exr"
echo "case 6 (multiple scattering tables, cold then cached) ..."
sky time "c6-cold" "6: default scene (6 orders), tables built" 30 --width 256 --height 256
sky time "c6-warm" "6: the same, tables from the disk cache" 30 --width 256 --height 256
sky time "c6-single" "6: the same, single scattering (no tables)" 30 --width 256 --height 256 --set render.scattering_orders=1
# Issue 37's target 3: the default scene at 512 x 512, first with no cached tables (the cache
# emptied), then five times with them cached.
rm -rf "$SKYSPEC_CACHE_DIR"
sky time "c37-cold" "37: default scene 512x512 (6 orders), tables built" 30 --width 512 --height 512
N=5 sky time "c37-warm" "37: the same, tables from the disk cache" 30 --width 512 --height 512
# Issue 21's target 6 with multiple scattering: case 4's view of the default scene (tables cached).
sky time "c6-hemi" "6: default scene, 512x256 equirect upper hemisphere, tables cached, EXR (PIZ)" 10 "${HEMI[@]}"
# The default scene's accuracy at the default quality (ozone, sun disk, 6 orders; the reference
# shares its multiple-scattering tables, so this is the error of the march and the tables of
# the render itself).
sky main "c6e-2" "6: default scene 256x256 (6 orders), error at sun 2" 2 --width 256 --height 256
ref "c6e-2" 2 --width 256 --height 256

echo "scaling (case 1 scene, sun 30, 2 threads) ..."
sky time "s-256" "scale: 256x256" 30 --scene "$scene" --width 256 --height 256
sky time "s-1024" "scale: 1024x1024" 30 --scene "$scene" --width 1024 --height 1024
sky time "s-2048" "scale: 2048x2048" 30 --scene "$scene" --width 2048 --height 2048
sky time "s-wl3" "scale: 3 wl (440/550/680, spectral)" 30 --scene "$scene" --wavelengths 440,550,680
sky time "s-wl81" "scale: 81 wl" 30 --scene "$scene" --lambda-step 5
sky time "s-wl401" "scale: 401 wl" 30 --scene "$scene" --lambda-step 1
sky time "s-vs16" "scale: 16 view segments" 30 --scene "$scene" --view-segments 16
sky time "s-vs256" "scale: 256 view segments" 30 --scene "$scene" --view-segments 256
sky time "s-sv256" "scale: sky-view table 256 x 128" 30 --scene "$scene" --set render.sky_view_zenith_samples=256 --set render.sky_view_azimuth_samples=128
sky time "s-nosv" "scale: no sky-view table (every pixel marched)" 30 --scene "$scene" --set render.sky_view_table=false
WITH_PNG=1 sky time "s-noexr" "scale: PNG instead of EXR" 30 --scene "$scene" --no-exr

echo "reference check (sun 2: 512 instead of 256 view segments) ..."
timed "ref2-c1-2" "$skyspec" render -q --no-png --out "$out" --name "ref2-c1-2" --sun-elevation 2 --scene "$scene" \
  "${REF[@]}" --view-segments 512
printf 'refcheck\tref2-c1-2\treference check\t2\n' >> "$manifest"

echo "dataset (issue 37's target 4: 200 random atmospheres as a job on 2 workers; bench/dataset_skies.sh) ..."
if [[ "${DATASET:-1}" != 0 ]]; then
  "$here/dataset_skies.sh" --skyspec "$skyspec" --out "$out/dataset" > "$out/dataset.txt"
  grid=(--interpolated-cache "$out/dataset/cache-interpolated")
else
  echo "(skipped: DATASET=0)" > "$out/dataset.txt"; grid=()
fi

echo "viewer (skyspec view over HTTP: frames with the sun moved, the atmosphere changed) ..."
/usr/bin/python3 "$here/viewer_frames.py" "$skyspec" "${grid[@]}" > "$out/viewer.txt"

echo "docs figures (bench/docs_figures.sh: figures of docs/ too slow for the test command) ..."
"$here/docs_figures.sh" "$skyspec" > "$out/docs_figures.txt" || true

echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
/usr/bin/python3 "$here/bench_stats.py" "$out"
echo
cat "$out/dataset.txt"
echo
cat "$out/viewer.txt"
echo
cat "$out/docs_figures.txt"
