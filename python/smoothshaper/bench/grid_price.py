# SPDX-License-Identifier: Apache-2.0
"""What designing a kinematic chain on the sample grid costs: the grid duration minus the
continuous optimum, in samples, per number of bounds (docs/sampled-limits.md).

``python -m smoothshaper.bench.grid_price [--cases N] [--adversarial K] [--bounds 1 .. 8]
[--profile polynomial|trigonometric] [--mode RATIO] [--cost M [--cost-mode-range LOW HIGH]]``
draws N random problems per bound count (h
and every bound over six orders of magnitude, the i-th bound scaled by 10^i so every stage
matters, Ts from 1/3 to 1/3000 of the move), designs each continuously and on the grid (the C
design, ``sms_kinematic_design``, of the profile), and prints mean, 99th percentile and
largest price, split by whether every continuous stage lasts at least one sample; with
``--mode`` the last stage is tuned to a mode (see ``_designer``). With K > 0
it then walks K random steps (in the logarithms of h, the bounds and Ts) from the worst
problem of each class, keeping a step when the price grows: an adversarial search near the
worst seen. With ``--cost M`` it also prints what the grid design costs per bound count: CPU
time of ``sms_kinematic_design`` with Ts on M of these problems, each timed in one C loop of
20 repeats (``sms_kinematic_design_batch``, stride 0; best of three), so the binding's call is
not counted (with ``--mode``, the tuned designs); with K > 0 also the slowest design that K
such steps from the slowest drawn find. Nothing asserts; the figures are for reading.
"""
from __future__ import annotations

import argparse
import time

import numpy as np

from ..filters import _backend

__all__ = ["grid_price", "grid_prices", "grid_design_costs", "main"]


def _designer(profile: int = 0, mode_ratio: float | None = None):
    """sms_kinematic_design of (h, bounds, Ts) with `profile` (0 polynomial, 1 trigonometric).
    With `mode_ratio`, the last stage is tuned to a mode of damping ratio 0.05 whose period is
    mode_ratio times that stage's continuous length without a mode (the design picks the
    multiple k); on the grid that stage counts with its taps (L Ts, one to two samples over
    k Tm), not its length."""
    ffi, lib = _backend("double")
    L, T, cnt = ffi.new("double[8]"), ffi.new("double[8]"), ffi.new("size_t *")
    configs, taps = ffi.new("sms_stage_config[8]"), ffi.new("size_t *")

    def design(h, lim, Ts):
        n = len(lim)
        for i, v in enumerate(lim):
            L[i] = v
        wn = zeta = 0.0
        if mode_ratio is not None:
            if lib.sms_kinematic_design(h, L, n, profile, 0.0, 0.0, 0.0, T, n, cnt) != 0:
                return None
            wn, zeta = 2.0 * np.pi / (mode_ratio * T[n - 1]), 0.05
            if Ts > 0.0:
                # the tuned stage keeps its length k Tm; what the chain takes is its taps
                if lib.sms_kinematic_configs(h, L, n, profile, wn, zeta, Ts, configs, n,
                                             cnt) != 0:
                    return None
                if lib.sms_smoother_length(configs + (n - 1), Ts, taps) != 0:
                    return None
                return [configs[i].T for i in range(n - 1)] + [taps[0] * Ts]
        if lib.sms_kinematic_design(h, L, n, profile, wn, zeta, Ts, T, n, cnt) != 0:
            return None
        return [T[i] for i in range(n)]
    return design


def grid_price(h: float, lim, Ts: float, design=None):
    """(price in samples, every continuous stage >= Ts) of one problem, or None if refused."""
    design = design or _designer()
    cont, grid = design(h, lim, 0.0), design(h, lim, Ts)
    if cont is None or grid is None:
        return None
    return (sum(grid) - sum(cont)) / Ts, min(cont) >= Ts


def _draw(n: int, rng, design):
    """One random problem (h, n bounds, Ts), or None when the continuous design refuses it:
    h and every bound over six orders of magnitude, the i-th bound scaled by 10^i, Ts from 1/3
    to 1/3000 of the continuous duration."""
    h = 10.0 ** rng.uniform(-3, 3)
    lim = [10.0 ** rng.uniform(-3, 3) * 10.0 ** i for i in range(n)]
    cont = design(h, lim, 0.0)
    if cont is None:
        return None
    return h, lim, sum(cont) / 10.0 ** rng.uniform(0.5, 3.5)


def grid_prices(n: int, cases: int, seed: int = 5, adversarial: int = 0,
                profile: int = 0, mode_ratio: float | None = None) -> dict:
    """Prices of `cases` random problems with n bounds: {True: array, False: array} (True:
    every continuous stage lasts at least a sample) and the worst problem of each class
    (after `adversarial` steps of the local search) as {key: (price, h, limits, Ts)}.
    `profile`: 0 polynomial, 1 trigonometric (a harmonic last stage); `mode_ratio`: see
    :func:`_designer`."""
    rng = np.random.default_rng(seed)
    design = _designer(profile, mode_ratio)
    prices = {True: [], False: []}
    worst = {}
    for _ in range(cases):
        problem = _draw(n, rng, design)
        if problem is None:
            continue
        h, lim, Ts = problem
        r = grid_price(h, lim, Ts, design)
        if r is None:
            continue
        prices[r[1]].append(r[0])
        if r[0] > worst.get(r[1], (-np.inf,))[0]:
            worst[r[1]] = (r[0], h, lim, Ts)
    for key in list(worst):
        p, h, lim, Ts = worst[key]
        x = np.log10([h, *lim, Ts])
        for step in range(adversarial):
            scale = 0.3 if step % 2 else 0.01
            y = x + rng.normal(0.0, scale, x.size)
            r = grid_price(10.0 ** y[0], list(10.0 ** y[1:-1]), 10.0 ** y[-1], design)
            if r is not None and r[1] == key and r[0] > p:
                p, x = r[0], y
        worst[key] = (p, 10.0 ** x[0], list(10.0 ** x[1:-1]), 10.0 ** x[-1])
    return {True: np.array(prices[True]), False: np.array(prices[False]), "worst": worst}


def _timer(n: int, profile: int, repeats: int, mode_ratio=None, seed: int = 5):
    """CPU ns of one grid design of (h, bounds, Ts): `repeats` designs in one C loop (the batch
    call with stride 0), best of three loops, divided by `repeats`, whether the design
    succeeds or is refused. With `mode_ratio`, the last stage tuned to a mode as in
    :func:`_designer` (None when the design without the mode is refused); a pair (low, high)
    draws the ratio per problem, log-uniformly."""
    ffi, lib = _backend("double")
    rng = np.random.default_rng(seed)
    H, L = ffi.new("double[1]"), ffi.new("double[8]")
    T, index = ffi.new("double[]", 8 * repeats), ffi.new("size_t *")
    cnt = ffi.new("size_t *")

    def time_one(h, lim, Ts):
        H[0] = h
        for i, v in enumerate(lim):
            L[i] = v
        wn = zeta = 0.0
        if mode_ratio is not None:
            if lib.sms_kinematic_design(h, L, n, profile, 0.0, 0.0, 0.0, T, n, cnt) != 0:
                return None
            ratio = (10.0 ** rng.uniform(*np.log10(mode_ratio)) if isinstance(mode_ratio, tuple)
                     else mode_ratio)
            wn, zeta = 2.0 * np.pi / (ratio * T[n - 1]), 0.05
        best = np.inf
        for _ in range(3):
            t0 = time.process_time_ns()
            st = lib.sms_kinematic_design_batch(repeats, H, 0, L, 0, n, profile, wn, zeta, Ts, T,
                                                8 * repeats, index)
            best = min(best, time.process_time_ns() - t0)
        del st   # a refusal is timed too
        return best / repeats
    return time_one


def grid_design_costs(n: int, cases: int, seed: int = 5, repeats: int = 20,
                      profile: int = 0, adversarial: int = 0, mode_ratio: float | None = None):
    """CPU ns of one grid design (``sms_kinematic_design`` with Ts) for `cases` random problems
    with n bounds, drawn as in :func:`grid_prices`, each timed by :func:`_timer`. With
    `adversarial` > 0 also the slowest design found by that many random steps from the
    slowest problem drawn (kept when slower, as the price search does). Returns (array of
    ns, slowest ns after the steps). `profile`: 0 polynomial, 1 trigonometric; `mode_ratio`:
    the last stage tuned to a mode (:func:`_designer`). A refused design is timed as well:
    the caller waits for its status."""
    rng = np.random.default_rng(seed)
    design = _designer(profile)
    time_one = _timer(n, profile, repeats, mode_ratio, seed)
    out, slowest = [], (-np.inf, None)
    while len(out) < cases:
        problem = _draw(n, rng, design)
        if problem is None:
            continue
        ns = time_one(*problem)
        if ns is not None:
            out.append(ns)
            if ns > slowest[0]:
                slowest = (ns, problem)
    if slowest[1] is not None and adversarial:
        worst, (h, lim, Ts) = slowest
        x = np.log10([h, *lim, Ts])
        for step in range(adversarial):
            y = x + rng.normal(0.0, 0.3 if step % 2 else 0.01, x.size)
            ns = time_one(10.0 ** y[0], list(10.0 ** y[1:-1]), 10.0 ** y[-1])
            if ns is not None and ns > worst:
                worst, x = ns, y
        slowest = (worst, None)
    return np.array(out), slowest[0]


def report(n: int, cases: int, adversarial: int = 0, seed: int = 5, profile: int = 0,
           mode_ratio: float | None = None) -> str:
    """One line per bound count, as the benchmark prints it."""
    res = grid_prices(n, cases, seed, adversarial, profile, mode_ratio)
    parts = []
    for key, label in ((True, "every stage >= Ts"), (False, "a stage < Ts")):
        pr = res[key]
        if pr.size:
            part = (f"{label} ({pr.size}): mean {pr.mean():.2f}  p99 "
                    f"{np.percentile(pr, 99):.2f}  max {pr.max():.2f}")
            if adversarial and key in res["worst"]:
                part += f"  adversarial {res['worst'][key][0]:.2f}"
            parts.append(part)
    name = " (trigonometric)" if profile else ""
    if mode_ratio is not None:
        name += f" (last stage tuned to a mode of period {mode_ratio:g} times its length)"
    return f"grid price in samples{name}, {n} bound(s): " + "; ".join(parts)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m smoothshaper.bench.grid_price",
                                description=__doc__.split("\n\n")[0])
    p.add_argument("--cases", type=int, default=3000, help="random problems per bound count")
    p.add_argument("--adversarial", type=int, default=0,
                   help="local-search steps from the worst problem of each class (with --cost "
                        "also from the slowest design)")
    p.add_argument("--bounds", type=int, nargs="*", default=list(range(1, 9)))
    p.add_argument("--seed", type=int, default=5)
    p.add_argument("--profile", choices=("polynomial", "trigonometric"), default="polynomial",
                   help="the design's profile")
    p.add_argument("--mode", type=float, default=None, metavar="RATIO",
                   help="tune the last stage to a mode (zeta 0.05) whose period is RATIO times "
                        "that stage's length without a mode")
    p.add_argument("--cost", type=int, default=0, metavar="M",
                   help="also time the grid design on M problems per bound count")
    p.add_argument("--cost-mode-range", type=float, nargs=2, default=None,
                   metavar=("LOW", "HIGH"),
                   help="with --cost: tune each timed design to a mode whose period is a "
                        "log-uniform random LOW..HIGH times the last stage (instead of --mode)")
    args = p.parse_args(argv)
    profile = int(args.profile == "trigonometric")
    for n in args.bounds if args.cases else ():
        print(report(n, args.cases, args.adversarial, args.seed, profile, args.mode), flush=True)
    for n in args.bounds if args.cost else ():
        mode = tuple(args.cost_mode_range) if args.cost_mode_range else args.mode
        ns, slowest = grid_design_costs(n, args.cost, args.seed, profile=profile,
                                        adversarial=args.adversarial, mode_ratio=mode)
        us = ns / 1e3
        name = " (trigonometric)" if profile else ""
        if isinstance(mode, tuple):
            name += (f" (tuned to a mode of period {mode[0]:g} to {mode[1]:g} times the last "
                     "stage)")
        elif mode is not None:
            name += f" (tuned to a mode of period {mode:g} times the last stage)"
        extra = f"  adversarial {slowest / 1e3:.2f} us" if args.adversarial else ""
        print(f"grid design cost{name}, {n} bound(s) ({us.size} problems, CPU time in C): median "
              f"{np.median(us):.2f} us  p99 {np.percentile(us, 99):.2f} us  max {us.max():.2f} us"
              + extra, flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
