#!/usr/bin/env python3
"""`roadload psd` against scipy.signal.welch with the same settings, to 1e-9 relative in every bin:
synthetic signals (noise, lines, a step, a ramp) at several segment lengths and overlaps, and every
accelerometer axis of a short simulated recording at the rate meta.toml gives."""
import csv
import subprocess
import sys
import tempfile
import tomllib
from pathlib import Path

import numpy as np
from scipy.signal import welch

TOL = 1e-9
roadload = sys.argv[1]
work = Path(tempfile.mkdtemp(prefix="roadload-psd-"))
failures = []


def run(*args):
    out = subprocess.run([roadload, *map(str, args)], capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"roadload {' '.join(map(str, args))}: exit {out.returncode}: {out.stderr}")
    return out


def read_psd(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    header, data = rows[0], np.array([[float(v) for v in r] for r in rows[1:]])
    return header, data


def worst_relative(ours, ref):
    # Bins below 1e-15 of the peak carry only rounding of the mean removal.
    mask = np.abs(ref) > 1e-15 * np.max(np.abs(ref))
    return float(np.max(np.abs(ours[mask] - ref[mask]) / np.abs(ref[mask])))


def compare(label, freq, ours, f_ref, p_ref):
    if len(freq) != len(f_ref) or np.max(np.abs(freq - f_ref)) > 1e-12 * f_ref[-1]:
        failures.append(f"{label}: frequency grid differs")
        return
    err = worst_relative(ours, p_ref)
    print(f"{label}: {len(freq)} bins, worst relative difference {err:.2e}")
    if not err <= TOL:
        failures.append(f"{label}: worst relative difference {err:.2e} > {TOL:g}")


rng = np.random.default_rng(20141020)
fs = 1200.0
t = np.arange(60000) / fs
signals = {
    "noise": rng.normal(0.0, 0.3, t.size),
    "lines": 0.5 * np.sin(2 * np.pi * 2.93 * t) + 0.05 * np.sin(2 * np.pi * 11.72 * t + 1) + 9.81
    + rng.normal(0.0, 0.01, t.size),
    "step-ramp": np.where(t > 20, 1.0, 0.0) + 0.01 * t + rng.normal(0.0, 1e-3, t.size),
}
for name, x in signals.items():
    path = work / f"{name}.csv"
    with open(path, "w") as f:
        f.write("t_s,x\n")
        for ti, xi in zip(t, x):
            f.write(f"{ti!r},{xi!r}\n")
    for nperseg, noverlap in ((256, 128), (4096, 2048), (1000, 0), (2048, 1536)):
        out = work / f"{name}-{nperseg}-{noverlap}.csv"
        run("psd", path, "--column", "x", "--fs", fs, "--nperseg", nperseg, "--noverlap", noverlap, "-o", out)
        _, ours = read_psd(out)
        f_ref, p_ref = welch(x, fs=fs, window="hann", nperseg=nperseg, noverlap=noverlap)
        compare(f"{name} nperseg={nperseg} noverlap={noverlap}", ours[:, 0], ours[:, 1], f_ref, p_ref)

rec = work / "rec"
run("simulate", "--scenario", "mnroad-mainline-30mph", "--seed", 5, "--duration", 20, "--out", rec, "-q")
meta = tomllib.loads((rec / "meta.toml").read_text())
with open(rec / "accel.csv") as f:
    rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#"))]
out = work / "rec-psd.csv"
run("psd", rec, "--axis", "all", "--nperseg", 2048, "-o", out)
header, ours = read_psd(out)
checked = 0
for sensor in meta["sensor"]:
    if sensor["kind"] != "accelerometer":
        continue
    for axis in "xyz":
        x = np.array([float(r[f"{axis}_mps2"]) for r in rows if int(r["sensor"]) == sensor["id"]])
        f_ref, p_ref = welch(x, fs=sensor["rate_hz"], window="hann", nperseg=2048)
        column = header.index(f"{sensor['name']}_{axis}")
        compare(f"recording {sensor['name']} {axis}", ours[:, 0], ours[:, column], f_ref, p_ref)
        checked += 1
if checked < 3:
    failures.append(f"recording: only {checked} accelerometer axes")

if failures:
    print("\n".join(["FAIL"] + failures))
    sys.exit(1)
print("psd-matches-scipy: PASS")
