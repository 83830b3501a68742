#!/usr/bin/env python3
"""`roadload decode --pgn-stats` against a count made here independently of the C++ codec:
every PGN's frame count and source set must match, for every real trace given."""
import csv
import io
import subprocess
import sys
from collections import defaultdict

roadload, *logs = sys.argv[1:]
failed = False
for log in logs:
    frames = defaultdict(int)
    sources = defaultdict(set)
    with open(log) as f:
        for line in f:
            if not line.startswith("("):
                continue
            ident = line.split()[2].split("#")[0]
            if len(ident) != 8 or int(ident, 16) & 0x20000000 or line.split()[2].split("#")[1][:1] in ("R", "#"):
                continue
            can_id = int(ident, 16)
            pf = (can_id >> 16) & 0xFF
            pgn = (can_id >> 8) & 0x3FF00 if pf < 240 else (can_id >> 8) & 0x3FFFF
            frames[pgn] += 1
            sources[pgn].add("%02X" % (can_id & 0xFF))
    out = subprocess.run([roadload, "decode", "--pgn-stats", log], capture_output=True, text=True)
    if out.returncode != 0:
        print(f"{log}: exit {out.returncode}: {out.stderr}")
        failed = True
        continue
    rows = {int(r["pgn"]): r for r in csv.DictReader(io.StringIO(out.stdout))}
    for pgn, n in frames.items():
        got = rows.get(pgn)
        if got is None or int(got["frames"]) != n or set(got["sources"].split(";")) != sources[pgn]:
            print(f"{log}: PGN {pgn}: expected {n} frames from {sorted(sources[pgn])}, got {got}")
            failed = True
    extra = [p for p, r in rows.items() if int(r["frames"]) > 0 and p not in frames]
    if extra:
        print(f"{log}: PGNs reported that the log does not carry: {extra}")
        failed = True
    print(f"{log}: {len(frames)} PGNs, {sum(frames.values())} frames checked")
sys.exit(1 if failed else 0)
