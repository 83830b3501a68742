#!/usr/bin/env bash
# roadload vehicle identify as a user runs it: the 18-speed tractor driven on the Mainline, its
# vehicle file written from the drive with notes on what was identified, read back by analyze;
# errors with their exit codes.
set -euo pipefail
roadload=${1:?usage: vehicle-cli.sh ROADLOAD_BIN}
# shellcheck source=cli-lib.sh source-path=SCRIPTDIR
. "$(dirname "${BASH_SOURCE[0]}")/cli-lib.sh" vehicle-cli

expect_status 0 "$roadload" vehicle --help
for o in --out --vehicle --name --dbc; do grep -q -- "$o" "$work/out" || fail "--help does not describe $o"; done
expect_status 64 "$roadload" vehicle
expect_status 64 "$roadload" vehicle guess "$work/x"
expect_status 64 "$roadload" vehicle identify --out "$work/v.toml"
expect_status 66 "$roadload" vehicle identify "$work/no-such-recording" --out "$work/v.toml"

"$roadload" simulate --scenario mnroad-mainline-30mph --vehicle tractor-53ft-18speed --duration 150 --seed 4 \
  --out "$work/rec" -q || fail "simulate failed"
expect_status 0 "$roadload" vehicle identify "$work/rec" --out "$work/mine.toml"
grep -q '^name = "mine"$' "$work/mine.toml" || fail "the vehicle is not named after its file"
grep -q '^# identified: 2508.0 +- 0.5 N m from EC1 SPN 544' "$work/mine.toml" || fail "the reference torque is not noted as identified"
grep -q '^# identified: .* m from GNSS speed' "$work/mine.toml" || fail "the tire radius is not noted as identified"
grep -q "ETC2 SPN 526 in gear" "$work/mine.toml" || fail "no gear ratio noted as identified"
grep -q '^reference_torque_nm' "$work/out" || fail "no table printed: $(cat "$work/out")"
grep -q "not identified: mass: CVW" "$work/err" || fail "the mass the bus does not send is not said: $(cat "$work/err")"
grep -q "not identified: vin:" "$work/err" || fail "the missing VIN is not said"
# The radius identified is the tractor file's 0.50 m within 0.3 %: this simulated truck is its file.
radius=$(awk '/^# identified: .* m from GNSS speed/ { getline; print $3; exit }' "$work/mine.toml")
awk -v r="$radius" 'BEGIN { exit !(r > 0.50 * 0.997 && r < 0.50 * 1.003) }' || fail "drive tire radius $radius, the truth 0.50"
echo "vehicle-cli: drive tire radius identified $radius m (the truck's 0.50)"
# The file written is a vehicle file every command takes.
expect_status 0 "$roadload" analyze "$work/rec" --route mnroad-mainline-westbound --vehicle "$work/mine.toml" --out "$work/a" -q
# A recording that describes no truck needs a prior.
mkdir "$work/bare"
cp "$work/rec/can.log" "$work/rec/gnss.csv" "$work/bare/"
awk '/^\[+/ { drop = /^\[+vehicle\.file/ } !drop' "$work/rec/meta.toml" >"$work/bare/meta.toml"
expect_status 64 "$roadload" vehicle identify "$work/bare" --out "$work/v.toml"
grep -q "give the nearest vehicle file as the prior" "$work/err" || fail "no prior asked for: $(cat "$work/err")"
echo "vehicle-cli: PASS"
