#!/usr/bin/env bash
# Real-time factor of replay + daemon: a simulated highway drive's CAN traffic played by
# `roadload replay --rate max` onto vcan0 into the real roadloadd (recording, J1939 decoding and the
# live CRR filter), in User-Mode Linux. Prints simulated seconds per wall second, the hour of
# driving projected from it against the goal (well under a minute), and whether the daemon's
# recording equals the input frame for frame. ROADLOAD_BENCH_REPLAY_SECONDS sets the drive (default
# one hour; CI runs ten minutes and projects).
# usage: tests/bench/replay_rtf.sh BUILD_DIR
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
readonly route=synthetic-highway goal_s=60

if [[ ${1:-} == --kernel-part ]]; then
  work=${2:?} build=${3:?} rate=${4:?}
  # Room in the socket's queue for what the sender gets ahead of the daemon (UML: one CPU for both).
  sysctl -qw net.core.rmem_max=67108864
  printf '[[can]]\ninterface = "vcan0"\nreceive_buffer_kib = 65536\n' >"$work/roadloadd.toml"
  "$build/firmware/roadloadd" --config "$work/roadloadd.toml" --no-gnss --route "$route" --data-dir "$work/rec" --status "$work/status.log" \
    --status-json "$work/status.jsonl" --results "$work/live" 2>"$work/daemon.err" &
  daemon=$!
  sleep 1
  frames=$(wc -l <"$work/sim/can.log")
  start=$(date +%s.%N)
  "$build/tools/roadload" replay "$work/sim" --iface vcan0 --rate "$rate" -q
  sent=$(date +%s.%N)
  # Done when the daemon has taken every frame off the bus (its status counts them), or when its
  # count has stood still for two seconds (frames lost: the comparison below says so).
  last=-1 still=0
  while ((still < 40)); do
    items=$(tail -n 1 "$work/status.jsonl" | grep -o '"kind":"can","state":"[a-z]*","items":[0-9]*' | grep -o '[0-9]*$' || echo 0)
    ((items >= frames)) && break
    if ((items == last)); then still=$((still + 1)); else still=0; fi
    last=$items
    sleep 0.05
  done
  done_at=$(date +%s.%N)
  kill -TERM "$daemon"
  wait "$daemon"
  echo "$start $sent $done_at" >"$work/times"
  exit 0
fi

build=${1:?usage: tests/bench/replay_rtf.sh BUILD_DIR}
build=$(realpath "$build")
seconds=${ROADLOAD_BENCH_REPLAY_SECONDS:-3600}
rate=${ROADLOAD_BENCH_REPLAY_RATE:-max}
work=$(mktemp -d "${TMPDIR:-/tmp}/replay-rtf.XXXXXX")
[[ -n ${ROADLOAD_KEEP:-} ]] || trap 'rm -rf -- "$work"' EXIT
"$build/tools/roadload" simulate --scenario highway-1h --seed 1 --duration "$seconds" --out "$work/sim" -q
# CAN only: the sensor streams' replay drivers are measured by the daemon's own benchmark.
rm -f "$work/sim/accel.csv"
# shellcheck source=uml-part.sh source-path=SCRIPTDIR
. "$here/uml-part.sh"
run_uml_part "replay RTF" "$work" "$here/replay_rtf.sh" "$build" "$rate"
read -r start sent done_at <"$work/times"
frames=$(wc -l <"$work/sim/can.log")
segs=("$work"/rec/*/)
"$here/../support/unpack-streams" "${segs[@]}"
recorded=$(cat "$work"/rec/*/can.log | wc -l)
lost=$(tail -n 1 "$work/status.jsonl" | grep -o '"kind":"can",[^}]*' | grep -o '"dropped":[0-9]*,"ring_dropped":[0-9]*' || true)
equal="no ($recorded of $frames recorded; $lost)"
cmp -s <(cut -d' ' -f3 "$work/sim/can.log") <(cut -d' ' -f3 "${segs[0]}can.log") && equal=yes
awk -v rate="$rate" -v s="$seconds" -v f="$frames" -v a="$start" -v b="$sent" -v c="$done_at" -v goal="$goal_s" -v eq="$equal" 'BEGIN {
  wall = c - a; rtf = s / wall; hour = 3600 / rtf
  printf "replay + roadloadd at --rate %s (UML, vcan0, %d s highway drive, %d frames)\n", rate, s, f
  printf "  %-40s %12s %12s %8s\n", "", "measured", "goal", "ratio"
  printf "  %-40s %11.1fx %12s\n", "real-time factor (drive s per wall s)", rtf, ""
  printf "  %-40s %11.1fs %11ds %8.2f   (%s)\n", "one hour of driving, replayed", hour, goal, hour / goal, hour < goal / 2 ? "well under a minute: met" : "not met"
  printf "  %-40s %11.0f/s\n", "frames per second", f / wall
  printf "  %-40s %11.1fs\n", "sender done after", b - a
  printf "  %-40s %12s\n", "recording equals input, frame for frame", eq
}'
[[ $equal == yes ]] || { echo "replay RTF: the recording is not the input; kept in $work" >&2; trap - EXIT; exit 1; }
