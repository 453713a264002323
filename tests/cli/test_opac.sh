#!/usr/bin/env bash
# The microphysical aerosol from the command line (atmosphere.mie.model = "opac"): a render, its
# optics cached on disk beside the tables and read back bit for bit (a damaged cache file is
# recomputed, not trusted; render.cache_tables = false writes none), the progress bar's phase while
# they are computed (render and coefficients), the coefficient report naming the mixture, and bad values refused naming the key. Usage: test_opac.sh SKYSPEC
set -u
skyspec=$1
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
export SKYSPEC_CACHE_DIR="$work/cache"
# Without the insoluble component (the largest particles of the default mixture): the cheapest
# Lorenz-Mie, which this test computes several times (also under the sanitizers).
cheap=(--set atmosphere.mie.model=opac --set atmosphere.mie.opac.inso_per_cm3=0)
small=(--width 8 --height 8 --wavelengths 450,650 "${cheap[@]}" --set render.scattering_orders=1 -q)

"$skyspec" render "${small[@]}" --out "$work/a" 2>"$work/stderr" && ok || bad "render failed: $(cat "$work/stderr")"
files=("$work"/cache/aerosol-*.bin)
[ "${#files[@]}" = 1 ] && [ -s "${files[0]}" ] && ok || bad "no aerosol cache file: $(ls -A "$work/cache")"
exrheader "$work/a/sky.exr" | grep -q 'model = "opac"' && ok || bad "the EXR's scene lacks the aerosol model"

# Read back: the same image, bit for bit; the file is marked as used (its time), which only a
# successful read does.
touch -d '2001-01-01' "${files[0]}"
"$skyspec" render "${small[@]}" --out "$work/b" && cmp -s "$work/a/sky.exr" "$work/b/sky.exr" && ok \
  || bad "the cached optics give another image"
[ "$(stat -c %Y "${files[0]}")" -gt "$(date -d 2002-01-01 +%s)" ] && ok || bad "the cache file was not read"
# A damaged file (one byte of its values changed) is not trusted: computed again (the same image)
# and written again (the same bytes as before the damage).
cp "${files[0]}" "$work/intact.bin"
size=$(stat -c %s "${files[0]}")
printf '\x7f' | dd of="${files[0]}" bs=1 seek=$((size - 100)) conv=notrunc status=none
"$skyspec" render "${small[@]}" --out "$work/c" 2>"$work/stderr" && cmp -s "$work/a/sky.exr" "$work/c/sky.exr" && ok \
  || bad "a damaged cache file changed the image: $(cat "$work/stderr")"
cmp -s "$work/intact.bin" "${files[0]}" && ok || bad "the damaged cache file was used, not replaced"
"$skyspec" render "${small[@]}" --out "$work/d" && cmp -s "$work/a/sky.exr" "$work/d/sky.exr" && ok \
  || bad "the rewritten cache file gives another image"
# Without the cache, nothing is written there.
SKYSPEC_CACHE_DIR="$work/cache-off" "$skyspec" render "${small[@]}" --set render.cache_tables=false --out "$work/e" \
  && [ ! -e "$work/cache-off" ] && ok || bad "render.cache_tables = false wrote $(ls -A "$work/cache-off" 2>/dev/null)"

# On a terminal (script(1) gives it one) the bar shows the optics being computed.
SKYSPEC_CACHE_DIR="$work/cache-tty" script -qc "'$skyspec' render --width 8 --height 8 --wavelengths 400,500,600,700 \
  ${cheap[*]} --set render.scattering_orders=1 --out '$work/tty'" /dev/null >"$work/bar.txt" 2>&1
grep -qaE "rendering computing the aerosol's optics \(Lorenz-Mie\) \[#*\.*\] +[0-9]+%" "$work/bar.txt" && ok \
  || bad "no bar while the aerosol's optics were computed: $(tr '\r' '\n' <"$work/bar.txt" | head -5)"

# ... and so does the coefficient report's while it computes them, ending at 100 %; none with --quiet
# (the release stage only: under the sanitizers two more runs of the Lorenz-Mie optics are slow, and
# the render's bar above and the report below run under them).
[ -n "${SKYSPEC_SANITIZER_STAGE:-}" ] || for q in "" -q; do
  SKYSPEC_CACHE_DIR="$work/cache-tty$q" script -qc "'$skyspec' coefficients $q --wavelengths 400,500,600,700 \
    ${cheap[*]} --out '$work/tty$q.md'" /dev/null >"$work/cbar.txt" 2>&1
  if [ -z "$q" ]; then
    grep -qaE "coefficients computing the aerosol's optics \(Lorenz-Mie\) \[#*\.*\] +[0-9]+%" "$work/cbar.txt" &&
      grep -qaE "coefficients \[#{30}\] 100%  elapsed" "$work/cbar.txt" && ok ||
      bad "no bar while the report's optics were computed: $(tr '\r' '\n' <"$work/cbar.txt" | tail -3)"
  else
    [ -s "$work/tty-q.md" ] && ! grep -qa "coefficients" "$work/cbar.txt" && ok || bad "a bar with --quiet: $(head -c 300 "$work/cbar.txt")"
  fi
done

# The coefficient report says what the aerosol is made of.
"$skyspec" coefficients --wavelengths 450,550 "${cheap[@]}" --out "$work/report.md" \
  && grep -q "OPAC components by Lorenz-Mie theory.*waso 7000" "$work/report.md" && ok \
  || bad "report: $(grep -i aerosol "$work/report.md")"

run_expecting_error "humidity" 2 "atmosphere.mie.opac.relative_humidity_percent = 100 is not allowed" "$work/x" \
  "$skyspec" render "${small[@]}" --set atmosphere.mie.opac.relative_humidity_percent=100 --out "$work/x"
run_expecting_error "wavelengths" 2 "OPAC's refractive indices of the aerosol components" "$work/x" \
  "$skyspec" render "${small[@]/450,650/3000,3500}" --set sun.spectrum=flat --set atmosphere.ozone.enabled=false \
  --set atmosphere.rayleigh.refractive_index=ciddor --out "$work/x"
run_expecting_error "no particles" 2 "atmosphere.mie.opac.*_per_cm3 = 0 for every component" "$work/x" \
  "$skyspec" render "${small[@]}" --set atmosphere.mie.opac.waso_per_cm3=0 --set atmosphere.mie.opac.inso_per_cm3=0 \
  --set atmosphere.mie.opac.soot_per_cm3=0 --out "$work/x"
run_expecting_error "model" 2 'atmosphere.mie.model = "mie" is not allowed: one of: angstrom, opac' "$work/x" \
  "$skyspec" render "${small[@]}" --set atmosphere.mie.model=mie --out "$work/x"

finish test_opac
