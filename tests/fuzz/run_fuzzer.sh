#!/usr/bin/env bash
# Runs one libFuzzer target for a bounded time (CTest fuzz_scene, fuzz_cli):
#   run_fuzzer.sh FUZZER WORK_DIR SECONDS SEED_DIR...
# The seeds (the committed corpus and regressions) are copied into WORK_DIR/corpus, which the
# fuzzer grows; the committed folders are never written. A finding (crash, sanitizer report,
# timeout of one input, memory limit) fails the test and leaves the input in WORK_DIR/artifacts/:
# fix the bug, then commit the input under tests/fuzz/regressions/<target>/ with a telling name.
set -euo pipefail
fuzzer=$1 work=$2 seconds=$3
shift 3
rm -rf "$work"
mkdir -p "$work/corpus" "$work/artifacts"
for seeds in "$@"; do
  [ -d "$seeds" ] && cp -r "$seeds"/. "$work/corpus/"
done
dict=()
[ -f "$(dirname "$0")/$(basename "$fuzzer").dict" ] && dict=(-dict="$(dirname "$0")/$(basename "$fuzzer").dict")
status=0
"$fuzzer" "${dict[@]}" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
  -artifact_prefix="$work/artifacts/" "$work/corpus" || status=$?
if [ "$status" -ne 0 ]; then
  echo "run_fuzzer: $(basename "$fuzzer") found a problem (exit $status); the input is in $work/artifacts/:" >&2
  ls -l "$work/artifacts" >&2
  exit 1
fi
