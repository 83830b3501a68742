#!/usr/bin/env python3
"""Judges `roadload network` on a simulated fleet against its truth (issue 26's acceptance).

- Sections: each section's CRR (network.csv) against the pavement's own CRR (truth/sections.csv,
  the route file's, apart from the trucks' tires): the share whose 90 % interval holds the truth
  must lie in 80-97 %.
- Trucks: the spread of the trucks' tires (truth/trucks.csv's tire_crr_scale, in CRR units at the
  fleet's mean pavement) must lie inside network.json's interval of the trucks' spread; each
  truck's fitted tire_offset (trucks.csv) is compared with its truth as a correlation, printed.

usage: check_network.py NETWORK_DIR FLEET_DIR
Exit 0 when both hold, 1 otherwise; the figures are printed either way.
"""
import csv
import json
import math
import statistics
import sys
import tomllib


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def number(text):
    try:
        v = float(text)
    except ValueError:
        return math.nan
    return v


def route_truth(fleet):
    """Every cell of every route the fleet drove, from the route files: the pavement's own CRR."""
    truth = {}
    for f in sorted({r["route_file"] for r in read(f"{fleet}/truth/sections.csv")}):
        route = tomllib.loads(open(f"{fleet}/{f}").read())
        for c in route.get("cell", []):
            truth[(route["name"], c["id"])] = c.get("crr", route.get("default_crr", 0.0055))
    return truth


def sections(net, fleet):
    truth = route_truth(fleet)
    inside, judged, errors, missing = 0, 0, [], []
    for r in read(f"{net}/network.csv"):
        crr, lo, hi = number(r["crr"]), number(r["crr_lo"]), number(r["crr_hi"])
        if math.isnan(crr):
            continue
        key = (r["route"], r["cell"])
        if key not in truth:
            missing.append(key)
            continue
        judged += 1
        inside += lo <= truth[key] <= hi
        errors.append((crr - truth[key], number(r["crr_sigma"])))
    return inside, judged, errors, missing


def trucks(net, fleet, mean_crr):
    truth = {r["vin"]: number(r["tire_crr_scale"]) for r in read(f"{fleet}/truth/trucks.csv")}
    fitted = {r["vin"]: number(r["tire_offset"]) for r in read(f"{net}/trucks.csv")}
    pairs = [(fitted[v], (truth[v] - 1) * mean_crr) for v in fitted if v in truth]
    true_sd = statistics.stdev(t for _, t in pairs) if len(pairs) > 1 else math.nan
    corr = statistics.correlation([f for f, _ in pairs], [t for _, t in pairs]) if len(pairs) > 2 else math.nan
    return len(pairs), true_sd, corr


def main():
    net, fleet = sys.argv[1], sys.argv[2]
    inside, judged, errors, missing = sections(net, fleet)
    if missing:
        print(f"check: {len(missing)} sections of network.csv not in the truth, e.g. {missing[0]}")
    share = inside / judged if judged else 0.0
    rms = math.sqrt(sum(e * e for e, _ in errors) / len(errors)) if errors else math.nan
    z = math.sqrt(sum((e / s) ** 2 for e, s in errors if s > 0) / len(errors)) if errors else math.nan
    print(f"check: sections inside their 90 % interval: {inside} of {judged} ({100 * share:.1f} %, goal 80-97 %); "
          f"RMS error {rms:.6f}, RMS z {z:.2f}")
    summary = json.load(open(f"{net}/network.json"))
    mean_crr = statistics.mean(number(r["crr"]) for r in read(f"{fleet}/truth/sections.csv"))
    n, true_sd, corr = trucks(net, fleet, mean_crr)
    spread = summary["spread"]["truck"]
    held = spread["sd_lo"] is not None and spread["sd_hi"] is not None and spread["sd_lo"] <= true_sd <= spread["sd_hi"]
    print(f"check: trucks' tire spread: true {true_sd:.6f} over {n} trucks, fitted {spread['sd']:.6f} "
          f"[{spread['sd_lo']}, {spread['sd_hi']}] (90 %): {'inside' if held else 'OUTSIDE'}; "
          f"per-truck tire offsets against the truth: correlation {corr:.2f}")
    ok = judged >= 20 and 0.80 <= share <= 0.97 and held and not missing
    print("check: PASS" if ok else "check: FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
