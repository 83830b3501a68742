#!/usr/bin/env python3
"""roadload.analyze runs `roadload analyze` in-process: the same results folder byte for byte
(cells.csv, pavements.csv, trip.json, the PSDs), its keywords the command's options, its frames
the files' numbers; Python's lock released while it runs; errors raised with the C++'s message.

usage: analyze-matches-cli.py ROADLOAD_BIN
"""

import filecmp
import json
import os
import subprocess
import sys
import tempfile
import threading
import time

import pandas as pd

import roadload

roadload_bin = sys.argv[1]
fail = []
work = tempfile.mkdtemp(prefix="analyze-matches-cli.")


def run(*args):
    subprocess.run([roadload_bin, *args], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def same_folders(a, b):
    names = sorted(os.listdir(a))
    if names != sorted(os.listdir(b)) or "cells.csv" not in names:
        return "files %s vs %s" % (names, sorted(os.listdir(b)))
    _, differ, errors = filecmp.cmpfiles(a, b, names, shallow=False)
    return "differ: %s" % (differ + errors) if differ or errors else None


rec = os.path.join(work, "rec")
run("simulate", "--scenario", "th66-55mph", "--seed", "4", "--duration", "60", "--out", rec, "-q")
options = ["--route", "th66-good-thunder", "--mass", "36500", "--estimate-cda", "--cda-sigma", "0.4"]
run("analyze", rec, *options, "-o", os.path.join(work, "cli"), "-q")
res = roadload.analyze(rec, route="th66-good-thunder", out=os.path.join(work, "py"), mass=36500, estimate_cda=True, cda_sigma=0.4)
if (why := same_folders(os.path.join(work, "cli"), os.path.join(work, "py"))) is not None:
    fail.append("analyze in-process and the CLI wrote different folders: " + why)

cells = pd.read_csv(os.path.join(work, "cli", "cells.csv"))
trip = json.load(open(os.path.join(work, "cli", "trip.json")))
if not res.cells.equals(cells) or not res.pavements.equals(pd.read_csv(os.path.join(work, "cli", "pavements.csv"))):
    fail.append("Results' frames are not the CLI's files")
if res.trip != trip or res.dir != os.path.join(work, "py"):
    fail.append("Results.trip is not the CLI's trip.json, or dir is %r" % res.dir)
if len(res.cells) < 3 or not (0.003 < res.trip["crr"] < 0.012) or res.cells["crr"].isna().all():
    fail.append("implausible results: %d cells, trip CRR %r" % (len(res.cells), res.trip["crr"]))
plain = roadload.analyze(rec, route="th66-good-thunder")
if plain.trip["cda_m2"] == res.trip["cda_m2"] or plain.trip["mass_kg"] == res.trip["mass_kg"]:
    fail.append("the keywords changed nothing: CdA %r and mass %r either way" % (res.trip["cda_m2"], res.trip["mass_kg"]))
print("analyze: %d cells, trip CRR %.5f, the same folder as the CLI's" % (len(res.cells), res.trip["crr"]))

# Without out=, a temporary folder read and removed; the same numbers.
again = roadload.analyze(rec, route="th66-good-thunder", mass=36500, estimate_cda=True, cda_sigma=0.4)
if again.dir is not None or not again.cells.equals(res.cells) or again.trip["crr"] != res.trip["crr"]:
    fail.append("out=None gave dir %r or other numbers" % again.dir)
if not roadload.read_results(os.path.join(work, "cli")).cells.equals(cells):
    fail.append("read_results differs from the files")

# Python's lock is released while the C++ runs: a thread counts meanwhile.
ticks, stop = [0], threading.Event()


def count():
    while not stop.is_set():
        ticks[0] += 1
        time.sleep(0.001)


counter = threading.Thread(target=count)
counter.start()
start = time.monotonic()
roadload.analyze(rec, route="th66-good-thunder")
wall = time.monotonic() - start
stop.set()
counter.join()
# Held, the thread would tick only before and after; released, about once a millisecond.
if ticks[0] < max(10, 0.25 * wall * 1000):
    fail.append("a thread counted %d ms-ticks in %.2f s of analysis: the lock was held" % (ticks[0], wall))
print("lock released: a thread ticked %d times during %.2f s of analysis" % (ticks[0], wall))


def expect(error, status, text, call):
    try:
        call()
        fail.append("%s raised nothing" % text)
    except error as e:
        if e.status != status or text not in str(e):
            fail.append("expected %s %d with %r; got %d: %s" % (error.__name__, status, text, e.status, e))
        return e


expect(roadload.InputError, 66, "none: No such file", lambda: roadload.analyze(os.path.join(work, "none")))
expect(roadload.UsageError, 64, "--mass: '5' is not a finite number", lambda: roadload.analyze(rec, mass=5))
expect(roadload.UsageError, 64, "unknown keyword 'colour'", lambda: roadload.analyze(rec, colour="red"))
expect(roadload.InputError, 66, "nosuch.toml", lambda: roadload.analyze(rec, route="nosuch"))
expect(roadload.InputError, 66, "trip.json", lambda: roadload.read_results(work))
# collect in-process: the counts of the fleet library, then its errors as the command's.
db = os.path.join(work, "fleet.db")
first, second = roadload.collect([os.path.join(work, "cli")], db), roadload.collect(os.path.join(work, "py"), db)
if (first["drives_added"], first["sections_added"], second["drives_unchanged"]) != (1, len(res.cells), 1):
    fail.append("collect: %s, then the same drive again %s" % (first, second))
expect(roadload.InputError, 65, "cells.csv: cannot be opened", lambda: roadload.collect([work], db))
expect(roadload.OutputError, 73, "cannot open the SQLite database", lambda: roadload.collect([os.path.join(work, "cli")], os.path.join(work, "none", "x", "fleet.db")))
with open(os.path.join(rec, "can.log")) as f:
    lines = f.readlines()
lines[9] = "(12.5) can0 0CF00400#00\n"
with open(os.path.join(rec, "can.log"), "w") as f:
    f.writelines(lines)
e = expect(roadload.InputError, 65, "can.log:10: ", lambda: roadload.analyze(rec, route="th66-good-thunder"))
if e is not None and (e.result is None or len(e.result.cells) != len(res.cells)):
    fail.append("malformed line: the rest was not analysed into the error's result")

if fail:
    sys.exit("analyze-matches-cli: FAIL:\n  " + "\n  ".join(fail))
import shutil  # noqa: E402

shutil.rmtree(work)
print("analyze-matches-cli: PASS")
