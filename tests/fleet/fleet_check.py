#!/usr/bin/env python3
"""A small fleet (2 trucks, 3 roads both ways, 2 days) made and checked against what
make_fleet.py promises: the analysis gets the type's numbers with the truck's own VIN and the
type's mass, the drawn scales reach the simulator, the reversed lanes mirror the forward ones,
and the truth and manifest files name every drive.

usage: fleet_check.py ROADLOAD_BIN
"""
import csv
import pathlib
import subprocess
import sys
import tempfile
import tomllib

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import fleet_routes  # noqa: E402

FAILURES = []


def check(ok, what):
    if not ok:
        FAILURES.append(what)
        print(f"FAIL: {what}")


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def check_drives(out, trucks, drives):
    for d in drives:
        t = trucks[d["truck"]]
        meta = tomllib.loads((out / d["recording"] / "meta.toml").read_text())
        truth = tomllib.loads((out / d["truth"] / "truth.toml").read_text())
        scenario = tomllib.loads((out / "drives" / d["drive"] / "scenario.toml").read_text())
        check(meta["vehicle"]["vin"] == t["vin"], f"{d['drive']}: the recording's VIN is the truck's")
        check(abs(meta["vehicle"]["mass_kg"] - float(t["nominal_mass_kg"])) < 0.01, f"{d['drive']}: the recording declares the type's mass")
        check(abs(truth["true_mass_kg"] - float(t["mass_kg"])) < 1.0, f"{d['drive']}: the simulated truck carries its cargo")
        check(abs(truth["cda_m2"] - float(t["cda_m2"])) < 1e-3, f"{d['drive']}: the simulated truck has its drag area")
        check(truth.get("tire_crr_scale", 1.0) == float(t["tire_crr_scale"]), f"{d['drive']}: its tires' scale reaches the truth")
        check(scenario["tire_crr_scale"] == float(t["tire_crr_scale"]), f"{d['drive']}: and the scenario")
        check((out / d["results"] / "cells.csv").exists(), f"{d['drive']}: analysed")
        type_file = tomllib.loads((HERE.parent.parent / t["type_file"]).read_text())
        own = tomllib.loads((out / t["vehicle_file"]).read_text())
        check({k: v for k, v in own.items() if k != "vin"} == {k: v for k, v in type_file.items() if k != "vin"},
              f"{t['truck']}: its vehicle file is its type's but for the VIN")


def check_lanes(out, sections):
    """Each reversed lane's cells are the forward lane's, mirrored: same ids, CRR and lengths."""
    lanes = {}
    for s in sections:
        lanes.setdefault((s["road"], s["direction"]), {})[s["cell"]] = s
    for road in fleet_routes.ROADS:
        a, b = lanes[(road.name, road.forward_direction)], lanes[(road.name, road.backward_direction)]
        check(set(a) == set(b), f"{road.name}: both lanes drive the same cells")
        for cell in set(a) & set(b):
            check(a[cell]["crr"] == b[cell]["crr"], f"{road.name} {cell}: one CRR both ways")
            la = float(a[cell]["end_m"]) - float(a[cell]["start_m"])
            lb = float(b[cell]["end_m"]) - float(b[cell]["start_m"])
            check(abs(la - lb) < 0.01, f"{road.name} {cell}: one length both ways")
        check({s["surface"] for s in a.values()} >= {"concrete", "bituminous"}, f"{road.name}: concrete and asphalt")


def main():
    roadload = pathlib.Path(sys.argv[1]).resolve()
    with tempfile.TemporaryDirectory(prefix="fleet-check.") as tmp:
        out = pathlib.Path(tmp)
        r = subprocess.run([sys.executable, HERE / "make_fleet.py", "--out", out, "--roadload", roadload, "--trucks", "2",
                            "--days", "2", "--seed", "3"], capture_output=True, text=True)
        if r.returncode != 0:
            print(r.stdout[-2000:], r.stderr[-2000:])
            return 1
        trucks = {t["truck"]: t for t in rows(out / "truth" / "trucks.csv")}
        drives = rows(out / "truth" / "drives.csv")
        manifest = rows(out / "manifest.csv")
        sections = rows(out / "truth" / "sections.csv")
        check(len(drives) == 2 * 2 * len(fleet_routes.ROADS), "every truck drives every road both ways")
        check([m["recording"] for m in manifest] == [d["recording"] for d in drives], "the manifest names every drive")
        check(all((out / m[k]).exists() for m in manifest for k in ("recording", "vehicle", "route")), "its paths exist")
        check(len({t["vin"] for t in trucks.values()}) == len(trucks) and all(len(t["vin"]) == 17 for t in trucks.values()),
              "17-character VINs, one per truck")
        check({t["type"] for t in trucks.values()} == {"mnroad-truck", "tractor-53ft-18speed"}, "both types")
        check(len({d["speed_mph"] for d in drives if d["truck"] == "T01"}) >= 2, "a truck drives at two speeds")
        check_drives(out, trucks, drives)
        check_lanes(out, sections)
    print(f"fleet check: {len(FAILURES)} failures")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
