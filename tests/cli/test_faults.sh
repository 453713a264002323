#!/usr/bin/env bash
# Faults: a full disk, a failing flush, a taken output name and SIGINT / SIGTERM / SIGHUP during a render.
# Each must end with a non-zero exit, a clear message, and no partial or temporary file
# ("<name>.tmp-...") in the output folder.
# The full-disk case mounts a 64 KiB tmpfs and needs root (CAP_SYS_ADMIN); without it that case
# is reported as skipped. A disk that fails to flush needs the LD_PRELOAD library given as the
# second argument (tests/fault_inject/fail_fdatasync.cpp). Usage: test_faults.sh SKYSPEC [SHIM]
set -u
skyspec=$1
shim=${2:-}
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

# --- full disk ---------------------------------------------------------------------------------
full="$work/full"
mkdir -p "$full"
if mount -t tmpfs -o size=64k skyspec-test-full "$full" 2>/dev/null; then
  trap 'umount "$full" 2>/dev/null; rm -rf "$work"' EXIT
  # 64 x 64 pixels x 44 float channels is ~720 KB before compression: it cannot fit.
  # --force: past the up-front check of the free space (test_budget.sh), into the full disk.
  run_expecting_error full_disk_exr 3 "No space left on device" "$full/out" \
    "$skyspec" render -q --force --out "$full/out" --width 64 --height 64 --set render.scattering_orders=1
  # The PNG alone (the EXR is not written): still too big for what is left after filling.
  head -c 60k /dev/zero >"$full/filler" 2>/dev/null
  run_expecting_error full_disk_png 3 "No space left on device" "$full/out2" \
    "$skyspec" render -q --force --out "$full/out2" --width 256 --height 256 --no-exr --set render.scattering_orders=1
  rm -f "$full/filler"
  umount "$full" && ok || bad "could not unmount the test tmpfs"
  trap 'rm -rf "$work"' EXIT
else
  echo "SKIP full_disk: cannot mount a tmpfs here (needs root)"
fi

# --- a disk that fails to flush -----------------------------------------------------------------
# Every fdatasync fails with EIO: the spectral EXR's band flush reports it, as a write error
# would be (exit 3, the system's message), and no file is left. (ASan, when the binary has it,
# must be told that a library comes before its runtime.)
if [ -n "$shim" ]; then
  run_expecting_error failing_flush 3 "Input/output error" "$work/eio" \
    env LD_PRELOAD="$shim" ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0" \
    "$skyspec" render -q --out "$work/eio" --width 64 --height 64 --set render.scattering_orders=1
  # Several bands (a tall image), so that a band's flush fails before the file is completed: the
  # same error and exit (which of the two reports it first is not observable from here).
  run_expecting_error failing_flush_bands 3 "Input/output error" "$work/eio2" \
    env LD_PRELOAD="$shim" ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0" \
    "$skyspec" render -q --out "$work/eio2" --width 16 --height 512 --set render.scattering_orders=1
else
  echo "SKIP failing_flush: no fdatasync shim given"
fi

# --- an output that cannot be committed --------------------------------------------------------
# A folder already holds the name of one output, so its rename fails (EISDIR) after the other
# output may have been completed (the EXR is completed beside the PNG's encoding): exit 3, the
# other output removed, no temporary file, the folder left as it was.
# taken_name NAME TAKEN: renders EXR and PNG into a folder where TAKEN (x.exr or x.png) is a folder.
taken_name() {
  local name=$1 taken=$2 out="$work/taken-$1"
  mkdir -p "$out/$taken"
  "$skyspec" render -q --out "$out" --name x --width 32 --height 32 --set render.scattering_orders=1 \
    >"$work/stdout" 2>"$work/stderr"
  local rc=$?
  if [ "$rc" != 3 ]; then bad "$name: exit $rc, expected 3"; cat "$work/stderr"; return; fi
  # Refused before anything is written (it used to fail at the rename: "cannot rename ... Is a directory").
  grep -q "refusing to write '.*$taken': it is a folder" "$work/stderr" && ok || { bad "$name: message missing"; cat "$work/stderr"; }
  if [ "$(ls -A "$out")" != "$taken" ] || [ -n "$(ls -A "$out/$taken")" ]; then
    bad "$name: the folder holds: $(ls -A "$out")"
  else
    ok
  fi
}
taken_name exr_name_taken x.exr
taken_name png_name_taken x.png

# --- signals -----------------------------------------------------------------------------------
# render_and_signal NAME SIGNAL EXPECTED_EXIT: starts a render big enough to take a while, waits
# until its EXR writer has created the temporary file (so the signal lands mid-render), sends the
# signal, and checks exit code, message and that the folder is empty.
render_and_signal() {
  local name=$1 sig=$2 code=$3 out="$work/sig-$1"
  # A ray marched per pixel (no sky-view table): about 2.5 s on 2 cores, so that the signal, sent
  # 0.3 s after the temporary file appears, lands mid-render (with the table it took 0.5 s in all).
  "$skyspec" render -q --out "$out" --width 512 --height 512 --set render.scattering_orders=1 \
    --set render.sky_view_table=false >"$work/stdout" 2>"$work/stderr" &
  local pid=$! waited=0
  until ls "$out" 2>/dev/null | grep -q '\.tmp-'; do
    sleep 0.1
    waited=$((waited + 1))
    if [ $waited -gt 1200 ] || ! kill -0 $pid 2>/dev/null; then break; fi
  done
  sleep 0.3
  kill -s "$sig" $pid 2>/dev/null
  wait $pid
  local rc=$?
  if [ "$rc" != "$code" ]; then bad "$name: exit $rc, expected $code"; cat "$work/stderr"; return; fi
  grep -q "interrupted by SIG$sig" "$work/stderr" && ok || { bad "$name: message missing"; cat "$work/stderr"; }
  if [ -n "$(ls -A "$out" 2>/dev/null)" ]; then bad "$name: left files: $(ls -A "$out")"; else ok; fi
}
render_and_signal sigint INT 130
render_and_signal sigterm TERM 143
# A dropped SSH session (issue 42, item 10): SIGHUP stops like SIGTERM, temporaries and lock removed.
render_and_signal sighup HUP 129

finish faults
