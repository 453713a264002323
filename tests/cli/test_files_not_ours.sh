#!/usr/bin/env bash
# Files that are not ours (issue 42, items 2, 4, 5, 6), each attack repeated as the issue wrote it:
# a symbolic link planted as an output's lock file, --out naming a device, a link or /dev/stdout,
# a FIFO named like a table cache file, and standard output that cannot be written.
# Usage: test_files_not_ours.sh SKYSPEC
set -u
skyspec=$1
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
export SKYSPEC_CACHE_DIR="$work/cache"
small=(--width 8 --height 8 --quality draft)

# 2. A link planted as the lock file: its target must not be truncated or written; the render
# refuses (exit 3) and leaves the link and its target as they were.
mkdir -p "$work/victim" "$work/out"
echo precious > "$work/victim/file"
ln -s "$work/victim/file" "$work/out/.sky.lock"
run_expecting_error lock_link 3 "refusing to use the lock file" "$work/none" \
  "$skyspec" render -q --out "$work/out" "${small[@]}"
[ "$(cat "$work/victim/file")" = precious ] && ok || bad "lock_link: the link's target was written"
[ -L "$work/out/.sky.lock" ] && ok || bad "lock_link: the planted link was replaced"
[ ! -e "$work/out/sky.exr" ] && ok || bad "lock_link: rendered anyway"

# 4. --out naming something that is not a regular file: a character device, /dev/stdout, a FIFO.
# Never the machine's own /dev/null and /dev/full: a build with this bug, run as root, replaces
# them with regular files (it did, once, while this test was written). Our own nodes of the same
# devices in the scratch folder (mknod needs root; without it the device cases are skipped), and
# our own link to /proc/self/fd/1, which is what /dev/stdout is.
t="$work/targets"  # (not $work/stdout: lib.sh keeps captured output there)
mkdir -p "$t"
targets=("$t/stdout")
ln -s /proc/self/fd/1 "$t/stdout"
if mknod -m 666 "$t/null" c 1 3 2>/dev/null && mknod -m 666 "$t/full" c 1 7 2>/dev/null; then
  targets+=("$t/null" "$t/full")
else
  echo "SKIP device --out: cannot make device nodes here (needs root)"
fi
mkfifo "$t/fifo"
targets+=("$t/fifo")
for target in "${targets[@]}"; do
  before=$(stat -c %F "$target")
  run_expecting_error "out_$(basename "$target")" 3 "skyspec creates and replaces only regular files" "$work/none" \
    timeout 60 "$skyspec" coefficients --out "$target"
  [ "$(stat -c %F "$target")" = "$before" ] && ok || bad "$target became $(stat -c %F "$target")"
done
ln -s "$work/victim/file" "$work/report-link.md"
run_expecting_error out_link 3 "it is a symbolic link" "$work/none" "$skyspec" coefficients --out "$work/report-link.md"
[ -L "$work/report-link.md" ] && [ "$(cat "$work/victim/file")" = precious ] && ok || bad "out_link: the link or its target changed"
# A regular file is still replaced as before.
echo old > "$work/report.md"
"$skyspec" coefficients --out "$work/report.md" 2>"$work/stderr" && grep -q "Rayleigh" "$work/report.md" && ok \
  || bad "a regular --out file is not replaced: $(cat "$work/stderr")"

# 5. A FIFO named like every table cache file: the render must not hang; the tables are built, the
# cache write refused with a warning, and the FIFO left alone.
SKYSPEC_CACHE_DIR="$work/probe" "$skyspec" render -q --out "$work/probe-out" "${small[@]}" >/dev/null 2>&1
mkdir -p "$work/fifo-cache"
for f in "$work/probe"/*.bin; do mkfifo "$work/fifo-cache/$(basename "$f")"; done
[ -n "$(ls "$work/fifo-cache")" ] && ok || bad "fifo: no cache file to imitate"
SKYSPEC_CACHE_DIR="$work/fifo-cache" timeout 120 "$skyspec" render -q --out "$work/fifo-out" "${small[@]}" \
  2>"$work/stderr"
rc=$?
[ "$rc" = 0 ] && [ -s "$work/fifo-out/sky.exr" ] && ok || bad "fifo: exit $rc (124: it hung): $(cat "$work/stderr")"
grep -qF "cannot be cached" "$work/stderr" && ok || bad "fifo: no warning about the cache"
for f in "$work/fifo-cache"/*; do [ -p "$f" ] && ok || bad "fifo: $f was replaced"; done

# 6. Standard output that cannot be written is a failure (exit 3), for every printing command.
if [ -w /dev/full ]; then
  for args in "coefficients" "render --print-scene" "render --help-keys" "irradiance --sun-elevations 30 --quality draft"; do
    # shellcheck disable=SC2086
    "$skyspec" $args >/dev/full 2>"$work/stderr"
    rc=$?
    [ "$rc" = 3 ] && grep -qF "cannot write to standard output" "$work/stderr" && ok \
      || bad "'skyspec $args > /dev/full': exit $rc, $(cat "$work/stderr")"
  done
else
  echo "SKIP stdout: no /dev/full"
fi

finish files_not_ours
