#!/usr/bin/env bash
# Terrain from the command line (terrain.*): a synthetic ridge that hides the sun and shadows the
# air, an elevation raster read through GDAL (an ESRI ASCII grid with its .prj, written here), height
# maps (PNG and EXR, written with oiiotool) and albedo maps, and bad input refused naming the key or
# the file. Usage: test_terrain.sh SKYSPEC
set -u
skyspec=$1
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
export SKYSPEC_CACHE_DIR="$work/cache"
# Looking west at a ridge 20 km away with the sun low behind it.
view=(--set camera.type=perspective --width 32 --height 18 --set camera.position_m=[0,0,200]
  --set camera.look_at_m=[-1000,0,230] --set camera.fov_deg=40 --set sun.elevation_deg=3 --set sun.azimuth_deg=270
  --wavelengths 450,550,650 --set render.scattering_orders=1 -q)
ridge=(--set terrain.model=ridge --set terrain.ridge.notch_spacing_m=6000)

"$skyspec" render "${view[@]}" "${ridge[@]}" --out "$work/ridge" 2>"$work/stderr" && ok \
  || bad "ridge render failed: $(cat "$work/stderr")"
exrheader "$work/ridge/sky.exr" | grep -q 'model = "ridge"' && ok || bad "the EXR's scene lacks the terrain"
# output.surface: a third file with each pixel's distance (Z) and masks that other tools read; the
# centre looks at the ridge (mask.terrain 1, Z about 17-20 km).
"$skyspec" render "${view[@]}" "${ridge[@]}" --set output.surface=true --set output.png=false \
  --out "$work/surface" 2>"$work/stderr" && ok || bad "surface render failed: $(cat "$work/stderr")"
exrheader "$work/surface/sky-surface.exr" | grep -q 'mask.terrain' && ok || bad "no mask.terrain channel"
# A tile cannot carry it: refused naming the key and the flag, nothing written.
"$skyspec" render "${view[@]}" "${ridge[@]}" --set output.surface=true --pixel-bounds 0,16,0,9 \
  --out "$work/surface-tile" >"$work/stdout" 2>&1 && bad "a tile with output.surface was rendered" \
  || { grep -q 'output.surface = true is not allowed: false with --pixel-bounds' "$work/stdout" && ok \
    || bad "refusal: $(cat "$work/stdout")"; }
[ ! -e "$work/surface-tile" ] && ok || bad "the refused tile left $(ls -R "$work/surface-tile")"
z=$(oiiotool "$work/surface/sky-surface.exr" --ch Z --cut 1x1+16+9 --printstats 2>/dev/null | awk '/Stats Avg/ {print $3}')
awk -v z="$z" 'BEGIN { exit !(z > 15000 && z < 21000) }' && ok || bad "Z at the centre $z"
"$skyspec" render "${view[@]}" --out "$work/open" 2>"$work/stderr" && ok || bad "render failed: $(cat "$work/stderr")"
# The ridge hides the sun (its disk and the glow around it): the image is darker than the open sky's.
sum() { oiiotool "$1" --ch 0 --printstats 2>/dev/null | awk '/Stats Avg/ {print $3}'; }
a=$(sum "$work/ridge/sky.exr") b=$(sum "$work/open/sky.exr")
awk -v a="$a" -v b="$b" 'BEGIN { exit !(a > 0 && a < 0.8 * b) }' && ok || bad "mean radiance $a with the ridge, $b without"

# An elevation raster: a 700 m high block 2.5 km west of the location on a 300 m plain (lat/long
# grid, 0.002 degree cells), as an ESRI ASCII grid GDAL reads, with its coordinate system.
{
  printf 'ncols 100\nnrows 100\nxllcorner 7.15\nyllcorner 46.15\ncellsize 0.002\nNODATA_value -9999\n'
  for r in $(seq 0 99); do
    row=""
    for c in $(seq 0 99); do
      if [ "$c" -ge 30 ] && [ "$c" -lt 34 ]; then row+="700 "; else row+="300 "; fi
    done
    echo "$row"
  done
} >"$work/dem.asc"
echo 'GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433]]' \
  >"$work/dem.prj"
dem=(--set terrain.model=file --set "terrain.file=\"$work/dem.asc\"" --set terrain.extent_m=6000
  --set location.latitude_deg=46.25 --set location.longitude_deg=7.25 --set camera.position_m=[0,0,400])
"$skyspec" render "${view[@]}" "${dem[@]}" --out "$work/dem" 2>"$work/stderr" && ok \
  || bad "DEM render failed: $(cat "$work/stderr")"
c=$(sum "$work/dem/sky.exr")
awk -v a="$c" -v b="$b" 'BEGIN { exit !(a > 0 && a < 0.8 * b) }' && ok || bad "mean radiance $c behind the DEM's block, $b without"

# The same block as a height map without georeferencing, centred on the reference point: a 16-bit
# PNG (codes over 65535 times terrain.heightmap.height_scale_m) and an EXR in metres render alike.
oiiotool --create 101x101 1 --fill:color=0.42857143 101x101+0+0 --fill:color=1 4x101+23+0 -d uint16 \
  -o "$work/block.png" && oiiotool --create 101x101 1 --fill:color=300 101x101+0+0 --fill:color=700 4x101+23+0 \
  -d float -o "$work/block.exr" && ok || bad "oiiotool could not write the height maps"
hm=(--set terrain.model=heightmap --set terrain.heightmap.pixel_m=100 --set terrain.extent_m=6000
  --set camera.position_m=[0,0,400])
"$skyspec" render "${view[@]}" "${hm[@]}" --set "terrain.file=\"$work/block.png\"" \
  --set terrain.heightmap.height_scale_m=700 --out "$work/hm-png" 2>"$work/stderr" && ok \
  || bad "PNG height map render failed: $(cat "$work/stderr")"
"$skyspec" render "${view[@]}" "${hm[@]}" --set "terrain.file=\"$work/block.exr\"" --out "$work/hm-exr" \
  2>"$work/stderr" && ok || bad "EXR height map render failed: $(cat "$work/stderr")"
p=$(sum "$work/hm-png/sky.exr") e=$(sum "$work/hm-exr/sky.exr")
awk -v p="$p" -v e="$e" -v b="$b" 'BEGIN { exit !(p > 0 && p < 0.8 * b && (p - e) ^ 2 < (1e-3 * e) ^ 2) }' && ok \
  || bad "mean radiance $p (PNG) and $e (EXR) behind the height map's block, $b without"

# The release stage only (scripts/test.sh's sanitizer stage sets SKYSPEC_SANITIZER_STAGE): these four
# renders run no code the renders above do not, only other settings of it.
if [ -z "${SKYSPEC_SANITIZER_STAGE:-}" ]; then
  # A relative terrain.file in a scene file is taken from the scene file's folder, wherever skyspec runs.
  mkdir -p "$work/scenes"
  printf '[terrain]\nmodel = "heightmap"\nfile = "../block.exr"\nheightmap.pixel_m = 100\nextent_m = 6000\n' \
    >"$work/scenes/block.toml"
  (cd / && "$skyspec" render --scene "$work/scenes/block.toml" "${view[@]}" --set camera.position_m=[0,0,400] \
    --out "$work/hm-scene" 2>"$work/stderr") && ok || bad "scene with a relative height map failed: $(cat "$work/stderr")"
  r=$(sum "$work/hm-scene/sky.exr")
  awk -v r="$r" -v e="$e" 'BEGIN { exit !((r - e) ^ 2 < (1e-6 * e) ^ 2) }' && ok \
    || bad "mean radiance $r from the scene file, $e with --set"

  # The terrain's own albedo and its map, looking down at the height map's plain in the sun: a white
  # map (factor 1) changes nothing, a black one (0) leaves the air's light only.
  oiiotool --create 2x2 1 --fill:color=1 2x2+0+0 -d uint8 -o "$work/white.png" \
    && oiiotool --create 2x2 1 -d uint8 -o "$work/black.png" && ok || bad "oiiotool could not write the albedo maps"
  down=(--set camera.type=perspective --width 16 --height 9 --set camera.look_at_m=[0,-1000,0] --set camera.fov_deg=30
    --set sun.elevation_deg=40 --wavelengths 450,550,650 --set render.scattering_orders=1 -q "${hm[@]}"
    --set "terrain.file=\"$work/block.exr\"" --set terrain.albedo=0.5)
  for map in none white black; do
    extra=()
    [ "$map" = none ] || extra=(--set "terrain.albedo_map=\"$work/$map.png\"")
    "$skyspec" render "${down[@]}" "${extra[@]}" --out "$work/albedo-$map" 2>"$work/stderr" && ok \
      || bad "render with albedo map $map failed: $(cat "$work/stderr")"
  done
  n=$(sum "$work/albedo-none/sky.exr") w=$(sum "$work/albedo-white/sky.exr") k=$(sum "$work/albedo-black/sky.exr")
  awk -v n="$n" -v w="$w" -v k="$k" 'BEGIN { exit !(n > 0 && (w - n) ^ 2 < (1e-6 * n) ^ 2 && k < 0.5 * n) }' && ok \
    || bad "mean radiance looking down: $n (terrain.albedo = 0.5), $w (white map), $k (black map)"
fi
run_expecting_error "albedo map on the ridge" 2 "terrain.albedo_map" "$work/x" \
  "$skyspec" render "${view[@]}" "${ridge[@]}" --set "terrain.albedo_map=\"$work/white.png\"" --out "$work/x"

# A camera standing 2 m above the crest: its height is computed along its own vertical (the crest,
# 20 km from the reference point, stands 1500 m above the sphere, whose curvature there is 31.4 m).
"$skyspec" render "${view[@]}" "${ridge[@]}" --set camera.position_m=[-20000,0,5] --set camera.above_ground_m=2 \
  --set camera.look_at_m=[-30000,0,1400] --out "$work/peak" 2>"$work/stderr" && ok \
  || bad "render on the crest failed: $(cat "$work/stderr")"
height=$(exrheader "$work/peak/sky.exr" | sed -n 's/.*position_m = \[-20000, 0, \([0-9.]*\)\].*/\1/p')
awk -v z="$height" 'BEGIN { exit !(z > 1470.3 && z < 1470.5) }' && ok || bad "camera height on the crest: '$height'"

# The Monte Carlo reference sees the terrain: single scattering looking at the ridge's face from
# the air in its shadow is exactly 0 (no path point sees the sun), and positive without the ridge.
mc=(reference --position 0,0,300 --sun-elevation 3 --sun-azimuth 270 --wavelengths 450,650 --probe face=270,3
  --paths 200 --orders 1 --format csv -q)
"$skyspec" "${mc[@]}" "${ridge[@]}" --out "$work/mc-ridge.csv" 2>"$work/stderr" && ok \
  || bad "reference with terrain failed: $(cat "$work/stderr")"
"$skyspec" "${mc[@]}" --out "$work/mc-open.csv" && ok || bad "reference without terrain failed"
col=5  # monte_carlo (probe, azimuth_deg, elevation_deg, wavelength_nm, monte_carlo, standard_error)
ridge_mc=$(awk -F, -v c="$col" 'NR > 1 { s += $c } END { print s }' "$work/mc-ridge.csv")
open_mc=$(awk -F, -v c="$col" 'NR > 1 { s += $c } END { print s }' "$work/mc-open.csv")
awk -v a="$ridge_mc" -v b="$open_mc" 'BEGIN { exit !(a == 0 && b > 0) }' && ok \
  || bad "Monte Carlo single scattering towards the ridge: $ridge_mc (open: $open_mc; column $col of $(head -1 "$work/mc-ridge.csv"))"

# The scenes of docs/terrain.md's pictures load and plan (their renders take 10-15 s each); in the
# release stage only: a file's keys are what is checked, and under the sanitizers each plan is slow
# (reading its height map and building the terrain), which the renders above run under them.
if [ -z "${SKYSPEC_SANITIZER_STAGE:-}" ]; then
  for scene in "$(dirname "${BASH_SOURCE[0]}")"/../../docs/images/terrain-*.toml; do
    "$skyspec" render --scene "$scene" --dry-run --out "$work/docs" >"$work/stdout" 2>&1 && ok \
      || bad "$(basename "$scene"): $(cat "$work/stdout")"
  done
fi

run_expecting_error "camera in the ridge" 2 "camera.position_m" "$work/x" \
  "$skyspec" render "${view[@]}" "${ridge[@]}" --set camera.position_m=[-20000,0,100] --out "$work/x"
run_expecting_error "camera under the DEM" 2 "a position above the terrain" "$work/x" \
  "$skyspec" render "${view[@]}" "${dem[@]}" --set camera.position_m=[0,0,100] --out "$work/x"
run_expecting_error "no file" 2 "terrain.file" "$work/x" \
  "$skyspec" render "${view[@]}" --set terrain.model=file --out "$work/x"
run_expecting_error "missing file" 2 "$work/none.tif" "$work/x" \
  "$skyspec" render "${view[@]}" --set terrain.model=file --set "terrain.file=\"$work/none.tif\"" --out "$work/x"
run_expecting_error "height map without its scale" 2 "terrain.heightmap.pixel_m" "$work/x" \
  "$skyspec" render "${view[@]}" --set terrain.model=heightmap --set "terrain.file=\"$work/block.png\"" --out "$work/x"
rm "$work/dem.prj"
run_expecting_error "no coordinate system" 2 "georeferenced" "$work/x" \
  "$skyspec" render "${view[@]}" "${dem[@]}" --out "$work/x"
run_expecting_error "model" 2 'terrain.model = "alps" is not allowed' "$work/x" \
  "$skyspec" render "${view[@]}" --set terrain.model=alps --out "$work/x"
finish terrain
