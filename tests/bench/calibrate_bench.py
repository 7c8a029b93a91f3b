# SPDX-License-Identifier: Apache-2.0
"""Benchmark: `smoothshaper calibrate` on 10 s, 60 s and 600 s resonance records at 3.2 kHz,
three axes (Klipper's raw format), each run as the command a user types, in its own process.

Prints CPU time (user + system) and peak memory (max RSS) per record length, and the modes
found. Run: python tests/bench/calibrate_bench.py [--lengths 10 60 600] [--out DIR]
Pass ``--compare "python /path/to/klipper/scripts/calibrate_shaper.py"`` to time the established
tool on the same files (it is not part of this repository).
"""
from __future__ import annotations

import argparse
import math
import os
import resource
import shlex
import subprocess
import sys
import tempfile

from smoothshaper.calibrate import synthetic


def _run(cmd: list[str]) -> tuple[float, float, str]:
    """(CPU seconds, peak MiB, stdout) of one command in a child process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run(cmd, capture_output=True, text=True, check=False)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, after.ru_maxrss / 1024.0, out.stdout


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lengths", type=float, nargs="+", default=[10.0, 60.0, 600.0])
    ap.add_argument("--out", help="also write the figures here (calibrate --out)")
    ap.add_argument("--compare", help="another calibration command to time on the same files")
    args = ap.parse_args()
    two_pi = 2 * math.pi
    modes = [(two_pi * 38.0, 0.04), (two_pi * 61.0, 0.06)]
    fs = 3200.0
    with tempfile.TemporaryDirectory() as tmp:
        for T in args.lengths:
            t, a = synthetic.resonance_record(modes, fs=fs, T=T, f0=5.0, f1=133.0, snr_db=30.0,
                                              axes=3, seed=7)
            path = os.path.join(tmp, f"raw_data_x_{int(T)}s.csv")
            synthetic.write_csv(path, [t, a[:, 0], a[:, 1], a[:, 2]],
                                ["time", "accel_x", "accel_y", "accel_z"], fmt="%.6f")
            cmd = [sys.executable, "-m", "smoothshaper", "calibrate", path, "--no-progress"]
            if args.out:
                cmd += ["--out", os.path.join(args.out, f"{int(T)}s")]
            cpu, mib, out = _run(cmd)
            modes_line = next((ln.strip() for ln in out.splitlines() if "Hz =" in ln), "")
            print(f"{T:6.0f} s record ({t.size} samples x 3): calibrate {cpu:6.2f} s CPU, "
                  f"{mib:6.0f} MiB peak; first mode: {modes_line}")
            if args.compare:
                # the established tool's RSS is its own: RUSAGE_CHILDREN keeps the largest child
                cpu2, mib2, _ = _run(shlex.split(args.compare) + [path])
                print(f"{'':6s}   compared command: {cpu2:6.2f} s CPU, {mib2:6.0f} MiB peak "
                      "(peak is the largest child so far)")


if __name__ == "__main__":
    main()
