# SPDX-License-Identifier: Apache-2.0
"""Benchmark: `smoothshaper calibrate` on a 60 s, 3.2 kHz, three-axis resonance record.

Prints the CPU time of each step (one core; the target is under 10 s in total) and the modes
found. Run: python tests/bench/calibrate_bench.py [--out DIR]
"""
from __future__ import annotations

import argparse
import math
import os
import tempfile
import time

import numpy as np

from smoothshaper import calibrate
from smoothshaper.calibrate import synthetic


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", help="also write the figures here")
    args = ap.parse_args()
    two_pi = 2 * math.pi
    modes = [(two_pi * 38.0, 0.04), (two_pi * 61.0, 0.06)]
    fs, T = 3200.0, 60.0
    t, a = synthetic.resonance_record(modes, fs=fs, T=T, f0=5.0, f1=133.0, snr_db=30.0,
                                      axes=3, seed=7)
    # make the y and z axes see modes too (cross-talk scaled), as on a real printer
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "resonance.csv")
        synthetic.write_csv(path, [t, a[:, 0], a[:, 1], a[:, 2]],
                            ["time", "accel_x", "accel_y", "accel_z"], fmt="%.6f")
        print(f"record: {t.size} samples x 3 axes at {fs:g} Hz ({T:g} s)")
        c0 = time.process_time()
        rec = calibrate.load(path)
        c1 = time.process_time()
        cal = calibrate.run([path], max_delay=0.04)
        c2 = time.process_time()
        if args.out:
            from smoothshaper.calibrate import plots
            plots.write(cal, args.out)
        c3 = time.process_time()
    print(f"read + resample one file: {c1 - c0:6.2f} s CPU")
    print(f"whole calibrate.run:      {c2 - c1:6.2f} s CPU (reads the file again; target < 10 s)")
    if args.out:
        print(f"figures:                  {c3 - c2:6.2f} s CPU")
    for res in cal.axes:
        found = ", ".join(f"{m.f_hz:.3f} Hz zeta {m.zeta:.4f}" for m in res.modes)
        print(f"axis {res.name}: {found}; recommended {res.recommended.name}")
    print(f"skipped: {cal.skipped}" if cal.skipped else "")
    assert rec.signals.shape == (t.size, 3) and np.isfinite(rec.signals).all()


if __name__ == "__main__":
    main()
