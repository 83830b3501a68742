#!/usr/bin/env bash
# roadload gap as a user runs it: a short drive with an effect it is not told, diagnosed from the
# recording alone after the ground-truth folder is gone; the JSON's fields; bad input refused.
set -euo pipefail
roadload=${1:?usage: gap-cli.sh ROADLOAD_BIN}
# shellcheck source=cli-lib.sh source-path=SCRIPTDIR
. "$(dirname "${BASH_SOURCE[0]}")/cli-lib.sh" gap-cli
export ROADLOAD_CACHE_DIR=$work/cache

expect_status 0 "$roadload" gap --help
grep -q -- "--real DIR" "$work/out" || fail "--help does not describe --real"
expect_status 64 "$roadload" gap
expect_status 64 "$roadload" gap --real "$work/rec" --model a --model b --real "$work/rec2" --model c
expect_status 64 "$roadload" gap bench --cases 10 --case 11
grep -q -- "--case 11: the draw has 10 cases" "$work/err" || fail "a case beyond the draw not named: $(cat "$work/err")"
expect_status 66 "$roadload" gap --real "$work/no-such-recording"
grep -q "no-such-recording" "$work/err" || fail "missing recording not named: $(cat "$work/err")"

# The engine reports 4 % more torque than it makes: the one effect that moves torque and not fuel.
expect_status 0 "$roadload" simulate --scenario mnroad-mainline-30mph --seed 21 --duration 120 --out "$work/rec" \
  --truth "$work/truth" --effect torque-bias=0.04 -q
rm -rf "$work/truth"
expect_status 0 "$roadload" gap --real "$work/rec" --noise-runs 3 --jobs 2 --json "$work/gap.json" --features "$work/f.csv" -q
[[ ! -e $work/truth ]] || fail "the diagnosis recreated the truth folder"
grep -q "model mnroad-mainline-30mph" "$work/out" || fail "the model scenario was not found from the GNSS track: $(head -3 "$work/out")"
grep -q "^effect: torque-bias" "$work/out" || fail "torque-bias not named: $(grep -A8 '^candidates' "$work/out")"
named=$(grep -A1 "^effect:" "$work/out" | tail -n 1 | sed "s/^ *//")
python3 - "$work/gap.json" "$roadload" <<'PY'
import json, subprocess, sys
g = json.load(open(sys.argv[1]))
names = [l.split()[0] for l in subprocess.run([sys.argv[2], "simulate", "--list-effects"], capture_output=True,
                                               text=True, check=True).stdout.splitlines()[1:]]
for key in ("effect", "magnitude", "where", "residual_before", "residual_after"):
    assert key in g, f"gap.json lacks {key}"
assert g["effect"] in names, f"effect {g['effect']} is not a --list-effects name"
assert 0.03 < g["magnitude"] < 0.05, f"torque-bias fitted as {g['magnitude']}"
assert g["interval"][0] < 0.04 < g["interval"][1] or abs(g["magnitude"] - 0.04) < 0.003, g["interval"]
assert g["where"] and g["where"][0]["channel"] == "torque_nm", g["where"][:2]
assert g["residual_after"] < 0.5 * g["residual_before"] < 0.5 * g["residual_raw"], (g["residual_raw"], g["residual_before"], g["residual_after"])
# What no feature sees is left out and said so, never fitted; a rival is a fitted candidate.
unseen = {e["name"] for e in g["not_fitted"]}
assert unseen == {"wind-gusts", "can-accel-offset", "fan-engagement", "drafting"}, unseen
assert all(e["why"] for e in g["not_fitted"]), g["not_fitted"]
fitted = {c["name"] for c in g["candidates"]}
assert not fitted & unseen and fitted | unseen == set(names), (fitted, unseen)
assert all(r["name"] in fitted and r["name"] != g["effect"] for r in g["rivals"]), g["rivals"]
PY
head -1 "$work/f.csv" | grep -qx "run,channel,where,half,real,model,sigma,z,calibrated,after" || fail "features CSV header"
expect_csv "$work/f.csv"

# The library is kept for the next drive of this truck on this road: the same drive again reads it
# and says the same; a damaged library is named, removed and built again.
cp "$work/out" "$work/first"
ls "$work"/cache/*.lib >/dev/null || fail "no library stored in the cache: $(ls -la "$work/cache")"
expect_status 0 "$roadload" gap --real "$work/rec" --noise-runs 3 --jobs 2
grep -q "^gap: library read from $work/cache/" "$work/err" || fail "the stored library was not read: $(cat "$work/err")"
cmp -s "$work/out" "$work/first" || fail "the cached library changed the diagnosis: $(diff "$work/first" "$work/out")"
sed -i '2s/\t[^\t]*$/\tgarbage/' "$work"/cache/*.lib
expect_status 0 "$roadload" gap --real "$work/rec" --noise-runs 3 --jobs 2 -q
grep -q "^roadload gap: cache: $work/cache/[0-9a-f-]*\.lib:2: .*not a number: 'garbage' (removed)" "$work/err" ||
  fail "the damaged library was not named: $(cat "$work/err")"
cmp -s "$work/out" "$work/first" || fail "the rebuilt library changed the diagnosis: $(diff "$work/first" "$work/out")"

# A neutral coast-down is compared with a coast, never with the cruise nearest its mean speed: the
# Mainline's own coast scenario, and on TH 10 (which has none) its cruise turned into a coast-down
# from the recording's first speed.
expect_status 0 "$roadload" gap --real "$work/rec" --dry-run
grep -q "model mnroad-mainline-30mph (route [^)]*)," "$work/out" || fail "the cruise's model: $(cat "$work/out")"
grep -q "coast-down" "$work/out" && fail "the cruise taken for a coast-down: $(cat "$work/out")"
expect_status 0 "$roadload" simulate --scenario mnroad-mainline-coast-64mph --seed 24 --duration 60 --out "$work/coast" -q
expect_status 0 "$roadload" gap --real "$work/coast" --dry-run
grep -q "model mnroad-mainline-coast-64mph (route [^)]*, coast-down)" "$work/out" ||
  fail "the Mainline coast-down's model: $(cat "$work/out")"
config=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../config" && pwd)
printf 'name = "th10-coast"\nroute = "%s"\nmode = "coast"\nspeed_mph = 52\nstart_m = 50\nduration_s = 60\nstart_utc = 2014-06-20T16:00:00Z\n' \
  "$config/routes/th10-sartell.toml" >"$work/th10-coast.toml"
expect_status 0 "$roadload" simulate --scenario "$work/th10-coast.toml" --seed 25 --out "$work/th10-coast" -q
expect_status 0 "$roadload" gap --real "$work/th10-coast" --dry-run
grep -q "model th10-55mph (route TH 10, Sartell, coast-down)" "$work/out" || fail "the TH 10 coast-down's model: $(cat "$work/out")"

# A road no built-in scenario drives, by a truck of the recording's own vehicle file: no --model,
# the model drives the road the drive's GNSS traces. One pass's heights and a road of unknown
# pavement are not a model to blame effects on: the places are ranked, no effect is named.
printf 'name = "county"\nroute = "%s"\nvehicle = "%s"\nspeed_mph = 40\nstart_m = 100\nduration_s = 90\n' \
  "$config/routes/example-county-road-eastbound.toml" "$config/vehicles/tractor-53ft-18speed.toml" >"$work/county.toml"
expect_status 0 "$roadload" simulate --scenario "$work/county.toml" --seed 22 --out "$work/county" -q
# Its library, built here, is not kept: --no-cache neither reads nor stores one.
libraries=$(ls "$work"/cache/*.lib | wc -l)
expect_status 0 "$roadload" gap --real "$work/county" --noise-runs 3 --jobs 2 --json "$work/county.json" --no-cache
grep -q "read from\|stored in" "$work/err" && fail "--no-cache used the cache: $(cat "$work/err")"
[[ $(ls "$work"/cache/*.lib | wc -l) == "$libraries" ]] || fail "--no-cache stored a library: $(ls "$work/cache")"
grep -q "model traced (route traced from county)" "$work/out" || fail "the county drive's model: $(head -3 "$work/out")"
grep -q "^where the gap lies" "$work/out" || fail "no diagnosis of the county drive: $(cat "$work/out")"
grep -q "^effect: none named: county: the model's road is traced" "$work/out" ||
  fail "an effect named on a traced road: $(grep -A2 '^effect' "$work/out")"
python3 -c 'import json, sys; g = json.load(open(sys.argv[1])); sys.exit(1 if g["unmatched"] or not g["withheld"] or g["effect"] else 0)' \
  "$work/county.json" ||
  fail "the county drive's sensors did not all meet the model's: $(grep -A9 '^not compared' "$work/out")"

# The same road given as the user's route file, driven by a truck that is not the model's: 15 %
# more drag area and 10 % less engine friction than its vehicle file, and no unmodelled effect.
# The nominal calibration finds the truck; no effect is blamed for it.
printf 'name = "county-other-truck"\nroute = "%s"\nvehicle = "%s"\nspeed_mph = 50\nstart_m = 100\nduration_s = 200\ncda_scale = 1.15\nengine_friction_scale = 0.9\n' \
  "$config/routes/example-county-road-eastbound.toml" "$config/vehicles/tractor-53ft-18speed.toml" >"$work/other.toml"
expect_status 0 "$roadload" simulate --scenario "$work/other.toml" --seed 23 --out "$work/other" -q
expect_status 0 "$roadload" gap --real "$work/other" --route example-county-road-eastbound --noise-runs 6 --jobs 2 \
  --json "$work/other.json" -q
grep -q "model Example county road, eastbound lane" "$work/out" || fail "the route's model: $(head -3 "$work/out")"
grep -q "^the model's truck against this one" "$work/out" || fail "no nominal rows: $(head -12 "$work/out")"
python3 - "$work/other.json" <<'PY' || fail "the other truck: $(sed -n '/^the model/,/^where/p' "$work/out")"
import json, sys
g = json.load(open(sys.argv[1]))
assert g["withheld"] is None and g["effect"] is None, (g["withheld"], g["effect"])
rows = {r["name"]: r for r in g["nominal"]}
for name, truth in (("CdA", 5.8 * 1.15), ("engine friction", 0.9)):
    r = rows[name]
    assert r["lo"] <= truth <= r["hi"], (name, truth, r)
assert abs(rows["CdA"]["fitted"] - 5.8 * 1.15) < abs(5.8 - 5.8 * 1.15), rows["CdA"]
assert g["residual_before"] < 0.5 * g["residual_raw"], (g["residual_raw"], g["residual_before"])
PY

# A damaged line is skipped and named as every command skips it; the diagnosis goes on (from the
# cached library) and the exit status tells of the damage. A recording damaged beyond 1 % of its
# lines is refused.
cp -r "$work/rec" "$work/bad"
sed -i '20s/.*/(12.5) can0 not-a-frame/' "$work/bad/can.log"
expect_status 65 "$roadload" gap --real "$work/bad" --noise-runs 3 --jobs 2 -q
grep -q "can.log:20" "$work/err" || fail "damaged line not named: $(cat "$work/err")"
grep -q "1 malformed lines skipped" "$work/err" || fail "the count of skipped lines not told: $(cat "$work/err")"
grep -q "^effect: torque-bias" "$work/out" || fail "one damaged line stopped the diagnosis: $(grep -A3 '^effect' "$work/out")"
sed -i '0~40s/.*/garbage/' "$work/bad/can.log"
expect_status 65 "$roadload" gap --real "$work/bad" --noise-runs 3 --jobs 2 -q
grep -q "more than 1 %, too damaged to diagnose" "$work/err" || fail "a badly damaged recording was diagnosed: $(cat "$work/err")"
echo "gap-cli: PASS: $named"
