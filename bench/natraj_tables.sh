#!/usr/bin/env bash
# skyspec's vector transport against every value of Natraj, Li & Yung (2009)'s corrected
# Coulson-Dave-Sekera tables (../shared/reference/natraj2009: six optical thicknesses, three ground
# albedos, the top and the bottom, 7 x 16 x 7 geometries, I, Q and U), in the plane-parallel
# configuration of tests/render/test_natraj_tables.cpp with finer tables (192 sun angles, 64
# altitudes, 20 orders). Prints one Markdown row per case (docs/validation.md): I's largest relative
# difference, I's largest difference as a fraction of the limit (0.5 % or 1e-4), Q's and U's largest
# absolute differences (limit 0.002), and the values outside the limits. About 22 minutes on 2 cores.
# Usage: bench/natraj_tables.sh [--taus 0.02,0.1] [BUILD_DIR] [TABLES_DIR]
# --taus: only these optical thicknesses (of 0.02, 0.05, 0.1, 0.25, 0.5, 1).
set -euo pipefail
if [ "${1:-}" = --taus ]; then
  [ -n "${2:-}" ] || { echo "--taus needs a comma-separated list of optical thicknesses" >&2; exit 2; }
  for t in ${2//,/ }; do
    case $t in 0.02 | 0.05 | 0.1 | 0.25 | 0.5 | 1) ;; *) echo "--taus: $t is not one of 0.02, 0.05, 0.1, 0.25, 0.5, 1" >&2; exit 2 ;; esac
  done
  export SKYSPEC_NATRAJ_TAUS=$2
  shift 2
fi
build=${1:-build}
tables=${2:-$(dirname "$0")/../../shared/reference/natraj2009}
[ -f "$tables/I_UP_TAU_1" ] || { echo "no tables in $tables (give their folder as the second argument)" >&2; exit 2; }
cmake --build "$build" --target skyspec_tests >/dev/null
echo "| optical thickness | albedo | where | I, largest relative difference | I, largest difference / limit | Q, largest difference | U, largest difference | outside the limits |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- |"
SKYSPEC_NATRAJ_DIR=$(cd "$tables" && pwd) "$build/tests/skyspec_tests" --run_test=test_natraj_tables/all_published_tables \
  --log_level=nothing --report_level=short | grep '^|'
