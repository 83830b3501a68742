#!/usr/bin/env bash
# The sim-to-real diagnosis's blind bench (`roadload gap bench`, seed 2026) from an empty library
# cache, its time beside the goal (issue 27 item 6: 50 cases in 10 minutes on 2 cores, 12 s a
# case) and beside one simulation of a 6-minute drive measured in the same run, as that many
# simulations.
# usage: tests/bench/gap_bench.sh BUILD_DIR CASES
set -euo pipefail
build=${1:?usage: tests/bench/gap_bench.sh BUILD_DIR CASES}
cases=${2:?usage: tests/bench/gap_bench.sh BUILD_DIR CASES}
roadload=$build/tools/roadload
work=$(mktemp -d "${TMPDIR:-/tmp}/gap-bench.XXXXXX")
trap 'rm -rf -- "$work"' EXIT
export ROADLOAD_CACHE_DIR=$work/cache

t0=$(date +%s.%N)
"$roadload" simulate --scenario mnroad-mainline-30mph --seed 31 --out "$work/drive" -q >/dev/null 2>"$work/err" ||
  { cat "$work/err" >&2; exit 1; }
t1=$(date +%s.%N)
"$roadload" gap bench --cases "$cases" --seed 2026 2>"$work/err" || { tail -5 "$work/err" >&2; exit 1; }
t2=$(date +%s.%N)
awk -v a="$t0" -v b="$t1" -v c="$t2" -v n="$cases" -v cores="$(nproc)" 'BEGIN {
  sim = b - a; bench = c - b; goal = 12 * n
  printf "gap bench: %d cases in %.0f s on %d cores, %.0f simulations of a 6-minute drive (one: %.1f s); goal %.0f s: %s (%.1f times the goal)\n",
         n, bench, cores, bench / sim, sim, goal, (bench <= goal ? "reached" : "NOT reached"), bench / goal
}'
