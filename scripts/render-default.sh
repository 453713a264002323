#!/usr/bin/env bash
# Installs what is missing, builds, and renders the built-in default scene into ./skyspec-out/
# (sky.exr: spectral OpenEXR, sky.png: preview). Extra arguments go to `skyspec render`.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
install_missing_packages
build
./build/skyspec render --out skyspec-out "$@"
