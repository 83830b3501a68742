#!/usr/bin/env bash
# Regenerates tests/data/j1939-kernel/: one candump -L capture per J1939
# transport case (BAM and RTS/CTS, 9/100/1785 bytes) made by the Linux kernel's
# own J1939 stack, with the payload each one carries, so host unit tests can
# check TP reassembly against the kernel without booting UML.
#
# usage: tests/uml/capture-j1939-fixtures.sh [OUTDIR]
# Run on the host it re-runs itself inside tests/uml/uml-run. Payloads are
# seeded pseudo-random bytes, so a regeneration only changes the timestamps.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
if [[ ${UML_RUN:-} != 1 ]]; then
  exec "$here/uml-run" --timeout 120 -- "$here/${BASH_SOURCE[0]##*/}" "$@"
fi
# shellcheck source=j1939-lib.sh source-path=SCRIPTDIR
. "$here/j1939-lib.sh"

out=$(realpath -m "${1:-$here/../data/j1939-kernel}")
require_vcan vcan0
mkdir -p "$out" || die "cannot create $out"

work=$(mktemp -d "${TMPDIR:-/tmp}/j1939-fixtures.XXXXXX")
pids=()
# shellcheck disable=SC2317  # invoked through trap
cleanup() {
  ((${#pids[@]})) && stop_and_wait "${pids[@]}"
  rm -rf -- "$work"
}
trap cleanup EXIT

# name  size  sa  da  pgn   (da 0xff = BAM; PDU2 PGNs broadcast, PDU1 0xEF00 peer-to-peer)
cases=(
  "bam-9    9    0x80 0xff 0x0FEE3"
  "bam-100  100  0x81 0xff 0x0FF00"
  "bam-1785 1785 0x82 0xff 0x0FF01"
  "rts-9    9    0x40 0x90 0x0EF00"
  "rts-100  100  0x41 0x91 0x0EF00"
  "rts-1785 1785 0x42 0x92 0x0EF00"
)

seed=1939
for c in "${cases[@]}"; do
  read -r name size sa da pgn <<<"$c"
  seed=$((seed + 1))
  # perl's rand() is its own drand48, the same on every platform and version.
  perl -e 'srand($ARGV[1]); print map { chr int rand 256 } 1 .. $ARGV[0]' \
    "$size" "$seed" >"$work/$name.bin"
  # Per-case capture: the kernel filter keeps only this session's frames
  # (CAN id bits 0-15 = PS/DA and SA, in both directions for CTS/EOMA).
  s=${sa#0x} d=${da#0x}
  filters="0000$d$s:0000FFFF"
  [[ $da != 0xff ]] && filters+=",0000$s$d:0000FFFF"
  candump -L "vcan0,$filters" >"$work/$name.log" &
  pids+=($!)
  if [[ $da == 0xff ]]; then
    j1939cat -r -B "vcan0:,$pgn" ":$sa" >"$work/$name.rx" &
  else
    j1939cat -r "vcan0:$da" >"$work/$name.rx" &
  fi
  pids+=($!)
done
wait_listening "${pids[@]}"

senders=()
for c in "${cases[@]}"; do
  read -r name size sa da pgn <<<"$c"
  if [[ $da == 0xff ]]; then
    # BAM runs at the kernel's fixed 50 ms per packet: all at once.
    j1939_send "$work/$name.err" -B -i "$work/$name.bin" "vcan0:$sa" ":0xff,$pgn" &
    senders+=("$!:$name")
  else
    j1939_send "$work/$name.err" -i "$work/$name.bin" "vcan0:$sa" ":$da,$pgn" ||
      die "sending $name failed"
  fi
done
for s in "${senders[@]}"; do
  wait "${s%%:*}" || die "sending ${s#*:} failed"
done
sleep 0.2
stop_and_wait "${pids[@]}"
pids=()

# Only a capture the kernel itself reassembled correctly becomes a fixture.
: >"$work/expected.txt"
for c in "${cases[@]}"; do
  read -r name size sa da pgn <<<"$c"
  cmp -s "$work/$name.bin" "$work/$name.rx" ||
    die "$name: the kernel receiver did not get the payload back (got $(stat -c %s "$work/$name.rx") bytes)"
  dt=$(grep -Ec '^\([0-9.]+\) vcan0 1[0-9A-F]EB[0-9A-F]{4}#' "$work/$name.log" || true)
  ((dt == (size + 6) / 7)) || die "$name: $dt TP.DT frames, expected $(((size + 6) / 7))"
  printf '%s vcan0 TP pgn=%d sa=0x%02x da=0x%02x len=%d data=%s\n' \
    "$name" $((pgn)) $((sa)) $((da)) "$size" "$(hex_of "$work/$name.bin")" >>"$work/expected.txt"
  cp "$work/$name.log" "$work/$name.bin" "$out/"
  note "$name: $(wc -l <"$work/$name.log") frames, $size bytes"
done
cp "$work/expected.txt" "$out/expected.txt"
note "fixtures written to $out"
