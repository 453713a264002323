#!/usr/bin/env bash
# Figures of docs/ that a command reproduces but that take too long for the test command: each is
# run again and compared with what the page quotes; prints "pass" or "FAIL" per figure and exits
# non-zero if any failed. bench/run_benchmarks.sh runs it. Usage (from the repository root):
#
#   bench/docs_figures.sh [SKYSPEC]     (default: build/skyspec)
set -u
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
docs="$here/../docs"
skyspec=${1:-build/skyspec}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failed=0

# docs/jobs.md, "Irradiance and pyranometers": the default scene's broadband irradiance (all
# orders, the tables' angular degree 4), rounded as the table shows it.
if "$skyspec" irradiance -q --sun-elevations 20,41.81,60,90 --set irradiance.broadband=true \
  --set render.ms_angular_degree=4 --format csv >"$work/bb.csv" 2>"$work/stderr" &&
  /usr/bin/python3 - "$work/bb.csv" "$docs/jobs.md" <<'PY'; then
import csv, sys
docs = open(sys.argv[2]).read()
for r in csv.DictReader(open(sys.argv[1])):
    el = float(r["sun_elevation_deg"])
    row = "| %g deg%s | %.1f W/m2 | %.1f W/m2 |" % (el, " (air mass 1.5)" if el == 41.81 else "",
                                                 float(r["global_horizontal_W_m2"]), float(r["broadband_global_horizontal_W_m2"]))
    assert row in docs, "docs/jobs.md lacks the row " + row
PY
  echo "docs/jobs.md broadband irradiance table: pass"
else
  echo "docs/jobs.md broadband irradiance table: FAIL"; cat "$work/stderr"
  failed=1
fi
exit $failed
