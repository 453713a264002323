#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test through CTest; then builds again with
# AddressSanitizer + UndefinedBehaviorSanitizer (build-asan/) and runs the Boost.Test suites and
# the command-line tests there (no Python or notebooks: that build has no Python module). Any
# sanitizer report aborts the process under test and fails its test. Both builds replay every
# input of the fuzz corpora and regressions (fuzz_replay_*); live fuzzing with libFuzzer is
# scripts/fuzz.sh (clang, build-fuzz/), outside this command for time.
# Each stage's wall time is printed to stderr ("skyspec test: <stage> <seconds> s").
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
# Tests keep their multiple-scattering table cache inside the build folder, not in ~/.cache.
export SKYSPEC_CACHE_DIR="$PWD/build/test-cache"
stage_start=$SECONDS
stage() {  # stage NAME: the time since the previous stage
  echo "skyspec test: $1 $((SECONDS - stage_start)) s" >&2
  stage_start=$SECONDS
}
install_missing_packages "${SKYSPEC_TEST_PACKAGES[@]}"
stage "packages"
build
stage "release build"
ctest --test-dir build --output-on-failure -j"$(nproc)"
stage "release tests"
build_sanitized
stage "sanitizer build"
# Not repeated here, for time: the Python and notebook tests (no module in that build), the
# installed package, the Slurm cluster (its skyspec commands run here in cli_job), the layering
# check (it reads sources and preprocesses probes: nothing a sanitizer sees); seven tests of
# properties a sanitizer does not change (byte-identical renders, provenance round trips, the
# multiple-scattering physics, grid independence, the Monte Carlo reference, its polarised cases
# and the renderer against it, with terrain, ice and rain too: cli_reference runs the scalar and the vector Monte
# Carlo here, cli_terrain the Monte Carlo with terrain); and
# two long ones whose code the others run under the sanitizers: cli_display (the
# display pipeline; every PNG of the other tests goes through it) and test_properties (random
# scenes; the renderer's code), and viewer_browser (Chromium drives the page; the viewer's requests
# run here in test_view_requests). cli (renders, time-lapses, aerial perspective) runs here with small
# scattering-order tables (docs/performance.md, "Build and test times").
# SKYSPEC_SANITIZER_STAGE also leaves a test's longest parts to the release stage where it says so
# (cli_hostile, cli_tiles, cli_budget's job, cli's progress bar, cache cap and broadband irradiance,
# cli_job's broadband job, cli_terrain's docs scenes, cli_opac's report bars, test_polarised_sky,
# test_natraj_tables, test_sphere_ensemble's convergence,
# test_microphysical_aerosol's Monte Carlo comparison, test_media's split aerosol and fog optics)
# and makes cli's renders use small tables. cli_files_not_ours (links, devices, FIFOs planted as
# outputs: system calls and their errors) runs in the release stage only.
SKYSPEC_SANITIZER_STAGE=1 ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1 \
UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-asan --output-on-failure -j"$(nproc)" \
    -E '^(python_.*|notebook_.*|install_consumer|slurm_job|layering|cli_determinism|cli_reproduce|test_multiple_scattering|test_grid_independence|test_monte_carlo|test_monte_carlo_reference|test_monte_carlo_polarisation|test_terrain_reference|test_bows_reference|cli_display|test_properties|viewer_browser|cli_files_not_ours)$'
stage "sanitizer tests"
