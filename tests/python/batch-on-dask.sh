#!/usr/bin/env bash
# roadload batch on a Dask cluster started as a user starts one: a scheduler and two workers,
# each its own process (tests/support/dask-temp.sh) on ports the system picks. The batch connects
# with --scheduler; every drive's results must equal a direct `roadload analyze` byte for byte
# and be in the database, both workers must have analysed some, two recordings named alike get
# folders told apart by their parents; a missing recording fails its drive alone, named, with
# exit status 1. The processes are stopped on any exit. PYTHONPATH holds the build tree's
# package (tests/python/CMakeLists.txt).
set -euo pipefail
roadload=$(realpath "${1:?usage: batch-on-dask.sh ROADLOAD_BIN}")
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=../cli/cli-lib.sh
. "$here/../cli/cli-lib.sh" batch-on-dask
# shellcheck source=../support/dask-temp.sh
. "$here/../support/dask-temp.sh"
trap 'dask_temp_stop "$work/dask"; rm -rf -- "$work"' EXIT
python=/usr/bin/python3

# Three short drives: two on the route, in folders of one name as a logger names them, and one
# on the road its GNSS traces.
for seed in 1 2 3; do
  folder=$work/drives/t$seed/rec
  ((seed == 3)) && folder=$work/drives/d3
  "$roadload" simulate --scenario th10-55mph --seed "$seed" --duration 40 --out "$folder" -q 2>/dev/null ||
    fail "simulate seed $seed"
done
printf 'recording,vehicle,route\nt1/rec,,th10-sartell\nt2/rec,,th10-sartell\nd3,,\n' >"$work/drives/manifest.csv"

address=$(dask_temp_start "$work/dask" 2) || fail "no Dask cluster could start"
cd "$work"
expect_status 0 "$roadload" batch drives/manifest.csv --db "$work/fleet.db" --scheduler "$address" -o "$work/results"
grep -q "3/3 drives done, 0 failed" "$work/err" || fail "no progress to 3/3: $(cat "$work/err")"
# Both workers took drives: "batch: drives per worker: host:pid N, host:pid M".
entries=$(sed -n 's/^batch: drives per worker: //p' "$work/err" | tr ',' '\n' | grep -c . || true)
((entries == 2)) || fail "the drives did not go to both workers: $(grep "drives per worker" "$work/err")"

for d in t1/rec t2/rec d3; do
  route=(--route th10-sartell)
  [[ $d == d3 ]] && route=()
  "$roadload" analyze "$work/drives/$d" "${route[@]}" -o "$work/direct/${d/\//-}" -q >/dev/null 2>&1 || fail "direct analyze $d"
  diff -r "$work/direct/${d/\//-}" "$work/results/${d/\//-}" >"$work/diff" ||
    fail "$d: batch results differ from analyze's: $(head "$work/diff")"
done
"$python" - "$work/fleet.db" "$work/results" <<'PY' || fail "the database does not hold the drives' results"
import json, sqlite3, sys
rows = dict(sqlite3.connect(sys.argv[1]).execute("SELECT results_dir, crr FROM drives").fetchall())
for d in ("t1-rec", "t2-rec", "d3"):
    folder = "%s/%s" % (sys.argv[2], d)
    crr = json.load(open(folder + "/trip.json"))["crr"]
    stored = [v for k, v in rows.items() if k.rstrip("/") == folder]
    assert len(stored) == 1 and abs(stored[0] - crr) < 1e-12, (d, crr, rows)
print("batch-on-dask: the database holds the 3 drives with their trip CRR")
PY

# A drive that cannot be read fails alone, named with its error; the others are done.
printf 'recording,vehicle,route\nd3,,th10-sartell\nmissing,,th10-sartell\n' >"$work/drives/broken.csv"
expect_status 1 "$roadload" batch drives/broken.csv --db "$work/fleet.db" --scheduler "$address" -o "$work/results2"
grep -q "missing (manifest line 3) FAILED: .*missing: No such file or directory" "$work/err" ||
  fail "the failed drive is not named with its error: $(cat "$work/err")"
grep -q "2/2 drives done, 1 failed" "$work/err" || fail "progress does not count the failure: $(cat "$work/err")"
[[ -s $work/results2/d3/cells.csv ]] || fail "the good drive beside the failed one was not analysed"
echo "batch-on-dask: PASS"
