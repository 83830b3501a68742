#!/usr/bin/env bash
# roadload route build as a user runs it: a route made from their own passes over a road nobody
# gave them a survey of, analyzed with it; cells from a GIS file of pavement sections; geometry
# from a GPX file; a CAN-only recording placed by the truck's VP1; bad input named with its exit code.
set -euo pipefail
roadload=${1:?usage: route-cli.sh ROADLOAD_BIN}
# shellcheck source=cli-lib.sh source-path=SCRIPTDIR
. "$(dirname "${BASH_SOURCE[0]}")/cli-lib.sh" route-cli

expect_status 0 "$roadload" route --help
for o in --out --cell-length --sections --vehicle --antenna-height; do grep -q -- "$o" "$work/out" || fail "--help does not describe $o"; done
expect_status 64 "$roadload" route
expect_status 64 "$roadload" route survey
expect_status 64 "$roadload" route build --out "$work/r.toml"
expect_status 64 "$roadload" route build "$work/x" --out "$work/r.toml" --cell-length 100 --sections "$work/s.geojson"
expect_status 66 "$roadload" route build "$work/no-such-recording" --out "$work/r.toml"
grep -q "no-such-recording" "$work/err" || fail "missing recording not named: $(cat "$work/err")"

# Three passes over the Mainline at 30 mph; the route comes from them alone. No accelerometers:
# nothing here reads them, and they are most of a simulation's time (under the sanitizers too).
config=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../config" && pwd)
sed "s|^route = .*|route = \"$config/routes/mnroad-mainline-westbound.toml\"\naccelerometers = 0|" \
  "$config/scenarios/mnroad-mainline-30mph.toml" >"$work/m30.toml"
for seed in 1 2 3; do
  "$roadload" simulate --scenario "$work/m30.toml" --seed $seed --out "$work/rec$seed" \
    $([[ $seed == 1 ]] && echo --truth "$work/truth1") -q || fail "simulate failed"
done
expect_status 0 "$roadload" route build "$work/rec1" "$work/rec2" "$work/rec3" --out "$work/own.toml"
grep -q "3 passes" "$work/err" || fail "three passes not found: $(cat "$work/err")"
[[ -s $work/own.grade.csv ]] || fail "no grade profile written beside the route"
grep -q '^grade = "own.grade.csv"$' "$work/own.toml" || fail "the route does not name its grade profile"
! grep -q '^crr' "$work/own.toml" || fail "a built route states a CRR"
cells=$(grep -c '^\[\[cell\]\]' "$work/own.toml")
((cells >= 18 && cells <= 20)) || fail "$cells cells of 250 m over the 4.86 km drive"
# Three passes give a grade sigma of about 0.1 %: the trip's 99 % interval holds the truth
# (rolling work over weight and distance), and a CRR not identified says why.
expect_status 0 "$roadload" analyze "$work/rec1" --route "$work/own.toml" --out "$work/a" -q
truth=$(awk -F' = ' '/^true_mass_kg/ { m = $2 } /^rolling_j/ { r = $2 } END { print r / (m * 9.80665) }' "$work/truth1/truth.toml")
python3 - "$work/a/trip.json" "$truth" <<'PY' || fail "trip CRR on the built route"
import json, sys
t = json.load(open(sys.argv[1]))
dist = t["fuel"]["distance_m"]
truth = float(sys.argv[2]) / dist
print(f"route-cli: built route: trip CRR {t['crr']:.5f} +- {t['crr_sigma']:.5f}, truth {truth:.5f}, identified {t['crr_identified']}")
assert t["crr_identified"] or t["not_identified"], "not identified, and no reason given"
assert abs(t["crr"] - truth) < 2.58 * t["crr_sigma"], "the truth lies outside the 99 % interval"
PY

# Sections from a GIS layer: two drawn on the traced road, one on another road.
python3 - "$work/own.toml" "$work/sections.geojson" <<'PY'
import sys, tomllib
r = tomllib.load(open(sys.argv[1], "rb"))
pts = [[p["lon_deg"], p["lat_deg"]] for p in r["point"]]
half = len(pts) // 2
far = [[x + 0.05, y] for x, y in pts[:10]]
def f(name, props, line): return {"type": "Feature", "properties": dict(name=name, **props), "geometry": {"type": "LineString", "coordinates": line}}
import json
json.dump({"type": "FeatureCollection", "features": [
  f("JPCP 4.57", {"surface": "concrete", "panel_length_m": 4.57, "iri_m_per_km": 1.4}, pts[:half + 1]),
  f("HMA", {"surface": "asphalt"}, pts[half:]),
  f("elsewhere", {}, far)]}, open(sys.argv[2], "w"))
PY
expect_status 0 "$roadload" route build "$work/rec1" --sections "$work/sections.geojson" --out "$work/sec.toml"
grep -q "elsewhere: not on the route" "$work/err" || fail "the section elsewhere is not reported: $(cat "$work/err")"
[[ $(grep -c '^\[\[cell\]\]' "$work/sec.toml") == 2 ]] || fail "sections: $(grep '^id' "$work/sec.toml")"
grep -q '^joint_spacing_m = 4.57$' "$work/sec.toml" || fail "the panel length is not kept"
grep -q '^surface = "bituminous"$' "$work/sec.toml" || fail "asphalt is not read as bituminous"
expect_status 0 "$roadload" analyze "$work/rec1" --route "$work/sec.toml" --out "$work/s" -q
[[ $(grep -c '^"\?JPCP\|^"\?HMA' "$work/s/cells.csv") == 2 ]] || fail "cells.csv: $(cut -d, -f1 "$work/s/cells.csv")"

# Geometry from a GPX file: a route file that names it, analyzed.
python3 - "$work/own.toml" "$work/own.gpx" <<'PY'
import sys, tomllib
r = tomllib.load(open(sys.argv[1], "rb"))
pts = "".join(f'<trkpt lat="{p["lat_deg"]}" lon="{p["lon_deg"]}"><ele>{p["elev_m"]}</ele></trkpt>' for p in r["point"])
open(sys.argv[2], "w").write(f'<?xml version="1.0"?><gpx version="1.1" xmlns="http://www.topografix.com/GPX/1/1"><trk><trkseg>{pts}</trkseg></trk></gpx>')
PY
printf 'name = "from gpx"\ngeometry = "own.gpx"\ngrade = "own.grade.csv"\n\n[[cell]]\nid = "all"\nstart_m = 0\nlength_m = 4000\n' >"$work/gpx.toml"
expect_status 0 "$roadload" analyze "$work/rec1" --route "$work/gpx.toml" --out "$work/g" -q

# A CAN-only recording: the truck's VP1 places the road, it has no heights (no VDS), so no grade.
mkdir "$work/can"
cp "$work/rec1/can.log" "$work/rec1/meta.toml" "$work/can/"
expect_status 0 "$roadload" route build "$work/can" --out "$work/vp1.toml"
grep -q "from J1939 VP1" "$work/err" || fail "VP1 not used: $(cat "$work/err")"
grep -q "no bin has a grade" "$work/err" || fail "a grade claimed without heights: $(cat "$work/err")"
! grep -q '^elev_m' "$work/vp1.toml" || fail "heights written without a 3-D fix"
# analyze places the same drive by VP1 on the built route; without a weather station's wind it
# is not identified, and says so.
expect_status 0 "$roadload" analyze "$work/can" --route "$work/own.toml" --out "$work/c" -q
python3 - "$work/c/trip.json" <<'PY' || fail "the CAN-only drive on its route: $(cat "$work/err")"
import json, sys
t = json.load(open(sys.argv[1]))
assert t["gnss_used"] >= 10, f"placed by {t['gnss_used']} fixes"
assert not t["crr_identified"] and any("no wind was measured" in r for r in t["not_identified"]), t["not_identified"]
PY

# Bad input: a GIS file's bad value (65, file and field), an unknown kind.
sed 's/"panel_length_m": 4.57/"panel_length_m": -4/' "$work/sections.geojson" >"$work/bad.geojson"
expect_status 65 "$roadload" route build "$work/rec1" --sections "$work/bad.geojson" --out "$work/bad.toml"
grep -q "bad.geojson: features\[0\].properties.panel_length_m" "$work/err" || fail "bad section value not named: $(cat "$work/err")"
expect_status 66 "$roadload" route build "$work/rec1" --sections "$work/none.geojson" --out "$work/bad.toml"
echo "route-cli: PASS"
