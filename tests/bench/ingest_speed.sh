#!/usr/bin/env bash
# The fleet database's ingest rate (roadload collect, docs/fleet.md): N analysed drives into SQLite
# and into a throw-away PostgreSQL/PostGIS server, in drives and section rows per second, beside a
# baseline measured in the same run: the sqlite3 shell bulk-importing the same cells.csv rows into
# a bare table (the engine's own speed, no parsing of trip.json, no keys, no geometry).
# usage: ingest_speed.sh BUILD_DIR [DRIVES]
set -euo pipefail
build=${1:?usage: ingest_speed.sh BUILD_DIR [DRIVES]}
drives=${2:-${ROADLOAD_BENCH_INGEST_DRIVES:-300}}
roadload=$build/tools/roadload
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=../support/pg-temp.sh
. "$here/../support/pg-temp.sh"
work=$(mktemp -d "${TMPDIR:-/tmp}/ingest-bench.XXXXXX")
pg=$(mktemp -d "${TMPDIR:-/tmp}/ingest-bench-pg.XXXXXX")
trap 'pg_temp_stop "$pg"; rm -rf -- "$work"' EXIT

# One drive over the whole Mainline (15 cells), copied under other run ids: collect reads and
# writes every copy in full, as it would distinct drives.
"$roadload" simulate --scenario mnroad-mainline-64mph --seed 1 --out "$work/rec" -q 2>/dev/null
"$roadload" analyze "$work/rec" --route mnroad-mainline-westbound -o "$work/res" -q >/dev/null 2>&1
id=$(sed -n 's/.*"recording_id": "\([^"]*\)".*/\1/p' "$work/res/trip.json")
for ((i = 0; i < drives; i++)); do
  mkdir -p "$work/d$i"
  cp "$work/res/cells.csv" "$work/res/pavements.csv" "$work/d$i/"
  sed "s/$id/$id-$i/" "$work/res/trip.json" >"$work/d$i/trip.json"
done
rows=$(($(wc -l <"$work/res/cells.csv") - 1))
now() { date +%s.%N; }
rate() { awk -v n="$1" -v a="$2" -v b="$3" 'BEGIN { printf "%.1f", n / (b - a) }'; }

t0=$(now)
"$roadload" collect "$work"/d* --db "$work/fleet.db" -q >/dev/null
t1=$(now)
url=$(pg_temp_start "$pg")
t2=$(now)
"$roadload" collect "$work"/d* --db "$url" -q >/dev/null
t3=$(now)
for ((i = 0; i < drives; i++)); do tail -n +2 "$work/d$i/cells.csv"; done >"$work/all.csv"
t4=$(now)
sqlite3 "$work/raw.db" "CREATE TABLE raw ($(head -1 "$work/res/cells.csv" | sed 's/,/ TEXT, /g') TEXT)" ".mode csv" ".import $work/all.csv raw"
t5=$(now)

sqlite_rows=$(rate $((drives * rows)) "$t0" "$t1")
pg_rows=$(rate $((drives * rows)) "$t2" "$t3")
raw_rows=$(rate $((drives * rows)) "$t4" "$t5")
echo "ingest: $drives drives of $rows sections each"
echo "ingest: SQLite      $(rate "$drives" "$t0" "$t1") drives/s, $sqlite_rows section rows/s"
echo "ingest: PostgreSQL  $(rate "$drives" "$t2" "$t3") drives/s, $pg_rows section rows/s"
echo "ingest: baseline    sqlite3 .import of the same rows: $raw_rows rows/s"
awk -v s="$sqlite_rows" -v p="$pg_rows" -v r="$raw_rows" \
  'BEGIN { printf "ingest: ratio to the baseline: SQLite %.3f, PostgreSQL %.3f\n", s / r, p / r }'
