#!/usr/bin/env bash
# Installs what is missing, builds, and renders the built-in default scene into ./skyspec-out/
# (sky.exr: spectral OpenEXR, sky.png: preview). Extra arguments go to `skyspec render`.
# Builds the program only (the library and the CLI), not the tests or the Python module.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
install_missing_packages
build skyspec_cli   # only the program: the tests are built by scripts/test.sh
./build/skyspec render --out skyspec-out "$@"
