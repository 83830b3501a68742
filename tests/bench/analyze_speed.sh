#!/usr/bin/env bash
# The office's side of a recording: a simulated highway drive (eight accelerometers at 1.2 kHz)
# compressed as roadloadd writes it (zstd frames), then
#   - `roadload analyze` of it, its time and peak memory beside the I/O floor measured in the same
#     run (`zstdcat` of every stream into `wc -l`), and its real-time factor (goal: 1,000 times,
#     at most 64 MB);
#   - the same drive with its accelerometers as FLAC (`simulate --accel-format flac`): their size
#     against accel.csv (goal: 1/8), and `roadload analyze` of it beside its own floor (`flac -d`
#     of every sensor's file and `zstdcat` of the other streams);
#   - `roadload decode --pgn-stats` of its can.log, plain and compressed, beside `wc -l` and
#     `zstdcat | wc -l` of the same file (goal: within 5 times).
# Each is the median of three runs. ROADLOAD_BENCH_ANALYZE_SECONDS sizes the drive (default 3600).
# usage: tests/bench/analyze_speed.sh BUILD_DIR
set -euo pipefail
build=${1:?usage: analyze_speed.sh BUILD_DIR}
roadload=$build/tools/roadload
seconds=${ROADLOAD_BENCH_ANALYZE_SECONDS:-3600}
work=$(mktemp -d "${TMPDIR:-/tmp}/bench-analyze.XXXXXX")
trap 'rm -rf -- "$work"' EXIT

# Median wall seconds (and peak resident KiB) of three runs of a command, its output discarded.
median() {
  local i t0 t1
  for i in 1 2 3; do
    t0=$(date +%s.%N)
    /usr/bin/time -f "%M" -o "$work/rss" bash -c "$1" >/dev/null 2>&1 || { echo "analyze_speed: '$1' failed" >&2; exit 1; }
    t1=$(date +%s.%N)
    echo "$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.4f", b - a }') $(cat "$work/rss")"
  done | sort -n | sed -n 2p
}

"$roadload" simulate --scenario highway-1h --seed 1 --duration "$seconds" --out "$work/plain" -q
cp -r "$work/plain" "$work/zst"
for f in "$work"/zst/*.csv "$work"/zst/can.log; do zstd -1 -q --rm "$f"; done
"$roadload" simulate --scenario highway-1h --seed 1 --duration "$seconds" --out "$work/flac" -q --accel-format flac
for f in "$work"/flac/*.csv "$work"/flac/can.log; do zstd -1 -q --rm "$f"; done
text_bytes=$(stat -c %s "$work/plain/accel.csv")
flac_bytes=$(cat "$work"/flac/accel-*.flac | wc -c)
rm "$work/plain/accel.csv"  # 1.5 GB an hour: only can.log is read plain below

read -r floor _ < <(median "zstdcat $work/zst/*.zst | wc -l")
read -r analyze rss < <(median "$roadload analyze $work/zst --out $work/results -q")
read -r flac_floor _ < <(median "{ zstdcat $work/flac/*.zst; for f in $work/flac/accel-*.flac; do flac -d -s -c --force-raw-format --endian=little --sign=signed \$f; done; } | wc -c")
read -r flac_analyze flac_rss < <(median "$roadload analyze $work/flac --out $work/results-flac -q")
frames=$(wc -l <"$work/plain/can.log")
read -r wc_plain _ < <(median "wc -l $work/plain/can.log")
read -r decode_plain _ < <(median "$roadload decode --pgn-stats $work/plain/can.log")
read -r wc_zst _ < <(median "zstdcat $work/zst/can.log.zst | wc -l")
read -r decode_zst _ < <(median "$roadload decode --pgn-stats $work/zst/can.log.zst")

awk -v s="$seconds" -v floor="$floor" -v a="$analyze" -v rss="$rss" -v f="$frames" -v wp="$wc_plain" -v dp="$decode_plain" \
  -v wz="$wc_zst" -v dz="$decode_zst" -v tb="$text_bytes" -v fb="$flac_bytes" -v ff="$flac_floor" -v fa="$flac_analyze" \
  -v frss="$flac_rss" 'function ratio(x, y) { return y > 0 ? sprintf("%.1f", x / y) : "inf" }
BEGIN {
  printf "analysis of a %.0f s drive, streams in zstd frames (medians of 3 runs)\n", s
  printf "  %-44s %8s %10s %8s\n", "", "seconds", "goal", "ratio"
  printf "  %-44s %8.2f\n", "zstdcat of every stream | wc -l (I/O floor)", floor
  printf "  %-44s %8.2f %10s %8s   (%.0fx real time, goal 1000x)\n", "roadload analyze", a, sprintf("%.2f", s / 1000), ratio(a, floor), s / a
  printf "  %-44s %8.0f %10s\n", "  its peak memory, MB", rss / 1024, "64"
  printf "the same drive, accelerometers as FLAC (accel-ID.flac), the other streams in zstd frames\n"
  printf "  %-44s %8.1f %10s %8s   (accel.csv %.1f MB/h, 1/%.2f)\n", "accelerometer stream, MB an hour", fb / s * 3600 / 1e6, \
    "1/8", ratio(tb, fb), tb / s * 3600 / 1e6, tb / fb
  printf "  %-44s %8.2f\n", "flac -d and zstdcat of every stream (I/O floor)", ff
  printf "  %-44s %8.2f %10s %8s   (%.0fx real time, goal 1000x)\n", "roadload analyze", fa, sprintf("%.2f", s / 1000), ratio(fa, ff), s / fa
  printf "  %-44s %8.0f %10s\n", "  its peak memory, MB", frss / 1024, "64"
  printf "decode --pgn-stats of the same drive'"'"'s can.log (%d frames)\n", f
  printf "  %-44s %8.3f\n", "wc -l can.log", wp
  printf "  %-44s %8.3f %10s %8s   (%.1f M frames/s)\n", "roadload decode --pgn-stats can.log", dp, "5x wc", ratio(dp, wp), f / dp / 1e6
  printf "  %-44s %8.3f\n", "zstdcat can.log.zst | wc -l", wz
  printf "  %-44s %8.3f %10s %8s\n", "roadload decode --pgn-stats can.log.zst", dz, "5x zstdcat", ratio(dz, wz)
}'
