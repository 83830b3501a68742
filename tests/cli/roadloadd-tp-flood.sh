#!/usr/bin/env bash
# A transport-protocol flood of our own making replayed into roadloadd: 20 s of 3,000 frames a
# second beside a 30 s drive, orphan TP.DT to the global address and RTS nobody answers, from 200
# source addresses. The daemon records every frame, raises the security warning with its rate, and
# its memory stays what it is without the flood (measured beside it in the same run).
# usage: roadloadd-tp-flood.sh ROADLOADD_BIN ROADLOAD_BIN
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=cli-lib.sh source-path=SCRIPTDIR
. "$here/cli-lib.sh" roadloadd-tp-flood
roadloadd=$(realpath "${1:?usage: roadloadd-tp-flood.sh ROADLOADD_BIN ROADLOAD_BIN}")
roadload=${2:?}

"$roadload" simulate --scenario mnroad-mainline-30mph --seed 5 --duration 30 --out "$work/drive" -q
cp -r "$work/drive" "$work/flood"
python3 - "$work/drive/can.log" "$work/flood/can.log" <<'PY'
import sys
frames = []
for line in open(sys.argv[1]):
    stamp = line.split(")")[0][1:]
    sec, frac = stamp.split(".")
    frames.append((int(sec) * 10**6 + int(frac), line))
t0 = frames[0][0] + 5 * 10**6
for k in range(60000):  # 20 s at 3,000 per second
    t = t0 + k * 333
    sa = 0x20 + k % 200
    if k % 2:
        fid, data = 0x1CEBFF00 | sa, "%02X" % (k % 255 + 1) + "AABBCCDDEEFF11"  # TP.DT, no session open
    else:
        fid, data = 0x1CEC0000 | sa, "1064000FFFE3FE00"  # TP.CM RTS for 100 bytes to the engine, never answered
    frames.append((t, "(%d.%06d) can0 %08X#%s\n" % (t // 10**6, t % 10**6, fid, data)))
frames.sort(key=lambda f: f[0])
open(sys.argv[2], "w").writelines(line for _, line in frames)
PY
peak_kib() { /usr/bin/time -f %M -o "$work/rss" "$@" >/dev/null 2>"$work/err" || fail "'$*' failed: $(cat "$work/err")"; cat "$work/rss"; }
printf '[status]\ninterval_s = 0.2\n' >"$work/status.toml"
# With a route the live filter runs beside the J1939 checks; without one (below) the daemon only
# records, and watches the bus all the same.
route=mnroad-mainline-westbound
base=$(peak_kib "$roadloadd" --config "$work/status.toml" --replay "$work/drive" --replay-can --replay-rate 10 --exit-when-done --route "$route" \
  --data-dir "$work/rec-drive" --status "$work/drive.log" --status-json '')
flood=$(peak_kib "$roadloadd" --config "$work/status.toml" --replay "$work/flood" --replay-can --replay-rate 10 --exit-when-done --route "$route" \
  --data-dir "$work/rec-flood" --status "$work/flood.log" --status-json "$work/flood.jsonl")
echo "peak resident memory: drive alone $base KiB, with the flood $flood KiB ($((flood - base)) KiB more)"
((flood <= base + 4096)) || fail "the flood grew the daemon by $((flood - base)) KiB"
grep -q "WARN SECURITY j1939: transport-protocol flood, [0-9]* orphan or unfinished transport frames/s" "$work/flood.log" ||
  fail "no flood warning: $(grep -m3 WARN "$work/flood.log")"
grep -q "SECURITY" "$work/drive.log" && fail "the drive alone was called a flood: $(grep -m1 SECURITY "$work/drive.log")"
seg=("$work"/rec-flood/*/)
"$support/unpack-streams" "${seg[@]}" || fail "the flood's recording does not decompress"
cmp -s <(cut -d' ' -f3 "$work/flood/can.log") <(cut -d' ' -f3 "${seg[0]}can.log") || fail "the flood's frames were not all recorded"
"$roadloadd" --config "$work/status.toml" --replay "$work/flood" --replay-can --replay-rate 10 --exit-when-done \
  --data-dir "$work/rec-only" --status "$work/only.log" --status-json '' >/dev/null 2>"$work/err" ||
  fail "the record-only daemon failed: $(cat "$work/err")"
grep -q "WARN SECURITY j1939: transport-protocol flood" "$work/only.log" ||
  fail "a daemon that only records did not see the flood: $(grep -m3 WARN "$work/only.log")"
rate=$(python3 -c 'import json,sys; print(max(json.loads(l)["j1939"]["tp_anomaly_rate"] for l in open(sys.argv[1])))' "$work/flood.jsonl")
echo "roadloadd-tp-flood: PASS: highest anomaly rate $rate/s in the status"
