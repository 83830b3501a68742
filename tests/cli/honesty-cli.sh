#!/usr/bin/env bash
# No confident wrong answers: a drive the model cannot place or does not fit is reported as not
# identified, with every reason; an impossible input is refused with its file, line and field; no
# result holds a bare NaN.
# usage: honesty-cli.sh ROADLOAD_BIN TRACES_DIR
set -euo pipefail
roadload=${1:?usage: honesty-cli.sh ROADLOAD_BIN TRACES_DIR}
traces=${2:?usage: honesty-cli.sh ROADLOAD_BIN TRACES_DIR}
# shellcheck source=cli-lib.sh source-path=SCRIPTDIR
. "$(dirname "${BASH_SOURCE[0]}")/cli-lib.sh" honesty-cli

# JSON as the standard has it: NaN and Infinity are not JSON.
strict_json() {
  python3 -c 'import json, sys
def bad(c): raise ValueError("bare " + c)
json.load(open(sys.argv[1]), parse_constant=bad)' "$1" || fail "$1 is not strict JSON"
}
no_cell_identified() {
  python3 -c 'import csv, sys
rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["identified"] == "1"]
sys.exit(1 if rows else 0)' "$1" || fail "$1 has a cell marked identified"
}

# Real trucks' CAN logs (CSS Electronics, MIT), each a recording of CAN alone: never a number marked
# identified, and the reason said.
for trace in "$traces"/*.log; do
  name=$(basename "$trace" .log)
  mkdir -p "$work/$name"
  cp "$trace" "$work/$name/can.log"
  expect_status 0 "$roadload" analyze "$work/$name" --out "$work/$name-res" -q
  grep -q "NOT identified" "$work/err" || fail "$name: not said to be unidentified: $(cat "$work/err")"
  grep -q "cannot be placed" "$work/err" || fail "$name: the reason is missing: $(cat "$work/err")"
  strict_json "$work/$name-res/trip.json"
  python3 -c 'import json, sys; t = json.load(open(sys.argv[1])); sys.exit(t["crr_identified"] or not t["not_identified"])' \
    "$work/$name-res/trip.json" || fail "$name: trip.json says identified or gives no reason"
  no_cell_identified "$work/$name-res/cells.csv"
  # On a route it does not lie on, the same: the GNSS check names it.
  expect_status 0 "$roadload" analyze "$work/$name" --route mnroad-mainline-westbound --out "$work/$name-route" -q
  grep -q "not placed on the route" "$work/err" || fail "$name on a route: $(cat "$work/err")"
  no_cell_identified "$work/$name-route/cells.csv"
  strict_json "$work/$name-route/trip.json"
done

# Options that are not finite numbers: usage errors naming the option.
expect_status 64 "$roadload" analyze "$work/none" --out "$work/r" --mass nan
grep -q -- "--mass: 'nan' is not a finite number" "$work/err" || fail "--mass nan: $(cat "$work/err")"
expect_status 64 "$roadload" analyze "$work/none" --out "$work/r" --cda inf
grep -q -- "--cda: 'inf' is not a finite number" "$work/err" || fail "--cda inf: $(cat "$work/err")"

# Impossible values in a recording: data errors naming file, line and field.
"$roadload" simulate --scenario mnroad-mainline-30mph --seed 3 --duration 40 --out "$work/rec" -q 2>/dev/null ||
  fail "simulate failed"
expect_status 0 "$roadload" analyze "$work/rec" --route mnroad-mainline-westbound --out "$work/ok" -q
strict_json "$work/ok/trip.json"
for mass in 0 inf -5 1e9; do
  rm -rf "$work/badmass" && cp -r "$work/rec" "$work/badmass"
  sed -i "s/^mass_kg = .*/mass_kg = $mass/" "$work/badmass/meta.toml"
  line=$(grep -n '^mass_kg' "$work/badmass/meta.toml" | cut -d: -f1)
  expect_status 65 "$roadload" analyze "$work/badmass" --route mnroad-mainline-westbound --out "$work/r" -q
  grep -q "badmass/meta.toml:$line: vehicle.mass_kg:" "$work/err" || fail "mass_kg = $mass: $(cat "$work/err")"
done
rm -rf "$work/cold" && cp -r "$work/rec" "$work/cold"
awk -F, 'BEGIN { OFS = "," } NR == 3 { $3 = "-273.15" } { print }' "$work/rec/weather.csv" >"$work/cold/weather.csv"
expect_status 65 "$roadload" analyze "$work/cold" --route mnroad-mainline-westbound --out "$work/cold-res" -q
grep -q "cold/weather.csv:3: air_temp_c: air temperature out of range" "$work/err" || fail "-273.15 C: $(cat "$work/err")"
strict_json "$work/cold-res/trip.json"
printf 'rpm,loss_nm,sigma_nm,friction_nm\n650,150,1e300,100\n' >"$work/losses.csv"
expect_status 65 "$roadload" analyze "$work/rec" --route mnroad-mainline-westbound --engine-losses "$work/losses.csv" --out "$work/r" -q
grep -q "losses.csv:2: sigma_nm:" "$work/err" || fail "sigma 1e300: $(cat "$work/err")"
echo "honesty-cli: PASS"
