#!/usr/bin/env bash
# roadload grade as a user runs it: help, errors with their exit codes, the survey profile of a
# built-in route, and the GNSS profile of two simulated passes checked against that survey.
set -euo pipefail
roadload=${1:?usage: grade-cli.sh ROADLOAD_BIN}
# shellcheck source=cli-lib.sh source-path=SCRIPTDIR
. "$(dirname "${BASH_SOURCE[0]}")/cli-lib.sh" grade-cli
route=mnroad-mainline-westbound
header=s_m,elevation_m,elevation_sigma_m,grade_pct,grade_sigma_pct,passes

expect_status 0 "$roadload" grade --help
for o in --route --out --base --bin --min-passes; do grep -q -- "$o" "$work/out" || fail "--help does not describe $o"; done
expect_status 64 "$roadload" grade --out "$work/g.csv"
expect_status 64 "$roadload" grade --route $route
expect_status 64 "$roadload" grade --route $route --out "$work/g.csv" --bin 10 --base 5
expect_status 66 "$roadload" grade --route "$work/no-such-route.toml" --out "$work/g.csv"
grep -q "no-such-route.toml" "$work/err" || fail "missing route not named: $(cat "$work/err")"
expect_status 66 "$roadload" grade --route $route "$work/no-such-recording" --out "$work/g.csv"
grep -q "no-such-recording" "$work/err" || fail "missing recording not named: $(cat "$work/err")"

# The survey: one bin per 10 m of the 5.2 km route, every bin with a grade, the route's +-0.5 %.
expect_status 0 "$roadload" grade --route $route --out "$work/survey.csv"
[[ $(head -1 "$work/survey.csv") == "# slope_base_m = 30.0" ]] || fail "survey.csv base: $(head -1 "$work/survey.csv")"
[[ $(sed -n 2p "$work/survey.csv") == "$header" ]] || fail "survey.csv header: $(sed -n 2p "$work/survey.csv")"
awk -F, 'NR > 2 { n++; if ($4 == "" || $5 == "" || $6 != 0) bad++; g = $4 < 0 ? -$4 : $4; if (g > max) max = g }
  END { exit !(n >= 500 && n <= 540 && bad == 0 && max > 0.4 && max < 0.6) }' "$work/survey.csv" ||
  fail "survey profile: $(awk -F, 'NR > 2 && NR < 7' "$work/survey.csv")"

# Two passes at 30 mph (the simulator drives westbound only). Its code-DGPS heights (Gauss-Markov
# 0.35 m over 100 s + white 0.2 m, docs/simulator.md 5.3) give about 0.24 % of grade per pass and
# +-30 m slope, so 0.17 % for two: the RMS difference from the survey must stay under 0.3 %, and
# the reported sigma must be within a factor of two of it.
for seed in 1 2; do
  "$roadload" simulate --scenario mnroad-mainline-30mph --seed $seed --out "$work/rec$seed" -q || fail "simulate failed"
done
expect_status 0 "$roadload" grade --route $route "$work/rec1" "$work/rec2" --out "$work/gnss.csv"
[[ $(head -1 "$work/gnss.csv") == "# slope_base_m = 30.0" ]] || fail "gnss.csv base: $(head -1 "$work/gnss.csv")"
[[ $(grep -v "^#" "$work/gnss.csv" | head -1) == "$header" ]] || fail "gnss.csv header: $(sed -n 2p "$work/gnss.csv")"
grep -Eq "^# error_correlation_m = [0-9.]+$" "$work/gnss.csv" || fail "gnss.csv records no measured error correlation"
grep -q "passes 2;" "$work/err" || fail "summary does not report 2 passes: $(cat "$work/err")"
grep -q "RMS difference" "$work/err" || fail "no comparison with the survey printed"
# The bins without the comment lines (the survey's records no measured correlation).
grep -v "^#" "$work/gnss.csv" >"$work/gnss-rows.csv"
grep -v "^#" "$work/survey.csv" >"$work/survey-rows.csv"
[[ $(wc -l <"$work/out") == $(wc -l <"$work/gnss-rows.csv") ]] || fail "not one comparison line per bin"
read -r bins rms sigma < <(paste -d, "$work/gnss-rows.csv" "$work/survey-rows.csv" | awk -F, 'NR > 1 && $4 != "" {
    n++; d = $4 - $10; s2 += d * d; sig += $5 } END { printf "%d %.4f %.4f\n", n, sqrt(s2 / n), sig / n }')
echo "grade-cli: 2 passes: $bins bins with a grade, RMS difference from the survey $rms %, mean sigma $sigma %"
((bins >= 450)) || fail "only $bins bins with a grade from two passes over 4.86 km"
awk -v r="$rms" -v s="$sigma" 'BEGIN { exit !(r < 0.3 && r < 2 * s && s < 2 * r) }' ||
  fail "GNSS grade vs survey: RMS $rms %, mean sigma $sigma %"
awk -F, 'NR > 1 && $6 < 2 && $4 != "" { exit 1 }' "$work/gnss-rows.csv" || fail "a bin with fewer than 2 passes has a grade"

# One pass is not enough for the default --min-passes: the file is written, nothing in it guessed.
mkdir "$work/one"
cp "$work/rec1/meta.toml" "$work/rec1/gnss.csv" "$work/one/"
expect_status 65 "$roadload" grade --route $route "$work/one" --out "$work/one.csv"
grep -q "no bin has a grade" "$work/err" || fail "a single pass not explained: $(cat "$work/err")"
awk -F, 'NR > 2 && $4 != "" { exit 1 }' "$work/one.csv" || fail "a grade from one pass"
sed -i '5s/^\([0-9]*,[0-9]*,\)[^,]*,/\1abc,/' "$work/one/gnss.csv"
expect_status 65 "$roadload" grade --route $route "$work/one" --out "$work/one.csv" --min-passes 1 -q
grep -q "one/gnss.csv:5: lat_deg" "$work/err" || fail "malformed fix not named: $(cat "$work/err")"
expect_csv "$work/survey.csv" "$work/gnss.csv"
echo "grade-cli: PASS"
