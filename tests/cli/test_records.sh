#!/usr/bin/env bash
# Records that lie (issue 42, items 3, 9, 17): task records are untrusted input. Each attack as the
# issue wrote it, on a finished 12-task job: `job collect` must name the damaged record, not crash
# or write a table from it, leave no temporary file and exit 4; `job run` must render the task again.
# Usage: test_records.sh SKYSPEC
set -u
skyspec=$1
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
export SKYSPEC_CACHE_DIR="$work/cache"
python=${SKYSPEC_PYTHON:-/usr/bin/python3}
cp "$(dirname "${BASH_SOURCE[0]}")/../data/jobs/small.toml" "$work/"
job=("$work/small.toml" --out "$work/J")
"$skyspec" job run "${job[@]}" --tasks 0-11 --threads 2 >/dev/null 2>"$work/stderr" || bad "the job did not run: $(cat "$work/stderr")"
[ "$(ls "$work/J/tasks/"*.json | wc -l)" = 12 ] && ok || bad "the job left $(ls "$work/J/tasks/" | wc -l) files"
cp -a "$work/J/tasks" "$work/pristine"
restore() { rm -rf "$work/J/tasks" && cp -a "$work/pristine" "$work/J/tasks"; }

# tamper TASK PYTHON-STATEMENT: edits the record r of task TASK (t000003.json) in place.
tamper() {
  "$python" - "$work/J/tasks/$1.json" "$2" <<'PY'
import json, sys
path, code = sys.argv[1], sys.argv[2]
r = json.load(open(path))
exec(code)
open(path, "w").write(json.dumps(r) + "\n")
PY
}

# collect_refuses NAME TEXT: collect names the record's problem, exits 4, leaves no temporary.
collect_refuses() {
  "$skyspec" job collect "${job[@]}" --quiet >"$work/stdout" 2>"$work/stderr"
  local rc=$?
  [ "$rc" = 4 ] && ok || bad "$1: collect exit $rc, expected 4: $(tail -3 "$work/stderr")"
  grep -qF -- "$2" "$work/stderr" "$work/J/manifest.jsonl" && ok || bad "$1: collect does not say '$2': $(tail -3 "$work/stderr")"
  ! find "$work/J" -name '*.tmp-*' | grep -q . && ok || bad "$1: temporaries left: $(find "$work/J" -name '*.tmp-*')"
}

# 3. Array lengths: a wavelengths list of 3e6 entries (SIGSEGV, 312 MB .nc.tmp), one value short.
tamper t000003 'r["irradiance"]["wavelengths_nm"] = list(range(3000000))'
collect_refuses long_wavelengths "t000003: its record is damaged: its irradiance has 3000000 wavelengths"
[ "$(du -sm "$work/J" | cut -f1)" -lt 100 ] && ok || bad "long_wavelengths: the job folder grew to $(du -sh "$work/J")"
restore
tamper t000004 'r["irradiance"]["diffuse_horizontal_W_m2_nm"].pop()'
collect_refuses one_short 'its "diffuse_horizontal_W_m2_nm" has 40 values for 41 wavelengths'
restore

# 9. Records trusted without their files: a deleted EXR; "files": []; a path outside the job.
rm "$work/J/tasks/t000005.exr"
collect_refuses deleted_exr "t000005: its file tasks/t000005.exr is missing"
"$skyspec" job run "${job[@]}" --tasks 0-11 >"$work/stdout" 2>&1 && grep -q "ran 1," "$work/stdout" && [ -s "$work/J/tasks/t000005.exr" ] \
  && ok || bad "deleted_exr: job run did not render it again: $(cat "$work/stdout")"
tamper t000006 'r["files"] = []'
"$skyspec" job run "${job[@]}" --tasks 0-11 >"$work/stdout" 2>&1 && grep -q "ran 1," "$work/stdout" \
  && ok || bad "no_files: a record without its files was not rendered again: $(cat "$work/stdout")"
tamper t000007 'r["files"][0]["path"] = "../../etc/passwd"'
collect_refuses outside_path 'a file'"'"'s "path" is not a relative path inside the job'"'"'s folder'
restore

# 17. Tampered fields: task -1 and 1e300, an id with commas, a bad date_time, no wavelengths.
for edit in 'r["task"] = -1' 'r["task"] = 1e300' 'r["id"] = "t0,00008"' 'r["date_time"] = "2026-02-30T12:00:00Z"' \
            'r["irradiance"]["wavelengths_nm"] = []'; do
  tamper t000008 "$edit"
  collect_refuses "$edit" "t000008: its record is damaged"
  restore
done

# 15. An empty --shard or --tasks (an unset variable in a Slurm array script) is an error, not the
# whole job on every node; an empty shard says so instead of "tasks 0--1".
run_expecting_error empty_shard 2 '--shard = "" is not allowed' "$work/none" "$skyspec" job run "${job[@]}" --shard ''
run_expecting_error empty_tasks 2 '--tasks = "" is not allowed' "$work/none" "$skyspec" job run "${job[@]}" --tasks ''
"$skyspec" job run "${job[@]}" --shard 1/13 --no-collect >"$work/stdout" 2>&1
grep -q "^no tasks (this shard is empty" "$work/stdout" && ok || bad "empty shard: $(cat "$work/stdout")"

# 16. Two `job run` of the same tasks at once (a resubmitted array job): each task runs once, in one
# of them; neither records a spurious failure; both exit 0 and both collect every task.
both=("$work/small.toml" --out "$work/K" --shard 1/1 --threads 1)
"$skyspec" job run "${both[@]}" >"$work/run1" 2>&1 &
first=$!
"$skyspec" job run "${both[@]}" >"$work/run2" 2>&1
rc2=$?
wait $first
rc1=$?
[ "$rc1" = 0 ] && [ "$rc2" = 0 ] && ok || bad "concurrent runs exited $rc1 and $rc2: $(tail -3 "$work/run1" "$work/run2" 2>&1)"
ran=$(cat "$work/run1" "$work/run2" | sed -n 's/^tasks 0-11: ran \([0-9]*\),.*/\1/p' | paste -sd+ | bc)
[ "$ran" = 12 ] && ok || bad "the two runs ran $ran tasks between them, not 12: $(cat "$work/run1" "$work/run2")"
[ "$(grep -c '"status":"ok"' "$work/K/manifest.jsonl")" = 12 ] && ok || bad "concurrent runs: $(grep -c ok "$work/K/manifest.jsonl") ok"
! grep -q "failed: " "$work/run1" "$work/run2" && ok || bad "a spurious failure: $(grep "failed: " "$work/run1" "$work/run2")"
! find "$work/K" -name '.*lock' | grep -q . && ok || bad "locks left: $(find "$work/K" -name '.*lock')"

# The pristine records collect cleanly again (the checks refuse only what is wrong).
"$skyspec" job collect "${job[@]}" --quiet 2>"$work/stderr" && ok || bad "pristine records: $(cat "$work/stderr")"

finish records
