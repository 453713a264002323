#!/usr/bin/env bash
# Water and ice in the air against the Monte Carlo, all orders (docs/bows-and-halos.md, "All
# orders against the Monte Carlo"): the default scene's clear sky, diamond dust, a cirrostratus,
# rain (Marshall-Palmer and 0.25 mm drops), a rain shower 8 km north and fog, the sun 25 degrees
# high, 450 and 650 nm, 40 000 paths per probe (fog 10 000); the largest difference 20 degrees and
# more above the horizon (per cent, and in standard errors) and the probes 3 degrees above the
# northern and southern horizon (test_bows_reference/benchmark_table; about ten minutes on 2
# cores, most of it fog's paths).
# Usage: bench/media_reference.sh [BUILD_DIR [RENDER_KEYS [MEDIUM]]]
#   RENDER_KEYS: [render] keys for the renderer alone, the Monte Carlo unchanged, e.g.
#   'ms_angular_degree = 12' or 'ms_altitude_samples = 48' (how the tables' resolution moves it).
#   MEDIUM: only the rows whose medium's name contains it, e.g. fog.
set -euo pipefail
build=${1:-build}
export SKYSPEC_BENCH_MEDIA_RENDER=${2:-}
export SKYSPEC_BENCH_MEDIA_ONLY=${3:-}
cmake --build "$build" --target skyspec_tests >/dev/null
echo "| medium | largest difference, 20 degrees and up (standard errors) | 3 degrees up, north: 450 / 650 nm | 3 degrees up, south: 450 / 650 nm |"
echo "| --- | --- | --- | --- |"
[ -n "$SKYSPEC_BENCH_MEDIA_RENDER" ] || unset SKYSPEC_BENCH_MEDIA_RENDER
SKYSPEC_BENCH_MEDIA=1 "$build/tests/skyspec_tests" --run_test=test_bows_reference/benchmark_table --log_level=nothing \
  --report_level=short | grep '^|'
# The shower's Stokes vector in all orders against the vector Monte Carlo (a check of its own,
# too long for the test command): pass or FAIL.
if [[ -z "$SKYSPEC_BENCH_MEDIA_ONLY" || "shower" == *"$SKYSPEC_BENCH_MEDIA_ONLY"* ]]; then
  if SKYSPEC_BENCH_MEDIA=1 "$build/tests/skyspec_tests" --run_test=test_bows_reference/a_shower_polarisation_in_all_orders \
    --log_level=nothing --report_level=no; then verdict=pass; else verdict=FAIL; fi
  echo "shower, all orders, Stokes vector at 650 nm against the vector Monte Carlo (4000 paths): $verdict"
fi
# Fog towards the sun, 3 degrees up, all orders, against the Monte Carlo drawing a share of its
# scatterings about the sun (3000 paths; moved here from the test command for its time): pass or FAIL.
if [[ -z "$SKYSPEC_BENCH_MEDIA_ONLY" || "fog" == *"$SKYSPEC_BENCH_MEDIA_ONLY"* ]]; then
  if SKYSPEC_BENCH_MEDIA=1 "$build/tests/skyspec_tests" --run_test=test_bows_reference/fog_all_orders_towards_the_sun \
    --log_level=nothing --report_level=no; then verdict=pass; else verdict=FAIL; fi
  echo "fog, all orders, towards the sun 3 degrees up, 450 and 650 nm, against the Monte Carlo (3000 paths): $verdict"
fi
