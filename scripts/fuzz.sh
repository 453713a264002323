#!/usr/bin/env bash
# Live fuzzing, outside the test command (scripts/test.sh replays every corpus and regression
# input in each of its builds; this explores for new ones): builds the three libFuzzer targets with
# clang, AddressSanitizer and UndefinedBehaviorSanitizer in build-fuzz/ (tests/fuzz/), then fuzzes
# each for SKYSPEC_FUZZ_SECONDS (default 60) from a copy of its corpus and regressions. A crash,
# leak, sanitizer report, timeout or out-of-memory fails its CTest test and leaves the input in
# build-fuzz/tests/fuzz/work-<target>/ (copy it into tests/fuzz/regressions/<target>/ once fixed).
#
#   ./scripts/fuzz.sh                          # a minute per target
#   SKYSPEC_FUZZ_SECONDS=3600 ./scripts/fuzz.sh  # an hour per target
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
export SKYSPEC_FUZZ_SECONDS=${SKYSPEC_FUZZ_SECONDS:-60}
install_missing_packages "${SKYSPEC_FUZZ_PACKAGES[@]}"
build_fuzz
ctest --test-dir build-fuzz --output-on-failure -j"$(nproc)" -R '^fuzz_'
