#!/usr/bin/env bash
# Formats every C++ source and header of the tree with .clang-format (clang-format-14, Debian's
# clang-format-14 package): ./scripts/format.sh; --check lists the files it would change and exits 1.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
files=$(git ls-files '*.cpp' '*.hpp' '*.h' | grep -v '^tests/fuzz/corpus/')
if [ "${1:-}" = --check ]; then
  status=0
  for f in $files; do clang-format-14 --dry-run -Werror "$f" >/dev/null 2>&1 || { echo "$f"; status=1; }; done
  exit $status
fi
# shellcheck disable=SC2086
clang-format-14 -i $files
