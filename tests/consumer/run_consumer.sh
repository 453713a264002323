#!/usr/bin/env bash
# Installs the build into a scratch prefix, then configures, builds and runs tests/consumer/ against
# it with find_package(skyspec), as a project outside skyspec would. Also checks that the package
# exports only the public headers and no -march flag.
# Usage: run_consumer.sh BUILD_DIR WORK_DIR
set -euo pipefail
build=$1 work=$2
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
rm -rf "$work"
cmake --install "$build" --prefix "$work/prefix" >/dev/null
if grep -rq -- "-march" "$work/prefix/lib"/cmake/skyspec/; then
  echo "FAIL: the installed package exports a -march flag" >&2; exit 1
fi
if ls "$work/prefix/include" | grep -vqx skyspec; then
  echo "FAIL: headers outside include/skyspec installed" >&2; exit 1
fi
for private in single_scattering.hpp spectral_exr.hpp embedded_data.hpp; do
  if [ -e "$work/prefix/include/skyspec/$private" ]; then echo "FAIL: internal header $private installed" >&2; exit 1; fi
done
# The built-in OpenColorIO config is installed as a file that OpenColorIO validates, the very
# config the program embeds, and the installed program names it.
config="$work/prefix/share/skyspec/ocio/config.ocio"
cmp -s "$config" "$here/../../data/ocio/config.ocio" || { echo "FAIL: $config missing or not data/ocio/config.ocio" >&2; exit 1; }
ociocheck --iconfig "$config" >"$work/ociocheck.txt" 2>&1 || { cat "$work/ociocheck.txt" >&2; echo "FAIL: ociocheck $config" >&2; exit 1; }
"$work/prefix/bin/skyspec" render --list-displays | grep -qF "ociocheck --iconfig): $config" \
  || { echo "FAIL: skyspec render --list-displays does not name $config" >&2; exit 1; }
cmake -S "$here" -B "$work/build" -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/build" >/dev/null
"$work/build/consumer" "$work"
# The docs' C++ example: its files, the zenith's spectrum and its refusal of a bad width.
mkdir -p "$work/example"
"$work/build/render_sky" "$work/example" >"$work/example.txt"
grep -q "^  *380 nm  [0-9]" "$work/example.txt" && grep -q 'refused: .*camera.width = 64.5 is not allowed' "$work/example.txt" \
  && [ -s "$work/example/sky.exr" ] && [ -s "$work/example/sky.png" ] \
  || { cat "$work/example.txt" >&2; echo "FAIL: docs/examples/render_sky.cpp" >&2; exit 1; }
oiiotool --info "$work/example/sky.exr" >/dev/null || { echo "FAIL: the example's EXR does not open in oiiotool" >&2; exit 1; }

