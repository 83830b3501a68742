#!/usr/bin/python3
"""Writes a recording's gnss.csv as the NMEA 0183 log a receiver would have sent: RMC then GGA per
fix, so that a real gpsd (fed by gpsfake) parses it. Only a writer: the test compares what gpsd
reports with the CSV, so the parsing under test is gpsd's, not ours.

usage: nmea_from_gnss.py GNSS_CSV OUT_NMEA [--start YYYY-MM-DDTHH:MM:SS] [--geoid-sep M] [--lead-in N]

UTC is the row's utc_ns, shifted with --start so that the first fix is at START (gpsd 3.22 takes a
two-digit-year date before its own release for a GPS week rollover and moves it 1024 weeks on); a
row with utc_ns 0 gets empty time fields. --lead-in puts no-fix cycles before the first fix. Positions carry 6 decimals of minutes (1.7e-8 deg), heights
and the geoid separation 2 decimals (m), speed 4 decimals (knots), course 2 decimals (deg), time
centiseconds: the test's tolerances follow from these."""
import argparse
import csv
import datetime
import math
import sys

KNOTS_PER_MPS = 3600.0 / 1852.0
# GGA quality and RMC/GGA mode indicator per gnss.csv mode (none, 2D, 3D, DGPS, RTK).
GGA_QUALITY = {0: 0, 2: 1, 3: 1, 4: 2, 5: 4}
RMC_MODE = {0: "N", 2: "A", 3: "A", 4: "D", 5: "R"}
# gnss.csv has no satellite count; gpsd 3.22 takes an empty one for "no fix".
SATELLITES_USED = 12


def sentence(body):
    checksum = 0
    for c in body.encode("ascii"):
        checksum ^= c
    return f"${body}*{checksum:02X}\r\n"


def angle(value_deg, degree_digits, hemispheres):
    """ddmm.mmmmmm with the hemisphere letter; empty fields for an unusable value."""
    if not math.isfinite(value_deg):
        return ","
    a = abs(value_deg)
    deg = int(a)
    minutes = round((a - deg) * 60.0, 6)
    if minutes >= 60.0:  # rounding carried into the next degree
        deg, minutes = deg + 1, 0.0
    return f"{deg:0{degree_digits}d}{minutes:09.6f},{hemispheres[value_deg < 0]}"


def fixed(value, decimals):
    return f"{value:.{decimals}f}" if math.isfinite(value) else ""


def number(row, field, where, kind=float):
    try:
        return kind(row[field])
    except (TypeError, ValueError):
        sys.exit(f"{where}: {field}: not a number: {row[field]!r}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("gnss_csv")
    ap.add_argument("out_nmea")
    ap.add_argument("--start", help="UTC of the first fix, YYYY-MM-DDTHH:MM:SS (default: the rows' utc_ns)")
    # EGM96 near MnROAD; any value round-trips, since gpsd adds it back to the MSL altitude.
    ap.add_argument("--geoid-sep", type=float, default=-27.60, help="geoid above the ellipsoid, m")
    # A receiver sends timed no-fix cycles while it acquires; they let gpsd learn which sentence
    # ends a cycle, and cover the sentences gpsfake writes while gpsd is still probing the device.
    ap.add_argument("--lead-in", type=int, default=0, metavar="N",
                    help="no-fix cycles before the first fix, at the spacing of the first two")
    args = ap.parse_args()
    start_ns = None
    if args.start:
        start = datetime.datetime.fromisoformat(args.start).replace(tzinfo=datetime.timezone.utc)
        start_ns = int(start.timestamp()) * 1_000_000_000
    sep = round(args.geoid_sep, 2)

    with open(args.gnss_csv, newline="") as f:
        rows = list(enumerate(csv.DictReader(f), start=2))  # (line, row)
    if args.lead_in > 0:
        first = int(rows[0][1]["utc_ns"]) if rows else 0
        if len(rows) < 2 or first == 0:
            sys.exit(f"{args.gnss_csv}: --lead-in needs two rows and the first fix's utc_ns")
        step = int(rows[1][1]["utc_ns"]) - first
        no_fix = dict.fromkeys(("lat_deg", "lon_deg", "alt_m", "speed_mps", "course_deg", "hdop"), "nan")
        lead = [(0, {**no_fix, "mode": "0", "utc_ns": str(first - k * step)}) for k in range(args.lead_in, 0, -1)]
        rows = lead + rows
        if start_ns is not None:
            start_ns -= args.lead_in * step  # START stays the first fix's time
    shift_ns = None  # added to every utc_ns
    with open(args.out_nmea, "w", newline="") as out:
        for line, row in rows:
            where = f"{args.gnss_csv}:{line}"
            utc_ns = number(row, "utc_ns", where, int)
            if utc_ns == 0:  # the receiver had no time: empty time and date fields
                hhmmss = ddmmyy = ""
            else:
                if shift_ns is None:
                    shift_ns = 0 if start_ns is None else start_ns - utc_ns
                utc_ns += shift_ns
                cs = (utc_ns // 10_000_000) % 100  # NMEA time has centiseconds
                when = datetime.datetime.fromtimestamp(utc_ns // 1_000_000_000, datetime.timezone.utc)
                hhmmss, ddmmyy = f"{when:%H%M%S}.{cs:02d}", f"{when:%d%m%y}"
            mode = number(row, "mode", where, int)
            if mode not in GGA_QUALITY:
                sys.exit(f"{where}: mode: {mode} is not 0, 2, 3, 4 or 5")
            lat = angle(number(row, "lat_deg", where), 2, "NS")
            lon = angle(number(row, "lon_deg", where), 3, "EW")
            knots = fixed(number(row, "speed_mps", where) * KNOTS_PER_MPS, 4)
            course = fixed(number(row, "course_deg", where), 2)
            status = "A" if mode >= 2 else "V"
            out.write(sentence(f"GPRMC,{hhmmss},{status},{lat},{lon},{knots},{course},{ddmmyy},,,{RMC_MODE[mode]}"))
            # A 2D fix has no altitude: gpsd then reports mode 2.
            msl = fixed(number(row, "alt_m", where) - sep, 2) if mode >= 3 else ""
            geoid = f"{sep:.2f}" if msl else ""
            hdop = fixed(number(row, "hdop", where), 1)
            used = f"{SATELLITES_USED:02d}" if mode >= 2 else "00"
            out.write(sentence(f"GPGGA,{hhmmss},{lat},{lon},{GGA_QUALITY[mode]},{used},{hdop},{msl},M,{geoid},M,,"))


if __name__ == "__main__":
    main()
