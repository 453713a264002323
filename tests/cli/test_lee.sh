#!/usr/bin/env bash
# `skyspec lee-diagram`: a small diagram's files (a spectral EXR that OpenEXR's and OpenImageIO's
# tools read, the PNG, S1 channels with --polarisation, no PNG with --no-png), the summary, and bad
# flags refused naming the flag, with no file left. Usage: test_lee.sh SKYSPEC
set -u
skyspec=$1
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
small=(--width 40 --height 6 --lambda-step 50 --radius-min-um 20 --radius-max-um 200)

if "$skyspec" lee-diagram "${small[@]}" --out "$work/a" >"$work/stdout" 2>"$work/stderr"; then
  [ -s "$work/a/lee.exr" ] && [ -s "$work/a/lee.png" ] && ok || bad "files missing: $(ls "$work/a")"
  [ "$(ls "$work/a" | wc -l)" = 2 ] && ok || bad "extra files: $(ls -A "$work/a")"
  grep -q "wrote $work/a/lee.exr" "$work/stdout" && grep -q "40 x 6 pixels" "$work/stdout" && ok || bad "summary: $(cat "$work/stdout")"
  [ ! -s "$work/stderr" ] && ok || bad "stderr not empty when not a terminal: $(cat "$work/stderr")"
  exrheader "$work/a/lee.exr" | grep -q "S0.380,000000nm" && ok || bad "exrheader: no S0.380,000000nm"
  exrheader "$work/a/lee.exr" | grep -q "Lee diagram" && ok || bad "exrheader: no skyspec:content"
  oiiotool --info -v "$work/a/lee.exr" | grep -q "12 channel" && ok || bad "oiiotool: not 9 wavelengths and R, G, B"
  oiiotool --info "$work/a/lee.png" | grep -qE "40 x +6, 3 channel" && ok || bad "oiiotool: PNG size"
else
  bad "lee-diagram failed: $(cat "$work/stderr")"
fi

"$skyspec" lee-diagram "${small[@]}" --polarisation --no-png --name p --out "$work/b" -q >"$work/stdout" 2>&1 \
  && ok || bad "--polarisation failed: $(cat "$work/stdout")"
[ -s "$work/b/p.exr" ] && [ ! -e "$work/b/p.png" ] && ok || bad "--no-png: $(ls "$work/b")"
exrheader "$work/b/p.exr" | grep -q "S1.430,000000nm" && ok || bad "--polarisation: no S1 channels"
[ ! -s "$work/stdout" ] && ok || bad "-q printed: $(cat "$work/stdout")"

# On a terminal (script(1) gives it one) the progress bar is drawn on stderr.
script -qc "'$skyspec' lee-diagram ${small[*]} --out '$work/tty'" /dev/null 2>&1 | grep -qa "lee diagram \[" \
  && ok || bad "no progress bar on a terminal"

# A PNG that cannot be written (a folder has its name): exit 3, and the EXR written before it is
# removed again (the pair or nothing).
mkdir -p "$work/c/lee.png"
"$skyspec" lee-diagram "${small[@]}" --out "$work/c" -q 2>"$work/stderr"
[ $? = 3 ] && [ ! -e "$work/c/lee.exr" ] && [ "$(ls -A "$work/c")" = lee.png ] && ok \
  || bad "failed PNG: $(ls -A "$work/c"); $(cat "$work/stderr")"

expect_error() {  # expect_error NAME 'text' ARGS...
  local name=$1 text=$2
  shift 2
  run_expecting_error "$name" 2 "$text" "$work/out-$name" \
    "$skyspec" lee-diagram --width 40 --height 6 --lambda-step 50 --out "$work/out-$name" "$@"
}
expect_error radius_too_large "--radius-max-um = 5000 is not allowed: from 10 (--radius-min-um) to 1209 um (size parameter 2e4 at 380 nm)" \
  --radius-max-um 5000
expect_error angles_reversed "--angle-max" --angle-min 140 --angle-max 130
expect_error ultraviolet "--lambda-min" --lambda-min 250
expect_error frozen "--water-temperature = -20 is not allowed: 0-100 degC" --water-temperature -20
expect_error no_width "--width" --width 0
expect_error bad_name "--name" --name a/b
expect_error bad_view "--view" --view "no such view"
finish cli_lee
