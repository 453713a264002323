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

# 10. Temporaries a killed run left (its process gone: pid 999999999 is above any pid_max) are
# removed by the next render of that name, holding its lock; another name's are left alone.
mkdir -p "$work/stale"
touch "$work/stale/sky.exr.tmp-999999999-0123abcd" "$work/stale/sky-polarisation.exr.tmp-999999999-1" \
      "$work/stale/other.exr.tmp-999999999-2"
"$skyspec" render -q --out "$work/stale" "${small[@]}" 2>"$work/stderr" || bad "stale: render failed: $(cat "$work/stderr")"
[ "$(ls -A "$work/stale" | sort | tr '\n' ' ')" = "other.exr.tmp-999999999-2 sky.exr sky.png " ] && ok \
  || bad "stale temporaries: $(ls -A "$work/stale" | tr '\n' ' ')"

# 12. A --name too long for the file system is refused up front, naming --name (it failed late,
# exit 3, with 245-300 characters).
long=$(printf 'n%.0s' $(seq 250))
run_expecting_error long_name 2 "--name: output.name = \"$long\" is not allowed: a non-empty file name of at most 200" \
  "$work/long" "$skyspec" render -q --out "$work/long" --name "$long" "${small[@]}"

# 22. A budget refusal leaves no empty output folder behind (the folder did not exist before).
run_expecting_error refused_folder 2 "would take about" "$work/none" \
  "$skyspec" render -q --out "$work/refused/deep" --camera equirectangular --width 16384 --height 16384 \
  --view-segments 4096 --threads 1 --no-exr --set render.sky_view_table=false --set render.scattering_orders=1
[ ! -e "$work/refused/deep" ] && ok || bad "refused_folder: $work/refused/deep was left behind"

# 11. convert trusts no crafted skyspec:exposureScale: 1e308 and 5e-324 are refused, naming it
# (they made an all-black PNG, exit 0); a sane one is applied and quoted as the number.
craft="${SKYSPEC_PYTHON:-/usr/bin/python3} $(dirname "${BASH_SOURCE[0]}")/craft_exr.py"
for bad_scale in 1e308 5e-324; do
  $craft "$work/stale/sky.exr" "$work/crafted.exr" set-double skyspec:exposureScale "$bad_scale"
  run_expecting_error "scale_$bad_scale" 3 "is not an exposure scale from 2^-200 to 2^200" "$work/conv-$bad_scale" \
    "$skyspec" convert "$work/crafted.exr" --out "$work/conv-$bad_scale"
done
$craft "$work/stale/sky.exr" "$work/crafted.exr" set-double skyspec:exposureScale 0.25
$craft "$work/crafted.exr" "$work/crafted2.exr" set-string skyspec:exposure "made up"
"$skyspec" convert "$work/crafted2.exr" --out "$work/conv-ok" >"$work/stdout" 2>&1
grep -q "recorded in the file: scale = 0.25 (EV -2)" "$work/stdout" && ok || bad "scale 0.25: $(cat "$work/stdout")"

# 19. merge --out naming a folder is refused before merging (exit 2, naming --out).
mkdir -p "$work/merge-dir"
run_expecting_error merge_into_folder 2 "--out = '$work/merge-dir' is not allowed" "$work/none" \
  "$skyspec" merge "$work/stale/sky.exr" --out "$work/merge-dir"

# 13. The Monte Carlo reference has a time budget: 1e12 paths per probe are refused up front.
run_expecting_error reference_budget 2 "the Monte Carlo reference would take about" "$work/none" \
  timeout 60 "$skyspec" reference --paths 1000000000000 --quality draft
grep -qF "use fewer --paths, or --force" "$work/stderr" && ok || bad "reference_budget: $(cat "$work/stderr")"
run_expecting_error reference_seed 2 "--seed" "$work/none" "$skyspec" reference --seed 18446744073709551616 --paths 2

finish files_not_ours
