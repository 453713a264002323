#!/usr/bin/env bash
# Builds bench/lorenz_mie_timing.cpp against build/libskyspec.a (build it first: scripts/test.sh or
# render-default.sh) and prints the Lorenz-Mie timings docs/performance.md quotes. About a minute.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
g++ -std=c++17 -O2 -Iinclude bench/lorenz_mie_timing.cpp build/libskyspec.a -ltbb -lcrypto -o "$work/lorenz_mie_timing"
"$work/lorenz_mie_timing"
