#!/usr/bin/env bash
# roadload report on a simulated MnROAD Mainline drive, rendered by headless Chromium: every figure
# must be drawn with data (SVG marks with a non-empty box after layout), the tables filled, and the
# page self-contained (no script, nothing fetched). Errors in the results name file and line.
set -euo pipefail
roadload=${1:?usage: report-draws-every-figure.sh ROADLOAD_BIN}
# shellcheck source=cli-lib.sh source-path=SCRIPTDIR
. "$(dirname "${BASH_SOURCE[0]}")/cli-lib.sh" report-cli

expect_status 0 "$roadload" report --help
grep -q -- "--truth" "$work/out" || fail "--help does not describe --truth"
expect_status 64 "$roadload" report "$work/none"
expect_status 66 "$roadload" report "$work/none" -o "$work/r.html"

"$roadload" simulate --scenario mnroad-mainline-30mph --seed 3 --out "$work/rec" --truth "$work/truth" -q || fail "simulate failed"
"$roadload" analyze "$work/rec" --route mnroad-mainline-westbound --out "$work/res" -q 2>/dev/null || fail "analyze failed"
# The sim-to-real section's inputs as `roadload gap --json` and `roadload gap tables --json` write them.
cat >"$work/res/gap.json" <<'JSON'
{"effect": "brake-drag", "magnitude": 118.2, "unit": "N", "interval": [110.1, 126.3],
 "effects": [{"name": "brake-drag", "magnitude": 118.2, "lo": 110.1, "hi": 126.3, "fitted_on_half0": 117.5, "unit": "N"}],
 "where": [{"run": "rec30", "channel": "torque_nm", "features": 30, "excess_chi2": 2500.5, "sigma": 322.8, "worst": "4", "worst_z": 12.5}],
 "nominal": [{"name": "CdA", "unit": "m2", "model": 6.2, "prior_sigma": 0.6, "fitted": 5.81, "lo": 5.7, "hi": 5.92, "shift_sigma": -0.65}],
 "residual_raw": 9.6, "residual_before": 7.8, "residual_after": 0.9, "held_out_features": 120,
 "channels": [{"channel": "torque_nm", "features": 15, "raw": 15.2, "before": 12.1, "after": 1.1},
              {"channel": "fuel_lph", "features": 15, "raw": 7.1, "before": 6.0, "after": 0.8}],
 "candidates": [{"name": "brake-drag", "gain": 4100.2, "magnitude": 118.2}], "runs": ["run rec30: model mnroad-mainline-30mph"],
 "rivals": [{"name": "tire-warmup", "gain": 4050.7}, {"name": "wet-road", "gain": 4011.0}]}
JSON
cat >"$work/res/gap-tables.json" <<'JSON'
{"rows": [{"pavement": "Mainline bituminous (Table 6.5)", "report_w": 442, "before_w": 300, "after_w": 300},
          {"pavement": "Mainline concrete (Table 6.5)", "report_w": 652, "before_w": 310, "after_w": 444},
          {"pavement": "TH 66 bituminous (Table 6.6)", "report_w": 6486, "before_w": 900, "after_w": 900},
          {"pavement": "TH 10 concrete (Table 6.6)", "report_w": 9353, "before_w": 800, "after_w": 1250}],
 "candidates": [{"effect": "joint-faulting", "reaches_mainline_ratio": true, "magnitude": 0.003, "highway_ratio": 1.39, "holdout_error": 0.04}],
 "effect": "joint-faulting", "report_mainline_ratio": 1.475, "report_highway_ratio": 1.442,
 "nominal": [{"name": "mass", "unit": "kg", "value": 36000, "sigma": 360, "power_per_sigma": 0.021,
              "ends": [{"value": 35408, "effect": "joint-faulting", "magnitude": 0.00322, "highway_ratio": 1.03},
                       {"value": 36592, "effect": "joint-faulting", "magnitude": 0.00331, "highway_ratio": 1.03}]},
             {"name": "CdA", "unit": "m2", "value": 6.2, "sigma": 0.6, "power_per_sigma": 0.001, "ends": []}]}
JSON
expect_status 0 "$roadload" report "$work/res" --truth "$work/truth" -o "$work/report.html"
page=$work/report.html
! grep -qi '<script' "$page" || fail "the page carries a script"
! grep -Eo '(src|href)="[a-z]+:[^"]*"' "$page" | grep -q . || fail "the page links outside itself"

# No attribute holds a number that is not one (a bar from 0 on a log axis gave height="inf"), and no
# table is a header without rows.
/usr/bin/python3 - "$page" <<'PY' || fail "the page has a broken figure or an empty table"
import re, sys
html = open(sys.argv[1]).read()
bad = sorted(set(re.findall(r'\b[a-z-]+="[^"]*(?<![a-z])(?:-?inf|nan|NaN|-?Infinity)(?![a-z])[^"]*"', html)))
for table in re.findall(r"<table\b.*?</table>", html, re.S):
    if "<td" not in table:
        bad.append("a table without rows: " + re.sub(r"\s+", " ", table)[:120])
print("\n".join(bad[:10]))
sys.exit(1 if bad else 0)
PY

cells=$(($(wc -l <"$work/res/cells.csv") - 1))
rows=$(sed -n '/id="crr"/,/<\/table>/p' "$page" | grep -c '<tr><td>' || true)
((rows == cells)) || fail "the CRR table has $rows rows for $cells cells"

grep -q 'id="gap"' "$work/report.html" || fail "no sim-to-real section although gap.json is there"
# The top answers per pavement type, and says which truck, route, date and calibration.
/usr/bin/python3 - "$work/report.html" "$work/res/pavements.csv" <<'PY' || fail "the answer per pavement is not at the top"
import csv, re, sys
page, pavements = open(sys.argv[1]).read(), list(csv.DictReader(open(sys.argv[2])))
top = page[: page.index('id="crr"')]
assert 'class="provenance"' in top and "mnroad-truck" in top and "mnroad-mainline-westbound" in top, "no provenance"
assert re.search(r"driven <b>\d{4}-\d\d-\d\dT", top), "no drive date"
rows = re.findall(r"<tr><td>([^<]+)</td><td>(0\.\d{5} \[0\.\d{5}, 0\.\d{5}\]|\u2013)</td>", top)
want = [p["pavement"] for p in pavements]
assert [r[0] for r in rows] == want and len(want) >= 2, f"answer rows {rows} against pavements.csv {want}"
PY
grep -q "brake-drag = 118.2 N" "$work/report.html" || fail "the gap section does not name the effect"
grep -q "<td>not told apart from</td><td>tire-warmup, wet-road " "$work/report.html" ||
  fail "the gap section does not list the rivals the drives cannot tell from the effect"
# Not grep -q: it would stop reading, and under pipefail sed's broken pipe would fail the check.
sed -n '/id="gap"/,$p' "$work/report.html" | grep "<td>CdA</td><td>6.2 m2</td><td>5.81</td>" >/dev/null ||
  fail "the gap section does not show the model's truck against this one"
sed -n '/id="gap"/,$p' "$work/report.html" | grep "<td>mass</td><td>36000 ± 360 kg</td>" >/dev/null ||
  fail "the tables do not show the truck's nominal parameters"
cp "$work/res/gap.json" "$work/gap.json"
sed -i '2s/"magnitude": 118.2/"magnitude": 118.2,,/' "$work/res/gap.json"
expect_status 65 "$roadload" report "$work/res" -o "$work/bad.html"
grep -q "gap.json:2" "$work/err" || fail "a bad gap.json is not named by file and line: $(cat "$work/err")"
cp "$work/gap.json" "$work/res/gap.json"

cp "$work/res/cells.csv" "$work/bad.csv"
sed -i '3s/,0\.0[0-9]*,/,0.0x,/' "$work/bad.csv" && cp "$work/bad.csv" "$work/res/cells.csv"
expect_status 65 "$roadload" report "$work/res" -o "$work/bad.html"
grep -q "cells.csv:3: " "$work/err" || fail "a bad number is not named by file and line: $(cat "$work/err")"

# After layout, each figure's drawn marks: those with class "datum" whose box is not empty; and
# the pairs of marker labels (mode numbers) whose boxes overlap, which must be none. The script
# goes in through render_check (cli-lib.sh).
check='
const out = {};
let overlaps = 0;
for (const f of document.querySelectorAll("figure")) {
  out[f.id] = [...f.querySelectorAll(".datum")].filter(e => { const b = e.getBBox(); return b.width > 0 || b.height > 0; }).length;
  const boxes = [...f.querySelectorAll(".marker-label")].map(e => e.getBoundingClientRect());
  for (let i = 0; i < boxes.length; ++i) for (let j = i + 1; j < boxes.length; ++j) {
    const a = boxes[i], b = boxes[j];
    if ((a.left < b.right) + (b.left < a.right) + (a.top < b.bottom) + (b.top < a.bottom) === 4) ++overlaps;
  }
}
out["overlapping-labels"] = overlaps;
document.getElementById("roadload-check").textContent = JSON.stringify(out);
'
drawn=$(render_check "$page" "$check")
[[ -n $drawn ]] || fail "the page did not render (no check output)"
echo "report-cli: drawn marks per figure: $drawn"
/usr/bin/python3 - "$drawn" "$cells" <<'PY' || fail "a figure is not drawn with data"
import json, sys
drawn, cells = json.loads(sys.argv[1]), int(sys.argv[2])
want = {"crr-per-cell": cells, "rolling-fuel-per-cell": cells, "fuel-breakdown-per-cell": cells,
        "trip-fuel-breakdown": 6, "contact-forces": cells, "dynamic-power-per-cell": cells, "psd-trip": 3,
        "gap-channels": 4, "gap-tables": 12}
bad = [f"{k}: {drawn.get(k, 0)} marks, expected at least {n}" for k, n in want.items() if drawn.get(k, 0) < n]
labels = drawn.pop("overlapping-labels", None)
if labels != 0: bad.append(f"{labels} pairs of marker labels overlap")
bad += [f"{k}: nothing drawn" for k, n in drawn.items() if n == 0]
groups = [k for k in drawn if k.startswith("psd-") and k != "psd-trip"]
if len(groups) < 2: bad.append(f"spectra per pavement group: {groups}")
print("\n".join(bad))
sys.exit(1 if bad else 0)
PY
echo "report-cli: PASS"
