"""What the Python benchmarks share: TOML writing, the simulator's truth per cell, running the CLI."""
import argparse
import csv
import datetime
import json
import pathlib
import subprocess
import tempfile

G = 9.80665


def toml_value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, datetime.datetime):
        return v.isoformat().replace("+00:00", "Z")
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    return json.dumps(v)


def toml_text(doc):
    """A document of scalars, tables of scalars and arrays of such tables (a scenario, a vehicle file)."""
    scalars = [f"{k} = {toml_value(v)}" for k, v in doc.items()
               if not isinstance(v, dict) and not (isinstance(v, list) and v and isinstance(v[0], dict))]
    lines = scalars
    for k, v in doc.items():
        if isinstance(v, dict):
            lines += ["", f"[{k}]"] + [f"{kk} = {toml_value(vv)}" for kk, vv in v.items()]
        elif isinstance(v, list) and v and isinstance(v[0], dict):
            for item in v:
                lines += ["", f"[[{k}]]"] + [f"{kk} = {toml_value(vv)}" for kk, vv in item.items()]
    return "\n".join(lines) + "\n"


def write_toml(path, doc):
    path.write_text(toml_text(doc))


def truth_cells(truth_dir, mass_kg):
    """Per complete cell, what the force balance measures: the tires' CRR plus the suspension's and
    tires' dissipated power over v m g."""
    cells = {}
    for r in csv.DictReader(open(truth_dir / "cells.csv")):
        if r["complete"] != "1":
            continue
        v = float(r["speed_mps"])
        dissipation = (float(r["damper_power_w"]) + float(r["tire_power_w"])) / (v * mass_kg * G) if v > 0 else 0.0
        cells[r["cell"]] = float(r["crr"]) + dissipation
    return cells


def run(cmd):
    return subprocess.run([str(c) for c in cmd], capture_output=True, text=True)


def run_checked(cmd, what):
    """Runs cmd; a failure stops the benchmark with its command and error."""
    r = run(cmd)
    if r.returncode != 0:
        raise SystemExit(f"{what}: exit {r.returncode}: {' '.join(str(c) for c in cmd)}\n{r.stderr.strip()[-600:]}")
    return r


def bench_args(doc, count_flag, default, prefix, switches=()):
    """ROADLOAD_BIN, a count, --keep DIR and the bench's own on/off `switches` (name, help): the
    arguments and the work folder (kept when given)."""
    ap = argparse.ArgumentParser(description=doc.splitlines()[0])
    ap.add_argument("roadload")
    ap.add_argument(count_flag, type=int, default=default)
    ap.add_argument("--keep")
    for name, text in switches:
        ap.add_argument(name, action="store_true", help=text)
    a = ap.parse_args()
    work = pathlib.Path(a.keep or tempfile.mkdtemp(prefix=prefix))
    work.mkdir(parents=True, exist_ok=True)
    return a, work
