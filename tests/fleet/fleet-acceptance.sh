#!/usr/bin/env bash
# Issue 26's acceptance, end to end as a pavement agency would run it: a simulated fleet (24 trucks
# drawn from the vehicle files' spreads, three roads with jointed concrete and asphalt, both
# directions, five days of different temperatures; tests/fleet/make_fleet.py) analysed on Dask (a
# scheduler and two workers started here) into a throw-away PostgreSQL/PostGIS server, collected
# into SQLite too; collecting every drive again changes no table; both databases give the same
# network; the network's sections hold the pavements' own CRR in 80-97 % of their 90 % intervals
# and the trucks' tire spread inside its interval (check_network.py); the map draws every section.
set -euo pipefail
roadload=$(realpath "${1:?usage: fleet-acceptance.sh ROADLOAD_BIN}")
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=../cli/cli-lib.sh
. "$here/../cli/cli-lib.sh" fleet-acceptance
# shellcheck source=../support/pg-temp.sh
. "$here/../support/pg-temp.sh"
# shellcheck source=../support/dask-temp.sh
. "$here/../support/dask-temp.sh"
pg=$(mktemp -d "${TMPDIR:-/tmp}/fleet-acceptance-pg.XXXXXX")
trap 'dask_temp_stop "$work/dask"; pg_temp_stop "$pg"; rm -rf -- "$work"' EXIT
python=/usr/bin/python3
start=$SECONDS
said() { echo "fleet-acceptance: $* ($((SECONDS - start)) s)"; }

"$python" "$here/make_fleet.py" --out "$work/fleet" --roadload "$roadload" --trucks 24 --days 5 --seed 1 --simulate-only \
  >"$work/make.log" 2>&1 || fail "make_fleet.py: $(tail -5 "$work/make.log")"
drives=$(($(wc -l <"$work/fleet/manifest.csv") - 1))
said "$drives drives of $(($(wc -l <"$work/fleet/truth/trucks.csv") - 1)) trucks simulated"

url=$(pg_temp_start "$pg") || fail "no PostgreSQL server could start"
address=$(dask_temp_start "$work/dask" 2) || fail "no Dask cluster could start"
cd "$work/fleet"
expect_status 0 "$roadload" batch manifest.csv --db "$url" --scheduler "$address" -o "$work/results"
grep -q "$drives/$drives drives done, 0 failed" "$work/err" || fail "batch: $(tail -3 "$work/err")"
said "analysed on Dask into PostgreSQL"
expect_status 0 "$roadload" collect "$work"/results/* --db "$work/fleet.db" -q
grep -q "$drives drives added" "$work/out" || fail "SQLite collect: $(cat "$work/out")"

# Every table, as text in a fixed order, from each database.
tables="vehicles routes sections drives section_results schema_version"
sqlite_dump() {
  for t in $tables; do echo "== $t" && sqlite3 -csv "$work/fleet.db" "SELECT * FROM $t" | LC_ALL=C sort; done
}
pg_dump() {
  for t in $tables; do echo "== $t" && psql -q -A -t "$url" -c "SELECT * FROM $t" | LC_ALL=C sort; done
}
sqlite_dump >"$work/sqlite1.txt"
pg_dump >"$work/pg1.txt"
expect_status 0 "$roadload" collect "$work"/results/* --db "$work/fleet.db" -q
grep -q "0 drives added, $drives unchanged" "$work/out" || fail "collecting into SQLite again: $(cat "$work/out")"
expect_status 0 "$roadload" collect "$work"/results/* --db "$url" -q
grep -q "0 drives added, $drives unchanged" "$work/out" || fail "collecting into PostgreSQL again: $(cat "$work/out")"
sqlite_dump >"$work/sqlite2.txt"
pg_dump >"$work/pg2.txt"
cmp -s "$work/sqlite1.txt" "$work/sqlite2.txt" || fail "collecting again changed the SQLite tables"
cmp -s "$work/pg1.txt" "$work/pg2.txt" || fail "collecting again changed the PostgreSQL tables"
said "collecting every drive again changed no row ($(wc -l <"$work/pg1.txt") rows)"

expect_status 0 "$roadload" network --db "$url" -o "$work/net-pg"
said "$(cat "$work/out")"
expect_status 0 "$roadload" network --db "$work/fleet.db" -o "$work/net-sqlite"
for f in network.csv network-bands.csv trucks.csv network.geojson network.json; do
  cmp -s "$work/net-sqlite/$f" "$work/net-pg/$f" || fail "SQLite and PostgreSQL give another $f"
done
expect_csv "$work/net-pg"
"$python" "$here/check_network.py" "$work/net-pg" "$work/fleet" | tee "$work/check.txt"
grep -q "check: PASS" "$work/check.txt" || fail "the network does not hold the fleet's truth"

sections=$(($(wc -l <"$work/net-pg/network.csv") - 1))
check='const drawn = [...document.querySelectorAll("path.section")].filter(e => { const b = e.getBBox(); return b.width > 0 || b.height > 0; });
document.getElementById("roadload-check").textContent = String(drawn.length);'
drawn=$(render_check "$work/net-pg/network.html" "$check")
[[ $drawn == "$sections" ]] || fail "the map draws ${drawn:-no} sections of $sections"
said "the map draws $drawn of $sections sections; PASS"
