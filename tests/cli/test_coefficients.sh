#!/usr/bin/env bash
# `skyspec coefficients`: bad input is rejected with a message naming the flag, exit code 2 and no
# output file; each format is written atomically and is well formed (JSON parsed by Python's json,
# CSV rows as wide as the header, HTML with its plots). Usage: test_coefficients.sh PATH_TO_SKYSPEC
set -u
skyspec=$1
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

# expect_error NAME EXIT_CODE 'text that must appear in stderr' ARGS...
expect_error() {
  local name=$1 code=$2 text=$3
  shift 3
  mkdir -p "$work/err-$name"
  run_expecting_error "$name" "$code" "$text" "$work/err-$name" \
    "$skyspec" coefficients --out "$work/err-$name/report.md" "$@"
}

expect_error pressure_without_unit 2 "--pressure = \"250\" is not allowed: a pressure with its unit" --pressure 250 --temperature 220K
expect_error temperature_missing 2 "--temperature" --pressure 250hPa
expect_error negative_temperature 2 "--temperature" --pressure 250hPa --temperature -5K
expect_error bad_format 2 "--format = xml is not allowed: one of: md, csv, json, html" --format xml
expect_error altitude_above_top 2 "--altitudes = \"70000\" is not allowed" --altitudes 0,70000
expect_error altitude_not_number 2 "--altitudes" --altitudes 0,high
expect_error formula 2 "one of: peck-reeder, edlen, ciddor" --refractive-index peck_reeder
expect_error unknown_key 2 "unknown key" --set atmosphere.rayleigh.co2=400
expect_error grid 2 "spectrum" --lambda-min 100
# The report's range is the refractive index's (Peck & Reeder measured 230-1690 nm), said with why.
expect_error below_refractive_index 2 "wavelengths from 230 to 1690 nm: the refractive index of air: the range of Peck & Reeder's measurements" --wavelengths 225,550
expect_error above_refractive_index 2 "wavelengths from 230 to 1690 nm" --wavelengths 550,1700
expect_error unwritable 2 "--out" --out /proc/skyspec/report.md

# Markdown on stdout by default, with the published comparisons.
if "$skyspec" coefficients --wavelengths 440,550,680 >"$work/report.md" 2>"$work/stderr"; then
  grep -q "^# skyspec coefficient derivation report" "$work/report.md" && ok || bad "markdown title missing"
  grep -q "Bodhaine et al. 1999, Table 3" "$work/report.md" && ok || bad "Bodhaine comparison missing"
  grep -q "seed tutorial" "$work/report.md" && ok || bad "seed comparison missing"
  [ ! -s "$work/stderr" ] && ok || bad "stderr not empty"
else
  bad "markdown report failed"; cat "$work/stderr"
fi

# The ultraviolet and the near infrared: ozone where its table has data (to 1060 nm), n/a beyond;
# the published fits reach 250 nm (Bodhaine eq. 30) and 1650 nm (Bucholtz).
if "$skyspec" coefficients --wavelengths 300,350,1500 >"$work/uvnir.md" 2>"$work/stderr"; then
  grep -q "^| 1500 | .* | n/a | n/a | n/a | " "$work/uvnir.md" && ok || bad "1500 nm row without n/a ozone"
  grep -q "^| 300 | .*e-23 | " "$work/uvnir.md" && ok || bad "300 nm row without the Huggins-band cross-section"
  grep -q "Bodhaine et al. 1999, eq. 30" "$work/uvnir.md" && ok || bad "Bodhaine eq. 30 comparison missing"
  grep -q "^| 1500 | 7.8696e-33 | " "$work/uvnir.md" && ok || bad "Bucholtz fit at 1500 nm missing"
else
  bad "ultraviolet/near-infrared report failed"; cat "$work/stderr"
fi

# JSON through --out (format from the extension), 220 K and 250 hPa, two altitudes.
if "$skyspec" coefficients --pressure 250hPa --temperature 220K --altitudes 0,5000 --out "$work/cold.json" 2>"$work/stderr"; then
  [ "$(ls "$work" | grep -c cold)" = 1 ] && ok || bad "json: extra files $(ls "$work")"
  /usr/bin/python3 - "$work/cold.json" <<'PY' && ok || bad "json content"
import json, math, sys
j = json.load(open(sys.argv[1]), parse_constant=lambda c: (_ for _ in ()).throw(ValueError(c)))
n = len(j["wavelength_nm"])
assert n == 41, n
assert len(j["levels"]) == 2 and [l["altitude_m"] for l in j["levels"]] == [0, 5000]
c = j["conditions"]
assert abs(c["number_density_per_m3"] / (25000 / (1.380649e-23 * 220)) - 1) < 1e-14
sigma = j["rayleigh"]["cross_section_m2"]
assert all(abs(b / (s * c["number_density_per_m3"]) - 1) < 1e-14 for b, s in zip(c["rayleigh_scattering_per_m"], sigma))
refs = {r["id"]: r for r in j["references"]}
assert max(abs(r["difference_percent"]) for r in refs["bodhaine1999_table3"]["rows"]) < 0.1
PY
else
  bad "json report failed"; cat "$work/stderr"
fi

# CSV and HTML.
if "$skyspec" coefficients --format csv --out "$work/r.csv" --lambda-step 20 2>"$work/stderr"; then
  awk -F, '!/^#/ { if (!w) w = NF; else if (NF != w) exit 1; rows++ } END { exit !(rows == 22) }' "$work/r.csv" && ok || bad "csv shape"
else
  bad "csv report failed"; cat "$work/stderr"
fi
if "$skyspec" coefficients --out "$work/r.html" 2>"$work/stderr"; then
  [ "$(grep -c '<svg' "$work/r.html")" = 3 ] && ok || bad "html: expected 3 plots"
  grep -q "</html>" "$work/r.html" && ok || bad "html incomplete"
else
  bad "html report failed"; cat "$work/stderr"
fi

finish cli_coefficients
