#!/usr/bin/env bash
# roadloadd as an operator meets it: --help, the effective settings, clear refusals of bad input,
# a replayed drive recorded and reported on the host (no CAN interface needed: --replay-can), and
# the systemd unit as systemd itself checks it.
# usage: roadloadd-cli.sh ROADLOADD_BIN ROADLOAD_BIN UNIT_FILE
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=cli-lib.sh source-path=SCRIPTDIR
. "$here/cli-lib.sh" roadloadd-cli
roadloadd=$(realpath "${1:?usage: roadloadd-cli.sh ROADLOADD_BIN ROADLOAD_BIN UNIT_FILE}")
roadload=${2:?}
unit=${3:?}

expect_status 0 "$roadloadd" --help
grep -q -- '--data-dir DIR' "$work/out" || fail "--help does not describe --data-dir"
expect_status 0 "$roadloadd" --print-config --can vcan0 --can vcan1 --data-dir /srv/rec
grep -c '^interface = "vcan' "$work/out" | grep -qx 2 || fail "--print-config does not show both --can buses"
grep -q '^data_dir = "/srv/rec"' "$work/out" || fail "--print-config does not show --data-dir"

expect_status 2 "$roadloadd" --can
grep -q 'command line: --can: needs an interface name' "$work/err" || fail "bad --can: $(cat "$work/err")"
printf '[status]\ninterval_s = 0\n' >"$work/bad.toml"
expect_status 2 "$roadloadd" --config "$work/bad.toml"
grep -q "$work/bad.toml: status.interval_s: expected 0.1 to 60" "$work/err" || fail "bad config: $(cat "$work/err")"
printf '[status]\ninterval_s = "1"\n' >"$work/bad2.toml"
expect_status 2 "$roadloadd" --config "$work/bad2.toml"
grep -q "$work/bad2.toml:2: status.interval_s: expected a number" "$work/err" || fail "bad config: $(cat "$work/err")"

# A replayed drive: recorded frame for frame, reported every second with the live CRR.
"$roadload" simulate --scenario mnroad-mainline-30mph --seed 3 --duration 30 --out "$work/sim" -q
expect_status 0 "$roadloadd" --replay "$work/sim" --replay-can --replay-rate 10 --exit-when-done \
  --route mnroad-mainline-westbound --data-dir "$work/rec" --status "$work/status.log" --status-json "$work/status.jsonl"
seg=("$work"/rec/*/)
((${#seg[@]} == 1)) || fail "expected one segment, got ${#seg[@]}"
cmp -s <(cut -d' ' -f3 "$work/sim/can.log") <(cut -d' ' -f3 "${seg[0]}can.log") || fail "recorded CAN differs from the replayed"
cmp -s <(cut -d, -f2- "$work/sim/accel.csv") <(cut -d, -f2- "${seg[0]}accel.csv") || fail "recorded accelerometers differ"
grep -Eq '\| speed 13\.[0-9]+ m/s cell [^ ]+ crr 0\.[0-9]{5} \[0\.[0-9]{5} 0\.[0-9]{5}\]' "$work/status.log" ||
  fail "no status line with speed and CRR: $(tail -n 2 "$work/status.log")"
tail -n 1 "$work/status.jsonl" | grep -q '"lines_lost":0' || fail "the last JSON status line does not report 0 lines lost"
# Every JSON line parses.
/usr/bin/python3 -c 'import json,sys; [json.loads(l) for l in open(sys.argv[1])]' "$work/status.jsonl" ||
  fail "status.jsonl has a line that is not JSON"

# The unit file, with ExecStart pointing at this build, passes systemd's own checks.
if command -v systemd-analyze >/dev/null; then
  sed "s|/usr/sbin/roadloadd|$roadloadd|" "$unit" >"$work/roadloadd.service"
  expect_status 0 systemd-analyze verify "$work/roadloadd.service"
  [[ ! -s $work/err ]] || fail "systemd-analyze verify: $(cat "$work/err")"
  systemd-analyze security --offline=yes "$work/roadloadd.service" >"$work/security" 2>&1 || true
  exposure=$(sed -n 's/.*Overall exposure level for roadloadd.service: \([0-9.]*\).*/\1/p' "$work/security")
  awk -v e="$exposure" 'BEGIN { exit !(e != "" && e <= 3.0) }' || fail "systemd exposure level '$exposure' (want <= 3.0)"
  echo "roadloadd-cli: unit verified, systemd exposure $exposure"
fi
echo "roadloadd-cli: PASS"
