#!/usr/bin/env bash
# roadloadd's CPU beside candump's on the same bus, in User-Mode Linux (issue 27, item 5): a full
# 500 kbit/s J1939 bus (3,817 frames/s, 29-bit frames of 8 bytes, played onto vcan0 at their
# recorded spacing by `roadload replay`) while roadloadd records it and eight accelerometers at
# 4 kHz (a simulated drive's, written as FLAC and replayed by the daemon's own replay source), and
# `candump -L vcan0 > file` records the same bus. Each one's CPU (utime + stime from /proc) over
# the same window, as a fraction of one core, and their ratio. Goal: roadloadd under 2 % of a core.
# Under UML every system call and page fault costs far more than on a gateway, and is charged to
# the process: the same accelerometer replay took 4.1 s of user time in UML against 0.17 s on this
# host's own kernel (12 s of drive). The bus-alone ratio is the like-for-like figure; the in-process
# bench_daemon gives the native cost of the accelerometers.
# ROADLOAD_BENCH_CANDUMP_SECONDS sets each window (default 10).
# usage: tests/bench/daemon_vs_candump.sh BUILD_DIR
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
readonly goal_pct=2 bus_fps=3817

if [[ ${1:-} == --kernel-part ]]; then
  work=${2:?} build=${3:?} seconds=${4:?}
  # shellcheck source=../uml/j1939-lib.sh source-path=SCRIPTDIR
  . "$here/../uml/j1939-lib.sh"
  require_vcan vcan0
  sysctl -qw net.core.rmem_max=67108864
  sysctl -qw net.core.netdev_max_backlog=100000
  printf '[[can]]\ninterface = "vcan0"\nreceive_buffer_kib = 16384\n' >"$work/roadloadd.toml"
  ticks() { awk '{ print $14 + $15 }' "/proc/$1/stat"; }
  # One window: the bus played, roadloadd (with the options given) and candump recording it.
  window() {
    local name=$1
    shift
    rm -rf "$work/rec"
    "$build/firmware/roadloadd" --config "$work/roadloadd.toml" --no-gnss --data-dir "$work/rec" "$@" \
      --status "$work/status.log" --status-json "$work/status.jsonl" 2>"$work/daemon.err" &
    local daemon=$!
    candump -L -r 16777216 vcan0 >"$work/candump.log" &
    local dump=$!
    sleep 1
    "$build/tools/roadload" replay "$work/bus.log" --iface vcan0 --rate 1 -q &
    local sender=$!
    sleep 2  # past the start: both have their sockets and buffers
    local d0 c0 t0 d1 c1 t1
    d0=$(ticks "$daemon") c0=$(ticks "$dump") t0=$(awk '{ print $1 }' /proc/uptime)
    sleep "$seconds"
    d1=$(ticks "$daemon") c1=$(ticks "$dump") t1=$(awk '{ print $1 }' /proc/uptime)
    wait "$sender"
    kill -TERM "$daemon" "$dump"
    wait "$daemon" || true
    wait "$dump" || true
    echo "$name $d0 $d1 $c0 $c1 $t0 $t1 $(getconf CLK_TCK) $(cat "$work"/rec/*/accel-*.flac 2>/dev/null | wc -c)" >>"$work/cpu"
  }
  window can
  window accel --replay "$work/sensors"
  exit 0
fi

build=${1:?usage: tests/bench/daemon_vs_candump.sh BUILD_DIR}
build=$(realpath "$build")
seconds=${ROADLOAD_BENCH_CANDUMP_SECONDS:-10}
work=$(mktemp -d "${TMPDIR:-/tmp}/daemon-candump.XXXXXX")
[[ -n ${ROADLOAD_KEEP:-} ]] || trap 'rm -rf -- "$work"' EXIT
span=$((seconds + 6))
# The bus: frames 262 us apart (3,817 frames/s), payloads counting up.
awk -v n="$((span * bus_fps))" 'BEGIN { for (i = 0; i < n; i++) { t = i * 262; printf "(%d.%06d) can0 %08X#%08X%08X\n", 1000 + int(t / 1e6), t % 1000000, 419299328 + i % 4096, i, i * 7 % 4294967296 } }' >"$work/bus.log"
# The accelerometers: a simulated drive at 4 kHz with its CAN left out (the bus above stands in).
printf 'name = "bench-4khz"\nroute = "%s"\nspeed_mph = 64\nstart_m = 50\nduration_s = %d\naccel_rate_hz = 4000\n' \
  "$here/../../config/routes/synthetic-highway.toml" "$((span + 4))" >"$work/scenario.toml"
"$build/tools/roadload" simulate --scenario "$work/scenario.toml" --seed 1 --out "$work/sensors" --accel-format flac -q
rm -f "$work/sensors/can.log" "$work/sensors/gnss.csv" "$work/sensors/weather.csv"
# shellcheck source=uml-part.sh source-path=SCRIPTDIR
. "$here/uml-part.sh"
run_uml_part "daemon vs candump" "$work" "$here/daemon_vs_candump.sh" "$build" "$seconds"
awk -v g="$goal_pct" -v fps="$bus_fps" '
  { d[$1] = 100 * ($3 - $2) / $8 / ($7 - $6); c[$1] = 100 * ($5 - $4) / $8 / ($7 - $6); wall = $7 - $6; fb = $9 }
  END {
    printf "roadloadd beside candump in UML, %.0f s windows of a 500 kbit/s bus (%d frames/s), CPU as a fraction of one core\n", wall, fps
    printf "  %-52s %7s %9s %7s\n", "", "roadloadd", "candump", "ratio"
    printf "  %-52s %6.2f%% %8.2f%% %7.2f\n", "the bus alone", d["can"], c["can"], (c["can"] > 0 ? d["can"] / c["can"] : 0)
    printf "  %-52s %6.2f%% %8.2f%% %7.2f   (goal < %d %%: %s)\n", "the bus + 8 accelerometers at 4 kHz (replayed, FLAC)", d["accel"],
      c["accel"], (c["accel"] > 0 ? d["accel"] / c["accel"] : 0), g, (d["accel"] < g ? "reached" : "NOT reached")
    printf "  (%.1f MB of accelerometer FLAC written; UML charges system calls and page faults to the process:\n", fb / 1e6
    printf "   the bus-alone ratio is the like-for-like one, bench_daemon the accelerometers'"'"' native cost)\n"
  }' "$work/cpu"
