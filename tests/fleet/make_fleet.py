#!/usr/bin/env python3
"""A simulated fleet's drives, for the acceptance of one map from many trucks (issue 26).

Trucks of the two shipped vehicle files' types, each drawn from its file's spreads (cargo, drag
area, tires' rolling resistance, engine friction: fleet_trucks.py), drive three roads with jointed
concrete and asphalt, both ways (fleet_routes.py), on days of different air temperature and wind.
Every truck drives every road once, both ways on one day, at the road's slow or fast speed (each
truck at least once at each, so its drag area is told from its tires), so every section gets
drives from every truck; the roads fall on different days.

Each drive is a scenario file, simulated and then analysed as a fleet would analyse it:

  roadload simulate --scenario drives/N/scenario.toml --seed S --out drives/N/rec --truth drives/N/truth -q
  roadload analyze drives/N/rec --vehicle vehicles/T.toml --route routes/R.toml -o drives/N/results -q

The analysis gets the truck's vehicle file, which is its type's with the truck's own VIN, and the
declared (the type's) mass in the recording; never the drawn scales.

Writes into --out (every path in its CSV files relative to that folder):
  manifest.csv          recording,vehicle,route: one line per drive, what `roadload analyze` needs
  vehicles/, routes/    the trucks' vehicle files and the lanes' route files
  drives/N/             scenario.toml, rec/ (the recording), truth/ (the simulator's, without its
                        0.01 s axles.csv), results/ (the analysis)
  truth/trucks.csv      per truck: VIN, type, true mass, CdA and the drawn scales
  truth/sections.csv    per lane's cell: surface, the pavement's own CRR, where it lies, drives on it
  truth/drives.csv      per drive: truck, day, lane, speed, weather, seeds

The truth of a cell is the pavement's own CRR (the route file's); a drive's truth/cells.csv has
the CRR the truck's tires met there, the pavement's times the truck's tire_crr_scale.

usage: make_fleet.py --out DIR --roadload PATH [--trucks 24] [--days 5] [--seed 1] [--jobs 2]
                     [--simulate-only]
"""
import argparse
import concurrent.futures
import csv
import datetime
import os
import pathlib
import sys
import time

import numpy as np

import fleet_routes
import fleet_trucks

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "bench"))
from benchlib import run_checked, write_toml  # noqa: E402

CONFIG = HERE.parent.parent / "config"
# Accelerometers at 200 Hz, the analysis' own grid (its anti-alias filter at 80 Hz; the body and
# axle-hop modes at 1.5-19 Hz): a drive's recording about 10 MB instead of 50 MB at the default
# 1,200 Hz. On the Mainline at 45 mph the dampers' power reads 3 % and the tires' 14 % low against
# 1 % and 2 % at 1,200 Hz, the cells' CRR the same to 1e-5 (docs/journal.md, 2026-11-27).
ACCEL_RATE_HZ = 200
FIRST_DAY = datetime.datetime(2026, 4, 6, 8, 0, tzinfo=datetime.timezone.utc)


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", required=True, type=pathlib.Path)
    ap.add_argument("--roadload", required=True, help="the roadload program")
    ap.add_argument("--trucks", type=int, default=24)
    ap.add_argument("--days", type=int, default=5)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--jobs", type=int, default=2, choices=(1, 2), help="drives simulated at once (the machine has two cores)")
    ap.add_argument("--simulate-only", action="store_true", help="no analysis (the manifest's runner does it)")
    a = ap.parse_args()
    if a.trucks < 2 or a.days < 1:
        ap.error("at least 2 trucks (both types) and 1 day")
    return a


def make_days(count, rng):
    """Air temperatures spread over -3..29 C in a shuffled order, a wind of 1-5 m/s from anywhere,
    the pressure of the region's weather."""
    temps = np.linspace(-3.0, 29.0, count) + rng.uniform(-1.5, 1.5, count) if count > 1 else np.array([15.0])
    rng.shuffle(temps)
    return [{"day": d + 1, "date": FIRST_DAY + datetime.timedelta(days=9 * d), "air_temp_c": round(float(temps[d]), 1),
             "pressure_pa": round(float(rng.uniform(96800, 100800))), "wind_speed_mps": round(float(rng.uniform(1.0, 5.0)), 1),
             "wind_from_deg": round(float(rng.uniform(0, 360)))} for d in range(count)]


def plan(trucks, lanes, days, rng):
    """Every truck on every road, both ways on one day; a truck's roads on different days, the days
    taken in turn so each gets its share; each truck's speeds both slow and fast."""
    roads = list(dict.fromkeys(lane.road for lane in lanes))
    drives = []
    for i, truck in enumerate(trucks):
        slots = [(i * len(roads) + k) % len(days) for k in range(len(roads))]
        speeds = list(rng.permutation([0, 1] + [int(rng.integers(2))] * (len(roads) - 2)))
        for r, road in enumerate(rng.permutation(roads)):
            spec = next(x for x in fleet_routes.ROADS if x.name == road)
            day = days[slots[r]]
            later = 2 * slots[:r].count(slots[r])  # hours: with fewer days than roads, one road after the other
            for k, lane in enumerate(x for x in lanes if x.road == road):
                drives.append({"name": f"{truck.id}-d{day['day']}-{road}-{lane.direction}", "truck": truck, "lane": lane,
                               "day": day, "speed_mph": spec.speeds_mph[speeds[r]], "faulting_m": spec.faulting_m,
                               "start": day["date"] + datetime.timedelta(hours=later, minutes=10 * i + 5 * k),
                               "seed": int(rng.integers(1, 2**31))})
    return drives


def scenario(d):
    truck, lane, day = d["truck"], d["lane"], d["day"]
    return {"name": d["name"], "description": f"fleet truck {truck.id} ({truck.kind}) on {lane.road} {lane.direction}, day {day['day']}",
            "route": f"../../{lane.file}", "vehicle": f"../../{truck.file}", "speed_mph": d["speed_mph"],
            "start_m": lane.start_m, "end_m": lane.end_m, "start_utc": d["start"], "road_seed": lane.road_seed,
            **truck.scales, "accel_rate_hz": ACCEL_RATE_HZ,
            "weather": {k: day[k] for k in ("air_temp_c", "pressure_pa", "wind_speed_mps", "wind_from_deg")},
            # The recording declares the type's mass, as a fleet that does not weigh each load.
            "effects": {"mass-error": 1.0 / truck.load_scale - 1.0, "joint-faulting": d["faulting_m"]}}


def run_drive(out, roadload, d, analyse):
    """Simulates one drive and analyses it; returns the wall seconds of each."""
    folder = out / "drives" / d["name"]
    folder.mkdir(parents=True, exist_ok=True)
    write_toml(folder / "scenario.toml", scenario(d))
    t0 = time.monotonic()
    run_checked([roadload, "simulate", "--scenario", folder / "scenario.toml", "--seed", d["seed"], "--out", folder / "rec",
                 "--truth", folder / "truth", "-q"], f"simulate {d['name']}")
    (folder / "truth" / "axles.csv").unlink()  # 0.01 s forces per axle: most of the truth's bytes, unused here
    t1 = time.monotonic()
    if analyse:
        run_checked([roadload, "analyze", folder / "rec", "--vehicle", out / d["truck"].file, "--route", out / d["lane"].file,
                     "-o", folder / "results", "-q"], f"analyze {d['name']}")
    return t1 - t0, time.monotonic() - t1


def run_all(out, roadload, drives, jobs, analyse):
    """The drives, `jobs` at once, with a progress line per drive done."""
    start = time.monotonic()
    sim_s = ana_s = 0.0
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        futures = {pool.submit(run_drive, out, roadload, d, analyse): d for d in drives}
        for n, f in enumerate(concurrent.futures.as_completed(futures), 1):
            s, a = f.result()
            sim_s, ana_s = sim_s + s, ana_s + a
            elapsed = time.monotonic() - start
            left = elapsed / n * (len(drives) - n)
            print(f"[{n:3d}/{len(drives)}] {futures[f]['name']}: simulate {s:.1f} s, analyze {a:.1f} s; "
                  f"{elapsed:.0f} s elapsed, about {left:.0f} s left", flush=True)
    return time.monotonic() - start, sim_s, ana_s


def write_csv(path, rows):
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


def section_rows(out, lanes, drives):
    """Per lane's cell: the route file's truth, where the analysis placed it, who drove it."""
    rows = []
    for lane in lanes:
        on = [d for d in drives if d["lane"] is lane]
        placed = {}
        results = out / "drives" / on[0]["name"] / "results" / "cells.csv"
        if results.exists():
            placed = {r["cell"]: r for r in csv.DictReader(open(results))}
        route = fleet_routes.tomllib.loads((out / lane.file).read_text())
        name = route["name"]
        for c in lane.cells:
            where = placed.get(c["id"], {})
            rows.append({"road": lane.road, "direction": lane.direction, "route_name": name, "route_file": lane.file,
                         "cell": c["id"], "surface": c.get("surface", ""), "start_m": c["start_m"],
                         "end_m": round(c["start_m"] + c["length_m"], 3), "crr": c.get("crr", route.get("default_crr", 0.0055)),
                         "joint_spacing_m": c.get("joint_spacing_m", 0),
                         "iri_m_per_km": c.get("iri_m_per_km", route.get("default_iri_m_per_km", "")),
                         **{k: where.get(k, "") for k in ("start_lat_deg", "start_lon_deg", "end_lat_deg", "end_lon_deg")},
                         "drives": len(on), "trucks": len({d["truck"].id for d in on})})
    return rows


def drive_rows(drives):
    return [{"drive": d["name"], "recording": f"drives/{d['name']}/rec", "truth": f"drives/{d['name']}/truth",
             "results": f"drives/{d['name']}/results", "truck": d["truck"].id, "vin": d["truck"].vin, "day": d["day"]["day"],
             "road": d["lane"].road, "direction": d["lane"].direction, "route_file": d["lane"].file,
             "speed_mph": d["speed_mph"], "start_utc": d["start"].isoformat().replace("+00:00", "Z"),
             **{k: d["day"][k] for k in ("air_temp_c", "pressure_pa", "wind_speed_mps", "wind_from_deg")},
             "seed": d["seed"], "road_seed": d["lane"].road_seed} for d in drives]


def folder_mb(path):
    return sum(f.stat().st_size for f in path.rglob("*") if f.is_file()) / 1e6


def main():
    a = parse_args()
    out = a.out.resolve()
    out.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(a.seed)
    trucks = fleet_trucks.draw_trucks(CONFIG, out, a.trucks, rng)
    lanes = fleet_routes.make_lanes(CONFIG, out, a.seed)
    days = make_days(a.days, rng)
    drives = plan(trucks, lanes, days, rng)
    print(f"fleet: {len(trucks)} trucks, {len(lanes)} lanes of {len(fleet_routes.ROADS)} roads, {len(days)} days: "
          f"{len(drives)} drives into {out}", flush=True)
    wall, sim_s, ana_s = run_all(out, os.path.abspath(a.roadload), drives, a.jobs, not a.simulate_only)
    write_csv(out / "manifest.csv", [{"recording": f"drives/{d['name']}/rec", "vehicle": d["truck"].file,
                                      "route": d["lane"].file} for d in drives])
    write_csv(out / "truth" / "trucks.csv", [t.row() for t in trucks])
    write_csv(out / "truth" / "sections.csv", section_rows(out, lanes, drives))
    write_csv(out / "truth" / "drives.csv", drive_rows(drives))
    recordings = sum(folder_mb(out / "drives" / d["name"] / "rec") for d in drives)
    print(f"fleet: {len(drives)} drives in {wall:.0f} s wall ({sim_s:.0f} s simulating, {ana_s:.0f} s analysing, "
          f"{a.jobs} at once); {folder_mb(out):.0f} MB, of which recordings {recordings:.0f} MB")
    return 0


if __name__ == "__main__":
    sys.exit(main())
