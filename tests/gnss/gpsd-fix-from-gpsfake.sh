#!/usr/bin/env bash
# GpsdSource against a real gpsd: a 60 s simulated drive's gnss.csv written as NMEA (RMC + GGA per
# fix), fed to gpsd by gpsfake and read by gpsd_probe. Every fix must come back in order as the NMEA
# carried it (compare_fixes.py: lat/lon to 1e-8 deg, ellipsoid height to 0.01 m, speed to
# 0.002 m/s, course to 0.01 deg, UTC to the centisecond) with increasing stamps.
set -euo pipefail
usage="usage: gpsd-fix-from-gpsfake.sh ROADLOAD GPSD_PROBE NMEA_FROM_GNSS"
roadload=${1:?$usage} probe=${2:?$usage} to_nmea=${3:?$usage}
here=$(dirname "${BASH_SOURCE[0]}")
# shellcheck source=gpsfake-lib.sh source-path=SCRIPTDIR
. "$here/gpsfake-lib.sh" gpsd-fix-from-gpsfake
# gpsd 3.22 moves a two-digit-year date before its release 1024 weeks on (a GPS week rollover), so
# the simulator's 2014 drive is replayed in 2024.
start=2024-06-01T15:00:00

"$roadload" simulate --scenario mnroad-mainline-30mph --duration 60 --out "$work/rec" -q >"$work/sim.out" 2>&1 ||
  fail "roadload simulate: $(cat "$work/sim.out")"
# gpsfake writes from its start, ~9 ms per cycle; what comes before gpsd has probed the pty (~2 s)
# and the probe has connected is lost. 800 no-fix cycles (~7 s) cover both on a loaded machine.
"$to_nmea" "$work/rec/gnss.csv" "$work/drive.nmea" --start "$start" --lead-in 800 || fail "nmea_from_gnss.py failed"
fixes=$(($(wc -l <"$work/rec/gnss.csv") - 1))

port=$(free_port)
start_gpsfake "$port" "$work/drive.nmea"
status=0
"$probe" localhost "$port" "$fixes" 60 >"$work/probe.csv" 2>"$work/probe.err" || status=$?
cat "$work/probe.err"
((status != 1)) || fail "gpsd_probe could not reach gpsd"
"$here/compare_fixes.py" "$work/rec/gnss.csv" "$work/probe.csv" "$start" || fail "fixes differ from the NMEA"
((status == 0)) || fail "gpsd_probe exited $status before $fixes fixes"
# TOFF: gpsd's receipt stamps (CLOCK_REALTIME) placed on the capture clock; no heap in reads ("-": ASan)
grep -Eq "^counters: items $fixes errors 0 restarts 0 .* toff [1-9][0-9]* .* unplaced 0 allocations_in_reads (0|-)$" "$work/probe.err" ||
  fail "counters: $(grep counters "$work/probe.err")"
echo "gpsd-fix-from-gpsfake: PASS"
