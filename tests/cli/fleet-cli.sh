#!/usr/bin/env bash
# roadload collect and network on four short drives of two trucks, both lanes of the example county
# road, at two speeds: into SQLite and into a throw-away PostgreSQL/PostGIS server; collecting again
# changes no row; both databases give the same network; the map draws every section in headless
# Chromium; results without provenance and a bad database are refused with file and field.
set -euo pipefail
roadload=${1:?usage: fleet-cli.sh ROADLOAD_BIN [ROADLOADD_BIN]}
roadloadd=${2:-$(dirname "$roadload")/../firmware/roadloadd}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
config=$(cd "$here/../../config" && pwd)
# shellcheck source=cli-lib.sh source-path=SCRIPTDIR
. "$here/cli-lib.sh" fleet-cli
# shellcheck source=../support/pg-temp.sh
. "$here/../support/pg-temp.sh"
# The server runs as `postgres` when this runs as root: its folder is not under the private $work.
pg=$(mktemp -d "${TMPDIR:-/tmp}/fleet-cli-pg.XXXXXX")
trap 'pg_temp_stop "$pg"; rm -rf -- "$work"' EXIT

expect_status 0 "$roadload" collect --help
expect_status 0 "$roadload" network --help
expect_status 64 "$roadload" collect "$work/none"

n=0
for lane in eastbound westbound; do
  for speed in 45 60; do
    n=$((n + 1))
    vehicle=$([[ $speed == 45 ]] && echo mnroad-truck || echo tractor-53ft-18speed)
    cat >"$work/s$n.toml" <<TOML
name = "county-$lane-$speed"
route = "$config/routes/example-county-road-$lane.toml"
speed_mph = $speed
start_m = 200
end_m = 2700
start_utc = 2026-05-0${n}T14:00:00Z
accel_rate_hz = 400
accelerometers = 4
[weather]
air_temp_c = $((10 + 3 * n))
pressure_pa = 98000
wind_speed_mps = 2.0
wind_from_deg = 200
TOML
    "$roadload" simulate --scenario "$work/s$n.toml" --vehicle "$vehicle" --seed "$n" --out "$work/rec$n" -q 2>/dev/null ||
      fail "simulate $n failed"
    "$roadload" analyze "$work/rec$n" --route "example-county-road-$lane" -o "$work/res$n" -q >/dev/null 2>&1 ||
      fail "analyze $n failed"
  done
done
grep -q '"route_hash": "fnv1a64:' "$work/res1/trip.json" || fail "trip.json has no route hash"

expect_status 0 "$roadload" collect "$work"/res[1-4] --db "$work/fleet.db" -q
grep -q "4 drives added" "$work/out" || fail "first collect: $(cat "$work/out")"
sqlite3 "$work/fleet.db" .dump >"$work/dump1.sql"
expect_status 0 "$roadload" collect "$work"/res[1-4] --db "sqlite://$work/fleet.db" -q
grep -q "0 drives added, 4 unchanged" "$work/out" || fail "collecting again changed something: $(cat "$work/out")"
sqlite3 "$work/fleet.db" .dump >"$work/dump2.sql"
cmp -s "$work/dump1.sql" "$work/dump2.sql" || fail "collecting again changed the SQLite tables: $(diff "$work/dump1.sql" "$work/dump2.sql" | head -5)"
[[ $(sqlite3 "$work/fleet.db" "SELECT COUNT(DISTINCT direction) FROM sections") == 2 ]] || fail "sections are not in two directions"
[[ $(sqlite3 "$work/fleet.db" "SELECT COUNT(*) FROM vehicles") == 2 ]] || fail "not two trucks"

expect_status 0 "$roadload" network --db "$work/fleet.db" -o "$work/net-sqlite"
echo "fleet-cli: $(cat "$work/out")"
expect_csv "$work/net-sqlite"
sections=$(($(wc -l <"$work/net-sqlite/network.csv") - 1))
((sections >= 4)) || fail "only $sections sections in network.csv"

# roadloadd's live results name the same truck and road as analyze's, and collect takes them.
"$roadloadd" --replay "$work/rec1" --replay-can --replay-rate 0 --exit-when-done --no-gnss --route example-county-road-eastbound \
  --results "$work/live" --data-dir "$work/data" --status "$work/status.log" --status-json '' >/dev/null 2>&1 ||
  fail "roadloadd's replay failed"
for key in vehicle_hash route_hash drive_start_utc; do
  a=$(grep "\"$key\"" "$work/res1/trip.json") b=$(grep "\"$key\"" "$work/live/trip.json")
  [[ -n $a && $a == "$b" ]] || fail "roadloadd's $key ($b) is not analyze's ($a)"
done
grep -q '"program": "roadloadd ' "$work/live/trip.json" || fail "roadloadd's results do not name it"
expect_status 0 "$roadload" collect "$work/live" --db "$work/live.db" -q

url=$(pg_temp_start "$pg") || fail "no PostgreSQL server could start"
expect_status 0 "$roadload" collect "$work"/res4 "$work"/res3 "$work"/res2 "$work"/res1 --db "$url" -q
pg_dump() { psql -q -A -t "$url" -c "SELECT section_key, cell, direction, ST_AsText(geometry) FROM sections ORDER BY 1" \
  -c "SELECT drive_key, vehicle_key, route_hash, results_hash FROM drives ORDER BY 1" \
  -c "SELECT drive_key, section_key, crr FROM section_results ORDER BY 1, 2"; }
pg_dump >"$work/pg1.txt"
expect_status 0 "$roadload" collect "$work"/res[1-4] --db "$url" -q
grep -q "0 drives added, 4 unchanged" "$work/out" || fail "collecting into PostgreSQL again: $(cat "$work/out")"
pg_dump >"$work/pg2.txt"
cmp -s "$work/pg1.txt" "$work/pg2.txt" || fail "collecting again changed the PostgreSQL tables"
expect_status 0 "$roadload" network --db "$url" -o "$work/net-pg"
cmp "$work/net-sqlite/network.csv" "$work/net-pg/network.csv" || fail "SQLite and PostgreSQL give other networks"
cmp "$work/net-sqlite/trucks.csv" "$work/net-pg/trucks.csv" || fail "SQLite and PostgreSQL give other trucks"

# Refusals: results of an older roadload, a database URL of no known kind.
cp -r "$work/res1" "$work/old"
/usr/bin/python3 - "$work/old/trip.json" <<'PY'
import json, sys
trip = json.load(open(sys.argv[1])); del trip["provenance"]["route_hash"]; json.dump(trip, open(sys.argv[1], "w"))
PY
expect_status 65 "$roadload" collect "$work/old" --db "$work/fleet.db"
grep -q "trip.json:.*provenance.route_hash" "$work/err" || fail "missing route hash not named: $(cat "$work/err")"
expect_status 73 "$roadload" collect "$work/res1" --db "mysql://nowhere/x"

check='const drawn = [...document.querySelectorAll("path.section")].filter(e => { const b = e.getBBox(); return b.width > 0 || b.height > 0; });
document.getElementById("roadload-check").textContent = String(drawn.length);'
drawn=$(render_check "$work/net-pg/network.html" "$check")
[[ $drawn == "$sections" ]] || fail "the map draws ${drawn:-no} sections of $sections"
echo "fleet-cli: the map draws $drawn of $sections sections; PASS"
