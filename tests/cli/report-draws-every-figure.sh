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
expect_status 0 "$roadload" report "$work/res" --truth "$work/truth" -o "$work/report.html"
page=$work/report.html
! grep -qi '<script' "$page" || fail "the page carries a script"
! grep -Eo '(src|href)="[a-z]+:[^"]*"' "$page" | grep -q . || fail "the page links outside itself"

cells=$(($(wc -l <"$work/res/cells.csv") - 1))
rows=$(sed -n '/id="crr"/,/<\/table>/p' "$page" | grep -c '<tr><td>' || true)
((rows == cells)) || fail "the CRR table has $rows rows for $cells cells"

cp "$work/res/cells.csv" "$work/bad.csv"
sed -i '3s/,0\.0[0-9]*,/,0.0x,/' "$work/bad.csv" && cp "$work/bad.csv" "$work/res/cells.csv"
expect_status 65 "$roadload" report "$work/res" -o "$work/bad.html"
grep -q "cells.csv:3: " "$work/err" || fail "a bad number is not named by file and line: $(cat "$work/err")"

chromium=$(command -v chromium || true)
if [[ -z $chromium ]]; then
  [[ ${ROADLOAD_REQUIRE_CHROMIUM:-0} == 1 ]] && fail "chromium is missing (scripts/setup installs it)"
  echo "report-cli: SKIPPED the rendering (no chromium)"
  exit 77
fi
# After layout, each figure's drawn marks: those with class "datum" whose box is not empty.
check='<pre id="roadload-check"></pre><script>
const out = {};
for (const f of document.querySelectorAll("figure")) {
  out[f.id] = [...f.querySelectorAll(".datum")].filter(e => { const b = e.getBBox(); return b.width > 0 || b.height > 0; }).length;
}
document.getElementById("roadload-check").textContent = JSON.stringify(out);
</script>'
sed "s#</body>#${check//$'\n'/ }</body>#" "$page" >"$work/check.html"
timeout 120 "$chromium" --headless=new --no-sandbox --disable-gpu --no-first-run --user-data-dir="$work/profile" \
  --dump-dom "file://$work/check.html" >"$work/dom.html" 2>"$work/chromium.err" || fail "chromium failed: $(tail -5 "$work/chromium.err")"
drawn=$(sed -n 's#.*<pre id="roadload-check">\([^<]*\)</pre>.*#\1#p' "$work/dom.html")
[[ -n $drawn ]] || fail "the page did not render (no check output)"
echo "report-cli: drawn marks per figure: $drawn"
/usr/bin/python3 - "$drawn" "$cells" <<'PY' || fail "a figure is not drawn with data"
import json, sys
drawn, cells = json.loads(sys.argv[1]), int(sys.argv[2])
want = {"crr-per-cell": cells, "rolling-fuel-per-cell": cells, "fuel-breakdown-per-cell": cells,
        "trip-fuel-breakdown": 6, "contact-forces": cells, "dynamic-power-per-cell": cells, "psd-trip": 3}
bad = [f"{k}: {drawn.get(k, 0)} marks, expected at least {n}" for k, n in want.items() if drawn.get(k, 0) < n]
bad += [f"{k}: nothing drawn" for k, n in drawn.items() if n == 0]
groups = [k for k in drawn if k.startswith("psd-") and k != "psd-trip"]
if len(groups) < 2: bad.append(f"spectra per pavement group: {groups}")
print("\n".join(bad))
sys.exit(1 if bad else 0)
PY
echo "report-cli: PASS"
