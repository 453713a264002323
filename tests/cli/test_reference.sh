#!/usr/bin/env bash
# `skyspec reference`: the Monte Carlo reference from the command line: output formats, determinism
# (same seed, any threads), single scattering against the renderer, bad input.
set -u
skyspec=${1:?usage: test_reference.sh SKYSPEC}
source "$(dirname "$0")/lib.sh"
py=/usr/bin/python3

# JSON with two probes at two wavelengths; the same seed gives the same numbers with 1 and 2 threads.
"$skyspec" reference --wavelengths 450,650 --probe up=0,90 --probe 180,1 --paths 3000 --format json -q \
  --set render.threads=1 >"$work/a.json" && ok || bad "reference json"
"$skyspec" reference --wavelengths 450,650 --probe up=0,90 --probe 180,1 --paths 3000 --format json -q \
  --set render.threads=2 >"$work/b.json" && ok || bad "reference json, 2 threads"
$py - "$work/a.json" "$work/b.json" <<'PY' && ok || bad "json content / thread independence"
import json, math, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
assert a["wavelengths_nm"] == [450, 650], a["wavelengths_nm"]
assert [p["label"] for p in a["probes"]] == ["up", "180,1"]
for p, q in zip(a["probes"], b["probes"]):
    assert p["radiance"] == q["radiance"] and p["standard_error"] == q["standard_error"], (p, q)
    for v, e in zip(p["radiance"], p["standard_error"]):
        assert v > 0 and 0 < e < 0.2 * v and math.isfinite(v), (v, e)
PY
# A probe's value does not depend on the other probes or wavelengths asked for.
"$skyspec" reference --wavelengths 550,650 --probe 180,1 --paths 3000 --format csv -q >"$work/one.csv" && ok || bad "csv"
$py - "$work/a.json" "$work/one.csv" <<'PY' && ok || bad "a probe alone gives the same value"
import csv, json, sys
a = json.load(open(sys.argv[1]))
rows = list(csv.DictReader(open(sys.argv[2])))
assert len(rows) == 2
assert abs(float(rows[1]["monte_carlo"]) / a["probes"][1]["radiance"][1] - 1) < 1e-8, (rows, a["probes"][1])
PY

# Single scattering: the reference and the renderer agree within their errors (order 1 only).
"$skyspec" reference --wavelengths 450,650 --sun-elevation 20 --orders 1 --compare --paths 20000 --format csv -q \
  --set render.sky_view_table=false >"$work/single.csv" && ok || bad "--orders 1 --compare"
$py - "$work/single.csv" <<'PY' && ok || bad "single scattering: reference vs renderer"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 10, rows
for r in rows:
    mc, se, det = float(r["monte_carlo"]), float(r["standard_error"]), float(r["renderer"])
    assert abs(det - mc) <= 4 * se + 0.003 * mc, r
PY

# In the planet's shadow (sun below the horizon, order 1 only, looking away from it) the sky is
# dark: relative columns are empty, never NaN.
"$skyspec" reference --wavelengths 450,650 --sun-elevation -4 --orders 1 --probe 180,1 --compare --paths 200 --format csv -q \
  >"$work/shadow.csv" && ok || bad "reference in the planet's shadow"
grep -qi "nan\|inf" "$work/shadow.csv" && bad "NaN or Inf in the shadow's CSV: $(cat "$work/shadow.csv")" || ok

# --out writes the file atomically; Markdown names the settings.
"$skyspec" reference --wavelengths 550,650 --probe 0,90 --paths 500 --irradiance --out "$work/t.md" -q && ok || bad "--out"
grep -q "diffuse horizontal irradiance" "$work/t.md" && grep -q "500 paths per value, seed 1" "$work/t.md" && ok \
  || bad "markdown content"

# --stokes: Rayleigh air once scattered at 90 degrees from the sun (sun on the horizon in the north,
# looking at the zenith) is polarised east-west to the degree 1 / (1 + 2 rho / (1 - rho)), 0.94-0.95
# for air's depolarisation ratio; V is 0; the same with 1 and 2 threads; I the scalar radiance
# within the errors (independent paths).
for t in 1 2; do
  "$skyspec" reference --wavelengths 450,650 --sun-elevation 0 --probe 0,90 --probe 90,30 --orders 1 --stokes \
    --paths 2000 --format json -q --set atmosphere.mie.enabled=false --set render.threads=$t >"$work/stokes$t.json" \
    && ok || bad "--stokes json ($t threads)"
done
$py - "$work/stokes1.json" "$work/stokes2.json" <<'PY' && ok || bad "--stokes: closed form, V = 0, thread independence"
import json, math, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
assert a["probes"][0]["stokes"] == b["probes"][0]["stokes"]
for p in a["probes"]:
    for s, e, r, re in zip(p["stokes"], p["stokes_standard_error"], p["radiance"], p["standard_error"]):
        assert len(s) == 4 and s[3] == 0.0 and all(math.isfinite(x) for x in s + e), s
        assert abs(s[0] - r) < 4 * math.hypot(e[0], re), (s, r)  # one order: the same expected intensity
zenith = a["probes"][0]["stokes"]
for I, Q, U, V in zenith:
    dolp, aolp = math.hypot(Q, U) / I, math.degrees(0.5 * math.atan2(U, Q))
    assert 0.93 < dolp < 0.96 and abs(abs(aolp) - 90) < 0.5, (dolp, aolp)
PY
# --stokes --compare with one order: the renderer's single-scattering polarisation is the Monte
# Carlo's within its errors (default scene: Rayleigh polarises, the aerosol does not).
"$skyspec" reference --wavelengths 450,650 --sun-elevation 20 --probe 90,30 --probe 200,10 --orders 1 --stokes \
  --compare --paths 20000 --format csv -q --set render.sky_view_table=false >"$work/stokes_det.csv" \
  && ok || bad "--stokes --compare"
$py - "$work/stokes_det.csv" <<'PY' && ok || bad "--stokes --compare: renderer's Q, U vs the Monte Carlo's"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 4, rows
for r in rows:
    I = float(r["stokes_i"])
    for c in "qu":
        mc, se, det = float(r[f"stokes_{c}"]), float(r[f"stokes_{c}_error"]), float(r[f"renderer_stokes_{c}"])
        assert abs(det - mc) <= 4 * se + 0.003 * I, (c, r)
    assert float(r["renderer_degree_of_linear_polarisation"]) > 0.1, r  # polarised: not a comparison of zeros
PY
"$skyspec" reference --wavelengths 550,650 --probe 90,20 --paths 500 --stokes --format csv -q >"$work/stokes.csv" \
  && $py -c 'import csv,sys; r=list(csv.DictReader(open(sys.argv[1]))); assert 0 < float(r[0]["degree_of_linear_polarisation"]) < 1 and r[0]["stokes_v"] == "0", r' "$work/stokes.csv" \
  && ok || bad "--stokes csv columns"
"$skyspec" reference --wavelengths 550,650 --probe 90,20 --paths 500 --stokes --irradiance -q | grep -q "AoLP (deg)" \
  && ok || bad "--stokes markdown columns"

mkdir -p "$work/empty"
run_expecting_error "bad probe" 2 "--probe" "$work/empty" "$skyspec" reference --probe 0,95 --paths 10
run_expecting_error "bad probe text" 2 "azimuth,elevation" "$work/empty" "$skyspec" reference --probe north
run_expecting_error "too few paths" 2 "--paths" "$work/empty" "$skyspec" reference --paths 1
run_expecting_error "bad format" 2 "--format" "$work/empty" "$skyspec" reference --format xml
run_expecting_error "orders with compare" 2 "--orders" "$work/empty" "$skyspec" reference --orders 2 --compare
run_expecting_error "sun peak share" 2 "--sun-peak-share = 0.7 is not allowed: a share from 0 to 0.5" "$work/empty" \
  "$skyspec" reference --sun-peak-share 0.7 --paths 10
: >"$work/a-file"
run_expecting_error "out under a file" 2 "--out" "$work/empty" "$skyspec" reference --paths 10 \
  --out "$work/a-file/t.md"
# A label with a quote and a comma stays one CSV field.
"$skyspec" reference --wavelengths 550,650 --probe 'a "b", c=0,90' --paths 200 --format csv -q >"$work/label.csv" \
  && $py -c 'import csv,sys; r=list(csv.DictReader(open(sys.argv[1]))); assert r[0]["probe"]=="a \"b\", c", r' "$work/label.csv" \
  && ok || bad "a probe label with quotes and commas in CSV"
run_expecting_error "irradiance from space" 2 "below the top of the atmosphere" "$work/empty" "$skyspec" reference \
  --position 0,0,100000 --irradiance --paths 10
run_expecting_error "bad scene key" 2 "sun.elevation_deg" "$work/empty" "$skyspec" reference --set sun.elevation_deg=200

finish cli_reference
