#!/usr/bin/env bash
# Runs a command in a fresh folder outside the repository (removed afterwards), without PYTHONPATH,
# so that Python finds skyspec only where it is installed. Usage: run_outside.sh COMMAND ARGS...
set -euo pipefail
outside=$(mktemp -d)
trap 'rm -rf "$outside"' EXIT
cd "$outside"
env -u PYTHONPATH "$@"
