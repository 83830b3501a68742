#!/usr/bin/env bash
# Drives per second of `roadload batch` on a local Dask cluster of 1 and then 2 worker processes,
# over the same simulated drives in the same run, and their ratio (the scale-out on this machine's
# cores; 2.0 would be perfect). Each run analyses every drive in-process and collects it into an
# SQLite file of its own. The rate is the batch's own (first task submitted to last drive done);
# the wall time beside it includes starting the cluster and Python.
# ROADLOAD_BENCH_BATCH_DRIVES (default 8) drives of ROADLOAD_BENCH_BATCH_SECONDS (default 600) each
# on the synthetic highway (highway-1h: its hour cut short).
# usage: tests/bench/batch_speed.sh BUILD_DIR
set -euo pipefail
build=${1:?usage: tests/bench/batch_speed.sh BUILD_DIR}
roadload=$(realpath "$build/tools/roadload")
drives=${ROADLOAD_BENCH_BATCH_DRIVES:-8} length_s=${ROADLOAD_BENCH_BATCH_SECONDS:-600}
work=$(mktemp -d "${TMPDIR:-/tmp}/batch-speed.XXXXXX")
trap 'rm -rf -- "$work"' EXIT

echo "recording,vehicle,route" >"$work/manifest.csv"
for ((i = 1; i <= drives; ++i)); do
  "$roadload" simulate --scenario highway-1h --seed "$i" --duration "$length_s" --out "$work/d$i" -q 2>/dev/null
  echo "d$i,,synthetic-highway" >>"$work/manifest.csv"
done

declare -A rate wall
for n in 1 2; do
  start=$(date +%s.%N)
  "$roadload" batch "$work/manifest.csv" --db "$work/fleet$n.db" --workers "$n" -o "$work/out$n" 2>"$work/err$n" ||
    { cat "$work/err$n" >&2; exit 1; }
  end=$(date +%s.%N)
  rate[$n]=$(sed -n 's/.*drives in .* s (\([0-9.]*\) drives\/s).*/\1/p' "$work/err$n")
  wall[$n]=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }')
done
diff -rq "$work/out1" "$work/out2" >/dev/null || { echo "batch speed: 1 and 2 workers wrote different results" >&2; exit 1; }
printf 'batch on Dask: %d drives of %d s (highway-1h), %s cores\n' "$drives" "$length_s" "$(nproc)"
for n in 1 2; do
  printf '  %d worker%s  %6.2f drives/s  (%s s wall with the cluster'"'"'s start)\n' "$n" "$([[ $n == 1 ]] && echo " " || echo s)" \
    "${rate[$n]}" "${wall[$n]}"
done
awk -v a="${rate[1]}" -v b="${rate[2]}" 'BEGIN { printf "  ratio      %6.2f  (2 workers over 1)\n", b / a }'
