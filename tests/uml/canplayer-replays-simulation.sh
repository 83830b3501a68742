#!/usr/bin/env bash
# A simulated recording replays unchanged with can-utils: `roadload simulate` writes 10 s of the
# MnROAD Mainline drive on the host; inside the UML kernel canplayer plays can.log onto vcan0 while
# candump records it; every frame must come back byte for byte, in order, with its spacing kept.
#
# usage (on the host; it boots UML itself):  canplayer-replays-simulation.sh ROADLOAD_BIN
#   inside UML (run by the host half):       canplayer-replays-simulation.sh --kernel-part DIR
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=j1939-lib.sh source-path=SCRIPTDIR
. "$here/j1939-lib.sh"

if [[ ${1:-} == --kernel-part ]]; then
  work=${2:?--kernel-part needs a directory}
  require_vcan vcan0
  candump -L vcan0 >"$work/replayed.log" &
  dump=$!
  wait_listening "$dump"
  canplayer -I "$work/rec/can.log" vcan0=can0 || die "canplayer failed with status $?"
  sleep 0.3
  stop_and_wait "$dump"
  exit 0
fi

roadload=${1:?usage: canplayer-replays-simulation.sh ROADLOAD_BIN}
[[ -x $roadload ]] || die "roadload binary '$roadload' does not exist or is not executable"
work=$(mktemp -d "${TMPDIR:-/tmp}/canplayer-sim.XXXXXX")
trap 'rm -rf -- "$work"' EXIT
"$roadload" simulate --scenario mnroad-mainline-30mph --seed 7 --duration 10 --out "$work/rec" -q ||
  die "roadload simulate failed with status $?"
rc=0
"$here/uml-run" --timeout 100 -- "$here/canplayer-replays-simulation.sh" --kernel-part "$work" || rc=$?
# 77: uml-run skipped (no kernel, or a CPU it cannot run on); ctest reports the skip.
((rc == 0 || rc == 77)) || die "kernel part in UML failed (status $rc)"
((rc == 0)) || exit 77

sent=$(wc -l <"$work/rec/can.log")
got=$(wc -l <"$work/replayed.log")
((sent > 2000)) || die "the simulation wrote only $sent frames in 10 s"
cmp -s <(cut -d' ' -f3 "$work/rec/can.log") <(cut -d' ' -f3 "$work/replayed.log") ||
  die "replayed frames differ from the recording (sent $sent, received $got)"
# canplayer keeps the recorded spacing: the replay spans the recording's time within 5 %.
span() { awk 'NR==1{gsub(/[()]/,"",$1); a=$1} {gsub(/[()]/,"",$1); b=$1} END{printf "%.3f", b-a}' "$1"; }
rec_span=$(span "$work/rec/can.log")
rep_span=$(span "$work/replayed.log")
awk -v a="$rec_span" -v b="$rep_span" 'BEGIN{exit !(b > 0.95*a && b < 1.05*a)}' ||
  die "recording spans $rec_span s but the replay $rep_span s"
note "PASS: $sent frames replayed byte for byte over $rep_span s (recording $rec_span s)"
