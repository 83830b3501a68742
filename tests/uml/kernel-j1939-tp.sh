#!/usr/bin/env bash
# Kernel-J1939 transport round trip: the Linux J1939 stack (driven by
# j1939cat) sends random payloads as BAM broadcasts and as RTS/CTS
# peer-to-peer transfers on vcan0 while candump records the raw frames; then
# `roadload decode --tp` must reassemble every payload byte-exactly from that
# recording. The kernel is the reference implementation the decoder is held to.
#
# usage (on the host; it boots UML itself):  kernel-j1939-tp.sh [ROADLOAD_BIN]
#   tests/uml/kernel-j1939-tp.sh build/tools/roadload
# The roadload binary comes from the first argument or $ROADLOAD_BIN. Without
# one, only the kernel-side checks run and the script exits 77 (skipped).
# Set ROADLOAD_KEEP_WORKDIR=1 to keep the capture and payloads.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=j1939-lib.sh source-path=SCRIPTDIR
. "$here/j1939-lib.sh"

# Modes: on the host (the ctest entry) the kernel part runs inside UML through uml-run and the
# decoder runs here, because sanitizer builds cannot run in UML (ASan's shadow memory does not fit
# its address space); `--kernel-part DIR` is that UML half; inside UML without it, both run there.
mode=both
if [[ ${1:-} == --kernel-part ]]; then
  mode=kernel
  work=${2:?--kernel-part needs a directory}
  roadload=""
elif [[ -z ${UML_RUN:-} ]]; then
  mode=host
fi
if [[ $mode != kernel ]]; then
  roadload=${1:-${ROADLOAD_BIN:-}}
  if [[ -n $roadload && ! -x $roadload ]]; then
    die "roadload binary '$roadload' does not exist or is not executable"
  fi
  work=$(mktemp -d "${TMPDIR:-/tmp}/kernel-j1939-tp.XXXXXX")
fi
pids=()
# shellcheck disable=SC2317  # invoked through trap
finish() {
  local rc=$?
  ((${#pids[@]})) && stop_and_wait "${pids[@]}"
  [[ $mode == kernel ]] && return
  if ((rc == 0 || rc == 77)) && [[ ${ROADLOAD_KEEP_WORKDIR:-0} != 1 ]]; then
    rm -rf -- "$work"
  else
    echo "$j1939_prog: work files kept in $work" >&2
  fi
}
trap finish EXIT

log=$work/capture.log
expected=$work/expected.txt
if [[ $mode == host ]]; then
  rc=0
  "$here/uml-run" --timeout 100 -- "$here/kernel-j1939-tp.sh" --kernel-part "$work" || rc=$?
  # 77: uml-run skipped (no kernel, or a CPU it cannot run on); ctest reports the skip.
  ((rc == 0 || rc == 77)) || die "kernel part in UML failed (status $rc)"
  ((rc == 0)) || exit 77
else

require_vcan vcan0
sizes=(9 10 100 1000 1785)
readonly PGN_P2P=0xEF00 # proprietary A, PDU1: the destination is in the CAN id
readonly PGN_BAM0=0xFF00 # proprietary B, PDU2: broadcast only
# Each transfer has its own source address (and BAMs their own PGN) so all
# can run at once: a 1785-byte BAM alone takes 255 x 50 ms = 13 s.
# printf -v, not $(...): each fork costs tens of milliseconds under UML.
bam_sa=() bam_pgn=() p2p_sa=() p2p_da=()
for i in "${!sizes[@]}"; do
  printf -v "bam_sa[i]" '0x%02x' $((0x80 + i))
  printf -v "bam_pgn[i]" '0x%05x' $((PGN_BAM0 + i))
  printf -v "p2p_sa[i]" '0x%02x' $((0x40 + i))
  printf -v "p2p_da[i]" '0x%02x' $((0x90 + i))
done

# Distinct payloads per transfer, so a decoder that mixes up sessions fails.
for i in "${!sizes[@]}"; do
  head -c "${sizes[i]}" /dev/urandom >"$work/payload-bam-$i.bin"
  head -c "${sizes[i]}" /dev/urandom >"$work/payload-p2p-$i.bin"
done

candump -L vcan0 >"$work/capture.log" &
pids+=($!)

# Kernel-side receivers: a bound address makes the kernel answer RTS with
# CTS/EOMA, and what they hand up is the kernel's own reassembly.
for i in "${!sizes[@]}"; do
  j1939cat -r "vcan0:${p2p_da[i]}" >"$work/rx-p2p-$i.bin" &
  pids+=($!)
  j1939cat -r -B "vcan0:,${bam_pgn[i]}" ":${bam_sa[i]}" >"$work/rx-bam-$i.bin" &
  pids+=($!)
done
wait_listening "${pids[@]}"

start=$SECONDS
senders=()
for i in "${!sizes[@]}"; do
  j1939_send "$work/tx-bam-$i.err" -B -i "$work/payload-bam-$i.bin" \
    "vcan0:${bam_sa[i]}" ":0xff,${bam_pgn[i]}" &
  senders+=($!)
done
# Peer-to-peer transfers are fast; run them one by one while the BAMs are on
# the bus, so the capture interleaves both kinds of session.
for i in "${!sizes[@]}"; do
  j1939_send "$work/tx-p2p-$i.err" -i "$work/payload-p2p-$i.bin" \
    "vcan0:${p2p_sa[i]}" ":${p2p_da[i]},$PGN_P2P" ||
    die "peer-to-peer send of ${sizes[i]} bytes ${p2p_sa[i]} -> ${p2p_da[i]} failed"
done
for i in "${!senders[@]}"; do
  wait "${senders[i]}" || die "BAM send of ${sizes[i]} bytes from ${bam_sa[i]} failed"
done
note "all transfers done in $((SECONDS - start)) s"
# The last frame is on the bus once the sender got its ACK, but candump may
# not have read it yet.
sleep 0.2
stop_and_wait "${pids[@]}"
pids=()

# --- kernel-side checks: prove the capture itself is right ------------------
[[ -s $log ]] || die "candump recorded nothing"
# Frames per CAN id without the priority bits, e.g. [EBFF80]=255 (TP.DT from 0x80).
declare -A frames=()
while read -r id n; do
  frames[$id]=$n
done < <(awk '{ split($3, f, "#"); n[toupper(substr(f[1], 3))]++ } END { for (k in n) print k, n[k] }' "$log")
errors=0
for i in "${!sizes[@]}"; do
  n=${sizes[i]}
  for kind in p2p bam; do
    if ! cmp -s "$work/payload-$kind-$i.bin" "$work/rx-$kind-$i.bin"; then
      echo "$j1939_prog: kernel $kind receiver for $n bytes got $(stat -c %s "$work/rx-$kind-$i.bin") bytes that differ from the payload" >&2
      errors=$((errors + 1))
    fi
  done
  # TP.DT is PGN 0xEB00: CAN id pp EB da sa.
  printf -v bam_id 'EBFF%02X' $((0x80 + i))
  printf -v p2p_id 'EB%02X%02X' $((0x90 + i)) $((0x40 + i))
  bam_dt=${frames[$bam_id]:-0} p2p_dt=${frames[$p2p_id]:-0}
  want=$(((n + 6) / 7))
  if ((bam_dt != want || p2p_dt != want)); then
    echo "$j1939_prog: ${n} bytes: expected $want TP.DT frames per transfer, capture has BAM $bam_dt, peer-to-peer $p2p_dt" >&2
    errors=$((errors + 1))
  fi
done
cm=0 dt=0 total=0
for id in "${!frames[@]}"; do
  total=$((total + frames[$id]))
  case $id in
    EC*) cm=$((cm + frames[$id])) ;;
    EB*) dt=$((dt + frames[$id])) ;;
  esac
done
note "capture: $total frames, $cm TP.CM (0xEC00), $dt TP.DT (0xEB00)"
((errors == 0)) || die "$errors kernel-side check(s) failed; the capture is not trustworthy"

# --- expected decoder output ----------------------------------------------
for i in "${!sizes[@]}"; do
  n=${sizes[i]}
  printf 'vcan0 TP pgn=%d sa=0x%02x da=0xff len=%d data=%s\n' \
    $((PGN_BAM0 + i)) $((0x80 + i)) "$n" "$(hex_of "$work/payload-bam-$i.bin")"
  printf 'vcan0 TP pgn=%d sa=0x%02x da=0x%02x len=%d data=%s\n' \
    $((PGN_P2P)) $((0x40 + i)) $((0x90 + i)) "$n" "$(hex_of "$work/payload-p2p-$i.bin")"
done | sort >"$expected"
fi
[[ $mode == kernel ]] && exit 0

if [[ -z $roadload ]]; then
  echo "$j1939_prog: SKIP: kernel-side checks passed; no roadload binary (argument or ROADLOAD_BIN) to check the decoder" >&2
  exit 77
fi

# --- decoder check ------------------------------------------------------------
decoded=$work/decoded.txt
drc=0
"$roadload" decode --tp "$log" >"$decoded" 2>"$work/decode.err" || drc=$?
if ((drc != 0)); then
  sed 's/^/  | /' "$work/decode.err" >&2
  die "'$roadload decode --tp $log' exited with status $drc"
fi

# Every output line must be exactly
#   (SECONDS.MICROS) IFACE TP pgn=DEC sa=0xHH da=0xHH len=DEC data=HEX
line_re='^\(([0-9]+\.[0-9]{6})\) ([^ ]+ TP pgn=[0-9]+ sa=0x[0-9a-f]{2} da=0x[0-9a-f]{2} len=[0-9]+ data=([0-9a-f][0-9a-f])*)$'
actual=$work/actual.txt
bad=0
while IFS= read -r line; do
  if [[ $line =~ $line_re ]]; then
    ts=${BASH_REMATCH[1]}
    # The timestamp must be one of the transfer's frames' own, copied as
    # logged; anything else points at a parsing or formatting slip.
    if ! grep -qF "($ts) " "$log"; then
      echo "$j1939_prog: timestamp ($ts) is not the time of any frame in the capture: ${line:0:120}" >&2
      bad=$((bad + 1))
    fi
    echo "${BASH_REMATCH[2]}" >>"$actual.unsorted"
  else
    echo "$j1939_prog: line not in the documented format: ${line:0:160}" >&2
    bad=$((bad + 1))
  fi
done <"$decoded"
touch "$actual.unsorted"
sort "$actual.unsorted" >"$actual"

if cmp -s "$expected" "$actual" && ((bad == 0)); then
  note "PASS: roadload reassembled all $(wc -l <"$expected") transfers byte-exactly"
  exit 0
fi

# Explain per transfer, then show a diff with the hex shortened to stay readable.
while IFS= read -r want; do
  grep -qxF "$want" "$actual" && continue
  key=${want%% len=*}
  got=$(grep -F "$key len=" "$actual" || true)
  if [[ -z $got ]]; then
    echo "MISSING: ${want:0:120}..." >&2
  else
    awk -v w="$want" -v g="$(head -n1 <<<"$got")" 'BEGIN {
      split(w, a, "len="); split(g, b, "len=");
      wl = a[2]; sub(/ .*/, "", wl); gl = b[2]; sub(/ .*/, "", gl);
      wd = w; sub(/.*data=/, "", wd); gd = g; sub(/.*data=/, "", gd);
      for (i = 1; i <= length(wd) && substr(wd, i, 2) == substr(gd, i, 2); i += 2) {}
      sub(/ +$/, "", a[1]);
      printf "WRONG: %s: len expected %s got %s; first differing byte at offset %d (expected %s got %s)\n",
        a[1], wl, gl, (i - 1) / 2, substr(wd, i, 2), substr(gd, i, 2) > "/dev/stderr"
    }'
  fi
done <"$expected"
while IFS= read -r got; do
  key=${got%% len=*}
  grep -qF "$key len=" "$expected" || echo "UNEXPECTED: ${got:0:120}..." >&2
done <"$actual"
if ! short_diff=$(diff -u --label expected --label roadload \
  <(cut -c1-120 "$expected") <(cut -c1-120 "$actual")); then
  echo "--- expected vs. roadload output, lines cut to 120 characters:" >&2
  echo "$short_diff" >&2
fi
die "roadload decode --tp does not match what the kernel sent (files in $work)"
