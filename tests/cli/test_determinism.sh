#!/usr/bin/env bash
# Determinism: the same scene gives the same EXR, byte for byte, run after run and whatever the
# number of threads. The EXR header records the whole effective scene (including render.threads
# and output.directory), so every run writes to the same folder, and the renders with 1 and with 2
# threads must differ in exactly one byte: the digit of "threads = N" in that header. Everything
# else, the compressed pixel data included, must be identical. Usage: test_determinism.sh SKYSPEC
set -u
skyspec=$1
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

# render_to NAME THREADS: renders the scene into $work/out, then moves the EXR to $work/NAME.exr.
render_to() {
  if "$skyspec" render -q --out "$work/out" --no-png --camera equirectangular --width 48 --height 40 \
      --sun-elevation 3 --set render.scattering_orders=3 --threads "$2" 2>"$work/stderr"; then
    mv "$work/out/sky.exr" "$work/$1.exr"
  else
    bad "render with --threads $2 failed"; cat "$work/stderr"
  fi
}

render_to t2a 2
render_to t2b 2
render_to t1 1
if [ -s "$work/t2a.exr" ] && [ -s "$work/t2b.exr" ] && [ -s "$work/t1.exr" ]; then
  cmp "$work/t2a.exr" "$work/t2b.exr" && ok || bad "two runs with --threads 2 differ"
  diffs=$(cmp -l "$work/t1.exr" "$work/t2a.exr")
  # cmp -l prints: offset, byte of the first file, byte of the second (octal): '1' = 61, '2' = 62.
  if [ "$(printf '%s\n' "$diffs" | awk 'NF' | wc -l)" = 1 ] && printf '%s\n' "$diffs" | awk '{exit !($2 == 61 && $3 == 62)}'; then
    ok
  else
    bad "--threads 1 and --threads 2 differ beyond the recorded thread count: $(printf '%s\n' "$diffs" | head -5)"
  fi
  # The one difference is the recorded setting (the header is uncompressed text).
  grep -qa "^threads = 1$" "$work/t1.exr" && grep -qa "^threads = 2$" "$work/t2a.exr" && ok || bad "threads not recorded in the header"
fi
finish determinism
