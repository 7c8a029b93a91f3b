# SPDX-License-Identifier: Apache-2.0
"""Benchmark: CPU time and peak memory of ``smoothshaper calibrate`` and ``identify`` on long
records, each run as the command a user types, in its own process, next to the established
tool (Klipper's ``scripts/calibrate_shaper.py``) on the same files.

Records (written to a temporary folder, Klipper's raw format ``#time,accel_x,accel_y,accel_z``
with 6 decimals as the firmware writes them):

* resonance tests of 10 s, 60 s and 600 s at 3.2 kHz, three axes (a 5 -> 133 Hz sweep through
  modes at 38 and 61 Hz, cross-talk on y and z, 30 dB of noise, gravity on z);
* ``--lines``: a free decay and a one-axis sweep of that many lines (default 1e6 and 1e7).

Per run it prints CPU seconds (user + system of that process alone, ``os.wait4`` in a small launcher), peak
resident memory (its max RSS), bytes of peak memory per input sample, the CLI's own estimate
(``--estimate``) and the measured / estimated ratio; with ``--klipper DIR`` (a Klipper checkout,
not part of this repository) the established tool's figures on the same raw records and the
ratios ours / Klipper's. ``calibrate`` runs with ``--progress`` (the bar drawn, to a pipe).

Run: ``python tests/bench/calibrate_bench.py [--lengths 10 60 600] [--lines 1e6 1e7]
[--klipper /path/to/klipper] [--bytecode]`` (``--bytecode``: both tools with Python's bytecode
cache, as a normal install runs them; without it the environment is inherited, and where it
sets PYTHONDONTWRITEBYTECODE every run compiles this package's modules again)
"""
from __future__ import annotations

import argparse
import math
import os
import re
import subprocess
import sys
import tempfile

import numpy as np


#: Runs the command as its own child and prints its CPU seconds and max RSS [KiB] on the last
#: line of stderr: a small launcher, because max RSS survives exec and a child forked from this
#: process (NumPy and the records in memory) would start from this process's size.
_LAUNCHER = """
import os, sys
pid = os.fork()
if pid == 0:
    os.execvp(sys.argv[1], sys.argv[1:])
_, status, ru = os.wait4(pid, 0)
sys.stderr.write(f"\\n@@ {ru.ru_utime + ru.ru_stime} {ru.ru_maxrss} {os.waitstatus_to_exitcode(status)}\\n")
"""


#: The environment of every measured command (``--bytecode``: with Python's bytecode cache).
_ENV = None


def run_measured(cmd: list[str]) -> tuple[float, float, str]:
    """(CPU seconds, peak MiB, stdout) of one command, measured on its own process."""
    out = subprocess.run([sys.executable, "-S", "-c", _LAUNCHER] + cmd, capture_output=True,
                         text=True, env=_ENV)
    tail = out.stderr.rstrip().rsplit("\n", 1)[-1].split()
    cpu, kib, code = float(tail[1]), float(tail[2]), int(tail[3])
    if code != 0:
        sys.stderr.write(f"{' '.join(cmd)} exited {code}:\n{out.stderr[-2000:]}\n")
    return cpu, kib / 1024.0, out.stdout


def _modes_response(u, fs, modes):
    """Acceleration response of modes in series (wn^2 / (s^2 + 2 zeta wn s + wn^2) each) to
    ``u`` held over every sample: the exact zero-order-hold discretisation of each mode."""
    import scipy.signal
    y = u
    for f, z in modes:
        wn = 2 * math.pi * f
        b, a, _ = scipy.signal.cont2discrete(([wn * wn], [1.0, 2 * z * wn, wn * wn]), 1 / fs,
                                             method="zoh")
        y = scipy.signal.lfilter(np.ravel(b), a, y)
    return y


def _sweep(n, fs, f0=5.0, f1=133.0, accel_per_hz=60.0):
    t = np.arange(n) / fs
    f = f0 + (f1 - f0) * t / (n / fs)
    return accel_per_hz * f * np.sin(2 * np.pi * np.cumsum(f) / fs)


def _write(path, columns, header, fmt):
    with open(path, "w") as fh:
        fh.write("#" + ",".join(header) + "\n")
        n = columns[0].size
        for a in range(0, n, 1 << 18):
            b = min(n, a + (1 << 18))
            np.savetxt(fh, np.column_stack([c[a:b] for c in columns]), delimiter=",", fmt=fmt)


def resonance_file(folder, T, fs=3200.0, seed=7):
    rng = np.random.default_rng(seed)
    n = int(round(T * fs))
    u = _sweep(n, fs)
    y = _modes_response(u, fs, [(38.0, 0.04)]) + 0.3 * _modes_response(u, fs, [(61.0, 0.06)])
    sd = math.sqrt(float(np.mean(y ** 2))) * 10 ** (-30 / 20)
    t = np.arange(n) / fs + rng.uniform(0.0, 0.01 / fs, n)
    cols = [t, y + rng.normal(0, sd, n), 0.3 * y + rng.normal(0, sd, n),
            0.05 * y + rng.normal(0, sd, n) + 9810.0]
    path = os.path.join(folder, f"raw_data_x_{T:g}s.csv")
    _write(path, cols, ["time", "accel_x", "accel_y", "accel_z"], "%.6f")
    return path, n


def decay_file(folder, lines, seed=8):
    """A free decay of two lightly damped modes (10 and 37 Hz) over 25 s, sampled at lines / 25 s,
    with an offset and noise: the sum of damped cosines written out exactly."""
    rng = np.random.default_rng(seed)
    n = int(lines)
    t = np.arange(n) * (25.0 / n)
    y = np.full(n, 0.7)
    for A, f, z, ph in ((2.0, 10.0, 0.002, 0.3), (0.6, 37.0, 0.001, 1.0)):
        y += A * np.exp(-z * 2 * np.pi * f * t) * np.cos(2 * np.pi * f * math.sqrt(1 - z * z) * t
                                                         + ph)
    y += rng.normal(0.0, 0.002, n)
    path = os.path.join(folder, f"decay_{lines:.0e}.csv")
    _write(path, [t, y], ["time_s", "position_mm"], ["%.7f", "%.6f"])
    return path, n


def sweep_file(folder, lines, fs=3200.0, seed=9):
    rng = np.random.default_rng(seed)
    n = int(lines)
    y = _modes_response(_sweep(n, fs), fs, [(38.0, 0.04)])
    y += rng.normal(0.0, math.sqrt(float(np.mean(y ** 2))) * 10 ** (-30 / 20), n)
    path = os.path.join(folder, f"sweep_{lines:.0e}.csv")
    _write(path, [np.arange(n) / fs, y], ["time", "accel_x"], "%.6f")
    return path, n


def _estimate(cmd) -> float | None:
    """The CLI's own estimate [s] (``--estimate``), or None."""
    out = subprocess.run(cmd + ["--estimate"], capture_output=True, text=True).stdout
    m = re.search(r"about (< 1 s|[\d.]+ (?:s|min))", out)
    if not m:
        return None
    text = m.group(1)
    if text.startswith("<"):
        return 0.5
    value, unit = text.split()
    return float(value) * (60.0 if unit == "min" else 1.0)


def _row(label, n, cpu, mib, est, other=None):
    line = (f"{label:28s} {cpu:7.2f} s {mib:7.0f} MiB {mib * 2 ** 20 / n:6.0f} B/sample")
    if est is not None:
        line += f"  estimate {est:6.1f} s (measured/estimate {cpu / est:4.2f})"
    if other is not None:
        cpu2, mib2 = other
        line += (f"\n{'':28s} {cpu2:7.2f} s {mib2:7.0f} MiB   Klipper's calibrate_shaper.py;"
                 f" ratio ours/Klipper: CPU {cpu / cpu2:4.2f}, memory {mib / mib2:4.2f}")
    print(line, flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lengths", type=float, nargs="*", default=[10.0, 60.0, 600.0])
    ap.add_argument("--lines", type=float, nargs="*", default=[1e6, 1e7])
    ap.add_argument("--klipper", help="a Klipper checkout: time its scripts/calibrate_shaper.py")
    ap.add_argument("--tmp", help="folder for the records (default: a temporary one)")
    ap.add_argument("--bytecode", action="store_true",
                    help="run every command with Python's bytecode cache (as a normal install "
                         "has it: PYTHONDONTWRITEBYTECODE unset, a cache folder of its own, "
                         "each command run once before it is measured); by default the "
                         "environment is inherited as it is")
    args = ap.parse_args()
    me = [sys.executable, "-m", "smoothshaper"]
    with tempfile.TemporaryDirectory(dir=args.tmp) as tmp:
        if args.bytecode:
            global _ENV
            _ENV = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
            _ENV["PYTHONPYCACHEPREFIX"] = os.path.join(tmp, "pycache")
        print(f"{'command, record':28s} {'CPU':>9s} {'peak':>11s} {'per sample':>15s}")
        for T in args.lengths:
            path, n = resonance_file(tmp, T)
            cmd = me + ["calibrate", path]
            if args.bytecode:          # the first run writes the cache
                run_measured(cmd + ["--progress"])
            cpu, mib, _ = run_measured(cmd + ["--progress"])
            other = None
            if args.klipper:
                script = os.path.join(args.klipper, "scripts", "calibrate_shaper.py")
                kcmd = [sys.executable, script, path, "-c", os.path.join(tmp, "klipper.csv")]
                if args.bytecode:
                    run_measured(kcmd)
                k = run_measured(kcmd)
                other = k[:2]
            _row(f"calibrate {T:g} s x 3 axes", n, cpu, mib, _estimate(cmd), other)
            os.remove(path)
        for lines in args.lines:
            for make, name in ((decay_file, "decay"), (sweep_file, "sweep")):
                path, n = make(tmp, lines)
                for sub in ("identify", "calibrate"):
                    if sub == "identify" and name == "sweep":
                        continue          # a sweep is refused by identify (not a free decay)
                    cmd = me + [sub, path]
                    cpu, mib, _ = run_measured(cmd + (["--progress"] if sub == "calibrate"
                                                      else []))
                    _row(f"{sub} {name} {lines:.0e} lines", n, cpu, mib, _estimate(cmd))
                os.remove(path)


if __name__ == "__main__":
    main()
