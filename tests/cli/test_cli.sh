#!/usr/bin/env bash
# Command-line behaviour: bad input is rejected with a message naming the flag or key, the value
# and what is allowed, a non-zero exit code and no output file; a good render writes an EXR that
# OpenEXR's and OpenImageIO's tools read. Usage: test_cli.sh PATH_TO_SKYSPEC
set -u
skyspec=$1
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

# expect_error NAME EXIT_CODE 'text that must appear in stderr' ARGS...
expect_error() {
  local name=$1 code=$2 text=$3
  shift 3
  run_expecting_error "$name" "$code" "$text" "$work/out-$name" \
    "$skyspec" render -q --out "$work/out-$name" --width 8 --height 8 "$@"
}

expect_error unknown_flag 2 "--bogus" --bogus 3
expect_error negative_width 2 "--width: camera.width = -5 is not allowed: a whole number from 1 to 65536" --width -5
expect_error non_number 2 "--sun-elevation: sun.elevation_deg = \"high\"" --sun-elevation high
expect_error elevation_range 2 "sun.elevation_deg = 95" --sun-elevation 95
expect_error unknown_key 2 "did you mean \"atmosphere.mie.g\"" --set atmosphere.mie.gg=0.7
expect_error set_syntax 2 "KEY=VALUE" --set novalue
expect_error camera_type 2 "one of: fisheye, perspective, equirectangular" --camera pinhole
expect_error grid_outside_tables 2 "from 280 nm (the extraterrestrial solar spectrum" --lambda-min 270
expect_error below_ground 2 "below" --position 0,0,-50
expect_error top_not_above_ground 2 "atmosphere.top_altitude_m = -1000" --set atmosphere.top_altitude_m=-1000
expect_error negative_radius 2 "planet.radius_m = -6360000" --set planet.radius_m=-6360e3
expect_error unknown_preset 2 "one of: default, hazy, high-altitude, mars, seed" --preset moon
expect_error missing_scene 2 "--scene" --scene "$work/nope.toml"
printf '[camera]\nwidth = 8\nheigth = 8\n' >"$work/typo.toml"
expect_error scene_typo 2 "typo.toml:3:1: unknown key \"camera.heigth\" (did you mean \"camera.height\"?)" --scene "$work/typo.toml"
expect_error unwritable_out 2 "output.directory" --set "output.directory=\"/proc/skyspec\""
expect_error no_outputs 2 "at least one output" --no-exr --no-png
expect_error convention_of_a_fisheye 2 "--panorama-convention: camera.panorama_convention = \"blender\" is not allowed: only with camera.type = \"equirectangular\"" --panorama-convention blender
expect_error fov_of_a_panorama 2 "--fov: camera.fov_deg = 30 is not allowed: only with camera.type = \"perspective\"" --camera equirectangular --fov 30
expect_error unknown_quality 2 "--quality = \"ultra\" is not allowed: one of: draft, lean, default, high, reference" --quality ultra
expect_error bad_compression 2 "output.exr_compression = \"dwaa\" is not allowed: one of: piz, zip, zips, rle, none" --set output.exr_compression=dwaa

# --quality sets the sample counts that are not given explicitly; explicit ones win.
"$skyspec" render --quality draft --print-scene | grep -qx "view_segments = 16" && ok || bad "--quality draft: view_segments"
"$skyspec" render --quality draft --view-segments 40 --print-scene | grep -qx "view_segments = 40" && ok || bad "--quality draft --view-segments 40"
"$skyspec" render --quality reference --print-scene | grep -qx "sky_view_table = false" && ok || bad "--quality reference: sky_view_table"
# A bare word for a text key stays a word, even one TOML would read as a number.
"$skyspec" render --name nan --print-scene | grep -qxE "name = [\"']nan[\"']" && ok || bad "--name nan"
"$skyspec" render --name 2026 --print-scene | grep -qxE "name = [\"']2026[\"']" && ok || bad "--name 2026"

# Small scattering-order tables (a single table order, render.scattering_orders = 2, and harmonics to
# degree 4: polarisation needs 2) and every pixel marched (no sky-view table: these images have
# fewer pixels than it has entries), for the
# commands whose files and behaviour are checked, not their physics. Under the sanitizers
# (scripts/test.sh sets SKYSPEC_SANITIZER_STAGE) the good render, the aerial perspective and the
# irradiance use them too: building the default tables there was most of this test's time
# (docs/performance.md, "Build and test times"); the release stage builds the default ones.
small_tables=(--set render.ms_altitude_samples=8 --set render.ms_sun_samples=24 --set render.scattering_orders=2
              --set render.ms_angular_degree=4 --set render.sky_view_table=false)
stage_tables=()
[ -n "${SKYSPEC_SANITIZER_STAGE:-}" ] && stage_tables=("${small_tables[@]}")

# A good render: exit 0, both files, nothing else left in the folder, quiet stderr when piped.
out="$work/good"
if "$skyspec" render --out "$out" --width 24 --height 16 --camera equirectangular "${stage_tables[@]}" \
    >"$work/stdout" 2>"$work/stderr"; then
  [ -s "$out/sky.exr" ] && [ -s "$out/sky.png" ] && ok || bad "good render: files missing"
  [ "$(ls "$out" | wc -l)" = 2 ] && ok || bad "good render: extra files $(ls "$out")"
  [ ! -s "$work/stderr" ] && ok || { bad "good render: stderr not empty when not a terminal"; cat "$work/stderr"; }
  grep -q "wrote $out/sky.exr" "$work/stdout" && ok || bad "good render: summary missing"
  exrheader "$out/sky.exr" | grep -q "S0.550,000000nm" && ok || bad "exrheader does not list S0.550,000000nm"
  exrheader "$out/sky.exr" | grep -q 'emissiveUnits (type string): "W.m^-2.sr^-1"' && ok || bad "emissiveUnits missing"
  oiiotool --info -v "$out/sky.exr" | grep -q "44 channel" && ok || bad "oiiotool does not read 44 channels"
  oiiotool "$out/sky.exr" --ch R,G,B --printstats 2>&1 | grep -q "Stats Min" && ok || bad "oiiotool cannot compute stats"
  # The numbers docs/other-tools.md quotes for this scene (a panorama: the ground albedo 0.25) are
  # the program's now (issue 41: docs that went stale). With the default tables only.
  if [ ${#stage_tables[@]} = 0 ]; then
    zenith=$(sed -n 's/^luminance at the zenith \([0-9]*\) cd\/m2.*/\1/p' "$work/stdout")
    diffuse=$(sed -n 's/.*, diffuse \([0-9]*\) lx$/\1/p' "$work/stdout")
    tools="$(dirname "${BASH_SOURCE[0]}")/../../docs/other-tools.md"
    grep -q "sky has $zenith cd/m^2" "$tools" && grep -q "to $zenith cd/m^2)" "$tools" && grep -q "to $diffuse lx" "$tools" \
      && ok || bad "docs/other-tools.md does not quote the zenith's $zenith cd/m^2 and the diffuse $diffuse lx of the summary"
  fi
else
  bad "good render failed"; cat "$work/stderr"
fi

# Time-lapse: frames with one exposure, --resume keeps finished frames (small tables: the frames'
# files are checked here, not their physics).
tl="$work/tl"
if "$skyspec" timelapse -q --latitude 48.14 --longitude 11.58 --start 2026-06-21T20:00:00+02:00 \
    --end 2026-06-21T20:30:00+02:00 --step-minutes 15 --out "$tl" --width 8 --height 8 "${small_tables[@]}" 2>"$work/stderr"; then
  # Each frame's EXR, PNG and record, and the manifest.
  [ "$(ls "$tl" | grep -c '^sky_000[0-2]\.\(exr\|png\|json\)$')" = 9 ] && [ -f "$tl/manifest.jsonl" ] && ok \
    || bad "timelapse: expected 3 frames with records and a manifest, got $(ls "$tl")"
  touch -d '2001-01-01' "$tl/sky_0001.exr"
  "$skyspec" timelapse -q --resume --latitude 48.14 --longitude 11.58 --start 2026-06-21T20:00:00+02:00 \
    --end 2026-06-21T20:30:00+02:00 --step-minutes 15 --out "$tl" --width 8 --height 8 "${small_tables[@]}"
  [ "$(stat -c %Y "$tl/sky_0001.exr")" -lt 1000000000 ] && ok || bad "timelapse --resume re-rendered a finished frame"
else
  bad "timelapse failed"; cat "$work/stderr"
fi
"$skyspec" timelapse -q --start 2026-06-21T20:00:00Z --end 2026-06-21T19:00:00Z --step-minutes 5 --out "$work/tl2" 2>"$work/stderr"
[ $? = 2 ] && grep -q -- "--end" "$work/stderr" && [ ! -e "$work/tl2" -o -z "$(ls -A "$work/tl2" 2>/dev/null)" ] && ok || bad "timelapse: end before start not rejected"
"$skyspec" timelapse -q --start 2026-13-01T00:00:00Z --end 2026-06-21T19:00:00Z --step-minutes 5 --out "$work/tl3" 2>"$work/stderr"
[ $? = 2 ] && grep -q -- "--start" "$work/stderr" && ok || bad "timelapse: bad date not rejected"

# The ultraviolet (from the solar spectrum's 280 nm) and the near infrared (to the ozone table's
# 1060 nm): finite radiances, colour from the overlap with the CMFs, and the header says which gas
# bands are not modelled (none in the UV; the oxygen A band and water vapour in the near infrared).
for band in "uv 290 400 10" "nir 700 1060 20"; do
  set -- $band
  # Single scattering: the ranges and the header are what is tested here, not the tables (which
  # would be built for each grid).
  if "$skyspec" render -q --out "$work/$1" --width 16 --height 8 --lambda-min "$2" --lambda-max "$3" --lambda-step "$4" \
      --set render.scattering_orders=1 2>"$work/stderr"; then
    exrheader "$work/$1/sky.exr" | grep -q "S0.$2,000000nm" && ok || bad "$1: no S0.$2 channel"
    nans=$(oiiotool "$work/$1/sky.exr" --printstats 2>&1 | grep -E "Stats (Nan|Inf)Count" | tr -d ' a-zA-Z:' | tr -d '0\n')
    [ -z "$nans" ] && ok || bad "$1: NaN or Inf in the file"
    [ -s "$work/$1/sky.png" ] && ok || bad "$1: no PNG"
  else
    bad "$1 render failed"; cat "$work/stderr"
  fi
done
exrheader "$work/uv/sky.exr" | grep -q 'skyspec:notModelled (type string): "no band of the Earth'"'"'s oxygen or water vapour in 290-400 nm' \
  && ok || bad "uv: skyspec:notModelled missing or wrong"
exrheader "$work/nir/sky.exr" | grep 'skyspec:notModelled' | grep -q "oxygen A band 759-771 nm.*water vapour (940 nm band)" \
  && ok || bad "nir: skyspec:notModelled does not name the A band and the 940 nm band"
expect_error grid_beyond_ozone 2 "to 1060 nm (the built-in ozone cross-sections" --lambda-min 700 --lambda-max 1100 --lambda-step 20

# Daylight's colour temperature (irradiance): global light with the sun 30 degrees up lies between
# CIE D50 and D65 (5003-6504 K), the skylight alone is bluer than 10000 K; a sun 4 degrees down
# leaves only skylight (docs/validation.md, "Daylight", has the figures).
if "$skyspec" irradiance --sun-elevations 30,-4 --format csv "${stage_tables[@]}" >"$work/irr.csv" 2>"$work/stderr"; then
  /usr/bin/python3 - "$work/irr.csv" <<'PY' && ok || bad "irradiance: colour temperatures out of range"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
day, dusk = rows
assert 5003 < float(day["global_cct_K"]) < 6504, day
assert float(day["diffuse_cct_K"]) > 10000, day
assert float(dusk["direct_horizontal_lux"]) == 0 and dusk["global_cct_K"] == dusk["diffuse_cct_K"], dusk
# The W/m2 columns say which band they integrate (the render's wavelengths), and global = direct + diffuse.
assert (day["band_min_nm"], day["band_max_nm"]) == ("380", "780"), day
g, parts = float(day["global_horizontal_W_m2"]), float(day["direct_horizontal_W_m2"]) + float(day["diffuse_horizontal_W_m2"])
assert abs(g - parts) <= 2e-4, day
PY
else
  bad "irradiance failed"; cat "$work/stderr"
fi

# The broadband irradiance (300-4000 nm, the gases' bands: docs/jobs.md): its columns when asked for
# (single scattering here: the columns are tested, test_broadband_irradiance the physics and, under
# the sanitizers, the runs' sum; so this part is the release stage's); the water vapour's keys
# refused without it, fog (water's index ends at 1100 nm) refused with it.
if [ -n "${SKYSPEC_SANITIZER_STAGE:-}" ]; then
  :
elif "$skyspec" irradiance --format csv --set irradiance.broadband=true --set render.scattering_orders=1 \
    --set render.cache_tables=false --set atmosphere.water_vapour.column_cm=3 >"$work/bb.csv" 2>"$work/stderr"; then
  /usr/bin/python3 - "$work/bb.csv" <<'PY' && ok || bad "irradiance: broadband columns"
import csv, sys
(row,) = list(csv.DictReader(open(sys.argv[1])))
bb = float(row["broadband_global_horizontal_W_m2"])
assert bb > float(row["global_horizontal_W_m2"]) > 0, row
assert abs(bb - float(row["broadband_direct_horizontal_W_m2"]) - float(row["broadband_diffuse_horizontal_W_m2"])) <= 2e-4, row
PY
else
  bad "broadband irradiance failed"; cat "$work/stderr"
fi
# docs/jobs.md's table of the default scene's broadband irradiance: bench/docs_figures.sh checks it.
"$skyspec" irradiance --format csv --set render.scattering_orders=1 | head -1 | grep -q broadband && bad "broadband columns without irradiance.broadband" || ok
run_expecting_error water_vapour_without_broadband 2 "atmosphere.water_vapour.column_cm = 3 is not allowed: only with irradiance.broadband = true" \
  "$work/none" "$skyspec" irradiance --set atmosphere.water_vapour.column_cm=3
run_expecting_error broadband_with_fog 2 "irradiance.broadband = true is not allowed: false unless every medium" \
  "$work/none" "$skyspec" irradiance --set irradiance.broadband=true --set atmosphere.fog.enabled=true \
  --set render.scattering_orders=1

# Aerial perspective: a constant distance, then a bad depth-mode.
"$skyspec" aerial -q --distance 2000 --camera perspective --position 0,0,2 --look-at 0,1000,300 --fov 40 \
  "${stage_tables[@]}" --image "$out/sky.exr" --out "$work/ap" 2>"$work/stderr" && [ -s "$work/ap/sky_transmittance.exr" ] \
  && [ -s "$work/ap/sky_inscatter.exr" ] && [ -s "$work/ap/sky_composite.exr" ] && ok || { bad "aerial failed"; cat "$work/stderr"; }
"$skyspec" aerial -q --distance 2000 --depth-is sideways --image "$out/sky.exr" --out "$work/ap2" 2>"$work/stderr"
[ $? = 2 ] && grep -q -- "--depth-is" "$work/stderr" && [ ! -e "$work/ap2" ] && ok || bad "aerial: bad --depth-is not rejected"
# A depth pass (z along the view axis, 200 m at the top row to 5 km at the bottom) and an RGB
# image, every row looking above the horizon: the composite is R,G,B = image x transmittance +
# inscatter, pixel by pixel, and the air in front of the farther pixels lets less of the image
# through.
oiiotool --pattern fill:top=200:bottom=5000 24x16 1 --chnames Z -d float -o "$work/depth.exr" \
  && oiiotool --pattern constant:color=0.5,0.4,0.3 24x16 3 --chnames R,G,B -d float -o "$work/rgb.exr" \
  && "$skyspec" aerial -q --depth "$work/depth.exr" --depth-is z --image "$work/rgb.exr" --camera perspective \
       --position 0,0,2 --look-at 0,1000,700 --fov 40 "${stage_tables[@]}" --out "$work/ap3" 2>"$work/stderr" \
  && /usr/bin/python3 - "$work/rgb.exr" "$work/ap3" <<'PY' && ok || { bad "aerial with a depth pass and an RGB image"; cat "$work/stderr"; }
import sys, numpy as np, OpenImageIO as oiio
def read(path, channels):
    spec = oiio.ImageInput.open(path).spec()
    img = oiio.ImageBuf(path).get_pixels(oiio.FLOAT)
    return np.stack([img[..., spec.channelnames.index(c)] for c in channels], axis=-1)
rgb = read(sys.argv[1], "RGB")
t = read(sys.argv[2] + "/sky_transmittance.exr", "RGB")
l = read(sys.argv[2] + "/sky_inscatter.exr", "RGB")
c = read(sys.argv[2] + "/sky_composite.exr", "RGB")
assert np.allclose(c, rgb * t + l, rtol=1e-6, atol=0), "composite is not image x transmittance + inscatter"
assert (t[-1] < t[0]).all(), "the farther bottom row should transmit less than the top row"
PY

# --quiet prints nothing at all on success.
"$skyspec" render -q --out "$work/quiet" --width 4 --height 4 "${stage_tables[@]}" >"$work/stdout" 2>"$work/stderr"
[ ! -s "$work/stdout" ] && [ ! -s "$work/stderr" ] && ok || bad "--quiet was not quiet"

# The numbers the docs quote for the default scene over a black ground (its own camera keeps the
# albedo 0) and for the exposure of a 1024 x 512 panorama of it, as the docs' commands give them now
# (issue 41: docs that went stale). The default tables of both are built above.
if [ ${#stage_tables[@]} = 0 ]; then
  tools="$(dirname "${BASH_SOURCE[0]}")/../../docs/other-tools.md"
  physics="$(dirname "${BASH_SOURCE[0]}")/../../docs/physics.md"
  "$skyspec" render --out "$work/black" --width 4 --height 4 >"$work/stdout" 2>"$work/stderr" \
    || bad "black-ground render failed: $(cat "$work/stderr")"
  zenith=$(sed -n 's/^luminance at the zenith \([0-9]*\) cd\/m2.*/\1/p' "$work/stdout")
  diffuse=$(sed -n 's/.*, diffuse \([0-9]*\) lx$/\1/p' "$work/stdout")
  grep -q "the default scene's zenith: $zenith cd/m^2" "$tools" && grep -q "($zenith cd/m^2 over a black ground)" "$tools" \
    && grep -q "($zenith to " "$tools" && grep -q "($diffuse to " "$tools" && grep -q "$zenith cd m^-2 (measured" "$physics" \
    && ok || bad "docs/other-tools.md and physics.md do not quote the black ground's zenith $zenith cd/m^2 and diffuse $diffuse lx"
  "$skyspec" render --camera equirectangular --width 1024 --height 512 --panorama-convention blender \
    --exr-space "Linear Rec.709" --no-png --out "$work/pano" >"$work/stdout" 2>"$work/stderr" \
    || bad "the docs' panorama failed: $(cat "$work/stderr")"
  exposure=$(sed -n 's/^exposure: automatic: .*, scale = \([^ ]*\) (EV \([^)]*\))$/\1 (EV \2)/p' "$work/stdout")
  [ -n "$exposure" ] && grep -qF "exposure scale $exposure" "$tools" && grep -qF "scale = $exposure" "$tools" \
    && ok || bad "docs/other-tools.md does not quote the panorama's exposure scale '$exposure'"
fi

# --help is something a newcomer can follow, and --help-keys documents every key with its unit.
"$skyspec" render --help | grep -q -- "--sun-elevation" && ok || bad "render --help lacks --sun-elevation"
"$skyspec" render --help-keys | grep -q "atmosphere.rayleigh.scale_height_m  (a number in m" && ok || bad "--help-keys"
# Polarisation: S0-S3 per wavelength with the layout's polarisationHandedness, the Y/DoLP/AoLP EXR
# and the colour-wheel PNG; OpenImageIO reads them; the keys that cannot go together are refused.
expect_error polarisation_png_alone 2 "output.polarisation_png = true is not allowed" --set output.polarisation_png=true
# The scenes of docs/bows-and-halos.md's pictures load (--print-scene: a plan would compute the
# media's optics, seconds to a minute each; test_bows_reference renders such media).
for scene in ice-halo cirrostratus-halo fogbow-and-glory glory corona rainbow rainbow-polarised \
  rainbow-supernumeraries rainbow-shower; do
  "$skyspec" render --scene "$(dirname "${BASH_SOURCE[0]}")/../../docs/images/$scene.toml" --print-scene \
    >"$work/stdout" 2>&1 && ok || bad "$scene.toml: $(cat "$work/stdout")"
done
# A cloud's droplets' keys are read only with droplets = "lognormal", and named with their range.
expect_error fog_radius_unread 2 'atmosphere.fog.median_radius_um = 5 is not allowed: only with atmosphere.fog.enabled = true and atmosphere.fog.droplets = "lognormal"' \
  --set atmosphere.fog.enabled=true --set atmosphere.fog.median_radius_um=5
expect_error fog_radius_too_large 2 "atmosphere.fog.median_radius_um = 40 is not allowed: a number in um, >= 2 and <= 25" \
  --set atmosphere.fog.enabled=true --set atmosphere.fog.droplets=lognormal --set atmosphere.fog.median_radius_um=40
# A shower's keys are read only with extent = "shower", and named with their range.
expect_error shower_keys_unread 2 'atmosphere.rain.shower_radius_m = 2000 is not allowed: only with atmosphere.rain.enabled = true and atmosphere.rain.extent = "shower"' \
  --set atmosphere.rain.enabled=true --set atmosphere.rain.shower_radius_m=2000
expect_error shower_too_narrow 2 "atmosphere.rain.shower_radius_m = 50 is not allowed: a number in m, >= 100" \
  --set atmosphere.rain.enabled=true --set atmosphere.rain.extent=shower --set atmosphere.rain.shower_radius_m=50
# Ice crystals: intensity only; the index of ice is carried from 300 to 1100 nm.
expect_error ice_polarised 2 "atmosphere.ice.enabled = true is not allowed: false with output.polarisation" \
  --set atmosphere.ice.enabled=true --set output.polarisation=true
expect_error ice_beyond_its_index 2 "spectrum = 290 nm is not allowed" --set atmosphere.ice.enabled=true \
  --wavelengths 290,550
expect_error cirrus_upside_down 2 "atmosphere.ice.top_m = 7000 is not allowed: above atmosphere.ice.base_m (8000 m)" \
  --set atmosphere.ice.enabled=true --set atmosphere.ice.layer=cloud --set atmosphere.ice.top_m=7000
expect_error cirrus_above_the_air 2 "atmosphere.ice.top_m = 70000 is not allowed: below atmosphere.top_altitude_m" \
  --set atmosphere.ice.enabled=true --set atmosphere.ice.layer=cloud --set atmosphere.ice.top_m=70000
expect_error ice_layer_unknown 2 "atmosphere.ice.layer" --set atmosphere.ice.layer=sky
# A flag or --set the scene would not read (docs/cli.md's example, then ice's layers and terrain).
expect_error unread_fog_key 2 "--set atmosphere.fog.visibility_m: atmosphere.fog.visibility_m = 300 is not allowed: only with atmosphere.fog.enabled = true (this scene does not read it)" \
  --set atmosphere.fog.visibility_m=300
expect_error unread_ice_key 2 "atmosphere.ice.optical_depth = 0.1 is not allowed: only with atmosphere.ice.enabled = true and atmosphere.ice.layer = \"cloud\"" \
  --set atmosphere.ice.enabled=true --set atmosphere.ice.optical_depth=0.1
expect_error unread_drop_radius 2 "atmosphere.rain.median_radius_mm = 0.3 is not allowed: only with atmosphere.rain.enabled = true and atmosphere.rain.drops = \"lognormal\"" \
  --set atmosphere.rain.enabled=true --set atmosphere.rain.median_radius_mm=0.3
expect_error drops_too_small 2 "atmosphere.rain.median_radius_mm = 0.1 is not allowed" \
  --set atmosphere.rain.enabled=true --set atmosphere.rain.drops=lognormal --set atmosphere.rain.median_radius_mm=0.1
expect_error drops_unknown 2 "atmosphere.rain.drops" --set atmosphere.rain.enabled=true --set atmosphere.rain.drops=hail
expect_error drops_beyond_the_series 2 "atmosphere.rain.median_radius_mm = 0.5 is not allowed: at most 0.46" \
  --set atmosphere.rain.enabled=true --set atmosphere.rain.drops=lognormal --set atmosphere.rain.median_radius_mm=0.5 \
  --set atmosphere.rain.radius_spread=1.2 --wavelengths 250,550 --set sun.spectrum=flat --set atmosphere.ozone.enabled=false
expect_error unread_ridge_key 2 "terrain.ridge.height_m = 900 is not allowed: only with terrain.model = \"ridge\"" \
  --set terrain.ridge.height_m=900
"$skyspec" render --help-keys | grep -q 'atmosphere.ice.base_m  .*; read only with atmosphere.ice.enabled = true and atmosphere.ice.layer = "cloud"' \
  && ok || bad "--help-keys does not give atmosphere.ice.base_m's condition"
expect_error polarisation_isotropic 2 "render.ms_angular_degree = 0" --set output.polarisation=true --quality draft
pol="$work/polarised"  # small scattering-order tables: the files are checked here
if "$skyspec" render -q --out "$pol" --camera equirectangular --width 32 --height 16 --lambda-min 450 --lambda-max 650 \
    --lambda-step 100 --set output.polarisation=true --set output.polarisation_png=true \
    "${small_tables[@]}" >"$work/stdout" 2>"$work/stderr"; then
  [ "$(ls "$pol" | sort | tr '\n' ' ')" = "sky-polarisation.exr sky-polarisation.png sky.exr sky.png " ] && ok \
    || bad "polarised render: files $(ls "$pol")"
  exrheader "$pol/sky.exr" | grep -q 'polarisationHandedness (type string): "right"' && ok || bad "polarised: no polarisationHandedness"
  for c in S0 S1 S2 S3; do exrheader "$pol/sky.exr" | grep -q "$c.550,000000nm" && ok || bad "polarised: no $c.550 channel"; done
  oiiotool --info -v "$pol/sky.exr" | grep -q "15 channel" && ok || bad "polarised: oiiotool does not read 15 channels"
  /usr/bin/python3 - "$pol/sky-polarisation.exr" <<'PY' && ok || bad "polarised: Y, DoLP, AoLP read by OpenImageIO"
import sys, OpenImageIO as oiio, numpy as np
image = oiio.ImageInput.open(sys.argv[1])
names = list(image.spec().channelnames)
pixels = image.read_image(oiio.FLOAT)
dolp, aolp = pixels[..., names.index("DoLP")], pixels[..., names.index("AoLP")]
assert 0.0 <= dolp.min() and dolp.max() <= 1.0 and dolp.max() > 0.5, (dolp.min(), dolp.max())  # the band 90 deg from the sun
assert -90.0 < aolp.min() and aolp.max() <= 90.0, (aolp.min(), aolp.max())
PY
else
  bad "polarised render failed"; cat "$work/stderr"
fi

# Progress on a terminal (issue 41): while the scattering-order tables build, the bar shows their
# share built with an ETA (not silence), then the rows; not a character of it when stderr is not a
# terminal. A pseudo-terminal from script(1), a cache of its own so that the tables are built.
# Both this and the cache cap below build tables: left to the release stage (seconds there, minutes
# under the sanitizers).
if [ -n "${SKYSPEC_SANITIZER_STAGE:-}" ]; then
  echo "SKIP progress on a terminal and the cache cap: left to the release stage"
elif command -v script >/dev/null; then
  SKYSPEC_CACHE_DIR="$work/bar-cache" script -qec "'$skyspec' render --width 16 --height 64 --out '$work/bar' \
    --set render.ms_altitude_samples=16 --set render.ms_sun_samples=64 --set render.scattering_orders=3" \
    /dev/null >"$work/bar.txt" 2>&1 || bad "render on a terminal failed: $(tail -c 300 "$work/bar.txt")"
  grep -qaE "rendering building the scattering tables \[#*\.*\] +[0-9]+%  ETA" "$work/bar.txt" && ok \
    || bad "no table phase in the bar: $(tr '\r' '\n' <"$work/bar.txt" | head -5)"
  grep -qaE "rendering \[#{30}\] 100%  elapsed" "$work/bar.txt" && ok || bad "no finished row bar: $(tail -c 300 "$work/bar.txt")"
  SKYSPEC_CACHE_DIR="$work/bar-cache2" "$skyspec" render --width 16 --height 64 --out "$work/bar2" \
    --set render.ms_altitude_samples=16 --set render.ms_sun_samples=64 --set render.scattering_orders=3 2>"$work/stderr" >/dev/null
  [ ! -s "$work/stderr" ] && ok || bad "a bar without a terminal: $(head -c 200 "$work/stderr")"
  # irradiance: a bar on a terminal (the tables above, cached: the elevations done), none with --quiet.
  for q in "" -q; do
    SKYSPEC_CACHE_DIR="$work/bar-cache" script -qec "'$skyspec' irradiance $q --sun-elevations 10,20 \
      --set render.ms_altitude_samples=16 --set render.ms_sun_samples=64 --set render.scattering_orders=3" \
      /dev/null >"$work/ibar.txt" 2>&1 || bad "irradiance $q on a terminal failed: $(tail -c 300 "$work/ibar.txt")"
    if [ -z "$q" ]; then
      grep -qaE "irradiance \[#{30}\] 100%  elapsed" "$work/ibar.txt" && ok || bad "no bar: $(tail -c 300 "$work/ibar.txt")"
    else
      ! grep -qaE "irradiance .*(ETA|elapsed)" "$work/ibar.txt" && ok || bad "a bar with --quiet: $(tail -c 300 "$work/ibar.txt")"
    fi
  done
else
  echo "SKIP progress on a terminal: no script(1)"
fi

# The table cache has a cap (issue 41): SKYSPEC_CACHE_MAX_MB, least recently used first. Sets of
# 4.2 MB under a 10 MB cap: A, B, A again (a use), then C evicts B, not A. A bad cap names the variable.
if [ -z "${SKYSPEC_SANITIZER_STAGE:-}" ]; then
cap_cache="$work/cap-cache"
cap_render() {  # ALBEDO: a small-table render of that ground's atmosphere; prints nothing
  SKYSPEC_CACHE_DIR="$cap_cache" SKYSPEC_CACHE_MAX_MB=10 "$skyspec" render -q --width 4 --height 4 --out "$work/cap" \
    --set render.ms_altitude_samples=8 --set render.ms_sun_samples=24 --set render.scattering_orders=2 \
    --set ground.albedo="$1" || bad "render with albedo $1 under a cache cap failed"
}
cap_render 0.1; a=$(ls "$cap_cache")
cap_render 0.2; b=$(ls "$cap_cache" | grep -v "$a")
sleep 0.05; cap_render 0.1; sleep 0.05
cap_render 0.3
[ -e "$cap_cache/$a" ] && [ ! -e "$cap_cache/$b" ] && [ "$(ls "$cap_cache" | wc -l)" = 2 ] && ok \
  || bad "cache cap: after A, B, A, C the cache holds $(ls "$cap_cache" | tr '\n' ' ') (A $a, B $b)"
SKYSPEC_CACHE_DIR="$cap_cache" SKYSPEC_CACHE_MAX_MB=2GB "$skyspec" render -q --width 4 --height 4 --out "$work/cap" \
  --set render.scattering_orders=2 --set ground.albedo=0.4 2>"$work/stderr"
[ $? = 2 ] && grep -q 'SKYSPEC_CACHE_MAX_MB = "2GB" is not allowed' "$work/stderr" && ok \
  || bad "a bad cache cap: $(cat "$work/stderr")"
SKYSPEC_CACHE_DIR="$cap_cache" SKYSPEC_CACHE_MAX_MB=9999999999 "$skyspec" render -q --width 4 --height 4 --out "$work/cap" \
  --set render.scattering_orders=2 --set ground.albedo=0.4 2>"$work/stderr"
[ $? = 2 ] && grep -q '0 to 1000000000 (0: no cap; unset: 2000)' "$work/stderr" && ok \
  || bad "a cache cap above the largest: $(cat "$work/stderr")"
fi

# docs/scene-keys.md is generated from the key registry: it must be what the program prints now.
"$skyspec" render --help-keys=markdown | cmp -s - "$(dirname "${BASH_SOURCE[0]}")/../../docs/scene-keys.md" && ok \
  || bad "docs/scene-keys.md is stale: regenerate it with skyspec render --help-keys=markdown > docs/scene-keys.md"

finish cli
