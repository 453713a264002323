#!/usr/bin/env bash
# Builds and runs bench/library_choices.cpp against skyspec's own CIEDE2000 as it was at commit
# 47a8051 (taken from git) and Little CMS 2; prints the figures docs/architecture.md quotes.
# Usage: bench/library_choices.sh   (from the repository, with liblcms2-dev and
# libhowardhinnant-date-dev installed; about 2 s)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/colour"
git show 47a8051:src/colour/ciede2000.hpp >"$work/colour/ciede2000.hpp"
git show 47a8051:src/colour/ciede2000.cpp >"$work/ciede2000_old.cpp"
g++ -std=c++17 -O2 -I"$work" -Iinclude -Isrc -I/usr/include/eigen3 bench/library_choices.cpp "$work/ciede2000_old.cpp" \
  -llcms2 -o "$work/library_choices"
"$work/library_choices" tests/data/ciede2000_sharma2005.csv
