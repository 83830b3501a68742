#!/usr/bin/env bash
# gpsd going away under a reading GpsdSource: a first gpsd serves the drive's first 10 s and exits;
# the probe must go down (and neither exit nor stop), then reconnect to a second gpsd started on
# the same port for the rest of the drive: restarts 1 and every fix of both parts, in order.
set -euo pipefail
usage="usage: gpsd-reconnect.sh ROADLOAD GPSD_PROBE NMEA_FROM_GNSS"
roadload=${1:?$usage} probe=${2:?$usage} to_nmea=${3:?$usage}
here=$(dirname "${BASH_SOURCE[0]}")
# shellcheck source=gpsfake-lib.sh source-path=SCRIPTDIR
. "$here/gpsfake-lib.sh" gpsd-reconnect
start=2024-06-01T15:00:00  # gpsd-fix-from-gpsfake.sh says why not 2014
first_part=100             # fixes, 10 s at 10 Hz

"$roadload" simulate --scenario mnroad-mainline-30mph --duration 60 --out "$work/rec" -q >"$work/sim.out" 2>&1 ||
  fail "roadload simulate: $(cat "$work/sim.out")"
csv=$work/rec/gnss.csv
fixes=$(($(wc -l <"$csv") - 1))
head -n $((first_part + 1)) "$csv" >"$work/a.csv"
{ head -n 1 "$csv"; tail -n +$((first_part + 2)) "$csv"; } >"$work/b.csv"
# The second part keeps the drive's UTC: its first fix comes a whole 10 s after the drive's first.
first_utc() { sed -n 2p "$1" | cut -d, -f2; }
b_after_s=$((($(first_utc "$work/b.csv") - $(first_utc "$csv")) / 1000000000))
b_start=$(date -u -d "@$(($(date -u -d "$start" +%s) + b_after_s))" +%Y-%m-%dT%H:%M:%S)
# No-fix cycles first, as gpsd-fix-from-gpsfake.sh explains; the second part's also cover the
# probe's wait for its next reconnection attempt (attempts 0.25, 0.75, 1.75, 3.75 s after the loss).
"$to_nmea" "$work/a.csv" "$work/a.nmea" --start "$start" --lead-in 800 || fail "nmea_from_gnss.py failed on part 1"
"$to_nmea" "$work/b.csv" "$work/b.nmea" --start "$b_start" --lead-in 1200 || fail "nmea_from_gnss.py failed on part 2"

port=$(free_port)
start_gpsfake "$port" "$work/a.nmea"
"$probe" localhost "$port" "$fixes" 90 >"$work/probe.csv" 2>"$work/probe.err" &
probe_pid=$!
background+=("$probe_pid")
for _ in $(seq 300); do
  grep -q "^state down" "$work/probe.err" && break
  kill -0 "$probe_pid" 2>/dev/null || break
  sleep 0.1
done
grep -q "^state down" "$work/probe.err" || fail "no down state within 30 s of gpsd's exit: $(cat "$work/probe.err")"
start_gpsfake "$port" "$work/b.nmea"
status=0
wait "$probe_pid" || status=$?
cat "$work/probe.err"
((status != 1)) || fail "gpsd_probe could not reach gpsd"
"$here/compare_fixes.py" "$csv" "$work/probe.csv" "$start" || fail "fixes differ from the NMEA"
((status == 0)) || fail "gpsd_probe exited $status before $fixes fixes"
# up on the first gpsd, down when it exits, up again on the second
[[ $(grep -o '^state [a-z]*' "$work/probe.err" | uniq | tr '\n' ' ') == "state waiting state up state down state waiting state up " ]] ||
  fail "states were: $(grep '^state' "$work/probe.err" | tr '\n' ';')"
# TOFF: gpsd's receipt stamps (CLOCK_REALTIME) placed on the capture clock; no heap in reads ("-": ASan)
grep -Eq "^counters: items $fixes errors 0 restarts 1 .* toff [1-9][0-9]* .* unplaced 0 allocations_in_reads (0|-)$" "$work/probe.err" ||
  fail "counters: $(grep counters "$work/probe.err")"
echo "gpsd-reconnect: PASS"
