#!/usr/bin/env bash
# Time of one `roadload gap` diagnosis of a 6-minute drive on the machine's cores (goal: 20 s with
# the truck's and road's library in the cache, issue 24 item 7): first with an empty cache (the
# library is built and stored), then the same drive and another drive of the same truck on the same
# road, each read from the cache (median of three). The baseline beside them is one simulation of
# the drive (`roadload simulate` of the same scenario and length), so each time is also printed as
# that many simulations.
# usage: tests/bench/gap_speed.sh BUILD_DIR
set -euo pipefail
build=${1:?usage: tests/bench/gap_speed.sh BUILD_DIR}
roadload=$build/tools/roadload
readonly scenario=mnroad-mainline-30mph goal_s=20
work=$(mktemp -d "${TMPDIR:-/tmp}/gap-speed.XXXXXX")
trap 'rm -rf -- "$work"' EXIT
export ROADLOAD_CACHE_DIR=$work/cache

seconds() {
  local start end
  start=$(date +%s.%N)
  "$@" >/dev/null 2>"$work/err" || { cat "$work/err" >&2; exit 1; }
  end=$(date +%s.%N)
  awk -v a="$start" -v b="$end" 'BEGIN { printf "%.2f", b - a }'
}
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%5.1f", a / b }'; }
verdict() { awk -v t="$1" -v g="$goal_s" 'BEGIN { print (t <= g ? "reached" : "NOT reached") }'; }
median() { printf '%s\n' "$@" | sort -g | sed -n "$((($# + 1) / 2))p"; }

sim_s=$(seconds "$roadload" simulate --scenario "$scenario" --seed 31 --out "$work/a" --effect brake-drag=300 -q)
"$roadload" simulate --scenario "$scenario" --seed 32 --out "$work/b" --effect torque-bias=0.03 -q >/dev/null 2>&1
length_s=$(awk -F, 'NR == 2 { first = $1 } END { printf "%.0f", ($1 - first) / 1e9 }' "$work/a/gnss.csv")
cold_s=$(seconds "$roadload" gap --real "$work/a")
same=() other=()
for _ in 1 2 3; do
  same+=("$(seconds "$roadload" gap --real "$work/a")")
  other+=("$(seconds "$roadload" gap --real "$work/b")")
done
same_s=$(median "${same[@]}") other_s=$(median "${other[@]}")
grep -q "library read from" "$work/err" || { echo "gap speed: the second drive did not read the cache" >&2; exit 1; }
printf 'gap diagnosis of a %s s drive (%s, %s cores): one simulation of it %.1f s\n' "$length_s" "$scenario" "$(nproc)" "$sim_s"
printf '  library built and stored  %6.1f s  (%s simulations)\n' "$cold_s" "$(ratio "$cold_s" "$sim_s")"
printf '  same drive, cached        %6.1f s  (%s simulations)  goal %d s: %s\n' "$same_s" "$(ratio "$same_s" "$sim_s")" \
  "$goal_s" "$(verdict "$same_s")"
printf '  another drive, cached     %6.1f s  (%s simulations)  goal %d s: %s\n' "$other_s" "$(ratio "$other_s" "$sim_s")" \
  "$goal_s" "$(verdict "$other_s")"
