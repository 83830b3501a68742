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

# roadload replay refuses a bad fault before touching any interface, naming the item.
expect_status 64 "$roadload" replay "$work/none" --faults 'drop=0.01,meteor@5'
grep -q -- '--faults: meteor@5: unknown fault' "$work/err" || fail "bad --faults: $(cat "$work/err")"
expect_status 64 "$roadload" replay "$work/none" --faults 'busoff@20'
grep -q -- '--faults: busoff@20: expected a time and a positive duration' "$work/err" || fail "bad --faults: $(cat "$work/err")"

expect_status 64 "$roadloadd" --can
grep -q 'command line: --can: 1 required IFACE missing' "$work/err" || fail "bad --can: $(cat "$work/err")"
printf '[status]\ninterval_s = 0\n' >"$work/bad.toml"
expect_status 78 "$roadloadd" --config "$work/bad.toml"
grep -q "$work/bad.toml: status.interval_s: expected 0.1 to 60" "$work/err" || fail "bad config: $(cat "$work/err")"
printf '[status]\ninterval_s = "1"\n' >"$work/bad2.toml"
expect_status 78 "$roadloadd" --config "$work/bad2.toml"
grep -q "$work/bad2.toml:2: status.interval_s: expected a number" "$work/err" || fail "bad config: $(cat "$work/err")"
# The truck's calibration is read at start: a missing table stops the daemon, naming it.
printf '[estimator]\nroute = "mnroad-mainline-westbound"\nengine_losses = "%s/no-losses.csv"\n' "$work" >"$work/cal.toml"
expect_status 1 "$roadloadd" --config "$work/cal.toml" --data-dir "$work/rec-cal" --status "$work/cal.log"
grep -q "no-losses.csv" "$work/err" || fail "missing engine-loss table not named: $(cat "$work/err")"

# A replayed drive: recorded frame for frame, reported every second with the live CRR.
# A status line every 0.1 s: at three times real time, the first 3 s of the drive (before its CRR
# is known) span ten of them. At ten times they spanned three, which a loaded machine (CI's
# sanitizer tests) could delay past the CRR's identification.
"$roadload" simulate --scenario mnroad-mainline-30mph --seed 3 --duration 30 --out "$work/sim" -q
printf '[status]\ninterval_s = 0.1\n' >"$work/fast-status.toml"
expect_status 0 "$roadloadd" --config "$work/fast-status.toml" --replay "$work/sim" --replay-can --replay-rate 3 --exit-when-done \
  --route mnroad-mainline-westbound --data-dir "$work/rec" --status "$work/status.log" --status-json "$work/status.jsonl"
seg=("$work"/rec/*/)
((${#seg[@]} == 1)) || fail "expected one segment, got ${#seg[@]}"
"$support/unpack-streams" "${seg[@]}" || fail "the daemon's streams are not zstd frames zstd reads back"
cmp -s <(cut -d' ' -f3 "$work/sim/can.log") <(cut -d' ' -f3 "${seg[0]}can.log") || fail "recorded CAN differs from the replayed"
cmp -s <(cut -d, -f2- "$work/sim/accel.csv") <(cut -d, -f2- "${seg[0]}accel.csv") || fail "recorded accelerometers differ"
grep -Eq '\| speed 13\.[0-9]+ m/s cell [^ ]+ crr 0\.[0-9]{5} \[0\.[0-9]{5} 0\.[0-9]{5}\]' "$work/status.log" ||
  fail "no status line with speed and CRR: $(tail -n 2 "$work/status.log")"
tail -n 1 "$work/status.jsonl" | grep -q '"lines_lost":0' || fail "the last JSON status line does not report 0 lines lost"
# Every JSON line parses.
/usr/bin/python3 -c 'import json,sys; [json.loads(l) for l in open(sys.argv[1])]' "$work/status.jsonl" ||
  fail "status.jsonl has a line that is not JSON"
# Early in the drive the CRR is not identified yet, and the status says which check holds it back.
grep -Eq 'WARN CRR not identified yet: (its uncertainty exceeds the limit|the drive is not placed on the route)' "$work/status.log" ||
  fail "no status line says why the CRR is not identified: $(grep -m1 'not identified' "$work/status.log")"
grep -q '"crr_not_identified":"' "$work/status.jsonl" || fail "status.jsonl never names why the CRR is not identified"

# SIGHUP (logrotate): the status files are reopened by name and the segment goes on; SIGUSR1 starts
# a new segment; SIGTERM flushes and exits cleanly with everything recorded.
"$roadloadd" --replay "$work/sim" --replay-can --data-dir "$work/rec2" --status "$work/s.log" --status-json '' 2>/dev/null &
pid=$!
for _ in $(seq 50); do [[ -s $work/s.log ]] && (($(wc -l <"$work/s.log") >= 2)) && break; sleep 0.1; done
# A second daemon on the same data directory is refused while the first runs, naming the holder.
expect_status 1 "$roadloadd" --replay "$work/sim" --replay-can --data-dir "$work/rec2" --status "$work/s2.log" --status-json ''
grep -q "in use by another roadloadd (pid $pid)" "$work/err" || fail "second daemon on one data directory: $(cat "$work/err")"
mv "$work/s.log" "$work/s.log.1"
kill -HUP "$pid"
for _ in $(seq 30); do [[ -s $work/s.log ]] && break; sleep 0.1; done
[[ -s $work/s.log ]] || fail "after SIGHUP no new status log was opened"
segs=("$work"/rec2/*/)
((${#segs[@]} == 1)) || fail "SIGHUP cut the recording: ${#segs[@]} segments"
kill -USR1 "$pid"
sleep 1.2
kill -TERM "$pid"
rc=0
wait "$pid" || rc=$?
((rc == 0)) || fail "roadloadd exited $rc on SIGTERM"
grep -q '^roadloadd stopped: [0-9]* lines recorded, 0 lost' "$work/s.log" || fail "no clean stop line: $(tail -n 1 "$work/s.log")"
segs=("$work"/rec2/*/)
((${#segs[@]} == 2)) || fail "SIGUSR1 should start a second segment; found ${#segs[@]}"
# Read compressed, as roadloadd wrote them: zstdcat gives the text, the commands read the frames.
frames=$(zstdcat "$work"/rec2/*/can.log.zst | wc -l)
((frames > 0)) || fail "nothing recorded across the signals"
cmp -s <(zstdcat "$work"/rec2/*/can.log.zst | cut -d' ' -f3) <(head -n "$frames" "$work/sim/can.log" | cut -d' ' -f3) ||
  fail "the two segments together are not the drive's first $frames frames"
# Given both segments, in either order, the commands read them as one drive: decode prints every
# frame once, in order; a recording of another run, or one segment twice, is refused (64).
expect_status 0 "$roadload" decode --pgn-stats "${segs[1]}" "${segs[0]}"
joined=$(awk -F, 'NR > 1 { n += $3 } END { print n }' "$work/out")
separate=$(for s in "${segs[@]}"; do "$roadload" decode --pgn-stats "$s" 2>/dev/null | awk -F, 'NR > 1 { n += $3 } END { print n }'; done |
  awk '{ n += $1 } END { print n }')
((joined == separate && joined > 0)) || fail "decode of both segments counted $joined frames, the segments $separate"
grep -Eq "^recording_id = ['\"][0-9a-f]{16}['\"]$" "${segs[0]}meta.toml" || fail "a segment's meta.toml has no recording_id"
expect_status 64 "$roadload" decode "${segs[0]}" "$work/sim"
grep -q "recording_id" "$work/err" || fail "joining another recording is not refused by its recording_id: $(cat "$work/err")"
expect_status 64 "$roadload" analyze "${segs[0]}" "${segs[0]}" --out "$work/twice"
grep -q "given twice" "$work/err" || fail "a segment given twice is not refused: $(cat "$work/err")"

# The unit file, with ExecStart pointing at this build, passes systemd's own checks.
if command -v systemd-analyze >/dev/null; then
  sed "s|^ExecStart=[^ ]*/roadloadd |ExecStart=$roadloadd |" "$unit" >"$work/roadloadd.service"
  # The man page it names is installed by the package (tests/package checks it there).
  expect_status 0 systemd-analyze verify --man=no "$work/roadloadd.service"
  [[ ! -s $work/err ]] || fail "systemd-analyze verify: $(cat "$work/err")"
  systemd-analyze security --offline=yes "$work/roadloadd.service" >"$work/security" 2>&1 || true
  exposure=$(sed -n 's/.*Overall exposure level for roadloadd.service: \([0-9.]*\).*/\1/p' "$work/security")
  awk -v e="$exposure" 'BEGIN { exit !(e != "" && e <= 3.0) }' || fail "systemd exposure level '$exposure' (want <= 3.0)"
  echo "roadloadd-cli: unit verified, systemd exposure $exposure"
fi
echo "roadloadd-cli: PASS"
