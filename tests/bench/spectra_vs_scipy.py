#!/usr/bin/env python3
"""The streaming PSD against scipy.signal.welch on the same data, side by side in one run:
bench_spectra times its C++ pipeline and dumps the 24 channels and its PSDs; here scipy computes
the same PSDs (timed) and the two are compared bin by bin."""
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from scipy.signal import welch

bench, seconds = sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else "60"
dump = Path(tempfile.mkdtemp(prefix="roadload-spectra-")) / "channels.f64"
out = subprocess.run([bench, seconds, "--dump", str(dump)], capture_output=True, text=True, check=True).stdout
print(out, end="")
cpp_ns = float(next(line for line in out.splitlines() if line.startswith("welch_ns_per_sample=")).split("=")[1])
channels, fs, nperseg = 24, 4000.0, 4096
n = int(float(seconds) * fs)
data = np.fromfile(dump, dtype=np.float64)
x = data[: channels * n].reshape(channels, n)
ours = data[channels * n:].reshape(channels, nperseg // 2 + 1)
t0 = time.perf_counter()
_, ref = welch(x, fs=fs, window="hann", nperseg=nperseg, noverlap=nperseg // 2, axis=-1)
scipy_s = time.perf_counter() - t0
scipy_ns = scipy_s * 1e9 / x.size
worst = float(np.max(np.abs(ours - ref) / np.abs(ref)))
print(f"  scipy.signal.welch on the same data (batch, all channels at once): {scipy_ns:.1f} ns/sample, "
      f"{100 * scipy_s / float(seconds):.3f} % of a core")
print(f"  streaming C++ / scipy time: {cpp_ns / scipy_ns:.2f}; PSDs agree to {worst:.1e} relative (worst bin)")
dump.unlink()
