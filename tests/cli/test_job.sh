#!/usr/bin/env bash
# skyspec job (issue 22): shards cover every task once; a Dask run (LocalCluster, 2 workers) gives
# the same bytes as the shards and as `skyspec render` of a task's scene; an interrupted job
# resumes with only the missing tasks; a worker killed with SIGKILL on a real `dask scheduler` +
# 2 `dask worker` cluster loses nothing; a task with bad input is recorded and the job goes on;
# a job file with an error is refused before any task runs, naming the key.
# Usage: test_job.sh path/to/skyspec   (the Dask parts need <dir of skyspec>/python/skyspec_jobs.py:
# the sanitizer build has no Python and runs the rest)
skyspec=$1
source "$(dirname "$0")/lib.sh"
python=${SKYSPEC_PYTHON:-/usr/bin/python3}
have_dask=0
jobs=$(dirname "$0")/../data/jobs  # small.toml: 12 tasks; mixed.toml: one task with bad input
cp "$jobs/small.toml" "$jobs/mixed.toml" "$work/"
[ -f "$(dirname "$skyspec")/python/skyspec_jobs.py" ] && have_dask=1

total=12

# digests DIR: "name sha256" of every task file and table, sorted (records hold timings: left out).
digests() { (cd "$1" && sha256sum tasks/*.exr tasks/*.png irradiance_*.csv irradiance_*.nc | sort -k2); }
no_temporaries() { ! find "$1" -name '*.tmp-*' | grep -q .; }
# wait_for_records DIR N: until DIR/tasks holds N task records (at most 30 s).
wait_for_records() {
  for _ in $(seq 600); do
    [ "$(ls "$1/tasks/"*.json 2>/dev/null | wc -l)" -ge "$2" ] && return
    sleep 0.05
  done
}

# --- a job file with an error: refused before any task runs, naming the key ---------------------
printf '[job]\nname = "bad"\n[axes]\n"atmosphere.mie.g" = [0.5, 1.2]\n' >"$work/bad.toml"
run_expecting_error "axis value out of range" 2 'axes.atmosphere.mie.g' "$work/bad-out" \
  "$skyspec" job run "$work/bad.toml" --out "$work/bad-out"
[ ! -e "$work/bad-out" ] && ok || bad "a refused job created its output folder"
printf '[job]\nname = "bad"\ntasks_per_chunck = 3\n' >"$work/bad2.toml"
run_expecting_error "unknown job key" 2 'job.tasks_per_chunck' "$work/bad-out" "$skyspec" job plan "$work/bad2.toml"
run_expecting_error "--workers with a shard" 2 '--workers' "$work/bad-out" "$skyspec" job run "$work/small.toml" --out "$work/bad-out" --shard 1/3 --workers 2
run_expecting_error "bad shard" 2 '--shard' "$work/bad-out" "$skyspec" job run "$work/small.toml" --out "$work/bad-out" --shard 4/3

# --- plan ----------------------------------------------------------------------------------------
"$skyspec" job plan "$work/small.toml" --out "$work/x" >"$work/plan.txt" 2>&1 || bad "job plan failed: $(cat "$work/plan.txt")"
grep -q "$total task(s)" "$work/plan.txt" && grep -q "estimate: outputs up to" "$work/plan.txt" && ok ||
  bad "job plan: $(cat "$work/plan.txt")"

# --- shards: every task exactly once, then collect -----------------------------------------------
ran=0
for i in 1 2 3; do
  out=$("$skyspec" job run "$work/small.toml" --out "$work/A" --shard $i/3 --threads 1) || bad "shard $i/3 failed"
  ran=$((ran + $(sed -n 's/.*: ran \([0-9]*\),.*/\1/p' <<<"$out")))
done
[ "$ran" = "$total" ] && ok || bad "the three shards ran $ran tasks, not $total"
[ "$(ls "$work/A/tasks/"*.json | wc -l)" = "$total" ] && ok || bad "shards: $(ls "$work/A/tasks" | wc -l) files"
"$skyspec" job collect "$work/small.toml" --out "$work/A" --quiet || bad "collect after the shards failed"
[ "$(grep -c '"status":"ok"' "$work/A/manifest.jsonl")" = "$total" ] && ok || bad "manifest: $(head -c 300 "$work/A/manifest.jsonl")"
[ "$(wc -l <"$work/A/irradiance_nairobi.csv")" = 7 ] && ok || bad "irradiance_nairobi.csv has $(wc -l <"$work/A/irradiance_nairobi.csv") lines"
# The NetCDF table: CF attributes, the CSV's values, UTC times (netCDF4, as xarray reads it).
"$python" - "$work/A" <<'PY' && ok || bad "irradiance_nairobi.nc does not match its CSV"
import csv, sys, netCDF4
ds = netCDF4.Dataset(sys.argv[1] + "/irradiance_nairobi.nc")
rows = list(csv.DictReader(open(sys.argv[1] + "/irradiance_nairobi.csv")))
assert ds.Conventions == "CF-1.8" and ds.featureType == "timeSeries"
assert ds["time"].units == "seconds since 1970-01-01 00:00:00 UTC"
t = netCDF4.num2date(ds["time"][:], ds["time"].units)
assert str(t[0]) == "2026-03-20 08:00:00", t[0]  # 09:00+01:00
assert len(rows) == 6 and ds.dimensions["sample"].size == 6 and ds.dimensions["wavelength"].size == 41
for k, r in enumerate(rows):
    assert abs(ds["diffuse_horizontal_irradiance"][k] - float(r["diffuse_horizontal_W_m2"])) <= 1e-7 * float(r["diffuse_horizontal_W_m2"])
    assert abs(ds["spectral_global_horizontal_irradiance"][k, 17] - float(r["global_horizontal_W_m2_nm_550"])) <= 1e-7 * float(r["global_horizontal_W_m2_nm_550"])
    assert ds["atmosphere_mie_scattering_per_m"][k] == float(r["atmosphere.mie.scattering_per_m"])
    g = float(r["global_horizontal_W_m2"])
    assert abs(g - float(r["direct_horizontal_W_m2"]) - float(r["diffuse_horizontal_W_m2"])) <= 1e-6 * g, r
    assert abs(ds["global_horizontal_irradiance"][k] - g) <= 1e-7 * g
    assert (float(r["band_min_nm"]), float(r["band_max_nm"])) == (380, 780), r
assert abs(ds["lat"][...] + 1.29) < 1e-12 and abs(ds["altitude"][...] - 1796) < 1e-9
# A swept key: CF's variable-name characters, the key and a UDUNITS unit in attributes (issue 41).
swept = ds["atmosphere_mie_scattering_per_m"]
assert swept.skyspec_scene_key == "atmosphere.mie.scattering_per_m" and swept.units == "m-1", swept
# The station's name reads as text (not bytes) where netCDF4 and xarray decode it.
name = ds["station_name"][...]
assert isinstance(name, str) or getattr(name, "dtype", None) is not None and name.dtype.kind == "U", repr(name)
assert str(name) == "nairobi", repr(name)
# The band-limited irradiance says so, and claims no CF "shortwave" standard name (the whole solar
# spectrum); the band is a global attribute.
assert ds.skyspec_band_nm == "380 780"
for v in ("direct_normal_irradiance", "direct_horizontal_irradiance", "diffuse_horizontal_irradiance",
          "global_horizontal_irradiance"):
    assert "380-780 nm only" in ds[v].comment and "standard_name" not in ds[v].ncattrs(), v
PY
# Run again: nothing left to do.
out=$("$skyspec" job run "$work/small.toml" --out "$work/A" --shard 1/1 --threads 1)
grep -q "ran 0, $total already done" <<<"$out" && ok || bad "a finished job ran again: $out"
# A damaged output is found by its checksum and that task alone runs again.
printf 'x' >>"$work/A/tasks/t000005.png"
out=$("$skyspec" job run "$work/small.toml" --out "$work/A" --shard 1/1 --threads 1)
grep -q "ran 1, $((total - 1)) already done" <<<"$out" && ok || bad "a damaged file: $out"
digests "$work/A" >"$work/A.sha"

# --- a task with bad input (a combination the job's own checks cannot see) is recorded -----------
"$skyspec" job run "$work/mixed.toml" --out "$work/M" --shard 1/1 >"$work/stdout" 2>"$work/stderr"
rc=$?
[ "$rc" = 4 ] && ok || bad "a job with a failed task: exit $rc, expected 4"
grep -q "t000002 failed: .*atmosphere.ozone.peak_m" "$work/stderr" && grep -q "3 task(s) done, 1 failed" "$work/stdout" && ok ||
  bad "failed task report: $(cat "$work/stdout" "$work/stderr")"
grep '"id":"t000002"' "$work/M/manifest.jsonl" | grep '"status":"failed"' | grep -q 'bottom_m < peak_m' && ok ||
  bad "the manifest lacks the failure: $(cat "$work/M/manifest.jsonl")"

# --- a time-lapse in frame ranges (a farm's shares): the same files as in one run -----------------
tl=(--latitude 48 --longitude 11 --start 2026-06-21T05:00:00+02:00 --end 2026-06-21T08:00:00+02:00 --step-minutes 60
    --width 24 --height 24 --quality draft --quiet)
"$skyspec" timelapse "${tl[@]}" --out "$work/TL" && "$skyspec" timelapse "${tl[@]}" --out "$work/TL-parts" --frames 0-1 &&
  "$skyspec" timelapse "${tl[@]}" --out "$work/TL-parts" --frames 2-3 || bad "time-lapse frame ranges failed"
# The images, byte for byte (the records hold each run's timing and host; the shares' manifest is
# the last share's view, with the other share's frames listed as it found them).
same=1
for f in "$work"/TL/sky_*.exr "$work"/TL/sky_*.png; do cmp -s "$f" "$work/TL-parts/$(basename "$f")" || same=0; done
[ "$same" = 1 ] && [ "$(ls "$work/TL-parts" | grep -c '^sky_000[0-3]\.\(exr\|png\)$')" = 8 ] && ok ||
  bad "time-lapse shares differ from one run"
grep -c '"status":"ok"' "$work/TL-parts/manifest.jsonl" | grep -qx 4 && ok || bad "the shares' manifest: $(cat "$work/TL-parts/manifest.jsonl")"
run_expecting_error "frames beyond the sequence" 2 "--frames" "$work/TL-none" "$skyspec" timelapse "${tl[@]}" --out "$work/TL-none" --frames 3-4

# --- a tiled job: each frame in strips, merged by collect into the bytes of the frame's render ---
cp "$jobs/tiled.toml" "$work/"
"$skyspec" job run "$work/tiled.toml" --out "$work/T" --shard 1/2 --quiet && "$skyspec" job run "$work/tiled.toml" --out "$work/T" --shard 2/2 --quiet ||
  bad "tiled job shards failed"
out=$("$skyspec" job collect "$work/tiled.toml" --out "$work/T")
grep -q "frames: 2 merged" <<<"$out" && ok || bad "tiled job collect: $out"
"$skyspec" job plan "$work/tiled.toml" --out "$work/T" --print-scene 3 >"$work/tiled3.toml"
"$skyspec" render --scene "$work/tiled3.toml" --no-png --quiet --out "$work/T-render" --name whole
cmp -s "$work/T-render/whole.exr" "$work/T/frames/f000001.exr" && ok || bad "a merged frame differs from its render"
out=$("$skyspec" job collect "$work/tiled.toml" --out "$work/T")
grep -q "frames: 0 merged, 2 already merged" <<<"$out" && ok || bad "collect merged again: $out"

if [ "$have_dask" = 1 ]; then
  # --- Dask, LocalCluster with 2 workers: the same bytes as the shards --------------------------
  mv "$work/A" "$work/A-shards"
  "$skyspec" job run "$work/small.toml" --out "$work/A" --workers 2 --quiet >"$work/stdout" 2>"$work/stderr" ||
    bad "job run on a LocalCluster failed: $(tail -5 "$work/stderr")"
  digests "$work/A" | diff - "$work/A.sha" >/dev/null && ok || bad "Dask and the shards wrote different files"
  [ "$(grep -c '"status":"ok"' "$work/A/manifest.jsonl")" = "$total" ] && ok || bad "Dask manifest incomplete"
  # ... and as `skyspec render` of the task's scene.
  "$skyspec" job plan "$work/small.toml" --out "$work/A" --print-scene 7 >"$work/t7.toml"
  mv "$work/A/tasks/t000007.exr" "$work/t7-job.exr"
  "$skyspec" render --scene "$work/t7.toml" --quiet >/dev/null 2>&1 || bad "render of task 7's scene failed"
  cmp -s "$work/A/tasks/t000007.exr" "$work/t7-job.exr" && ok || bad "render --scene of task 7 differs from the job's file"

  # --- resume: SIGINT mid-job, then only the missing tasks run (from Python: skyspec.run_job) -----
  sed -e 's/camera.width = 24/camera.width = 160/' -e 's/camera.height = 24/camera.height = 160/' \
      -e 's/tasks_per_chunk = 2/tasks_per_chunk = 1/' -e 's/step_minutes = 180/step_minutes = 60/' \
      "$work/small.toml" >"$work/resume.toml"  # 28 tasks
  "$skyspec" job run "$work/resume.toml" --out "$work/R" --workers 2 --quiet >/dev/null 2>"$work/resume-stderr" &
  pid=$!
  wait_for_records "$work/R" 3
  kill -INT $pid
  wait $pid
  rc=$?
  done_before=$(ls "$work/R/tasks/"*.json 2>/dev/null | wc -l)
  [ "$rc" = 130 ] && ok || bad "interrupted job: exit $rc, expected 130: $(tail -3 "$work/resume-stderr")"
  [ "$done_before" -ge 3 ] && [ "$done_before" -lt 28 ] && ok || bad "interrupted after $done_before of 28 tasks"
  sleep 0.5  # the children stop on SIGTERM when their worker ends
  no_temporaries "$work/R" && ok || bad "the interrupted job left temporary files: $(find "$work/R" -name '*.tmp-*')"
  (cd "$work/R/tasks" && stat -c '%n %i %Y' *.json >"$work/before.txt")
  PYTHONPATH="$(dirname "$skyspec")/python" SKYSPEC_CLI="$skyspec" "$python" -c "
import skyspec, sys
s = skyspec.run_job(sys.argv[1], out=sys.argv[2], workers=2, quiet=True)
assert s['ok'] == 28 and s['failed'] == 0 and s['missing'] == 0, s
" "$work/resume.toml" "$work/R" 2>"$work/py-stderr" || bad "skyspec.run_job (resume) failed: $(tail -5 "$work/py-stderr")"
  (cd "$work/R/tasks" && stat -c '%n %i %Y' $(cut -d' ' -f1 "$work/before.txt")) | diff - "$work/before.txt" >/dev/null &&
    ok || bad "the resumed job rewrote tasks that were done"
  [ "$(ls "$work/R/tasks/"*.json | wc -l)" = 28 ] && ok || bad "after resume: $(ls "$work/R/tasks/"*.json | wc -l) records"

  # --- a real scheduler and two workers; one worker SIGKILLed mid-job -----------------------------
  dask scheduler --scheduler-file "$work/sched.json" --port 0 --no-dashboard >"$work/sched.log" 2>&1 &
  sched=$!
  for _ in $(seq 200); do [ -s "$work/sched.json" ] && break; sleep 0.05; done
  dask worker --scheduler-file "$work/sched.json" --nthreads 1 --no-dashboard >"$work/w1.log" 2>&1 &
  w1=$!
  dask worker --scheduler-file "$work/sched.json" --nthreads 1 --no-dashboard >"$work/w2.log" 2>&1 &
  w2=$!
  address=$("$python" -c "import json,sys; print(json.load(open(sys.argv[1]))['address'])" "$work/sched.json")
  "$skyspec" job run "$work/resume.toml" --out "$work/K" --scheduler "$address" --quiet >/dev/null 2>"$work/kill-stderr" &
  job=$!
  wait_for_records "$work/K" 4
  kill -KILL $w1
  wait $w1 2>/dev/null
  wait $job
  rc=$?
  [ "$rc" = 0 ] && ok || bad "job with a killed worker: exit $rc: $(tail -5 "$work/kill-stderr")"
  [ "$(grep -c '"status":"ok"' "$work/K/manifest.jsonl" 2>/dev/null)" = 28 ] && ok || bad "killed worker: manifest incomplete"
  sleep 0.5
  no_temporaries "$work/K" && ok || bad "a killed worker left temporary files"
  kill $w2 $sched 2>/dev/null
  wait $w2 $sched 2>/dev/null
else
  echo "(Dask parts skipped: no $(dirname "$skyspec")/python/skyspec_jobs.py in this build)"
fi

# --- the broadband irradiance in a job's table (release stage: five runs of the transport per task)
if [ -z "${SKYSPEC_SANITIZER_STAGE:-}" ]; then
  printf '[job]\nname = "bb"\nproduce = ["irradiance"]\n[scene]\nrender.scattering_orders = 1\nrender.cache_tables = false\n' >"$work/bb.toml"
  printf 'irradiance.broadband = true\nsun.elevation_deg = 40\n' >>"$work/bb.toml"
  "$skyspec" job run "$work/bb.toml" --out "$work/BB" --shard 1/1 --quiet >/dev/null 2>"$work/stderr" &&
    "$skyspec" job collect "$work/bb.toml" --out "$work/BB" --quiet || bad "broadband job failed: $(cat "$work/stderr")"
  "$python" - "$work/BB" <<'PY' && ok || bad "the broadband irradiance is not in the job's tables as documented"
import csv, sys, netCDF4
rows = list(csv.DictReader(open(sys.argv[1] + "/irradiance_scene.csv")))
ds = netCDF4.Dataset(sys.argv[1] + "/irradiance_scene.nc")
assert len(rows) == 1
for k, r in enumerate(rows):
    bb, band = float(r["broadband_global_horizontal_W_m2"]), float(r["global_horizontal_W_m2"])
    assert bb > band > 0, r  # 300-4000 nm holds 380-780 nm
    assert abs(bb - float(r["broadband_direct_horizontal_W_m2"]) - float(r["broadband_diffuse_horizontal_W_m2"])) <= 1e-6 * bb
    assert abs(ds["broadband_global_horizontal_irradiance"][k] - bb) <= 1e-7 * bb
# CF standard names where the quantity is CF's (the whole solar spectrum but its ends), and the band.
v = ds["broadband_global_horizontal_irradiance"]
assert v.standard_name == "surface_downwelling_shortwave_flux_in_air" and "300-4000 nm" in v.comment, v
assert ds["broadband_diffuse_horizontal_irradiance"].standard_name == "surface_diffuse_downwelling_shortwave_flux_in_air"
assert "standard_name" not in ds["broadband_direct_normal_irradiance"].ncattrs()
PY
fi
finish cli_job
