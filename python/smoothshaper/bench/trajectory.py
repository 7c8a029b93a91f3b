# SPDX-License-Identifier: Apache-2.0
"""Trajectory benchmark: what the online generator and the kinematic design cost and how close
to time-optimal the generator is when targets change mid-motion.

``python -m smoothshaper.bench.trajectory [--quick]`` prints:

- the distribution of arrival time / ruckig's time-optimal duration from the same state, for
  a target that changes mid-motion (random limits over three orders of magnitude, random
  switch instants; the state (q, v, a) at the switch is the generator's own output);
- the same ratio for rest-to-rest moves (1 + at most one sample);
- the other profiles rest to rest: the trigonometric one against its kinematic design, a
  mode-tuned one against ruckig + its stage and against the offline design with that mode;
- ``Generator.process`` per sample on 1e6 samples (double and float, one C call);
- ``design.kinematic`` from Python against the bare C call through cffi;
- the price in samples of designing a kinematic chain on the grid (docs/sampled-limits.md);
- multi-axis: the phase-synchronised duration against ruckig's ``Synchronization.Phase``
  (how often ruckig falls back to a curved move, how much shorter and how far off the line
  it then is), and the C cost of a multi-axis re-plan (``tests/bench/multi_generator_bench.c``
  compiled here; docs/multi-axis.md).

Nothing asserts a time; the figures are for reading (CPU time, medians of several rounds).
"""
from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

from .. import _optional

__all__ = ["arrival_ratios", "profile_prices", "ruckig_phase", "phase_comparison", "main",
           "RUCKIG_RELAX"]


# ruckig's duration is discontinuous at states whose braking velocity v + a|a|/(2 jmax) equals
# vmax to the last bit (a state on the ramp that ends a velocity change to vmax, common at a
# switch): with vmax exactly, ruckig picks a slower profile (e.g. 8.35 s where the optimum is
# 4.26 s), with vmax (1 + 1e-12) it returns the optimum to 1e-12. The benchmark therefore asks
# ruckig with vmax relaxed by RUCKIG_RELAX, which moves the optimum by about that relative
# amount and nothing else.
RUCKIG_RELAX = 1e-12


def _ruckig_duration(ruckig, q, v, a, goal, vmax, amax, jmax, relax=RUCKIG_RELAX):
    otg, inp, traj = ruckig.Ruckig(1), ruckig.InputParameter(1), ruckig.Trajectory(1)
    inp.current_position, inp.current_velocity, inp.current_acceleration = [q], [v], [a]
    inp.target_position = [goal]
    inp.max_velocity = [vmax * (1.0 + relax)]
    inp.max_acceleration, inp.max_jerk = [amax], [jmax]
    otg.calculate(inp, traj)
    return traj.duration


def arrival_ratios(n_cases: int, seed: int = 1, mid_motion: bool = True,
                   unrelaxed: list | None = None) -> np.ndarray:
    """Arrival / ruckig's optimum from the same state, one per case. ``unrelaxed``, if given,
    receives the same ratio against ruckig asked with vmax exactly (see RUCKIG_RELAX)."""
    ruckig = _optional.require("ruckig", "the comparison with ruckig")
    from ..trajectory import Generator
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n_cases:
        vmax = 10.0 ** rng.uniform(-1, 1)
        amax = vmax * 10.0 ** rng.uniform(-0.5, 1.5)
        jmax = amax * 10.0 ** rng.uniform(0, 2)
        first = rng.choice([-1, 1]) * vmax * 10.0 ** rng.uniform(-2, 0.5)
        T1 = _ruckig_duration(ruckig, 0, 0, 0, first, vmax, amax, jmax)
        Ts = T1 / 2000
        g = Generator(vmax=vmax, amax=amax, jmax=jmax, Ts=Ts)
        k = int(rng.uniform(0.05, 0.95) * T1 / Ts) if mid_motion else 0
        second = first + rng.normal() * abs(first) if mid_motion else first
        g.process(np.full(k, first))
        saved = g.get_state()              # the state at the switch sample k: one more
        q, v, a = g.process([first])[0, :3] if k else (0.0, 0.0, 0.0)   # step, then undo it
        g.set_state(saved)
        T2 = _ruckig_duration(ruckig, q, v, a, second, vmax, amax, jmax)
        n = int(4 * T2 / Ts) + 10
        y = g.process(np.full(n, second))
        at_rest = np.flatnonzero((y[:, 0] == second) & (y[:, 1] == 0) & (y[:, 2] == 0))
        if T2 <= 50 * Ts or at_rest.size == 0:
            continue
        # sample i of this block is i Ts after the switch (sample 0 is the switch itself,
        # which evaluates the state at the switch instant)
        out.append(at_rest[0] * Ts / T2)
        if unrelaxed is not None:
            unrelaxed.append(at_rest[0] * Ts /
                             _ruckig_duration(ruckig, q, v, a, second, vmax, amax, jmax, 0.0))
    return np.array(out)


def profile_prices(n_cases: int, seed: int = 3) -> dict[str, np.ndarray]:
    """Rest-to-rest arrival of the other profiles against their continuous optimum:

    - ``"trigonometric"``: arrival / the trigonometric kinematic design's duration (the
      shortest motion with half-cosine transitions; at most one sample over 1);
    - ``"mode"``: arrival / (ruckig's duration + the tuned stage), the generator's own
      promise (at most a sample or two over 1: the plan's rounding and the stage's taps);
    - ``"mode vs design"``: arrival / the continuous kinematic design with the same mode,
      which lets the tuned stage shape the jerk instead of adding it after the plan (the
      price of the online structure; polynomial profile, wn with Tm from 0.3 to 3 times
      amax/jmax)."""
    ruckig = _optional.require("ruckig", "the comparison with ruckig")
    from .. import design
    from ..trajectory import Generator
    rng = np.random.default_rng(seed)
    out = {"trigonometric": [], "mode": [], "mode vs design": []}
    for _ in range(n_cases):
        vmax = 10.0 ** rng.uniform(-1, 1)
        amax = vmax * 10.0 ** rng.uniform(-0.5, 1.5)
        jmax = amax * 10.0 ** rng.uniform(0, 2)
        h = vmax * (vmax / amax + amax / jmax) * 10.0 ** rng.uniform(-1.5, 1.5)
        lim = dict(vmax=vmax, amax=amax, jmax=jmax)
        T_trig = design.duration(design.kinematic(h=h, profile="trigonometric", **lim))
        wn = 2 * np.pi / (amax / jmax * 10.0 ** rng.uniform(-0.5, 0.5))
        T_design = design.duration(design.kinematic(h=h, wn=wn, **lim))
        T_ruckig = _ruckig_duration(ruckig, 0.0, 0.0, 0.0, h, vmax, amax, jmax)
        for key, profile, mode, T_ref in (
                ("trigonometric", "trigonometric", {}, T_trig),
                ("mode", "polynomial", dict(wn=wn), None)):
            Ts = min((T_ref or T_ruckig) / 500, 2 * np.pi / wn / 20)
            g = Generator(Ts=Ts, profile=profile, **mode, **lim)
            y = g.process(np.full(int(3 * (T_ref or T_design + T_ruckig) / Ts) + 10, h))
            # y[i] is i Ts after the step (sample 0 sees the new target)
            arrive = np.flatnonzero((y[:, 0] == h) & (y[:, 1] == 0))[0] * Ts
            if key == "trigonometric":
                out[key].append(arrive / T_trig)
            else:
                out[key].append(arrive / (T_ruckig + g.stage_duration))
                out["mode vs design"].append(arrive / T_design)
    return {k: np.array(v) for k, v in out.items()}


def ruckig_phase(delta, vmax, amax, jmax, samples: int = 201) -> tuple[float, float]:
    """ruckig's Synchronization.Phase rest-to-rest move by ``delta`` (one entry per axis):
    its duration [s] and its largest distance from the straight line over ``samples`` instants,
    relative to the largest displacement (0 when ruckig found a phase-synchronised move; when
    it did not, it falls back to a curved time-synchronised one)."""
    ruckig = _optional.require("ruckig", "the comparison with ruckig")
    d = np.asarray(delta, dtype=float)
    n = d.size
    inp = ruckig.InputParameter(n)
    inp.current_position = [0.0] * n
    inp.target_position = list(d)
    inp.max_velocity, inp.max_acceleration, inp.max_jerk = list(vmax), list(amax), list(jmax)
    inp.synchronization = ruckig.Synchronization.Phase
    traj = ruckig.Trajectory(n)
    ruckig.Ruckig(n).calculate(inp, traj)
    pos = np.array([traj.at_time(t)[0] for t in np.linspace(0, traj.duration, samples)])
    k = int(np.argmax(np.abs(d)))
    return traj.duration, float(np.abs(pos - np.outer(pos[:, k] / d[k], d)).max()
                                / np.abs(d).max())


def phase_comparison(n_cases: int, seed: int = 3) -> dict:
    """Rest-to-rest moves of 2 to 6 axes (limits over 4 orders of magnitude, displacements in
    [-10, 10]): our time-optimal straight duration T against ruckig's Synchronization.Phase.

    Returns arrays over the cases: ``T``, ``T_ruckig``, ``straight`` (ruckig's move stays on
    the line to 1e-9 of the move, sampled at 201 instants) and ``deviation`` (its largest
    distance from the line, relative to the largest displacement)."""
    from ..multi_axis import phase_duration
    rng = np.random.default_rng(seed)
    rows = []
    for _ in range(n_cases):
        n = int(rng.integers(2, 7))
        v = 10.0 ** rng.uniform(-2, 2, n)
        a = v * 10.0 ** rng.uniform(-2, 2, n)
        j = a * 10.0 ** rng.uniform(-2, 2, n)
        d = rng.uniform(-10, 10, n)
        rows.append((phase_duration(d, vmax=v, amax=a, jmax=j), *ruckig_phase(d, v, a, j)))
    T, T_r, dev = (np.array(c) for c in zip(*rows))
    return dict(T=T, T_ruckig=T_r, deviation=dev, straight=dev < 1e-9)


def _multi_replan_bench(quick: bool) -> str:
    """Compile and run tests/bench/multi_generator_bench.c; its printed table."""
    import subprocess
    import tempfile
    from .suite import ROOT, _compiler
    cc = _compiler()
    if cc is None:
        return "(multi-axis re-plan cost skipped: no C compiler)"
    with tempfile.TemporaryDirectory() as tmp:
        exe = f"{tmp}/multi_generator_bench"
        subprocess.run([cc, "-std=c99", "-O2", "-I", str(ROOT / "c" / "include"),
                        "-I", str(ROOT / "c" / "src"),
                        str(ROOT / "tests" / "bench" / "multi_generator_bench.c"),
                        *map(str, sorted((ROOT / "c" / "src").rglob("*.c"))), "-lm", "-o", exe],
                       check=True)
        return subprocess.run([exe] + (["--quick"] if quick else []), check=True,
                              capture_output=True, text=True).stdout.rstrip()


def design_call_costs(n_cases: int, rounds: int, seed: int = 11) -> dict:
    """CPU ns per three-bound kinematic design from Python, each call on a different random
    problem (h, limits over four decades), so no call repeats another's work. Variants:
    ``"continuous"``; ``"Ts"`` (1 ms for all, each problem first rescaled in time so that its
    duration is 10^U(0.5, 3.5) samples, as in the grid price); ``"mode"`` (continuous, the
    last stage tuned to a mode of zeta 0.05 whose period is 10^U(-0.5, 0.5) times
    amax/jmax). Each maps to ``"raw"`` (``sms_kinematic_design`` through cffi, the bounds
    written into a prepared cffi array per call, as a caller of the C API from Python does),
    ``"python"`` (``design.kinematic``), ``"batch"`` (``design.kinematic_lengths`` on
    all the problems at once, per problem) and ``"cases"``; an empty loop over the same cases
    is subtracted from the loops."""
    from .. import design
    from ..filters import _backend
    ffi, lib = _backend("double")
    rng = np.random.default_rng(seed)
    lim = 10.0 ** rng.uniform(-2, 2, (n_cases, 4)) * [1.0, 250.0, 5000.0, 2e5]
    cases = [tuple(map(float, row)) for row in lim]
    spans = [design.duration(design.kinematic(h=h, vmax=v, amax=a, jmax=j))
             for h, v, a, j in cases]
    # time scaled by c: (h, v/c, a/c^2, j/c^3) lasts c times as long
    scale = [10.0 ** rng.uniform(0.5, 3.5) * 1e-3 / T for T in spans]
    variants = {
        "continuous": [c + (0.0, 0.0) for c in cases],
        "Ts": [(h, v / c, a / c ** 2, j / c ** 3, 1e-3, 0.0)
               for (h, v, a, j), c in zip(cases, scale)],
        "mode": [(h, v, a, j, 0.0, float(2 * np.pi / (a / j * 10.0 ** rng.uniform(-0.5, 0.5))))
                 for h, v, a, j in cases]}
    L, T, count = ffi.new("double[3]"), ffi.new("double[6]"), ffi.new("size_t *")
    c_design, kinematic = lib.sms_kinematic_design, design.kinematic
    out = {}
    for name, rows in variants.items():
        zeta = 0.05 if name == "mode" else 0.0

        def empty():
            for h, v, a, j, ts, wn in rows:
                pass

        def raw():
            for h, v, a, j, ts, wn in rows:
                L[0] = v
                L[1] = a
                L[2] = j
                c_design(h, L, 3, 0, wn, zeta, ts, T, 3, count)

        def python():
            if name == "Ts":
                for h, v, a, j, ts, wn in rows:
                    kinematic(h=h, vmax=v, amax=a, jmax=j, Ts=ts)
            elif name == "mode":
                for h, v, a, j, ts, wn in rows:
                    kinematic(h=h, vmax=v, amax=a, jmax=j, wn=wn, zeta=0.05)
            else:
                for h, v, a, j, ts, wn in rows:
                    kinematic(h=h, vmax=v, amax=a, jmax=j)
        columns = np.array(rows).T

        def batch():
            design.kinematic_lengths(h=columns[0], vmax=columns[1], amax=columns[2],
                                     jmax=columns[3], Ts=1e-3 if name == "Ts" else None)
        loop = _cpu(empty, rounds)
        out[name] = {key: (_cpu(fn, rounds) - loop) / len(rows)
                     for key, fn in (("raw", raw), ("python", python))}
        # the batch takes one mode for all problems: timed without one
        out[name]["batch"] = _cpu(batch, rounds) / len(rows) if name != "mode" else None
        out[name]["cases"] = len(rows)
    return out


def _cpu(fn, rounds: int) -> float:
    times = []
    for _ in range(rounds):
        t0 = time.process_time_ns()
        fn()
        times.append(time.process_time_ns() - t0)
    return statistics.median(times)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m smoothshaper.bench.trajectory",
                                description=__doc__.split("\n\n")[0])
    p.add_argument("--quick", action="store_true", help="a few-second smoke run")
    args = p.parse_args(argv)
    n_cases = 40 if args.quick else 1000
    rounds = 2 if args.quick else 7
    n_samples = 10_000 if args.quick else 1_000_000

    from .. import design
    from ..trajectory import Generator

    try:
        import ruckig  # noqa: F401
        for label, mid in (("target changed mid-motion", True), ("rest to rest", False)):
            exact = []
            r = arrival_ratios(n_cases, mid_motion=mid, unrelaxed=exact)
            q = np.percentile(r, [50, 90, 99])
            print(f"arrival / ruckig's optimum, {label} ({r.size} cases, Ts = T/2000): "
                  f"min {r.min():.4f}  median {q[0]:.4f}  p90 {q[1]:.4f}  p99 {q[2]:.4f}  "
                  f"max {r.max():.4f}")
            slower = int(np.sum(np.array(exact) < r * (1 - 1e-6)))
            print(f"  ruckig with vmax exactly (not relaxed by {RUCKIG_RELAX:g}) was slower "
                  f"from {slower} of these states (braking velocity on vmax; smallest ratio "
                  f"against it {min(exact):.4f})")
        for key, r in profile_prices(n_cases // 4).items():
            q = np.percentile(r, [50, 99])
            print(f"rest to rest, {key}: arrival / optimum ({r.size} cases, Ts <= T/500): "
                  f"min {r.min():.4f}  median {q[0]:.4f}  p99 {q[1]:.4f}  max {r.max():.4f}")
    except ImportError:
        print("(arrival ratios skipped: ruckig is not installed; pip install 'smoothshaper[bench]')")

    x = np.concatenate([np.full(n_samples // 4, v) for v in (1.0, -2.0, 0.5, 3.0)])
    for precision in ("double", "float"):
        g = Generator(vmax=1, amax=10, jmax=100, Ts=1e-3, precision=precision)

        def run():
            g.reset()
            g.process(x)
        ns = _cpu(run, rounds) / x.size
        print(f"Generator.process, {precision}: {ns:.2f} ns/sample ({x.size} samples, one C call)")

    cost = design_call_costs(200 if args.quick else 5000, rounds)
    for key, label in (("continuous", "kinematic design (3 bounds)"), ("Ts", "  with Ts"),
                       ("mode", "  with a mode")):
        c = cost[key]
        batch = "" if c["batch"] is None else (
            f", design.kinematic_lengths {c['batch'] / 1e3:.3f} us per problem "
            f"({c['batch'] / c['raw']:.2f}x the raw call)")
        print(f"{label}: raw C call through cffi {c['raw'] / 1e3:.3f} us (bounds written into "
              f"a prepared array), design.kinematic {c['python'] / 1e3:.3f} us "
              f"({c['python'] / c['raw']:.2f}x the raw call){batch}; "
              f"{c['cases']} different random designs, loop overhead subtracted")
    from .suite import kinematic_parts
    f = kinematic_parts(3 if args.quick else 15, 200 if args.quick else 5000)
    print(f"  one design (h=1, vmax=0.5, amax=5, jmax=100): design.kinematic "
          f"{f['python'] / 1e3:.3f} us ({f['python'] / f['raw']:.2f}x the raw call with its "
          f"arrays prepared, {f['raw'] / 1e3:.3f} us) = the keyword call {f['call'] / 1e3:.3f} "
          f"us + the fast path (types, C design, three Stage objects) "
          f"{f['fastpath'] / 1e3:.3f} us")

    from .grid_price import report
    for n in range(1, 9):   # more cases and an adversarial search: bench.grid_price
        print(report(n, 200 if args.quick else 3000))

    try:
        c = phase_comparison(n_cases)
        st, fb = c["straight"], ~c["straight"]
        print(f"multi-axis rest to rest vs ruckig Synchronization.Phase ({st.size} moves, 2-6 "
              f"axes): ruckig straight in {st.sum()}, fell back to a curved time-synchronised "
              f"move in {fb.sum()}")
        if st.any():
            rel = np.abs(c["T_ruckig"][st] / c["T"][st] - 1)
            print(f"  straight: |T_ruckig / T_ours - 1| max {rel.max():.1e}")
        if fb.any():
            r, dev = c["T_ruckig"][fb] / c["T"][fb], c["deviation"][fb]
            print(f"  fallback: T_ruckig / T_ours min {r.min():.4f}  median {np.median(r):.4f}  "
                  f"max {r.max():.4f}; distance from the straight line / move: median "
                  f"{np.median(dev):.1e}  max {dev.max():.1e}")
    except ImportError:
        print("(multi-axis comparison skipped: ruckig is not installed; "
              "pip install 'smoothshaper[bench]')")
    print(_multi_replan_bench(args.quick))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
