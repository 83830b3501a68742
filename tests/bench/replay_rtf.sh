#!/usr/bin/env bash
# Real-time factor of replay + daemon: a simulated highway drive's CAN traffic played by
# `roadload replay --rate max` onto vcan0 into the real roadloadd (recording, J1939 decoding and the
# live CRR filter on the drive's truck), in User-Mode Linux. The clock runs from the sender's start
# until roadloadd, stopped as the sender ends, has taken what its socket still holds, written it
# and exited. Prints simulated seconds per wall second for each run and their median, the hour of
# driving projected from it against the goal (1,000 times real time: an hour in 3.6 s), and whether
# every run's recording equals the input frame for frame, beside the sender alone on the bus (no
# daemon) as the baseline. ROADLOAD_BENCH_REPLAY_SECONDS sets the drive (default one hour, which
# the goal is judged on; CI runs five minutes), ROADLOAD_BENCH_REPLAY_RUNS the runs (default 3).
# usage: tests/bench/replay_rtf.sh BUILD_DIR
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
readonly route=synthetic-highway vehicle=mnroad-truck goal_rtf=1000

if [[ ${1:-} == --kernel-part ]]; then
  work=${2:?} build=${3:?} rate=${4:?} runs=${5:?}
  # Room in the socket's queue for what the sender gets ahead of the daemon (UML: one CPU for both).
  sysctl -qw net.core.rmem_max=67108864
  printf '[[can]]\ninterface = "vcan0"\nreceive_buffer_kib = 65536\n' >"$work/roadloadd.toml"
  # The baseline: the sender alone, nobody listening on the bus.
  start=$(date +%s.%N)
  "$build/tools/roadload" replay "$work/sim" --iface vcan0 --rate "$rate" -q
  echo "$start $(date +%s.%N)" >"$work/alone"
  for ((run = 1; run <= runs; ++run)); do
    "$build/firmware/roadloadd" --config "$work/roadloadd.toml" --no-gnss --route "$route" --vehicle "$vehicle" \
      --data-dir "$work/rec$run" --status "$work/status.log" --status-json "$work/status$run.jsonl" \
      --results "$work/live" 2>>"$work/daemon.err" &
    daemon=$!
    sleep 1
    start=$(date +%s.%N)
    "$build/tools/roadload" replay "$work/sim" --iface vcan0 --rate "$rate" -q
    sent=$(date +%s.%N)
    kill -TERM "$daemon"
    wait "$daemon"
    echo "$start $sent $(date +%s.%N)" >>"$work/times"
  done
  exit 0
fi

build=${1:?usage: tests/bench/replay_rtf.sh BUILD_DIR}
build=$(realpath "$build")
seconds=${ROADLOAD_BENCH_REPLAY_SECONDS:-3600}
rate=${ROADLOAD_BENCH_REPLAY_RATE:-max}
runs=${ROADLOAD_BENCH_REPLAY_RUNS:-3}
work=$(mktemp -d "${TMPDIR:-/tmp}/replay-rtf.XXXXXX")
[[ -n ${ROADLOAD_KEEP:-} ]] || trap 'rm -rf -- "$work"' EXIT
"$build/tools/roadload" simulate --scenario highway-1h --seed 1 --duration "$seconds" --out "$work/sim" -q
# CAN only: the sensor streams' replay drivers are measured by the daemon's own benchmark.
rm -f "$work/sim/accel.csv"
# shellcheck source=uml-part.sh source-path=SCRIPTDIR
. "$here/uml-part.sh"
run_uml_part "replay RTF" "$work" "$here/replay_rtf.sh" "$build" "$rate" "$runs"
frames=$(wc -l <"$work/sim/can.log")
equal=yes
for ((run = 1; run <= runs; ++run)); do
  segs=("$work/rec$run"/*/)
  "$here/../support/unpack-streams" "${segs[@]}"
  recorded=$(cat "$work/rec$run"/*/can.log | wc -l)
  lost=$(tail -n 1 "$work/status$run.jsonl" | grep -o '"kind":"can",[^}]*' | grep -o '"dropped":[0-9]*,"ring_dropped":[0-9]*' || true)
  cmp -s <(cut -d' ' -f3 "$work/sim/can.log") <(cat "$work/rec$run"/*/can.log | cut -d' ' -f3) ||
    equal="no (run $run: $recorded of $frames recorded; $lost)"
done
# Each run's wall time, fastest first, so that the median is the middle line.
read -r a b <"$work/alone"
awk -v s="$seconds" '{ print $3 - $1, $2 - $1, s / ($3 - $1) }' "$work/times" | sort -g |
  awk -v rate="$rate" -v s="$seconds" -v f="$frames" -v goal="$goal_rtf" -v eq="$equal" -v alone="$(echo "$b - $a" | bc)" '
  { wall[NR] = $1; send[NR] = $2; rtf[NR] = $3 }
  END {
    printf "replay + roadloadd at --rate %s (UML, vcan0, %d s highway drive, %d frames, %d runs)\n", rate, s, f, NR
    for (i = 1; i <= NR; ++i) printf "  %.3f s (sender done after %.3f s): %.1fx real time\n", wall[i], send[i], rtf[i]
    # The start-up of both programs, about 0.3 s under UML, weighs on a short drive: the goal is for an hour.
    if (NR % 2) median = rtf[(NR + 1) / 2]; else median = (rtf[NR / 2] + rtf[NR / 2 + 1]) / 2
    if (s < 3600) verdict = "judged on an hour"; else if (median >= goal) verdict = "met"; else verdict = "not met"
    printf "  %-40s %12s %12s %8s\n", "", "measured", "goal", "ratio"
    printf "  %-40s %11.1fx %11dx %8.2f   (%s)\n", "real-time factor, median", median, goal, median / goal, verdict
    printf "  %-40s %11.2fs %11.1fs\n", "one hour of driving, replayed", 3600 / median, 3600 / goal
    printf "  %-40s %11.0f/s\n", "frames per second, median", f * median / s
    printf "  %-40s %11.2fs %12s %8.2f   (baseline: the bus alone)\n", "the sender alone, nobody listening", alone, "", (s / median) / alone
    printf "  %-40s %12s\n", "recording equals input, frame for frame", eq
  }'
[[ $equal == yes ]] || { echo "replay RTF: the recording is not the input; kept in $work" >&2; trap - EXIT; exit 1; }
