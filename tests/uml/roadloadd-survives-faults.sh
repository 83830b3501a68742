#!/usr/bin/env bash
# roadloadd survives what a truck's gateway meets, and says so in its status log:
#   1. the CAN interface disappears and comes back: a `down` status line, then recording resumes;
#   2. the disk fills up: a status line naming the error, then recording resumes, and every frame
#      is either recorded or counted as lost;
#   3. SIGKILL at a random moment loses at most the open zstd frame of each stream, closed at every
#      fsync (0.5 s here; a frame candump saw 1 s before the kill is on file, whatever the load),
#      and every file it leaves reads back without error;
#   4. the same with the accelerometers written as FLAC: whole frames, the open one lost at most.
# usage (inside UML, through uml-run): roadloadd-survives-faults.sh ROADLOADD_BIN ROADLOAD_BIN
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=j1939-lib.sh source-path=SCRIPTDIR
. "$here/j1939-lib.sh"
# shellcheck source=roadloadd-lib.sh source-path=SCRIPTDIR
. "$here/roadloadd-lib.sh"

roadloadd=${1:?usage: roadloadd-survives-faults.sh ROADLOADD_BIN ROADLOAD_BIN}
roadload=${2:?usage: roadloadd-survives-faults.sh ROADLOADD_BIN ROADLOAD_BIN}
require_vcan vcan0
work=$(mktemp -d "${TMPDIR:-/tmp}/roadloadd-faults.XXXXXX")
cleanup() {
  kill -KILL "${daemon:-}" "${dump:-}" 2>/dev/null || true
  mountpoint -q "$work/small" && umount "$work/small"
  [[ -n ${ROADLOAD_KEEP:-} ]] || rm -rf -- "$work"
}
trap cleanup EXIT
send() { "$roadload" replay "$1" --iface vcan0 -q || die "roadload replay $1 failed"; }

# 1. Interface removed and re-created.
d=$work/iface
mkdir -p "$d"
gen_frames 1000 1000 0 >"$d/a.log"
gen_frames 1000 1000 1000 >"$d/b.log"
start_daemon "$d"
send "$d/a.log"
ip link del vcan0
wait_status_match "$d" 'vcan0 down'
ip link add dev vcan0 type vcan && ip link set up vcan0
wait_status_match "$d" 'vcan0 (waiting|up)'
send "$d/b.log"
sleep 0.5
stop_daemon || die "roadloadd exited with status $? after the interface came back"
cmp -s <(cat "$d/a.log" "$d/b.log" | frames_of) <(recorded_frames "$d") ||
  die "interface removed: recorded $(recorded_frames "$d" | wc -l) frames, sent 2000 while it existed"
note "PASS 1: vcan0 removed and re-created: status said 'vcan0 down', all 2000 frames sent while it existed recorded"

# 2. Disk full.
d=$work/disk
mkdir -p "$d/small"
mount -t tmpfs -o size=2m tmpfs "$d/small" || die "cannot mount a small tmpfs"
ln -s "$d/small" "$work/small"
gen_frames 3000 500 0 >"$d/a.log"
gen_frames 3000 500 3000 >"$d/b.log"
"$roadloadd" --can vcan0 --no-gnss --data-dir "$d/small/rec" --status "$d/status.log" \
  --status-json "$d/status.jsonl" 2>"$d/daemon.err" &
daemon=$!
wait_status_lines "$d" 1
dd if=/dev/zero of="$d/small/filler" bs=64k 2>/dev/null || true
send "$d/a.log"
wait_status_match "$d" 'WARN recording: .*No space left on device'
rm -f "$d/small/filler"
wait_status_match "$d" 'sync ok$'
send "$d/b.log"
sleep 1
lost=$(last_status_field "$d" lines_lost)
stop_daemon || true  # lines were lost: the daemon says so in its exit status
shopt -s nullglob
disk_logs=("$d"/small/rec/*/can.log.zst)
shopt -u nullglob
((${#disk_logs[@]})) || die "disk full: no compressed can.log recorded"
got=$(zstdcat "${disk_logs[@]}" | wc -l)
((got + lost == 6000)) || die "disk full: $got frames recorded + $lost counted lost != 6000 sent"
tail -n 3000 <(zstdcat "${disk_logs[@]}" | frames_of) | cmp -s - <(frames_of "$d/b.log") ||
  die "disk full: the frames sent after the disk had room again are not all recorded"
note "PASS 2: disk full: status named ENOSPC; $got of 6000 frames recorded, $lost counted lost, none unaccounted; recording resumed"

# 3. SIGKILL at a random moment.
d=$work/kill
mkdir -p "$d"
gen_frames 8000 500 0 >"$d/a.log"
printf '[recording]\nfsync_interval_s = 0.5\n' >"$d/sync.toml"
start_daemon "$d" --config "$d/sync.toml"
candump -L vcan0 >"$d/candump.log" &
dump=$!
wait_listening "$dump"
send "$d/a.log" &
sender=$!
sleep "$(awk -v r="$RANDOM" 'BEGIN { printf "%.3f", 1.0 + r / 32768 * 2.0 }')"
kill -KILL "$daemon"
killed_at=$(date +%s.%N)
wait "$daemon" 2>/dev/null || true
wait "$sender"
stop_and_wait "$dump"
for f in "$d"/rec/*/*; do
  case $f in
    *.zst)
      zstd -tq "$f" || die "after SIGKILL $f holds a frame cut short"
      [[ $f != */can.log.zst ]] || "$roadload" decode "$f" --pgn-stats >/dev/null 2>"$d/decode.err" ||
        die "after SIGKILL $f does not read back: $(cat "$d/decode.err")"
      ;;
    */can.log | */*.csv) die "after SIGKILL $f is a plain stream: roadloadd compresses by default" ;;
    */meta.toml) grep -q '^version = 1' "$f" || die "after SIGKILL $f is incomplete" ;;
  esac
done
recorded=$(recorded_frames "$d" | wc -l)
cmp -s <(recorded_frames "$d") <(frames_of "$d/a.log" | head -n "$recorded") ||
  die "after SIGKILL the recording is not the start of what was sent"
# Frame i carries i in its first four bytes. Every frame candump stamped more than 1 s before the
# kill must be on file; the loss window runs from the first frame candump saw that is not.
read -r late window < <(awk -v k="$killed_at" -v r="$recorded" '
  function hex(s,  v, j) { v = 0; for (j = 1; j <= length(s); j++) v = v * 16 + index("0123456789ABCDEF", substr(s, j, 1)) - 1; return v }
  { t = substr($1, 2, length($1) - 2); split($3, p, "#"); i = hex(substr(p[2], 1, 8)) }
  i >= r && t <= k - 1.0 { late++ }
  i >= r && !seen { seen = 1; w = k - t }
  END { printf "%d %.3f\n", late, seen ? w : 0 }' "$d/candump.log")
((late == 0)) || die "after SIGKILL: $late frames candump saw more than 1 s before the kill are not on file"
note "PASS 3: SIGKILL: $recorded frames on file in whole zstd frames; the first one missing arrived $window s before the kill (limit 1 s)"

# 4. SIGKILL while the accelerometers are recorded as FLAC (roadloadd's default for a replay of a
#    recording that has them so): every file left decodes (`flac -t`: whole frames, CRCs good), each
#    sensor's counts are the start of what was replayed, and nothing replayed more than 1 s before
#    the kill is missing (the open frame is closed at every fsync, 0.5 s here).
d=$work/flac
mkdir -p "$d"
"$roadload" simulate --scenario mnroad-mainline-30mph --duration 30 --seed 3 --out "$d/sim" --accel-format flac -q ||
  die "roadload simulate --accel-format flac failed"
start_daemon "$d" --config "$work/kill/sync.toml" --replay "$d/sim"
sleep "$(awk -v r="$RANDOM" 'BEGIN { printf "%.3f", 1.5 + r / 32768 * 2.0 }')"
kill -KILL "$daemon"
read -r killed_at _ </proc/uptime  # the capture clock (CLOCK_MONOTONIC) in 10 ms steps
wait "$daemon" 2>/dev/null || true
raw() { flac -d -s -c --force-raw-format --endian=little --sign=signed "$1" | od -An -v -t d4 -w20; }
shopt -s nullglob
files=("$d"/rec/*/accel-*.flac)
shopt -u nullglob
((${#files[@]} == 8)) || die "after SIGKILL: ${#files[@]} accelerometer FLAC files, expected 8"
for f in "$d"/rec/*/*.zst; do zstd -tq "$f" || die "after SIGKILL $f holds a frame cut short"; done
worst=0 samples=0
for f in "${files[@]}"; do
  flac -t -s "$f" 2>"$d/flac.err" || die "after SIGKILL $f does not decode: $(cat "$d/flac.err")"
  id=${f##*/accel-}
  raw "$f" >"$d/got"
  raw "$d/sim/accel-$id" >"$d/sent"
  n=$(wc -l <"$d/got")
  ((n > 0)) || die "after SIGKILL $f holds no sample"
  cmp -s <(awk '{ print $1, $2, $3 }' "$d/got") <(head -n "$n" "$d/sent" | awk '{ print $1, $2, $3 }') ||
    die "after SIGKILL $f is not the start of what was replayed"
  late=$(tail -n 1 "$d/got" | awk -v k="$killed_at" '{ printf "%.3f", k - ($4 + $5 / 1e9) }')
  worst=$(awk -v a="$worst" -v b="$late" 'BEGIN { print (b > a ? b : a) }')
  samples=$((samples + n))
done
awk -v w="$worst" 'BEGIN { exit !(w < 1.0) }' ||
  die "after SIGKILL: a sensor's last sample on file was replayed $worst s before the kill (limit 1 s)"
note "PASS 4: SIGKILL: $samples accelerometer samples in 8 FLAC files of whole frames, the start of what was replayed; the last on file ${worst} s before the kill at worst (limit 1 s)"
