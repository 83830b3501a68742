#!/usr/bin/env python3
"""A truck and a road the project did not ship its estimator with, measured as a user would.

Per seed, one truck of config/vehicles/tractor-53ft-18speed.toml's type, its parameters drawn from
the type's spreads (cargo, declared mass, CdA, driveline efficiency, tire wear, engine friction,
accessories, the ECU's torque accuracy), is simulated on config/routes/example-county-road-*
(asphalt and jointed concrete, its own geometry, grade and roughness), both ways at 40 and 60 mph,
plus an engine-loss hold in neutral. From those recordings alone (the nominal vehicle file as the
prior, the county's section file), the CLI runs as docs and README tell a user:

  roadload vehicle identify REC... --vehicle tractor-53ft-18speed --out truck.toml
  roadload route build REC... --sections example-county-road-sections.geojson --out ROUTE (each way)
  roadload calibrate HOLD --out losses.csv
  roadload calibrate --aero SLOW FAST SLOW FAST --route EAST --route WEST (one CdA, both ways)
  roadload analyze REC --vehicle truck.toml --route ROUTE [--engine-losses ... --cda ...]

and the per-cell CRR is scored against the simulator's truth (the tires' CRR plus the suspension's
and tires' dissipation over v m g, what the force balance measures): RMSE and coverage of the 90 %
intervals, calibrated and not; the identified values beside the truth.

With --coast, each way also has a coast-down in neutral from 60 mph, and the calibration adds

  roadload calibrate --torque-scale SLOW COAST SLOW COAST --route EAST --route WEST --cda ...

whose scale (printed beside the ECU's) the calibrated analyses hold.

usage: new_road_bench.py ROADLOAD_BIN [--seeds N] [--keep DIR] [--coast]
"""
import csv
import datetime
import json
import math
import pathlib
import random
import shutil
import sys
import tomllib

from benchlib import bench_args, run_checked, truth_cells, write_toml

HERE = pathlib.Path(__file__).resolve().parent
CONFIG = HERE.parent.parent / "config"
VEHICLE = "tractor-53ft-18speed"
ROAD = "example-county-road"
SPEEDS_MPH = (40, 60)
Z90 = 1.6449


def draw_truck(rng):
    """One truck of the type: each value from its spread (the vehicle file's sigmas, or a fleet's)."""
    v = tomllib.loads((CONFIG / "vehicles" / f"{VEHICLE}.toml").read_text())
    v["name"] = f"{VEHICLE} (drawn)"
    wear = rng.uniform(-0.012, 0.002)  # new tread to half worn: 13 mm of 1,000 mm diameter
    for axle in v["axle"]:
        axle["tire_radius_m"] = round(axle["tire_radius_m"] * (1 + wear + rng.gauss(0, 0.002)), 5)
    v["driveline"]["efficiency"] = round(min(0.98, max(0.94, rng.gauss(0.96, 0.01))), 4)
    scales = {
        "load_scale": round(rng.uniform(0.85, 1.05), 3),  # a dry van's cargo, 28-32 t gross
        "cda_scale": round(rng.gauss(1.0, 0.06), 3),  # skirts, gap, mirrors of one truck
        "engine_friction_scale": round(rng.gauss(1.0, 0.08), 3),
        "accessory_scale": round(rng.gauss(1.0, 0.15), 3),
    }
    effects = {
        "mass-error": round(rng.uniform(-0.03, 0.03), 4),  # the declared cargo against the scale
        "torque-bias": round(rng.gauss(0.0, 0.01), 4),  # the ECU's torque against the dynamometer's
        "joint-faulting": 0.002,
    }
    return v, scales, effects


def scenario(name, route, seed, vehicle_file, scales, effects, wind, **kw):
    s = {"name": name, "route": str(route), "vehicle": str(vehicle_file), "start_utc": datetime.datetime(2026, 6, 2, 14, 0, tzinfo=datetime.timezone.utc),
         "road_seed": 90000 + seed, "accelerometers": 0, **scales, **kw,
         "weather": {"air_temp_c": 21.0, "pressure_pa": 97800, "wind_speed_mps": wind[0], "wind_from_deg": wind[1]},
         "effects": effects}
    return s


def cells_of(path):
    return {r["cell"]: r for r in csv.DictReader(open(path))}


def score(results, truth, t):
    """Adds one analysis's cells to the tally t: errors and coverage of the identified cells, and of
    every cell with a CRR (identified or not)."""
    for cell, r in cells_of(results / "cells.csv").items():
        if cell not in truth or r["crr"] in ("", "nan"):
            continue
        err = float(r["crr"]) - truth[cell]
        inside = float(r["crr_lo"]) <= truth[cell] <= float(r["crr_hi"])
        t["all"].append((err, inside))
        if r["identified"] == "1":
            t["identified"].append((err, inside))


def summary(pairs):
    if not pairs:
        return "rmse=nan coverage90=nan"
    errors = [e for e, _ in pairs]
    rmse = math.sqrt(sum(e * e for e in errors) / len(errors))
    return (f"rmse={rmse:.5f} bias={sum(errors) / len(errors):+.5f} "
            f"coverage90={sum(1 for _, i in pairs if i) / len(pairs):.1%}")


def vehicle_figures(identified, truth_vehicle, truth_mass_kg, masses):
    """The identified values beside the truth: (text, within their goal). The mass is the drives'
    (analyze's trip.json): their mean and mean sigma, as the drives share their errors."""
    got = tomllib.loads(identified.read_text())
    ratios = got["driveline"]["gear_ratios"]
    true_ratios = truth_vehicle["driveline"]["gear_ratios"]
    ratio_err = max(abs(a / b - 1) for a, b in zip(ratios, true_ratios))
    drive = [a for a in got["axle"] if a.get("driven")]
    true_drive = [a for a in truth_vehicle["axle"] if a.get("driven")]
    radius_err = abs(drive[0]["tire_radius_m"] / true_drive[0]["tire_radius_m"] - 1)
    declared = sum(a["load_kg"] for a in got["axle"])
    mass = sum(m for m, _ in masses) / len(masses)
    mass_sigma = sum(s for _, s in masses) / len(masses)
    ok = ratio_err <= 0.005 and radius_err <= 0.003 and abs(mass - truth_mass_kg) <= Z90 * mass_sigma
    text = (f"ratios worst {ratio_err:.2%}, radius {drive[0]['tire_radius_m']:.4f} (truth "
            f"{true_drive[0]['tire_radius_m']:.4f}, {radius_err:.2%}), mass from the drives {mass:.0f} +- {mass_sigma:.0f} "
            f"(prior {declared:.0f}, truth {truth_mass_kg:.0f})")
    return text, ok


def main():
    a, work = bench_args(__doc__, "--seeds", 10, "new-road-bench.",
                         [("--coast", "add a coast-down each way and calibrate the ECU's torque scale from it")])
    rl = a.roadload
    totals = {"cal": {"all": [], "identified": []}, "uncal": {"all": [], "identified": []}}
    vehicles_ok = 0
    for seed in range(1, a.seeds + 1):
        rng = random.Random(f"new-road-{seed}")
        d = work / f"seed{seed:02d}"
        shutil.rmtree(d, ignore_errors=True)
        d.mkdir()
        truck, scales, effects = draw_truck(rng)
        write_toml(d / "truck-true.toml", truck)
        wind = (round(rng.uniform(1.0, 5.0), 1), round(rng.uniform(0, 360)))
        hold = tomllib.loads((CONFIG / "scenarios" / "engine-losses.toml").read_text())
        hold.update(route=str(CONFIG / "routes" / "flat-track.toml"), vehicle=str(d / "truck-true.toml"), **scales)
        hold["effects"] = {"torque-bias": effects["torque-bias"]}
        write_toml(d / "hold.toml", hold)
        run_checked([rl, "simulate", "--scenario", d / "hold.toml", "--seed", seed, "--out", d / "hold", "-q"], "simulate hold")
        drives = {}
        for w, way in enumerate(("eastbound", "westbound")):
            for mph in SPEEDS_MPH:
                name = f"{way}-{mph}"
                sc = scenario(name, CONFIG / "routes" / f"{ROAD}-{way}.toml", seed, d / "truck-true.toml", scales, effects, wind,
                              speed_mph=mph, start_m=100, end_m=4600)
                write_toml(d / f"{name}.toml", sc)
                run_checked([rl, "simulate", "--scenario", d / f"{name}.toml", "--seed", seed * 1000 + w * 100 + mph, "--out", d / name,
                             "--truth", d / f"{name}.truth", "-q"], f"simulate {name}")
                drives[name] = (way, mph)
            if a.coast:
                sc = scenario(f"{way}-coast", CONFIG / "routes" / f"{ROAD}-{way}.toml", seed, d / "truck-true.toml", scales, effects,
                              wind, speed_mph=max(SPEEDS_MPH), start_m=100, end_m=4600, mode="coast")
                write_toml(d / f"{way}-coast.toml", sc)
                run_checked([rl, "simulate", "--scenario", d / f"{way}-coast.toml", "--seed", seed * 1000 + w * 100 + 99, "--out",
                             d / f"{way}-coast", "-q"], f"simulate {way}-coast")
        # Each drive its own seed: two drives sharing one would share their GNSS's height errors,
        # mirrored along the road, and the route's heights would keep them (a bowl, not noise).
        recs = [d / n for n in drives]
        # What a user runs: nothing below reads the simulator's files but the recordings.
        run_checked([rl, "vehicle", "identify", *recs, "--vehicle", VEHICLE, "--out", d / "truck.toml"], "vehicle identify")
        run_checked([rl, "calibrate", d / "hold", "--out", d / "losses.csv", "-q"], "calibrate")
        routes, pairs, route_args = {}, [], []
        for way in ("eastbound", "westbound"):
            first = [r for r in recs if r.name.startswith(way)]
            rest = [r for r in recs if not r.name.startswith(way)]
            routes[way] = d / f"route-{way}.toml"
            run_checked([rl, "route", "build", *first, *rest, "--sections", CONFIG / "routes" / f"{ROAD}-sections.geojson",
                         "--vehicle", d / "truck.toml", "--out", routes[way], "-q"], f"route build {way}")
            pairs += first  # slow, fast
            route_args += ["--route", routes[way]]
        # One CdA from both directions' pairs, each on its own route.
        run_checked([rl, "calibrate", "--aero", *pairs, *route_args, "--engine-losses", d / "losses.csv",
                     "--vehicle", d / "truck.toml", "--out", d / "cda.csv"], "calibrate --aero")
        cda = aero_options(d / "cda.csv")
        scale_text = ""
        if a.coast:
            # Each way's slow drive beside its coast-down, with the CdA --aero measured and its slope.
            coast_pairs = [pairs[0], d / "eastbound-coast", pairs[2], d / "westbound-coast"]
            aero = next(csv.DictReader(open(d / "cda.csv")))
            run_checked([rl, "calibrate", "--torque-scale", *coast_pairs, *route_args, "--engine-losses", d / "losses.csv",
                         "--vehicle", d / "truck.toml", "--cda", aero["cda_m2"], "--cda-sigma", aero["cda_sigma_m2"],
                         "--cda-per-torque-scale", aero["cda_per_torque_scale_m2"], "--out", d / "scale.csv"], "calibrate --torque-scale")
            row = next(csv.DictReader(open(d / "scale.csv")))
            cda += ["--torque-scale", row["torque_scale"], "--torque-scale-sigma", row["torque_scale_sigma"]]
            # The fitted scale also takes up the driveline's efficiency against the vehicle file's.
            nominal = tomllib.loads((d / "truck.toml").read_text())["driveline"]["efficiency"]
            scale_text = (f"; torque scale {float(row['torque_scale']):+.4f} +- {float(row['torque_scale_sigma']):.4f} "
                          f"(ECU {1 / (1 + effects['torque-bias']) - 1:+.4f}, efficiency "
                          f"{truck['driveline']['efficiency'] / nominal - 1:+.4f} of the file's)")
        truth_mass, masses = None, []
        for name, (way, mph) in drives.items():
            truth_toml = tomllib.loads((d / f"{name}.truth" / "truth.toml").read_text())
            truth_mass = truth_toml["true_mass_kg"]
            truth = truth_cells(d / f"{name}.truth", truth_mass)
            base = [rl, "analyze", d / name, "--route", routes[way], "--vehicle", d / "truck.toml", "-q"]
            for kind, extra in (("cal", ["--engine-losses", d / "losses.csv", *cda]), ("uncal", [])):
                out = d / f"{name}.{kind}"
                run_checked(base + ["--out", out] + extra, f"analyze {name} {kind}")
                if kind == "cal":
                    trip = json.load(open(out / "trip.json"))
                    masses.append((trip["mass_kg"], trip["mass_sigma_kg"]))
                score(out, truth, totals[kind])
        text, ok = vehicle_figures(d / "truck.toml", truck, truth_mass, masses)
        vehicles_ok += ok
        cda_true = 5.8 * scales["cda_scale"]
        print(f"seed {seed:2d}: {text}; CdA {cda[1]} +- {cda[3]} (truth {cda_true:.2f}); "
              f"torque {1 + effects['torque-bias']:.3f}, efficiency {truck['driveline']['efficiency']:.3f}{scale_text}", flush=True)
    for kind, label in (("cal", "calibrated"), ("uncal", "uncalibrated")):
        t = totals[kind]
        goal = "rmse<=0.00025, coverage 80-97 %" if kind == "cal" else "coverage >=80 %"
        print(f"new road bench ({label}): seeds={a.seeds} cells={len(t['all'])} identified={len(t['identified'])}: "
              f"{summary(t['identified'])} (goal {goal}); every cell: {summary(t['all'])}")
    print(f"new road bench: identified vehicle values within their goal in {vehicles_ok} of {a.seeds} seeds")
    if not a.keep:
        shutil.rmtree(work, ignore_errors=True)
    return 0


def aero_options(path):
    """The CdA options `calibrate --aero --out` wrote."""
    row = next(csv.DictReader(open(path)))
    opts = ["--cda", row["cda_m2"], "--cda-sigma", row["cda_sigma_m2"]]
    return opts + ["--cda-torque-correlation", row["cda_torque_correlation"],
                   "--cda-per-torque-scale", row["cda_per_torque_scale_m2"]]


if __name__ == "__main__":
    sys.exit(main())
