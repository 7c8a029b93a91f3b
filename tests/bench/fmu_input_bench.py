# SPDX-License-Identifier: Apache-2.0
"""fmpy's simulate_fmu with an input signal: seconds and microseconds per step for 1e4, 1e5 and
1e6 steps of SmoothShaper.fmu (h = Ts = 1 ms, a new input value every step).

The FMUs' inputs have continuous variability, so fmpy interpolates them and makes no event per
change: the cost per step stays flat (with the former discrete input, fmpy's event search made
every step cost more as the run grew: 31, 75, 233 us/step at 1e3, 3e3, 1e4 steps, 1e5 steps
unfinished after 165 s). Exactness is kept: the signal's points are the communication points,
where interpolation returns the points' values.

Usage: python tests/bench/fmu_input_bench.py [--quick] [--build-dir DIR]
(--quick: 1e3, 1e4 steps, a smoke test of the harness.)
"""
from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np


def main(argv=None) -> int:
    import fmpy
    from smoothshaper import fmi
    from smoothshaper.stages import rectangular, shaper
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--build-dir", type=Path, default=Path(__file__).resolve().parents[2]
                    / "build-bench-fmu")
    args = ap.parse_args(argv)
    fmu = str(fmi.build_fmus(args.build_dir)["SmoothShaper"])
    unzipped = fmpy.extract(fmu)
    Ts = 1e-3
    stages = [rectangular(T=10.3 * Ts), shaper("zv", wn=150.0, zeta=0.05)]
    sizes = (1_000, 10_000) if args.quick else (10_000, 100_000, 1_000_000)
    print(f"{'steps':>10} {'seconds':>10} {'us/step':>10}")
    rows = []
    for n in sizes:
        t = np.arange(n + 1) * Ts
        u = np.random.default_rng(0).uniform(-1.0, 1.0, t.size)
        sig = np.zeros(t.size, dtype=[("time", float), ("u", float)])
        sig["time"], sig["u"] = t, u
        t0 = time.process_time()
        r = fmpy.simulate_fmu(unzipped, start_values=fmi.start_values(stages, Ts=Ts),
                              input=sig, stop_time=float(t[-1]), output_interval=Ts,
                              output=["y"], validate=False)
        seconds = time.process_time() - t0
        assert r.size == t.size
        rows.append((n, seconds))
        print(f"{n:>10} {seconds:>10.2f} {seconds / n * 1e6:>10.1f}")
    first, last = rows[0], rows[-1]
    print(f"cost per step, largest run / smallest run: "
          f"{(last[1] / last[0]) / (first[1] / first[0]):.2f} (1.0 = linear)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
