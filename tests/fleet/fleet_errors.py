#!/usr/bin/env python3
"""How a fleet's per-drive, per-cell CRR compares with the sections' truth (make_fleet.py's folder).

Per drive and cell, three errors of the analysis' cells.csv:
  own    crr_tire - the pavement's own CRR (truth/sections.csv): what a map of pavements sees,
         the truck's tires included
  truck  crr_tire - the CRR the truck's tires met (the drive's truth/cells.csv: the pavement's
         times the truck's tire_crr_scale): the analysis' own error
  fb     crr - (that + the suspension's and tires' dissipation over v m g): the force balance
         against what it measures
and how they split into a truck's offset, a drive's (within its truck) and a cell's (within its
drive); whether the trucks' offsets follow their tire scale, drag area, cargo and engine; and how
often each 90 % interval holds its truth.

usage: fleet_errors.py FLEET_DIR [--identified-only]
"""
import argparse
import csv
import pathlib
import sys
import tomllib

import numpy as np

G = 9.80665
Z90 = 1.6449


def number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return float("nan")


def rows_of(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def collect(fleet):
    """One record per (drive, cell) the analysis gave a force-balance CRR for."""
    trucks = {t["truck"]: t for t in rows_of(fleet / "truth" / "trucks.csv")}
    sections = {(s["road"], s["direction"], s["cell"]): s for s in rows_of(fleet / "truth" / "sections.csv")}
    out = []
    for d in rows_of(fleet / "truth" / "drives.csv"):
        results = fleet / d["results"] / "cells.csv"
        if not results.exists():
            continue
        truth_toml = tomllib.loads((fleet / d["truth"] / "truth.toml").read_text())
        mass = truth_toml["true_mass_kg"]
        truth = {r["cell"]: r for r in rows_of(fleet / d["truth"] / "cells.csv") if r["complete"] == "1"}
        t = trucks[d["truck"]]
        # The drag the analysis' CdA prior (the type's) leaves out, as CRR: 1/2 rho dCdA v^2 / (m g).
        rho = number(d["pressure_pa"]) / (287.05 * (number(d["air_temp_c"]) + 273.15))
        v = number(d["speed_mph"]) * 0.44704
        aero = 0.5 * rho * (number(t["cda_m2"]) - number(t["nominal_cda_m2"])) * v * v / (mass * G)
        for r in rows_of(results):
            key = (d["road"], d["direction"], r["cell"])
            if key not in sections or r["cell"] not in truth or not np.isfinite(number(r["crr"])):
                continue
            tc = truth[r["cell"]]
            dyn = (number(tc["damper_power_w"]) + number(tc["tire_power_w"])) / (number(tc["speed_mps"]) * mass * G)
            out.append({"drive": d["drive"], "truck": d["truck"], "type": t["type"], "road": d["road"],
                        "surface": sections[key]["surface"], "speed_mph": number(d["speed_mph"]),
                        "air_temp_c": number(d["air_temp_c"]), "identified": r["identified"] == "1", "aero": aero,
                        "pavement": number(sections[key]["crr"]), "met": number(tc["crr"]), "dynamic": dyn,
                        "crr": number(r["crr"]), "lo": number(r["crr_lo"]), "hi": number(r["crr_hi"]),
                        "sigma": number(r["crr_sigma"]), "tire": number(r.get("crr_tire")),
                        "tire_lo": number(r.get("crr_tire_lo")), "tire_hi": number(r.get("crr_tire_hi")),
                        "tire_scale": number(t["tire_crr_scale"]), "cda_scale": number(t["cda_scale"]),
                        "load_scale": number(t["load_scale"]), "friction_scale": number(t["engine_friction_scale"])})
    return out


def split(recs, error):
    """Mean, and the SDs of the truck means, of the drive means about their truck's, and of the
    cells about their drive's mean (one SD each, drives and trucks unweighted)."""
    e = np.array([error(r) for r in recs])
    by_drive, by_truck = {}, {}
    for r, x in zip(recs, e):
        by_drive.setdefault(r["drive"], []).append(x)
    drive_mean = {k: np.mean(v) for k, v in by_drive.items()}
    truck_of = {r["drive"]: r["truck"] for r in recs}
    for k, m in drive_mean.items():
        by_truck.setdefault(truck_of[k], []).append(m)
    truck_mean = {k: np.mean(v) for k, v in by_truck.items()}
    within_drive = np.array([x - drive_mean[r["drive"]] for r, x in zip(recs, e)])
    within_truck = np.array([m - truck_mean[truck_of[k]] for k, m in drive_mean.items()])
    n_cells = np.array([len(by_drive[r["drive"]]) for r in recs])
    # Residuals about a mean of n shrink by (n - 1) / n; put that back.
    within_drive_sd = np.sqrt(np.sum(within_drive**2) / max(1, np.sum(1 - 1 / n_cells)))
    return {"n": len(e), "mean": e.mean(), "rmse": np.sqrt(np.mean(e**2)), "sd": e.std(ddof=1),
            "truck_sd": np.std(list(truck_mean.values()), ddof=1), "drive_sd": np.std(within_truck, ddof=1),
            "cell_sd": within_drive_sd, "truck_mean": truck_mean, "drive_mean": drive_mean}


def fmt(s):
    return (f"n={s['n']} mean={s['mean']:+.5f} rmse={s['rmse']:.5f} sd={s['sd']:.5f}; "
            f"sd of truck means {s['truck_sd']:.5f}, of drives in a truck {s['drive_sd']:.5f}, "
            f"of cells in a drive {s['cell_sd']:.5f}")


def coverage(recs, lo, hi, truth):
    inside = [lo(r) <= truth(r) <= hi(r) for r in recs if np.isfinite(lo(r))]
    return f"{np.mean(inside):.1%} of {len(inside)}" if inside else "none"


def regress(y, columns, names):
    """Least squares of y on the columns with an intercept: each coefficient +- its standard error, R^2."""
    x = np.column_stack([np.ones(len(y))] + columns)
    beta, *_ = np.linalg.lstsq(x, y, rcond=None)
    resid = y - x @ beta
    dof = max(1, len(y) - x.shape[1])
    cov = np.linalg.inv(x.T @ x) * (resid @ resid) / dof
    r2 = 1 - (resid @ resid) / np.sum((y - y.mean()) ** 2)
    terms = ", ".join(f"{n} {b:+.5f} +- {np.sqrt(c):.5f}" for n, b, c in zip(["intercept"] + names, beta, np.diag(cov)))
    return f"{terms}; R^2 {r2:.2f}"


def truck_offsets(recs, stats, label):
    """The trucks' mean errors against what sets each truck apart."""
    trucks = sorted(stats["truck_mean"])
    first = {t: next(r for r in recs if r["truck"] == t) for t in trucks}
    pav = {t: np.mean([r["pavement"] for r in recs if r["truck"] == t]) for t in trucks}
    y = np.array([stats["truck_mean"][t] for t in trucks])
    cols = [np.array([(first[t][k] - 1) * (pav[t] if k == "tire_scale" else 1) for t in trucks])
            for k in ("tire_scale", "cda_scale", "load_scale", "friction_scale")]
    print(f"  {label}: truck means on (tire_scale-1)*CRR, cda_scale-1, load_scale-1, friction_scale-1: "
          + regress(y, cols, ["tire", "cda", "load", "friction"]))


def drive_offsets(recs, stats):
    """The drives' mean errors against the drag their CdA prior leaves out, and the spreads left
    once it is taken away."""
    drives = sorted(stats["drive_mean"])
    first = {d: next(r for r in recs if r["drive"] == d) for d in drives}
    y = np.array([stats["drive_mean"][d] for d in drives])
    aero = np.array([first[d]["aero"] for d in drives])
    load = np.array([first[d]["load_scale"] - 1 for d in drives])
    print("  truck: drive means on the drag the CdA prior leaves out (1/2 rho dCdA v^2 / m g) and load_scale-1: "
          + regress(y, [aero, load], ["aero", "load"]))
    s = split(recs, lambda r: r["tire"] - r["met"] - r["aero"])
    print(f"  truck less that drag: {fmt(s)}")


def by(recs, key, error):
    groups = {}
    for r in recs:
        groups.setdefault(r[key], []).append(error(r))
    return ", ".join(f"{k} {np.mean(v):+.5f} (sd {np.std(v):.5f}, {len(v)})" for k, v in sorted(groups.items()))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("fleet", type=pathlib.Path)
    ap.add_argument("--identified-only", action="store_true")
    a = ap.parse_args()
    recs = collect(a.fleet)
    if not recs:
        raise SystemExit(f"{a.fleet}: no analysed cell (run make_fleet.py without --simulate-only)")
    identified = [r for r in recs if r["identified"]]
    print(f"cells with a CRR: {len(recs)} in {len({r['drive'] for r in recs})} drives; identified {len(identified)} "
          f"({len(identified) / len(recs):.0%})")
    if a.identified_only:
        recs = identified
    tire = [r for r in recs if np.isfinite(r["tire"])]
    errors = {"own": lambda r: r["tire"] - r["pavement"], "truck": lambda r: r["tire"] - r["met"],
              "fb": lambda r: r["crr"] - r["met"] - r["dynamic"]}
    for name, rows in (("own", tire), ("truck", tire), ("fb", recs)):
        s = split(rows, errors[name])
        print(f"{name:5s}: {fmt(s)}")
        if name != "fb":
            truck_offsets(rows, s, name)
        if name == "truck":
            drive_offsets(rows, s)
    print(f"the tires' CRR's 90 % interval holds the pavement's own: {coverage(tire, lambda r: r['tire_lo'], lambda r: r['tire_hi'], lambda r: r['pavement'])}; "
          f"the CRR the truck met: {coverage(tire, lambda r: r['tire_lo'], lambda r: r['tire_hi'], lambda r: r['met'])}")
    print(f"the force balance's 90 % interval holds what it measures: "
          f"{coverage(recs, lambda r: r['lo'], lambda r: r['hi'], lambda r: r['met'] + r['dynamic'])}")
    z = np.array([(r["tire"] - r["met"]) / ((r["tire_hi"] - r["tire_lo"]) / (2 * Z90)) for r in tire])
    print(f"truck error over its stated sigma: sd {np.std(z):.2f} (1 if the intervals are right), mean {np.mean(z):+.2f}")
    print(f"mean sigma of crr {np.mean([r['sigma'] for r in recs]):.5f}; dynamic part (truth) "
          f"{np.mean([r['dynamic'] for r in recs]):.5f}")
    for key in ("type", "road", "surface", "speed_mph"):
        print(f"truck error by {key}: {by(tire, key, errors['truck'])}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
