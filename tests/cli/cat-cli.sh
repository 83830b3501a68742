#!/usr/bin/env bash
# roadload cat gives each stream of a recording back as its text, however it is stored: plain,
# zstd frames or the accelerometers' FLAC files; damage is reported with exit status 65 and the
# rest still written.
# usage: cat-cli.sh ROADLOAD_BIN
set -euo pipefail
roadload=${1:?usage: cat-cli.sh ROADLOAD_BIN}
. "$(dirname "$0")/cli-lib.sh" cat-cli

"$roadload" simulate --scenario mnroad-mainline-30mph --seed 5 --duration 20 --out "$work/text" -q
"$roadload" simulate --scenario mnroad-mainline-30mph --seed 5 --duration 20 --out "$work/flac" --accel-format flac -q
cp -r "$work/text" "$work/zst"
for f in "$work"/zst/*.csv "$work"/zst/can.log; do zstd -q --rm "$f"; done

for s in can.log accel.csv gnss.csv weather.csv; do
  expect_status 0 "$roadload" cat "$s" "$work/zst"
  cmp -s "$work/out" "$work/text/$s" || fail "cat $s of zstd frames is not the plain $s"
done
expect_status 0 "$roadload" cat accel.csv "$work/flac" -o "$work/from-flac.csv"
[[ $(head -n 1 "$work/from-flac.csv") == t_ns,sensor,x_mps2,y_mps2,z_mps2 ]] || fail "accel.csv from FLAC lacks its header"
# The same lines: samples of two sensors stamped in the same nanosecond come out by sensor id
# from FLAC, in the order the simulator took them in its text.
cmp -s <(sort "$work/from-flac.csv") <(sort "$work/text/accel.csv") || fail "accel.csv from FLAC is not the text recording's"
lines=$(wc -l <"$work/text/accel.csv")

# A FLAC file cut inside a frame: its whole frames and every other sensor are written, the cut named.
first=$(ls "$work"/flac/accel-*.flac | head -n 1)
truncate -s -100 "$first"
expect_status 65 "$roadload" cat accel.csv "$work/flac"
grep -q "${first##*/}" "$work/err" || fail "the cut file is not named: $(cat "$work/err")"
got=$(wc -l <"$work/out")
((got < lines && got > lines * 7 / 8)) || fail "a cut file gave $got of $lines lines"

expect_status 64 "$roadload" cat accel "$work/text"
grep -q "STREAM must be" "$work/err" || fail "a wrong stream name is not explained: $(cat "$work/err")"
expect_status 66 "$roadload" cat can.log "$work/missing"
expect_status 73 "$roadload" cat can.log "$work/text" -o "$work/no/such/dir/can.log"
echo "cat-cli: PASS"
