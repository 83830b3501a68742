#!/usr/bin/env python3
"""Bytes per hour of a recording's accelerometer stream in the layouts a recorder could write:
today's text, that text in zstd frames (what roadloadd writes), the same samples as binary rows in
zstd frames, the sensors' own counts delta-coded per sensor in byte planes in zstd frames, and those
counts as FLAC (one three-channel 24-bit stream per sensor; `flac`, Debian's, encodes it) with the
capture stamps beside them in zstd. The proposal these figures stand behind is in docs/journal.md
(2026-11-27, compressed streams).

usage: accel_layout.py RECORDING_DIR SECONDS
"""
import shutil
import subprocess
import sys

import numpy as np
import pandas as pd

G0 = 9.80665
FRAME_TEXT_BYTES = 1 << 18


def zstd_bytes(data: bytes) -> int:
    return len(subprocess.run(["zstd", "-1", "-q", "-c"], input=data, capture_output=True, check=True).stdout)


def main() -> int:
    folder, seconds = sys.argv[1], float(sys.argv[2])
    text = open(f"{folder}/accel.csv", "rb").read()
    d = pd.read_csv(f"{folder}/accel.csv")
    per_frame = max(1, int(len(d) * FRAME_TEXT_BYTES / len(text)))
    starts = range(0, len(d), per_frame)
    lines = text.split(b"\n", 1)[1].splitlines(keepends=True)
    text_z = sum(zstd_bytes(b"".join(lines[i:i + per_frame])) for i in starts)

    xyz = d[["x_mps2", "y_mps2", "z_mps2"]].to_numpy()
    rows = np.zeros(len(d), dtype=[("t_ns", "<i8"), ("sensor", "u1"), ("x_um", "<i4"), ("y_um", "<i4"), ("z_um", "<i4")])
    rows["t_ns"], rows["sensor"] = d["t_ns"], d["sensor"]
    for k, c in enumerate(("x_um", "y_um", "z_um")):
        rows[c] = np.round(xyz[:, k] * 1e6)
    rows_z = sum(zstd_bytes(rows[i:i + per_frame].tobytes()) for i in starts)

    # The sensors' counts: each value is a count times the sensor's step, its range over 2^19 (the
    # ADXL355's 20 bits); the step is the largest of the three ranges' that every value is a multiple of.
    sensor = d["sensor"].to_numpy()
    step = np.zeros(sensor.max() + 1)
    for s in np.unique(sensor):
        v = xyz[sensor == s]
        for range_g in (8.192, 4.096, 2.048):
            q = range_g * G0 / 2**19
            if np.max(np.abs(np.round(v / q) * q - v)) <= 6e-7:
                step[s] = q
                break
        else:
            print(f"accel_layout: sensor {s}: its values are no multiple of an ADXL355 step", file=sys.stderr)
            return 1
    counts = np.round(xyz / step[sensor][:, None]).astype(np.int64)
    worst = np.max(np.abs(counts * step[sensor][:, None] - xyz))
    planar_z = 0
    t = d["t_ns"].to_numpy()
    # A binary frame holds a second of samples, closed at each fsync; 1 s of 8 sensors at 4 kHz
    # is 32,000 samples, 512 KiB before compression.
    second = np.searchsorted(t, np.arange(t[0], t[-1] + 1, 1_000_000_000))
    for i, j in zip(second, list(second[1:]) + [len(t)]):
        planes = []
        for s in np.unique(sensor[i:j]):
            m = sensor[i:j] == s
            # Time as the change of each sensor's sample period (near zero at a steady rate), the
            # counts as their change from the sensor's previous sample.
            planes.append(np.diff(np.diff(t[i:j][m], prepend=0), prepend=0).astype("<i4"))
            planes += [np.diff(counts[i:j][m][:, k], prepend=0).astype("<i4") for k in range(3)]
        # Byte planes (the low bytes of every value, then the next, ...): zstd finds the runs of
        # zero high bytes that small deltas leave.
        both = np.concatenate(planes).view(np.uint8).reshape(-1, 4)
        planar_z += zstd_bytes(b"".join(both[:, b].tobytes() for b in range(4)))

    flac_z = None
    if shutil.which("flac"):
        flac_z = 0
        for s in np.unique(sensor):
            m = sensor == s
            rate = max(1, min(655350, round(np.count_nonzero(m) / seconds)))
            pcm = counts[m].astype("<i4").view(np.uint8).reshape(-1, 3, 4)[:, :, :3].tobytes()
            flac_z += len(subprocess.run(["flac", "-5", "-s", "--force-raw-format", "--endian=little", "--sign=signed", "--channels=3",
                                          "--bps=24", f"--sample-rate={rate}", "-c", "-"], input=pcm, capture_output=True,
                                         check=True).stdout)
            flac_z += zstd_bytes(np.diff(np.diff(t[m], prepend=0), prepend=0).astype("<i8").tobytes())

    hour = 3600.0 / seconds
    print(f"accelerometer layouts: {folder}, {len(d)} samples over {seconds:.0f} s, per hour of driving")
    for name, size in (("text (accel.csv)", len(text)), ("text in zstd-1 frames (roadloadd today)", text_z),
                       ("binary rows, micro-m/s^2, zstd-1 frames", rows_z),
                       ("counts, delta per sensor, byte planes, zstd-1 1 s", planar_z),
                       ("counts as FLAC -5 per sensor, stamps in zstd", flac_z)):
        if size is None:
            print(f"  {name:48s} (no flac here: apt-get install flac)")
            continue
        print(f"  {name:48s} {size * hour / 1e6:9.1f} MB/h   1/{len(text) / size:5.2f} of the text")
    print(f"  counts x step reproduce every value within {worst:.1e} m/s^2: the text's 6 decimals, losslessly")
    return 0


if __name__ == "__main__":
    sys.exit(main())
