#!/usr/bin/env bash
# Determinism: the same scene gives the same EXR, byte for byte, run after run, whatever the number
# of threads and whichever folder and name it is written to. The EXR header records the effective
# scene but not where it was written or with how many threads (SceneTomlKeys::Recorded), so the
# renders with 1 and with 2 threads, into two folders, must be identical files, the compressed
# pixel data and the header alike. Usage: test_determinism.sh SKYSPEC
set -u
skyspec=$1
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

# render_to NAME THREADS: renders the scene into $work/NAME/, under the name NAME.
render_to() {
  if ! "$skyspec" render -q --out "$work/$1" --name "$1" --no-png --camera equirectangular --width 48 --height 40 \
      --sun-elevation 3 --set render.scattering_orders=3 --threads "$2" 2>"$work/stderr"; then
    bad "render with --threads $2 failed"; cat "$work/stderr"
  fi
}

render_to t2a 2
render_to t2b 2
render_to t1 1
if [ -s "$work/t2a/t2a.exr" ] && [ -s "$work/t2b/t2b.exr" ] && [ -s "$work/t1/t1.exr" ]; then
  cmp "$work/t2a/t2a.exr" "$work/t2b/t2b.exr" && ok || bad "two runs with --threads 2 (two folders) differ"
  cmp "$work/t1/t1.exr" "$work/t2a/t2a.exr" && ok || bad "--threads 1 and --threads 2 differ: $(cmp -l "$work/t1/t1.exr" "$work/t2a/t2a.exr" | head -3)"
  # Neither the folder nor the threads are in the header; the rest of the scene is.
  grep -qa "^threads = " "$work/t1/t1.exr" && bad "render.threads recorded in the header" || ok
  grep -qa "$work" "$work/t1/t1.exr" && bad "the output folder recorded in the header" || ok
  grep -qa "^scattering_orders = 3$" "$work/t1/t1.exr" && ok || bad "the scene is not recorded in the header"
fi
finish determinism
