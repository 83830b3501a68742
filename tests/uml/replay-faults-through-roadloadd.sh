#!/usr/bin/env bash
# Every fault `roadload replay --faults` can inject, replayed into the real roadloadd over vcan0 in
# one simulated Mainline drive, each at its own time: dropped and duplicated frames, an error
# frame, a bus-off, a truncated transport session, a GNSS outage, an accelerometer FIFO overflow
# and a wall-clock step. For each: the daemon stays up, its status log reports the fault, it
# recovers (the source is up again, the estimate goes on), and it loses nothing that reached it:
# its recording equals what went onto the bus (the replay's --sent log) frame for frame, and the
# sensor streams equal the input less exactly what the fault withheld.
# usage (on the host; it boots UML itself): replay-faults-through-roadloadd.sh ROADLOADD_BIN ROADLOAD_BIN
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=j1939-lib.sh source-path=SCRIPTDIR
. "$here/j1939-lib.sh"
# shellcheck source=roadloadd-lib.sh source-path=SCRIPTDIR
. "$here/roadloadd-lib.sh"
# The faults 5-10 s of driving apart, each over before the next: at 5x, 1-2 s of replay. The daemon
# writes a status line every 0.25 s, so each fault has lines of its own.
readonly route=mnroad-mainline-westbound rate=5 duration_s=60
readonly faults="drop=0.002,dup=0.002,seed=5,error@5,busoff@10+3,tp-truncate@18,gnss-outage@24+10,accel-overflow@38,clock-step@45=7"

if [[ ${1:-} == --kernel-part ]]; then
  work=${2:?} roadloadd=${3:?} roadload=${4:?}
  require_vcan vcan0
  printf '[status]\ninterval_s = 0.25\n' >"$work/roadloadd.toml"
  daemon_args=(--config "$work/roadloadd.toml")
  replay_into_daemon "$work" "$route" "$rate" --faults "$faults" --sent "$work/sent.log"
  exit 0
fi

roadloadd=${1:?usage: replay-faults-through-roadloadd.sh ROADLOADD_BIN ROADLOAD_BIN}
roadload=${2:?usage: replay-faults-through-roadloadd.sh ROADLOADD_BIN ROADLOAD_BIN}
[[ -x $roadloadd && -x $roadload ]] || die "'$roadloadd' or '$roadload' is not an executable"
work=$(mktemp -d "${TMPDIR:-/tmp}/replay-faults.XXXXXX")
[[ -n ${ROADLOAD_KEEP:-} ]] || trap 'rm -rf -- "$work"' EXIT
"$roadload" simulate --scenario mnroad-mainline-30mph --seed 13 --duration "$duration_s" --out "$work/sim" -q ||
  die "roadload simulate failed with status $?"
rc=0
"$here/uml-run" --timeout 200 -- "$here/replay-faults-through-roadloadd.sh" --kernel-part "$work" "$roadloadd" "$roadload" || rc=$?
((rc != 77)) || exit 77
((rc == 0)) || die "kernel part in UML failed (status $rc)"
note "replay: $(grep 'faults:' "$work/replay.err")"

segs=("$work"/rec/*/)
((${#segs[@]} == 1)) || die "expected one recording segment, found ${#segs[@]}"
rec=${segs[0]}
"$here/../support/unpack-streams" "$rec" || die "the daemon's streams are not zstd frames zstd reads back"
log=$work/status.log
warned() { grep -q -- "WARN $1" "$log" || die "$2: the status log never says '$1'"; }

# Nothing that reached the daemon is lost: its can.log is the bus as sent, error frames included.
cmp -s <(cut -d' ' -f2- "$work/sent.log") <(cut -d' ' -f2- "${rec}can.log") ||
  die "the daemon's can.log ($(wc -l <"${rec}can.log") lines) differs from the $(wc -l <"$work/sent.log") frames sent"
note "recording: $(wc -l <"${rec}can.log") frames, equal to what went onto the bus"

# drop, dup: gaps and repeats in the periodic messages.
warned "j1939: [0-9]* gaps in periodic messages" "drop"
warned "j1939: [0-9]* frames repeated" "dup"
# error: the error frame is counted and named. A status line whose interval held the error frame
# warns of it; on a busy host UML can bunch it into an interval another event of the source names,
# so the source's running error count in the last JSON status, which no timing changes, stands for it.
grep -q -- "WARN vcan0 [0-9]* errors (protocol violation)" "$log" ||
  tail -n 1 "$work/status.jsonl" | grep -Eq '"name":"vcan0","kind":"can"[^}]*"errors":[1-9]' ||
  die "error: the status log neither warns of the error frame nor counts it for vcan0"
# busoff: the source goes down, then comes back; at 5x its 3 s last 0.6 s, often between two lines.
grep -Eq -- "WARN vcan0 (down: bus-off|recovered [0-9]+x \((restarted|receiving) after bus-off\))" "$log" ||
  die "busoff: the status log never says 'vcan0 down: bus-off' nor that it recovered"
# tp-truncate: the session that lost its last packet is reported incomplete.
warned "j1939: [0-9]* transport sessions incomplete" "tp-truncate"
# gnss-outage: the GNSS source waits for a fix; every fix outside the outage is recorded.
warned "gnss waiting: replay x5, no fix (outage replayed)" "gnss-outage"
# accel-overflow: one FIFO (32 samples) per sensor lost and reported as dropped.
sensors=$(grep -c "kind = .accelerometer." "$work/sim/meta.toml")
warned "accel dropped $((32 * sensors))" "accel-overflow"
# clock-step: seen under the kernel stamps, named, and the data unaffected.
warned "wall clock stepped [0-9]*x (data unaffected)" "clock-step"

/usr/bin/python3 - "$work/sim" "$rec" "$((32 * sensors))" <<'PY' || die "the sensor streams lost more than the faults withheld"
import csv, sys
sim, rec, fifo = sys.argv[1], sys.argv[2], int(sys.argv[3])
def rows(path): return [r for r in csv.reader(open(path)) if r and not r[0].startswith("#")][1:]
gi, gr = rows(sim + "/gnss.csv"), rows(rec + "gnss.csv")
t0 = int(open(sim + "/can.log").readline().split()[0].strip("()").replace(".", "")) * 1000
out = [r for r in gi if not (t0 + 24e9 <= int(r[0]) < t0 + 34e9)]
if [r[1:] for r in out] != [r[1:] for r in gr]:
    sys.exit(f"gnss: {len(gr)} fixes recorded, {len(out)} expected outside the outage ({len(gi)} in the input)")
ai, ar = rows(sim + "/accel.csv"), rows(rec + "accel.csv")
if len(ai) - len(ar) != fifo:
    sys.exit(f"accel: {len(ai) - len(ar)} samples missing, the overflow lost {fifo}")
print(f"replay-faults-through-roadloadd.sh: gnss {len(gi) - len(gr)} fixes withheld by the outage, accel {fifo} lost to the overflow; the rest recorded")
PY

# Recovered: at the end the bus is up, the sensors' replays ended, the estimate goes on, nothing
# lost on the way to disk, and the daemon stopped cleanly.
last=$(grep -E '^[0-9]{4}-' "$log" | tail -n 1)
[[ $last == *"| vcan0 up "* && $last == *"| gnss ended "* && $last == *"| accel ended "* && $last == *" lost 0"* ]] ||
  die "not recovered at the end: $last"
# The estimate goes on; its value under UML's bunched frames at 5x is (b)'s of the clean replay.
[[ $last =~ crr\ -?[0-9]\.[0-9]{5} ]] || die "no CRR at the end: $last"
[[ -s $work/live/cells.csv ]] || die "no live results written"
grep -q '^roadloadd stopped: [0-9]* lines recorded, 0 lost$' "$log" || die "no clean stop line"
note "PASS: every fault reported and recovered from; last status: $last"
