#!/usr/bin/env bash
# The microphysical aerosol (atmosphere.mie.model = "opac"), two tables for docs/validation.md:
#  1. every OPAC component at every humidity and wavelength of its table (250-2500 nm) against
#     OPAC's own extinction, single-scattering albedo and asymmetry parameter: the largest
#     difference per component (test_aerosol_components/all_opac_tables; about a minute);
#  2. the polarised renderer against the vector Monte Carlo with OPAC's continental average, suns
#     at 30, 10 and 2 degrees, 100000 paths per probe, 450 and 650 nm: the largest intensity
#     difference (per cent and standard errors) and the largest DoLP difference, off and on the
#     horizon across from / away from the sun (test_microphysical_aerosol/benchmark_table; about
#     five minutes).
# Usage: bench/opac_aerosol.sh [BUILD_DIR]
set -euo pipefail
build=${1:-build}
cmake --build "$build" --target skyspec_tests >/dev/null
tests="$build/tests/skyspec_tests"
echo "| component | extinction, largest difference | albedo, largest difference | g, largest difference |"
echo "| --- | --- | --- | --- |"
SKYSPEC_BENCH_OPAC=1 "$tests" --run_test=test_aerosol_components/all_opac_tables --log_level=nothing \
  --report_level=short | grep '^|'
echo
echo "| sun elevation, deg | intensity, largest difference | in standard errors | DoLP, largest difference | DoLP, horizon across / away from the sun |"
echo "| --- | --- | --- | --- | --- |"
SKYSPEC_BENCH_OPAC=1 "$tests" --run_test=test_microphysical_aerosol/benchmark_table --log_level=nothing \
  --report_level=short | grep '^|'
