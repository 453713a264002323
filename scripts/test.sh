#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test through CTest.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
install_missing_packages
build
ctest --test-dir build --output-on-failure -j"$(nproc)"
