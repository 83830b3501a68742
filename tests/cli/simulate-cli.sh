#!/usr/bin/env bash
# roadload simulate as a user runs it: help, lists, errors with their exit codes, and a short
# recording that `roadload decode` reads back.
set -euo pipefail
roadload=${1:?usage: simulate-cli.sh ROADLOAD_BIN}
# shellcheck source=cli-lib.sh source-path=SCRIPTDIR
. "$(dirname "${BASH_SOURCE[0]}")/cli-lib.sh" simulate-cli

expect_status 0 "$roadload" simulate --help
grep -q -- "--effect NAME" "$work/out" || fail "--help does not describe --effect"
expect_status 0 "$roadload" simulate --list-effects
effects=$(($(wc -l <"$work/out") - 1))
((effects >= 13)) || fail "--list-effects lists $effects effects"
expect_status 0 "$roadload" simulate --list-scenarios
for s in mnroad-mainline-30mph mnroad-mainline-64mph th10-55mph th66-55mph; do
  grep -q "^$s " "$work/out" || fail "--list-scenarios misses $s"
done
expect_status 64 "$roadload" simulate --out "$work/x"
expect_status 64 "$roadload" simulate --scenario th66-55mph --out "$work/x" --effect no-such-effect=1
grep -q "unknown effect 'no-such-effect'" "$work/err" || fail "bad effect message: $(cat "$work/err")"
expect_status 64 "$roadload" simulate --scenario th66-55mph --out "$work/x" --effect wind-gusts=lots
expect_status 66 "$roadload" simulate --scenario no-such-scenario --out "$work/x"
grep -q "no-such-scenario" "$work/err" || fail "missing scenario not named"

expect_status 0 "$roadload" simulate --scenario th66-55mph --seed 3 --duration 5 --out "$work/rec" --truth "$work/truth" \
  --effect wind-gusts --effect torque-bias=0.02 -q
for f in meta.toml can.log accel.csv gnss.csv weather.csv; do [[ -s $work/rec/$f ]] || fail "recording lacks $f"; done
for f in series.csv axles.csv cells.csv truth.toml; do [[ -s $work/truth/$f ]] || fail "truth lacks $f"; done
head -1 "$work/truth/cells.csv" | grep -q "^cell,.*crr,damper_power_w,tire_power_w" || fail "cells.csv header"
grep -q "torque-bias = 0.02" "$work/truth/truth.toml" || fail "truth.toml does not list the effect"
grep -qiE "torque-bias|wind-gusts|effects" "$work/rec/meta.toml" && fail "meta.toml reveals an effect"
expect_status 0 "$roadload" decode --pgn-stats "$work/rec"
grep -q "^61444,EEC1," "$work/out" || fail "decode finds no EEC1 in the simulated log"
cp "$work/out" "$work/pgn-stats.csv"
expect_csv "$work/rec" "$work/truth" "$work/pgn-stats.csv"
echo "simulate-cli: PASS"
