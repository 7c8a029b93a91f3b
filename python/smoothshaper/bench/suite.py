# SPDX-License-Identifier: Apache-2.0
"""Speed benchmark: every path of the library next to what it replaces, in one run.

``python -m smoothshaper.bench`` prints the tables and writes them to ``docs/benchmarks.md``
(``--output`` elsewhere, ``--quick`` for a few-second smoke run whose figures mean nothing).

What is measured, always CPU time (``time.process_time_ns``, or the C clock of the process),
the median of several rounds, the contenders of a row interleaved round by round so that a
busy machine slows them alike:

- C per-sample cost (``tests/bench/speed_bench.c`` compiled here against ``c/src`` at ``-O2``
  and ``-O3 -march=native``, double and float): each filter next to the plain recursion of the
  same filter, a plain biquad, a sparse FIR with the same taps and a direct-form FIR; a
  retunable stage next to the fixed one (between switches, and switching all the time);
  the online generator per sample; the kinematic design per regime.
- Python: the :class:`~smoothshaper.filters.Chain` call floor, throughput against
  ``scipy.signal.lfilter`` (the plain recursion, and the FIR taps) and ``oaconvolve``, the peak
  memory of ``Chain.process`` in double and float, the cost of building, copying, pickling a
  chain and of its taps.
- Trajectory: ``design.kinematic`` against ``ruckig`` (both called from Python), per regime;
  ``design.kinematic`` against the raw C call through cffi for one to three bounds, with and
  without ``Ts`` and a mode, and what its floor is made of.
- FMUs (when fmpy and cmake are available): one ``doStep`` of ``SmoothShaper`` and of
  ``TrajectoryGenerator`` per sample period through fmpy, and the per-sample cost inside one
  long ``doStep``. With cmake alone: the fixed cost of loading an FMU state
  (``DeSerializeFMUstate`` + ``FreeFMUstate``, FMI 2.0 and 3.0) from a raw C host
  (``tests/fmu/bench_fmu_feedthrough.c --state-load``).
- Memory per stage (not a time): the bytes each family's stage takes on this machine, next to
  the retired layout that sized every stage by the largest shaper; and, when
  ``arm-none-eabi-gcc`` and cmake are available (and not ``--quick``),
  ``tests/portability/cortex_m.cmake`` for a Cortex-M4F: the per-sample code size and the
  bytes of each family's instance there.

Nothing here asserts a time: machines are noisy; the numbers are for reading.
"""
from __future__ import annotations

import argparse
import math
import os
import pickle
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
import tracemalloc
from pathlib import Path

import numpy as np

__all__ = ["ROOT", "SPEED_BENCH", "interleaved", "Table", "run_c_bench", "C_ROWS", "C_STEP_ROWS",
           "FOLLOW_ROWS",
           "c_tables",
           "python_tables", "trajectory_table", "kinematic_call_table", "kinematic_parts",
           "fmu_table", "STATE_LOAD_BENCH", "fmu_state_load_table", "UNION_STAGE_BYTES",
           "memory_tables", "HAND_WRITTEN", "main"]

ROOT = Path(__file__).resolve().parents[3]
SPEED_BENCH = ROOT / "tests" / "bench" / "speed_bench.c"


# -- timing ---------------------------------------------------------------------------------

def interleaved(contenders: dict, *, rounds: int, repeat: int = 1) -> dict:
    """Median CPU seconds per call of each contender (name -> zero-argument callable). Each
    round runs every contender `repeat` times, rotating who goes first."""
    names = list(contenders)
    samples = {name: [] for name in names}
    for name in names:                      # warm caches, allocators, lazy imports
        contenders[name]()
    for r in range(rounds):
        for j in range(len(names)):
            name = names[(j + r) % len(names)]
            fn = contenders[name]
            t0 = time.process_time_ns()
            for _ in range(repeat):
                fn()
            samples[name].append((time.process_time_ns() - t0) * 1e-9 / repeat)
    return {name: statistics.median(v) for name, v in samples.items()}


class Table:
    """A titled table of rows, printed as it grows and rendered as Markdown."""

    def __init__(self, title: str, columns: list[str], note: str = ""):
        self.title, self.columns, self.note, self.rows = title, columns, note, []
        print(f"\n## {title}")
        print("  " + " | ".join(columns))

    def add(self, *cells) -> None:
        row = [c if isinstance(c, str) else _fmt(c) for c in cells]
        self.rows.append(row)
        print("  " + " | ".join(row), flush=True)

    def markdown(self) -> str:
        out = [f"## {self.title}", ""]
        if self.note:
            out += [self.note, ""]
        out.append("| " + " | ".join(self.columns) + " |")
        out.append("|" + "|".join("---" for _ in self.columns) + "|")
        out += ["| " + " | ".join(r) + " |" for r in self.rows]
        return "\n".join(out) + "\n"


def _fmt(v) -> str:
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "n/a"
    if isinstance(v, float):
        return f"{v:.3g}" if abs(v) < 100 else f"{v:.0f}"
    return str(v)


def _ratio(a, b) -> str:
    return f"{a / b:.2f}x" if a and b else "n/a"


# -- C per-sample paths ---------------------------------------------------------------------

def _compiler() -> str | None:
    return os.environ.get("CC") or shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")


def run_c_bench(flags: list[str], precision: str, workdir: Path, quick: bool) -> dict:
    """Compile speed_bench.c with the library sources and run it; {(kind, path, contender): ns}."""
    cc = _compiler()
    sources = sorted((ROOT / "c" / "src").rglob("*.c"))
    exe = workdir / f"speed_bench_{precision}_{'_'.join(f.strip('-') for f in flags)}"
    defines = ["-DSMS_USE_FLOAT"] if precision == "float" else []
    cmd = [cc, "-std=c99", *flags, *defines, "-I", str(ROOT / "c" / "include"),
           "-I", str(ROOT / "c" / "src"), str(SPEED_BENCH), *map(str, sources), "-lm",
           "-o", str(exe)]
    subprocess.run(cmd, check=True)
    out = subprocess.run([str(exe)] + (["--quick"] if quick else []), check=True,
                         capture_output=True, text=True).stdout
    figures = {}
    for line in out.splitlines():
        parts = line.split("\t")
        if parts[0] == "speed" and len(parts) == 4:
            figures[("speed", parts[1], parts[2])] = float(parts[3])
        elif parts[0] == "design" and len(parts) == 3:
            figures[("design", parts[1], "")] = float(parts[2])
    return figures


C_ROWS = [  # path, reference contender, target ratio (what the library aims at)
    ("rectangular", "plain recursion", "<= 1.5"),
    ("harmonic", "plain recursion", "<= 1.5"),
    ("damped harmonic", "plain recursion", "<= 1.5"),
    ("exponential", "plain recursion", "<= 1.5"),
    ("rectangular (FIR)", "direct-form FIR", "O(1) vs O(L)"),
    ("notch", "plain biquad", "<= 1.2"),
    ("ZV shaper", "sparse FIR", "<= 1"),
    ("ZVD shaper", "sparse FIR", "<= 1"),
    ("EI shaper", "sparse FIR", "<= 1"),
]

#: The one-call-per-sample rows (speed_bench's "<path> step"): sms_stage_step against the
#: plain form called once per sample the same way; path, reference, target ratio.
C_STEP_ROWS = [
    ("rectangular", "plain recursion", "<= 2"),
    ("harmonic", "plain recursion", "<= 2"),
    ("damped harmonic", "plain recursion", "<= 2"),
    ("exponential", "plain recursion", "<= 2"),
    ("notch", "plain biquad", "<= 2"),
    ("ZV shaper", "sparse FIR", "<= 1.3"),
    ("ZVD shaper", "sparse FIR", "<= 1.3"),
    ("EI shaper", "sparse FIR", "<= 1.3"),
]


#: Rows of the retunable and scheduled stages: path, contenders (the first is the fixed stage).
FOLLOW_ROWS = [
    ("ZVD shaper, retunable", ["fixed", "tunable", "tunable, switching"]),
    ("rectangular, retunable", ["fixed", "tunable", "tunable, switching"]),
    ("ZVD shaper, scheduled", ["fixed", "scheduled, every sample", "scheduled, every 16"]),
]


def c_tables(quick: bool) -> tuple[list[Table], dict]:
    """The C tables, and the figures of every build {(flags, precision): figures}."""
    if _compiler() is None or not SPEED_BENCH.is_file():
        print("\n(C per-sample benchmark skipped: needs a C compiler and a source checkout)")
        return [], {}
    variants = [(["-O2"], "double"), (["-O2"], "float")]
    if not quick:
        variants += [(["-O3", "-march=native"], "double"), (["-O3", "-march=native"], "float")]
    results = {}
    with tempfile.TemporaryDirectory() as tmp:
        for flags, precision in variants:
            results[(" ".join(flags), precision)] = run_c_bench(flags, precision, Path(tmp), quick)
    columns = ["path", "reference", "target"]
    for flags, precision in variants:
        columns += [f"{precision} {' '.join(flags)}: ns (ref ns)", "ratio"]
    per_sample = Table(
        "C per-sample cost against the plain realisation", columns,
        "ns per sample, N = T/Ts = 200 for the smoothers (paper timing), Ts = 1 ms; notch and "
        "shapers for a 40 Hz mode, zeta 0.05 (exact timing). Ratio = smoothshaper / reference.")
    for path, ref, target in C_ROWS:
        cells = [path, ref, target]
        for key, figures in results.items():
            mine = figures.get(("speed", path, "smoothshaper"))
            theirs = figures.get(("speed", path, ref))
            cells += [f"{_fmt(mine)} ({_fmt(theirs)})", _ratio(mine, theirs)]
        per_sample.add(*cells)
    step_columns = ["path", "reference", "target"]
    for flags, precision in variants:
        step_columns += [f"{precision} {' '.join(flags)}: ns (ref ns)", "ratio", "vs ref loop"]
    per_call = Table(
        "C one call per sample (step) against the plain form called the same way", step_columns,
        "sms_stage_step once per sample, as firmware calls it from its sample interrupt, "
        "against the plain form's own one-sample function (state in its struct, not inlined "
        "into the caller); same filters as above. Ratio = smoothshaper step / plain step; "
        "vs ref loop = smoothshaper step / the plain form's loop over a block (the table "
        "above), what a call costs against no call at all.")
    for path, ref, target in C_STEP_ROWS:
        cells = [path, ref, target]
        for key, figures in results.items():
            mine = figures.get(("speed", f"{path} step", "smoothshaper"))
            theirs = figures.get(("speed", f"{path} step", ref))
            loop = figures.get(("speed", path, ref))
            cells += [f"{_fmt(mine)} ({_fmt(theirs)})", _ratio(mine, theirs), _ratio(mine, loop)]
        per_call.add(*cells)
    follow = Table(
        "C per-sample cost of stages that follow the machine, next to the fixed stage",
        ["path", "contender"] + [f"{p} {f}: ns (ratio to fixed)" for f, p in results],
        "ns per sample, the same configuration as the row above (ZVD for the 40 Hz mode; "
        "rectangular N = 200, paper timing). tunable: a retunable stage (tunable.h) between "
        "switches; switching: retuned (to 0.8 wn or 0.8 T and back) as soon as each switch "
        "has ended, so always switching: the retune's design and delay-line zeroing and both "
        "filters running. scheduled: the ZVD whose mode follows a schedule sweeping a 9-point "
        "table (0.8 to 1.2 of the 40 Hz mode), its taps redesigned every sample or every 16. "
        "The fixed path is the stage of the table above, unchanged.")
    for path, contenders in FOLLOW_ROWS:
        for contender in contenders:
            cells = [path, contender]
            for figures in results.values():
                mine = figures.get(("speed", path, contender))
                fixed = figures.get(("speed", path, "fixed"))
                cells.append(f"{_fmt(mine)} ({_ratio(mine, fixed)})")
            follow.add(*cells)
    traj = Table("C trajectory paths", ["path"] + [f"{p} {f}" for f, p in results],
                 "Generator: ns per sample while cruising (vmax 250, amax 5000, jmax 2e5, "
                 "Ts = 0.1 ms). Kinematic design: ns per design of a rest-to-rest move.")
    traj.add("generator step [ns/sample]",
             *[r.get(("speed", "generator", "smoothshaper")) for r in results.values()])
    for regime in ("vmax reached", "amax reached, vmax not", "jmax only"):
        traj.add(f"kinematic design, {regime} [ns]",
                 *[r.get(("design", regime, "")) for r in results.values()])
    return [per_sample, per_call, follow, traj], results


# -- Python paths ---------------------------------------------------------------------------

def python_tables(quick: bool) -> list[Table]:
    import scipy.signal as sps

    from ..filters import Chain
    from ..stages import Stage

    rounds = 3 if quick else 15
    Ts = 1e-3
    n = 10_000 if quick else 1_000_000
    rng = np.random.default_rng(1)
    u = 1e3 + rng.uniform(-1, 1, n)
    tables = []

    floor = Table("Python call floor", ["call", "us per call"],
                  "Chain.process on one sample and Chain.step (rectangular stage).")
    for precision in ("double", "float"):
        chain = Chain([Stage("rectangular", T=0.01)], Ts=Ts, precision=precision)
        one = np.zeros(1)
        t = interleaved({"process": lambda: chain.process(one),
                         "step": lambda: chain.step(0.0)}, rounds=rounds, repeat=2000)
        floor.add(f"Chain.process(1 sample), {precision}", t["process"] * 1e6)
        floor.add(f"Chain.step, {precision}", t["step"] * 1e6)
    tables.append(floor)

    # The damped harmonic smoother, N = 200: the library, scipy on its plain recursion (b, a),
    # scipy on its FIR taps, overlap-add convolution.
    N, sigma = 200, -10.0
    stage = Stage("damped_harmonic", T=N * Ts, sigma=sigma, timing="paper")
    chain = Chain([stage], Ts=Ts)
    h = chain.taps()
    r, c = math.exp(sigma * Ts), math.cos(math.pi / N)
    K = (1 - 2 * r * c + r * r) / (1 + r ** N)
    a = np.array([1.0, -2 * r * c, r * r])

    def plain_recursion():
        # y = K (x[n-1] + r^N x[n-N-1]) + 2 r c y[n-1] - r^2 y[n-2]: the sparse numerator
        # in NumPy, the recursion in lfilter (a dense (b, a) of N + 2 taps would be O(N)).
        v = u.copy()
        v[N:] += r ** N * u[:-N]
        return sps.lfilter([0.0, K], a, v)

    t = interleaved({
        "Chain.process": lambda: chain.process(u),
        "lfilter, plain recursion": plain_recursion,
        "lfilter, FIR taps": lambda: sps.lfilter(h, [1.0], u),
        "oaconvolve, FIR taps": lambda: sps.oaconvolve(u, h)[:n],
    }, rounds=max(3, rounds // 3))
    through = Table("Python throughput (damped harmonic smoother, N = 200)",
                    ["contender", "ns per sample", "vs Chain.process"],
                    f"{n} samples of 1e3 + U(-1, 1), float64 in and out.")
    for name, sec in t.items():
        through.add(name, sec / n * 1e9, _ratio(sec, t["Chain.process"]))
    tables.append(through)

    big = 100_000 if quick else 10_000_000
    x = rng.uniform(-1, 1, big)
    memory = Table("Python peak memory of Chain.process",
                   ["precision", "signal MiB", "peak extra MiB", "extra / signal"],
                   f"{big} float64 samples; peak allocated during the call (tracemalloc), "
                   "output included.")
    for precision in ("double", "float"):
        ch = Chain([stage], Ts=Ts, precision=precision)
        tracemalloc.start()
        tracemalloc.reset_peak()
        before = tracemalloc.get_traced_memory()[0]
        y = ch.process(x)
        peak = tracemalloc.get_traced_memory()[1] - before
        tracemalloc.stop()
        del y
        memory.add(precision, x.nbytes / 2**20, peak / 2**20, f"{peak / x.nbytes:.2f}")
    tables.append(memory)

    design = Table("Design cost of a chain (damped harmonic stage, exact timing)",
                   ["N = T/Ts", "Chain() ms", "taps() ms", "copy() ms", "pickle round trip ms"])
    for N in ((10_000, 100_000) if quick else (100_000, 1_000_000)):
        st = [Stage("damped_harmonic", T=(N + 0.3) * 1e-4, sigma=-3.0)]
        ch = Chain(st, Ts=1e-4)
        t = interleaved({
            "init": lambda: Chain(st, Ts=1e-4),
            "taps": lambda: ch.taps(),
            "copy": lambda: ch.copy(),
            "pickle": lambda: pickle.loads(pickle.dumps(ch)),
        }, rounds=3 if quick else 7)
        design.add(N, t["init"] * 1e3, t["taps"] * 1e3, t["copy"] * 1e3, t["pickle"] * 1e3)
    tables.append(design)
    return tables


def trajectory_table(quick: bool, c_figures: dict) -> list[Table]:
    try:
        import ruckig
    except ImportError:
        print("\n(kinematic design against ruckig skipped: ruckig is not installed; "
              "pip install 'smoothshaper[bench]')")
        return []
    from .. import design as kinematic_design
    from ..filters import _backend

    ffi, lib = _backend("double")
    table = Table("Kinematic design against ruckig",
                  ["regime", "smoothshaper C ns", "smoothshaper via cffi ns",
                   "design.kinematic ns", "ruckig ns", "C / ruckig", "cffi / ruckig",
                   "design.kinematic / ruckig", "same duration"],
                  "One rest-to-rest move within {vmax, amax, jmax}, continuous and on a "
                  "1 ms grid (ruckig: Ruckig(1, Ts) with DurationDiscretization.Discrete; "
                  "smoothshaper: Ts=1e-3, bounding the sampled differences, so the durations "
                  "differ by design). ruckig: Ruckig.calculate "
                  "through its Python binding (the C++ core plus the binding's call), objects "
                  "prepared beforehand. smoothshaper: sms_kinematic_design in C (double, -O2), "
                  "through cffi (the call itself costs about 0.2 us), and design.kinematic "
                  "(the Python API: the call, the C design and three Stage objects; "
                  "design.kinematic_lengths designs many problems in one call at about the C "
                  "cost each, `python -m smoothshaper.bench.trajectory`).")
    cases = {"vmax reached": (1.0, 0.5, 5.0, 100.0),
             "amax reached, vmax not": (0.1, 2.0, 5.0, 100.0),
             "jmax only": (0.001, 2.0, 5.0, 100.0)}
    for (regime, (h, v, a, j)), Ts in [(c, Ts) for Ts in (None, 1e-3) for c in cases.items()]:
        limits = ffi.new("double[]", [v, a, j])
        T = ffi.new("double[]", 3)
        count = ffi.new("size_t *")
        design = lib.sms_kinematic_design
        poly = lib.SMS_PROFILE_POLYNOMIAL
        otg = ruckig.Ruckig(1) if Ts is None else ruckig.Ruckig(1, Ts)
        inp = ruckig.InputParameter(1)
        inp.current_position, inp.target_position = [0.0], [h]
        inp.max_velocity, inp.max_acceleration, inp.max_jerk = [v], [a], [j]
        if Ts is not None:
            inp.duration_discretization = ruckig.DurationDiscretization.Discrete
        traj = ruckig.Trajectory(1)
        kinematic = kinematic_design.kinematic
        Ts_c = 0.0 if Ts is None else Ts
        t = interleaved({
            "sms": lambda: design(h, limits, 3, poly, 0.0, 0.0, Ts_c, T, 3, count),
            "python": lambda: kinematic(h=h, vmax=v, amax=a, jmax=j, Ts=Ts),
            "ruckig": lambda: otg.calculate(inp, traj),
        }, rounds=3 if quick else 15, repeat=200 if quick else 5000)
        if Ts is None:
            same = abs(sum(T[i] for i in range(count[0])) - traj.duration) <= 1e-12 * traj.duration
            in_c = c_figures.get(("-O2", "double"), {}).get(("design", regime, ""))
        else:
            # on a grid the two bound different things (ruckig: the continuous profile,
            # its duration rounded up to a sample; here: the sampled differences)
            same, in_c = None, None
            regime = f"{regime}, Ts = {Ts * 1e3:g} ms"
        table.add(regime, in_c, t["sms"] * 1e9, t["python"] * 1e9, t["ruckig"] * 1e9,
                  _ratio(in_c * 1e-9 if in_c else None, t["ruckig"]),
                  _ratio(t["sms"], t["ruckig"]), _ratio(t["python"], t["ruckig"]),
                  "n/a" if same is None else "yes" if same else "NO")
    return [table, _phase_duration_table(quick, ruckig)]


def _phase_duration_table(quick: bool, ruckig) -> Table:
    """multi_axis.phase_duration against ruckig's phase-synchronised calculate, same moves."""
    from .. import multi_axis
    table = Table("Multi-axis duration against ruckig",
                  ["move", "multi_axis.phase_duration ns", "ruckig ns", "ratio", "same duration"],
                  "A phase-synchronised rest-to-rest move of three axes with limits per axis. "
                  "ruckig: Ruckig(3).calculate with Synchronization.Phase through its Python "
                  "binding, objects prepared beforehand; smoothshaper: "
                  "multi_axis.phase_duration with the lists as a user writes them (the "
                  "checks and sms_multi_phase_duration in one C call).")
    limits = dict(vmax=[0.5, 0.4, 0.2], amax=[5.0, 4.0, 2.0], jmax=[200.0, 150.0, 100.0])
    cases = {"long move (cruise)": [0.3, 0.1, 0.05], "short move": [0.01, -0.004, 0.002]}
    for move, delta in cases.items():
        otg, inp, traj = ruckig.Ruckig(3), ruckig.InputParameter(3), ruckig.Trajectory(3)
        inp.current_position, inp.target_position = [0.0] * 3, delta
        inp.max_velocity, inp.max_acceleration = limits["vmax"], limits["amax"]
        inp.max_jerk = limits["jmax"]
        inp.synchronization = ruckig.Synchronization.Phase
        duration = multi_axis.phase_duration
        t = interleaved({
            "sms": lambda: duration(delta, **limits),
            "ruckig": lambda: otg.calculate(inp, traj),
        }, rounds=3 if quick else 15, repeat=200 if quick else 5000)
        T = duration(delta, **limits)
        same = abs(T - traj.duration) <= 1e-9 * traj.duration
        table.add(move, t["sms"] * 1e9, t["ruckig"] * 1e9, _ratio(t["sms"], t["ruckig"]),
                  "yes" if same else "NO")
    return table


def kinematic_call_table(quick: bool) -> list[Table]:
    """``design.kinematic`` against ``sms_kinematic_design`` called through cffi with its
    arrays prepared beforehand (the bare C call from Python), per common case; and where a
    three-bound call's time goes: the keyword call, the fast path (the C function that tests
    the types, runs the C design and builds the Stage objects) and its objects."""
    from .. import design as kinematic_design
    from ..filters import _backend

    ffi, lib = _backend("double")
    kinematic = kinematic_design.kinematic
    rounds, repeat = (3, 200) if quick else (15, 5000)
    table = Table("Kinematic design from Python against the raw C call",
                  ["case", "raw C call via cffi ns", "design.kinematic ns", "ratio"],
                  "A rest-to-rest move, h=1, vmax=0.5, amax=5, jmax=100 (as many bounds as "
                  "the case says; Ts=1 ms, wn=30 rad/s with zeta=0.05 where given). Raw: "
                  "sms_kinematic_design through cffi, its bounds and output arrays prepared "
                  "beforehand. design.kinematic: the public call, its argument types checked, "
                  "the C design, the Stage objects.")
    cases = {"1 bound": dict(vmax=0.5), "2 bounds": dict(vmax=0.5, amax=5.0),
             "3 bounds": dict(vmax=0.5, amax=5.0, jmax=100.0),
             "3 bounds, int arguments": dict(vmax=2, amax=5, jmax=100),
             "3 bounds, trigonometric": dict(vmax=0.5, amax=5.0, jmax=100.0,
                                             profile="trigonometric"),
             "3 bounds, Ts": dict(vmax=0.5, amax=5.0, jmax=100.0, Ts=1e-3),
             "3 bounds, wn": dict(vmax=0.5, amax=5.0, jmax=100.0, wn=30.0, zeta=0.05),
             "3 bounds, wn and Ts": dict(vmax=0.5, amax=5.0, jmax=100.0, wn=30.0, zeta=0.05,
                                         Ts=1e-3)}
    T, count = ffi.new("double[]", 3), ffi.new("size_t *")
    raw_design = lib.sms_kinematic_design
    for name, kw in cases.items():
        kw = dict(h=1.0, **kw)
        bounds = [kw[b] for b in ("vmax", "amax", "jmax") if b in kw]
        limits, n = ffi.new("double[]", bounds), len(bounds)
        profile = kinematic_design.PROFILES.index(kw.get("profile", "polynomial"))
        wn, zeta, Ts = kw.get("wn", 0.0), kw.get("zeta", 0.0), kw.get("Ts", 0.0)
        # the keywords written out, as a caller writes them (a ** dict costs extra)
        call = eval("lambda: kinematic(" + ", ".join(f"{k}={k}" for k in kw) + ")",
                    {"kinematic": kinematic, **kw})
        t = interleaved({
            "raw": lambda: raw_design(1.0, limits, n, profile, wn, zeta, Ts, T, n, count),
            "python": call}, rounds=rounds, repeat=repeat)
        table.add(name, t["raw"] * 1e9, t["python"] * 1e9, _ratio(t["python"], t["raw"]))

    parts = kinematic_parts(rounds, repeat)
    split = Table("Where design.kinematic's time goes (3 bounds)",
                  ["part", "ns", "ratio to the raw C call"],
                  "Each part timed on its own, an empty lambda's cost subtracted from every "
                  "row (the table above keeps it in both columns, hence its smaller ratios). "
                  "The fast path is the C function design.kinematic calls: the argument types "
                  "tested, the C design, three Stage objects and their list.")
    for key, part in (("call", "the keyword call (an empty function with its signature)"),
                      ("fastpath", "the fast path, called directly"),
                      ("python", "design.kinematic"),
                      ("raw", "raw C call via cffi")):
        split.add(part, parts[key], _ratio(parts[key], parts["raw"]))
    return [table, split]


def kinematic_parts(rounds: int, repeat: int) -> dict:
    """CPU ns per call (an empty lambda's cost subtracted) of a three-bound design:
    ``"raw"`` (``sms_kinematic_design`` through cffi, arrays prepared), ``"python"``
    (``design.kinematic``), ``"call"`` (the keyword call of a function with its signature and
    no body) and ``"fastpath"`` (the C function design.kinematic calls, with positional
    arguments)."""
    from .. import design as kinematic_design
    from ..filters import _backend

    ffi, lib = _backend("double")
    raw_design, kinematic = lib.sms_kinematic_design, kinematic_design.kinematic
    fastpath = kinematic_design._fastpath
    limits, T = ffi.new("double[]", [0.5, 5.0, 100.0]), ffi.new("double[]", 3)
    count = ffi.new("size_t *")

    def signature(*, h, vmax, amax=None, jmax=None, higher=(), profile="polynomial", wn=None,
                  zeta=0.0, Ts=None):
        return None
    t = interleaved({
        "raw": lambda: raw_design(1.0, limits, 3, 0, 0.0, 0.0, 0.0, T, 3, count),
        "empty": lambda: None,
        "call": lambda: signature(h=1.0, vmax=0.5, amax=5.0, jmax=100.0),
        "fastpath": lambda: fastpath(1.0, 0.5, 5.0, 100.0, (), "polynomial", None, 0.0, None),
        "python": lambda: kinematic(h=1.0, vmax=0.5, amax=5.0, jmax=100.0)},
        rounds=rounds, repeat=repeat)
    out = {name: (sec - t["empty"]) * 1e9 for name, sec in t.items() if name != "empty"}
    return out


# -- FMUs -----------------------------------------------------------------------------------

def fmu_table(quick: bool, build_dir: Path) -> list[Table]:
    try:
        import fmpy  # noqa: F401
        from fmpy import extract, read_model_description
        from fmpy.fmi2 import FMU2Slave
    except ImportError:
        print("\n(FMU benchmark skipped: fmpy is not installed; "
              "pip install 'smoothshaper[validate]')")
        return []
    if shutil.which("cmake") is None:
        print("\n(FMU benchmark skipped: cmake is needed to build the FMUs)")
        return []
    from .. import fmi
    from ..filters import Chain
    from ..stages import Stage

    fmus = fmi.build_fmus(build_dir)
    Ts = 1e-3
    steps = 2_000 if quick else 50_000
    table = Table("FMU paths (fmpy, one instance)",
                  ["path", "us per doStep", "ns per sample", "Python Chain.step us"],
                  "doStep of one sample period Ts = 1 ms, and one doStep of 1000 Ts "
                  "(per-sample cost inside the FMU).")
    chain = Chain([Stage("damped_harmonic", T=0.0531, sigma=-10.0)], Ts=Ts)
    t_chain = interleaved({"step": lambda: chain.step(1.0)}, rounds=3, repeat=steps // 10)["step"]
    for model, start in (("SmoothShaper", fmi.start_values(
            [Stage("damped_harmonic", T=0.0531, sigma=-10.0)], Ts=Ts)),
            ("TrajectoryGenerator", dict(Ts=Ts, vmax=1.0, amax=10.0, jmax=1000.0))):
        if model not in fmus:
            continue
        with tempfile.TemporaryDirectory() as tmp:
            unzipped = extract(str(fmus[model]), tmp)
            md = read_model_description(unzipped)
            refs = {v.name: v.valueReference for v in md.modelVariables}
            slave = FMU2Slave(guid=md.guid, unzipDirectory=unzipped,
                              modelIdentifier=md.coSimulation.modelIdentifier,
                              instanceName="bench")
            slave.instantiate()
            slave.setupExperiment(startTime=0.0)
            for name, value in start.items():
                var = next(v for v in md.modelVariables if v.name == name)
                if var.type == "Integer" or var.type == "Enumeration":
                    slave.setInteger([refs[name]], [int(value)])
                else:
                    slave.setReal([refs[name]], [float(value)])
            slave.enterInitializationMode()
            slave.exitInitializationMode()
            clock = {"t": 0.0, "k": 0}
            # A new input before every step: a held input is absorbed after a few chain
            # lengths and the FMU then skips the ticks, which would hide the per-sample cost.
            vr_in = [refs["u" if "u" in refs else "target"]]

            def one_step():
                clock["k"] += 1
                slave.setReal(vr_in, [0.001 * (clock["k"] & 7)])
                slave.doStep(clock["t"], Ts)
                clock["t"] += Ts

            def long_step():
                clock["k"] += 1
                slave.setReal(vr_in, [0.001 * (clock["k"] & 7)])
                slave.doStep(clock["t"], 1000 * Ts)
                clock["t"] += 1000 * Ts

            t = interleaved({"one": one_step, "long": long_step}, rounds=3,
                            repeat=max(1, steps // 30))
            slave.terminate()
            slave.freeInstance()
        table.add(model, t["one"] * 1e6, (t["long"] - t["one"]) / 999 * 1e9,
                  t_chain * 1e6 if model == "SmoothShaper" else "")
    return [table]


#: The raw C host timing the state load (built by CMake with the tests, target of the same name).
STATE_LOAD_BENCH = ROOT / "tests" / "fmu" / "bench_fmu_feedthrough.c"


def fmu_state_load_table(quick: bool, build_dir: Path) -> list[Table]:
    """DeSerializeFMUstate + FreeFMUstate of SmoothShaper's own state, FMI 2.0 and 3.0, from
    ``bench_fmu_feedthrough --state-load`` built in ``build_dir`` (a CMake tree with the tests:
    configured here if it is not one)."""
    cmake = shutil.which("cmake")
    if cmake is None or not STATE_LOAD_BENCH.is_file():
        print("\n(FMU state load skipped: needs cmake and a source checkout)")
        return []
    if not (build_dir / "CMakeCache.txt").is_file():
        subprocess.run([cmake, "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                        "-DSMS_BUILD_TESTS=ON", "-DSMS_BUILD_SHARED=OFF",
                        f"-DPython3_EXECUTABLE={sys.executable}"],
                       check=True, stdout=subprocess.DEVNULL)
    subprocess.run([cmake, "--build", str(build_dir), "-j2", "--target", "bench_fmu_feedthrough"],
                   check=True, stdout=subprocess.DEVNULL)
    exe = build_dir / "fmu" / "bench_fmu_feedthrough"
    out = subprocess.run([str(exe), "--state-load"], check=True, capture_output=True,
                         text=True).stdout   # about a second: the same with --quick
    figures = {}
    for line in out.splitlines():
        parts = line.split("\t")
        if parts[0] == "state_load" and len(parts) == 4:
            figures[(parts[1], parts[2])] = float(parts[3])
    table = Table(
        "FMU state load (DeSerializeFMUstate)", ["path", "FMI 2.0 us", "FMI 3.0 us"],
        "DeSerializeFMUstate + FreeFMUstate of the SmoothShaper instance's own state (default "
        "chain, rectangular 10 ms + ZV), raw C host through dlopen'd function pointers, CPU time, "
        "median of 7 rounds of 20000 (`tests/fmu/bench_fmu_feedthrough.c --state-load`). A state "
        "holding the instance's own parameters is recognised by one comparison of its settable "
        "values with the instance's values image (the bytes a state writes for them, kept until "
        "a parameter may change), keeps the built filters and reads only the inputs and the "
        "filter values, all of them checked. Earlier, measured at a load average of 0.2: 16.1 / "
        "16.5 us when every stage was rebuilt on load, 8.7 / 9.2 us with the built filters kept "
        "but every parameter read and compared one by one (the bar: 2 us). Load average "
        f"during this run: {os.getloadavg()[0]:.1f}.")
    table.add("SmoothShaper (its default chain)", figures.get(("fmi2", "SmoothShaper")),
              figures.get(("fmi3", "SmoothShaper")))
    return [table]


# -- memory per stage -----------------------------------------------------------------------

#: sizeof(sms_stage) of the retired layout, a union of the three families sized by a shaper's
#: 45-entry tap arrays: every stage took this much plus its delay line, whatever its family.
#: Measured once with the compilers of the tables (GCC, x86-64; arm-none-eabi-gcc, Cortex-M4F);
#: the current layout is measured on every run.
UNION_STAGE_BYTES = {("x86-64", "double"): 784, ("x86-64", "float"): 600,
                     ("Cortex-M4F", "double"): 584, ("Cortex-M4F", "float"): 392}

#: One example per family (and the largest shaper), Ts = 1 ms.
_MEMORY_EXAMPLES = (
    ("rectangular, T = 200 Ts", "rectangular", dict(T=0.2, timing="paper")),
    ("damped harmonic, T = 200.3 Ts", "damped_harmonic", dict(T=0.2003, sigma=-3.0)),
    ("ZV, 40 Hz, exact", "zv", dict(wn=2 * math.pi * 40, zeta=0.05)),
    ("EI, 40 Hz, exact", "ei", dict(wn=2 * math.pi * 40, zeta=0.05)),
    ("ZV^8, 40 Hz, exact (45 taps)", "zvn", dict(wn=2 * math.pi * 40, zeta=0.05, order=8)),
    ("notch (Tustin), 40 Hz", "notch_tustin", dict(wn=2 * math.pi * 40, zeta=0.0)),
)


def memory_tables(quick: bool) -> list[Table]:
    """Bytes per stage by family on this machine (both precisions), against the union layout."""
    from ..filters import _backend, _fill_config
    from ..stages import Stage

    host = "x86-64" if platform.machine() in ("x86_64", "AMD64") else platform.machine()
    table = Table(
        "Memory per stage", ["stage", "precision", "bytes now", "instance + taps + delay line",
                             "union layout", "now / union"],
        f"{host}, Ts = 1 ms. Bytes now = the sms_stage descriptor + sms_stage_memory_size() "
        "cells (the family's instance, a shaper's own tap table, the delay line, each padded to "
        "whole cells). Union layout = the retired sizeof(sms_stage) "
        "(a union sized by a 45-tap shaper; UNION_STAGE_BYTES) + the same delay line. "
        "Exact ZV^8, the one shaper with 45 taps, is the case the union was sized for; in the "
        "float build on a 64-bit host each of its taps (a size_t delay and a float gain) pads "
        "to 16 B. Each instance also keeps its configuration identity (15 doubles, 120 B: kind, "
        "precision, Ts and the design parameters) so that a saved state from another "
        "configuration is refused.")
    for label, kind, params in _MEMORY_EXAMPLES:
        stage = Stage(kind, **params)
        for precision in ("double", "float"):
            ffi, lib = _backend(precision)
            config = ffi.new("sms_stage_config *")
            _fill_config(config, stage)
            cells, reals, n_taps = (ffi.new("size_t *") for _ in range(3))
            if lib.sms_stage_memory_size(config, 1e-3, cells) != 0 or \
                    lib.sms_stage_buffer_size(config, 1e-3, reals) != 0:
                table.add(label, precision, "n/a", "", "", "")
                continue
            family = ("sms_smoother" if kind in ("rectangular", "damped_harmonic")
                      else "sms_notch" if kind.startswith("notch") else "sms_shaper")
            taps = 0
            if family == "sms_shaper":
                lib.sms_shaper_tap_count(config, 1e-3, n_taps)
                taps = n_taps[0] * ffi.sizeof("sms_shaper_tap")
            ring = reals[0] * ffi.sizeof("sms_real")
            now = ffi.sizeof("sms_stage") + cells[0] * ffi.sizeof("sms_memory_cell")
            union = UNION_STAGE_BYTES.get((host, precision))
            union_total = union + ring if union else None
            table.add(label, precision, now,
                      f"{ffi.sizeof(family)} + {taps} + {ring}",
                      union_total, _ratio(now, union_total) if union_total else "n/a")
    return [table] + _cortex_m_tables(quick)


def _cortex_m_tables(quick: bool = False) -> list[Table]:
    """Code size of the per-sample paths and instance sizes on a Cortex-M4F, from
    tests/portability/cortex_m.cmake (skipped without arm-none-eabi-gcc or cmake, and in the
    ``--quick`` smoke run: the script cross-compiles the library three times, and ctest's
    ``cortex_m_compile`` runs the same script in every test run)."""
    if quick:
        print("\n(Cortex-M4F sizes skipped in --quick: ctest cortex_m_compile runs their script)")
        return []
    script = ROOT / "tests" / "portability" / "cortex_m.cmake"
    if not (shutil.which("arm-none-eabi-gcc") and shutil.which("cmake") and script.is_file()):
        print("\n(Cortex-M4F sizes skipped: needs arm-none-eabi-gcc and cmake)")
        return []
    with tempfile.TemporaryDirectory() as tmp:
        out = subprocess.run(["cmake", f"-DSOURCE_DIR={ROOT}", f"-DWORK_DIR={tmp}/work", "-P",
                              str(script)], capture_output=True, text=True)
    text = out.stdout + out.stderr
    code = Table(
        "Cortex-M4F per-sample code size", ["probe", "build", "bytes"],
        "arm-none-eabi-gcc -mcpu=cortex-m4 -mfpu=fpv4-sp-d16 -mfloat-abi=hard, newlib, "
        "--gc-sections (tests/portability/cortex_m.cmake): text + rodata of a program that "
        "takes the addresses of the step/process/reset functions of the group (filters: "
        "stage, chain, smoother, shaper, notch), minus an empty program with the same start-up "
        "code. Counted: those functions, what they call (dispatch, the per-sample loops) and "
        "newlib's memset (162 B, called by the smoothers' reset). The double build on this "
        "single-precision FPU includes libgcc's soft-float routines. The 1,480 B quoted earlier "
        "for this path is the filters probe in float at -Os, with the per-sample code of that "
        "time (the same script reproduces it exactly at those commits; at -O2 they gave "
        "1,700 B).")
    import re
    for precision, opt, group, size in re.findall(
            r"cortex-m4 (float|double) (-O[s2]): (\w+) per-sample path (\d+) B", text):
        code.add(group, f"{precision} {opt}", int(size))
    sizes = Table("Cortex-M4F instance bytes", ["precision", "sizeof"],
                  "The stage descriptor, each family's instance, one shaper tap and the memory "
                  "cell on the target (stage.h: a stage's memory is its instance, a shaper's "
                  f"taps and its delay line). The union layout took "
                  f"{UNION_STAGE_BYTES[('Cortex-M4F', 'float')]} B (float) and "
                  f"{UNION_STAGE_BYTES[('Cortex-M4F', 'double')]} B (double) per stage.")
    for precision, listing in re.findall(r"cortex-m4 (float|double): sizeof (.*) B", text):
        sizes.add(precision, listing)
    if not code.rows:
        print(f"(cortex_m.cmake printed no sizes; exit {out.returncode})")
    return [code, sizes]


# -- main -----------------------------------------------------------------------------------

def _machine() -> str:
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    cc = _compiler()
    version = ""
    if cc:
        try:
            version = subprocess.run([cc, "--version"], capture_output=True, text=True).stdout
            version = version.splitlines()[0]
        except (OSError, IndexError):
            version = cc
    import scipy
    return (f"{cpu}, {os.cpu_count()} cores; {version}; Python {platform.python_version()}, "
            f"NumPy {np.__version__}, SciPy {scipy.__version__}")


#: The line after which the output file's text is written by hand (measurements this module does
#: not make, such as the calibration against Klipper): kept as it is on every run.
HAND_WRITTEN = "<!-- Written by hand below this line: kept by python -m smoothshaper.bench. -->"


def _has_tests(build_dir: Path) -> bool:
    """Is build_dir a CMake tree configured with the tests (SMS_BUILD_TESTS on)?"""
    try:
        cache = (build_dir / "CMakeCache.txt").read_text(encoding="utf-8", errors="replace")
    except OSError:
        return False
    return "SMS_BUILD_TESTS:BOOL=ON" in cache


def _hand_written(path: Path) -> str:
    """The hand-written part of the existing output file (from HAND_WRITTEN on), or ""."""
    try:
        old = path.read_text(encoding="utf-8")
    except OSError:
        return ""
    at = old.find(HAND_WRITTEN)
    return old[at:] if at >= 0 else ""


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m smoothshaper.bench",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true",
                        help="a few seconds: short runs, -O2 only (a smoke test; figures are noise)")
    # In a source checkout the tables go to its docs/; from an installed package (no checkout
    # around it) to the current folder, never into site-packages' parents.
    in_checkout = (ROOT / "CMakeLists.txt").is_file() and (ROOT / "docs").is_dir()
    parser.add_argument("--output", type=Path,
                        default=ROOT / "docs" / "benchmarks.md" if in_checkout
                        else Path("benchmarks.md"),
                        help="Markdown file to write (default: docs/benchmarks.md of the source "
                             "checkout; ./benchmarks.md for an installed package)")
    parser.add_argument("--no-fmu", action="store_true", help="skip the FMU paths")
    parser.add_argument("--fmu-build-dir", type=Path, default=ROOT / "build-bench-fmu",
                        help="where the FMUs are built (default: build-bench-fmu)")
    parser.add_argument("--state-load-build-dir", type=Path, default=None,
                        help="CMake tree with the tests where the state-load host is built "
                             "(default: the FMU build folder if it has the tests, else "
                             "build-bench-state)")
    args = parser.parse_args(argv)
    machine = _machine()
    print(f"machine: {machine}")
    tables, c_figures = c_tables(args.quick)
    tables += python_tables(args.quick) + trajectory_table(args.quick, c_figures)
    tables += kinematic_call_table(args.quick)
    if not args.no_fmu:
        tables += fmu_table(args.quick, args.fmu_build_dir)
        state_dir = args.state_load_build_dir
        if state_dir is None:
            state_dir = (args.fmu_build_dir if _has_tests(args.fmu_build_dir)
                         else ROOT / "build-bench-state")
        tables += fmu_state_load_table(args.quick, state_dir)
    tables += memory_tables(args.quick)
    text = ["# Benchmarks", "",
            "Written by `python -m smoothshaper.bench`" + (" --quick (smoke run: figures are "
                                                           "noise)" if args.quick else "")
            + f". Machine: {machine}.", "",
            "CPU time, median of several rounds, contenders of a row interleaved round by "
            "round. Smaller is faster; a ratio is smoothshaper's time over the reference's.", ""]
    text += [t.markdown() for t in tables]
    kept = _hand_written(args.output)
    if kept:
        text += [kept]
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text("\n".join(text), encoding="utf-8")
    print(f"\nwrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
