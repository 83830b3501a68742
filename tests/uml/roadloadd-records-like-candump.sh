#!/usr/bin/env bash
# roadloadd on vcan0 records every frame sent, in order and byte for byte, with no drops reported,
# and so every frame candump records, at ten times the peak J1939 rate of a 500 kbit/s bus:
# 500,000 bit/s over 131 bits (an unstuffed 29-bit frame of 8 bytes) = 3,817 frames/s, so 38,170
# frames/s. Traffic: FRAMES J1939-like frames 26 us apart (38,462 frames/s) played at their
# recorded spacing by `roadload replay` (sendmmsg, a batch per 1 ms of the recording; cangen's one system call per
# frame is too slow under UML), whose payloads count up so that a reordering or a duplicate shows.
# The rate reached is printed against the goal. The check is against what was sent and against
# candump's own capture.
# usage (inside UML, through uml-run): roadloadd-records-like-candump.sh ROADLOADD_BIN ROADLOAD_BIN [FRAMES]
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=j1939-lib.sh source-path=SCRIPTDIR
. "$here/j1939-lib.sh"
# shellcheck source=roadloadd-lib.sh source-path=SCRIPTDIR
. "$here/roadloadd-lib.sh"

roadloadd=${1:?usage: roadloadd-records-like-candump.sh ROADLOADD_BIN ROADLOAD_BIN [FRAMES]}
roadload=${2:?usage: roadloadd-records-like-candump.sh ROADLOADD_BIN ROADLOAD_BIN [FRAMES]}
frames=${3:-200000}
readonly goal_fps=38170
require_vcan vcan0
work=$(mktemp -d "${TMPDIR:-/tmp}/roadloadd-rate.XXXXXX")
trap 'kill -KILL "${daemon:-}" "${dump:-}" 2>/dev/null || true; [[ -n ${ROADLOAD_KEEP:-} ]] || rm -rf -- "$work"' EXIT

# 26 us apart: the recorded spacing of 38,462 frames/s, for a replay at --rate 1.
awk -v n="$frames" 'BEGIN { for (i = 0; i < n; i++) printf "(%d.%06d) can0 %08X#%08X%08X\n", 1000 + int(i * 26 / 1e6), (i * 26) % 1000000, 419299328 + i % 65536, i, i * 7 % 4294967296 }' >"$work/sent.log"
# Room for a few seconds of traffic in the kernel's queues while UML's one CPU runs the sender.
sysctl -qw net.core.rmem_max=67108864
# vcan hands each frame to the receive backlog, whose default 1,000 overflows in the moments the
# host takes UML's CPU away; a frame dropped there reaches no socket, candump's nor the daemon's.
sysctl -qw net.core.netdev_max_backlog=100000
backlog_dropped_before=$(softnet_dropped)
printf '[[can]]\ninterface = "vcan0"\nreceive_buffer_kib = 65536\n' >"$work/roadloadd.toml"
start_daemon "$work" --config "$work/roadloadd.toml"
# candump at the lowest priority: under UML it needs two system calls per frame, and the daemon and
# the sender share its one CPU.
nice -n 19 candump -L -r 67108864 vcan0 >"$work/candump.log" &
dump=$!
wait_listening "$dump"
"$roadload" replay "$work/sent.log" --iface vcan0 --rate 1 2>"$work/replay.err" || die "roadload replay failed: $(cat "$work/replay.err")"
# Stopped once it has read them all, or has read nothing more for a few status lines: on a loaded
# host the daemon may still be catching up when the sender is done.
wait_status_items "$work" "$frames"
stop_and_wait "$dump"
stop_daemon || die "roadloadd exited with status $? ($(cat "$work/daemon.err"))"

recorded=("$work"/rec/*/can.log.zst)
[[ -f ${recorded[0]} ]] || die "roadloadd wrote no can.log.zst"
got=$(zstdcat "${recorded[@]}" | wc -l)
seen=$(wc -l <"$work/candump.log")
if ! cmp -s <(frames_of "$work/sent.log") <(zstdcat "${recorded[@]}" | frames_of); then
  die "roadloadd recorded $got frames that differ from the $frames sent (candump has $seen);" \
    "it counted $(last_status_field "$work" items) read, $(last_status_field "$work" dropped) dropped by its socket," \
    "$(last_status_field "$work" ring_dropped) by its ring, $(last_status_field "$work" lines_lost) lost on disk;" \
    "the kernel's receive backlog dropped $(($(softnet_dropped) - backlog_dropped_before))"
fi
# candump reads one frame per system call and falls behind under UML; what it did record must be
# in the daemon's recording, in the same order.
awk 'NR == FNR { c[++n] = $0; next } j < n && $0 == c[j + 1] { j++ } END { exit !(j == n) }' \
  <(frames_of "$work/candump.log") <(zstdcat "${recorded[@]}" | frames_of) ||
  die "candump recorded frames that roadloadd did not, or in another order"
dropped=$(last_status_field "$work" dropped)
ring=$(last_status_field "$work" ring_dropped)
lost=$(last_status_field "$work" lines_lost)
((dropped == 0 && ring == 0 && lost == 0)) || die "frames all there but drops reported: kernel $dropped, ring $ring, disk $lost"
rate=$(awk 'NR==1{gsub(/[()]/,"",$1); a=$1} {gsub(/[()]/,"",$1); b=$1} END{printf "%.0f", (NR-1)/(b-a)}' <(zstdcat "${recorded[0]}"))
note "PASS: all $got frames recorded in order, no drops; candump caught $seen of them"
note "rate: $rate frames/s = $((rate * 100 / 3817)) % of a 500 kbit/s bus's J1939 peak (goal $goal_fps = 1000 %)"
