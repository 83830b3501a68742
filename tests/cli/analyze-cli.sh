#!/usr/bin/env bash
# roadload analyze as a user runs it: help, errors with their exit codes, and a simulated drive
# analysed into cells.csv and trip.json whose cells are the simulator's.
set -euo pipefail
roadload=${1:?usage: analyze-cli.sh ROADLOAD_BIN}
# shellcheck source=cli-lib.sh source-path=SCRIPTDIR
. "$(dirname "${BASH_SOURCE[0]}")/cli-lib.sh" analyze-cli

expect_status 0 "$roadload" analyze --help
grep -q -- "--route" "$work/out" || fail "--help does not describe --route"
expect_status 64 "$roadload" analyze --out "$work/res"
expect_status 66 "$roadload" analyze "$work/none" --out "$work/res"
grep -q "none: No such file" "$work/err" || fail "a missing recording is not named: $(cat "$work/err")"
printf 'name = "bad"\n[[point]]\nlat_deg = 95\nlon_deg = 0\nelev_m = 0\n' >"$work/bad.toml"
expect_status 65 "$roadload" analyze "$work/none" --route "$work/bad.toml" --out "$work/res"
grep -q "bad.toml" "$work/err" || fail "route error does not name the file: $(cat "$work/err")"

"$roadload" simulate --scenario th66-55mph --seed 5 --out "$work/rec" --truth "$work/truth" -q ||
  fail "simulate failed"
expect_status 0 "$roadload" analyze "$work/rec" --route th66-good-thunder --out "$work/res" --truth "$work/truth"
head -1 "$work/res/cells.csv" | grep -q "^cell,start_m,end_m,samples,crr,crr_lo,crr_hi" || fail "cells.csv header"
cmp -s <(cut -d, -f1 "$work/res/cells.csv") <(cut -d, -f1 "$work/truth/cells.csv") ||
  fail "analysed cells are not the simulator's cells"
grep -q '"crr":' "$work/res/trip.json" || fail "trip.json has no crr"
python3 -c 'import json, sys; json.load(open(sys.argv[1]))["dynamic_rolling"]["groups"]' "$work/res/trip.json" ||
  fail "trip.json is not JSON or lacks dynamic_rolling.groups"
head -1 "$work/res/cells.csv" | grep -q ",damper_power_w,tire_power_w," || fail "cells.csv lacks the dynamic power columns"
accels=$(grep -c "kind = .accelerometer." "$work/rec/meta.toml")
[[ $(head -1 "$work/res/psd.csv" | tr ',' '\n' | wc -l) -eq $((accels + 1)) ]] || fail "psd.csv: not one column per accelerometer"
head -1 "$work/res/psd.csv" | grep -q "^freq_hz,TLF1," || fail "psd.csv header: $(head -1 "$work/res/psd.csv")"
[[ -s $work/res/psd-bituminous.csv && -s $work/res/psd-spatial-bituminous.csv ]] || fail "no PSD per pavement group"
grep -q "dampers.*against the truth\|against the truth.*dampers" "$work/err" || fail "no damper power against the truth"
grep -q "RMSE" "$work/err" || fail "no comparison with the truth printed"
mkdir -p "$work/badtruth"
printf 'cell,crr,damper_power_w,tire_power_w,time_s\nTH66-01,abc,1,2,3\n' >"$work/badtruth/cells.csv"
expect_status 65 "$roadload" analyze "$work/rec" --route th66-good-thunder --out "$work/res2" --truth "$work/badtruth"
grep -q "badtruth/cells.csv:2: crr: expected a number" "$work/err" || fail "bad truth row not named: $(cat "$work/err")"
expect_csv "$work/res"
echo "analyze-cli: PASS"
