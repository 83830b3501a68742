#!/usr/bin/python3
"""Compares what gpsd_probe read from gpsd with the gnss.csv that nmea_from_gnss.py wrote as NMEA
for it: every fix, in order, equal to the NMEA's rounding, and the probe's stamps increasing.

usage: compare_fixes.py EXPECTED_CSV PROBE_CSV START
START is nmea_from_gnss.py's --start: the UTC it gave the first fix."""
import csv
import datetime
import sys

# From the NMEA's decimals (nmea_from_gnss.py), gpsd's JSON (lat/lon 9, heights 4, speed 3) and the
# CSVs' (lat/lon 9, height 3, speed 3, course 2): 6 decimals of minutes are 8.3e-9 deg; MSL height
# and geoid separation 2 decimals each; knots 4 decimals, then 3 decimals of m/s twice.
TOLERANCE = {"lat_deg": 1e-8, "lon_deg": 1e-8, "alt_m": 0.01, "speed_mps": 0.002, "course_deg": 0.0101}
CS_NS = 10_000_000  # NMEA time has centiseconds


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def main():
    expected_path, probe_path, start = sys.argv[1:4]
    expected, got = rows(expected_path), rows(probe_path)
    start_ns = int(datetime.datetime.fromisoformat(start).replace(tzinfo=datetime.timezone.utc).timestamp()) * 10**9
    shift = start_ns - int(expected[0]["utc_ns"])
    want = {(int(r["utc_ns"]) + shift) // CS_NS * CS_NS: r for r in expected}
    got_utc = [int(r["utc_ns"]) for r in got]
    problems = []
    missing = sorted(set(want) - set(got_utc))
    extra = sorted(set(got_utc) - set(want))
    if missing or extra:
        problems.append(f"probe delivered {len(got)} fixes, the NMEA had {len(expected)}: missing {len(missing)} "
                        f"(first UTC ns {missing[:3]}), unexpected {len(extra)} ({extra[:3]})")
    if got_utc != sorted(set(got_utc)):
        problems.append("fixes out of order or repeated")
    worst = dict.fromkeys(TOLERANCE, 0.0)
    for i, g in enumerate(got):
        e = want.get(int(g["utc_ns"]))
        if e is None:
            continue
        where = f"fix {i} (UTC ns {g['utc_ns']})"
        if g["mode"] != e["mode"]:
            problems.append(f"{where}: mode {g['mode']}, expected {e['mode']}")
        # gpsd 3.22 sends HDOP only in SKY, which needs satellites in view (GSV) that the log does not have.
        if g["hdop"] not in ("", e["hdop"]):
            problems.append(f"{where}: hdop {g['hdop']}, expected {e['hdop']} or none")
        for field, tol in TOLERANCE.items():
            if g[field] == "":
                problems.append(f"{where}: {field} missing, expected {e[field]}")
                continue
            diff = abs(float(g[field]) - float(e[field]))
            worst[field] = max(worst[field], diff)
            if diff > tol:
                problems.append(f"{where}: {field} {g[field]}, expected {e[field]} (off {diff:.3g}, tolerance {tol:g})")
    stamps = [int(r["t_ns"]) for r in got]
    for i in range(1, len(stamps)):
        if stamps[i] <= stamps[i - 1]:
            problems.append(f"fix {i}: stamp t_ns {stamps[i]} not after {stamps[i - 1]}")
    print(f"{len(got)} of {len(expected)} fixes; worst differences: " + ", ".join(f"{k} {v:.3g}" for k, v in worst.items()))
    if problems:
        print("\n".join(problems[:12]) + (f"\n... {len(problems) - 12} more" if len(problems) > 12 else ""), file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
