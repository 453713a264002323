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
# The same above the ground in twilight, each thread count building its own tables (fresh caches):
# the scattering-order tables' steep rows once took their last bit from the heap's alignment.
for t in 1 2; do
  SKYSPEC_CACHE_DIR="$work/cache-$t" "$skyspec" render -q --out "$work/up$t" --name up --no-png --camera equirectangular \
    --width 32 --height 16 --sun-elevation -3 --position 0,0,500 --set render.scattering_orders=3 --threads "$t" \
    2>"$work/stderr" || { bad "render above the ground with --threads $t failed"; cat "$work/stderr"; }
done
cmp -s "$work/cache-1"/orders-*.bin "$work/cache-2"/orders-*.bin && ok || bad "tables built with 1 and 2 threads differ"
cmp "$work/up1/up.exr" "$work/up2/up.exr" && ok || bad "--threads 1 and 2 differ above the ground with their own tables"
finish determinism
