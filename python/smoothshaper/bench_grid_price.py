"""What designing a kinematic chain on the sample grid costs: the grid duration minus the
continuous optimum, in samples, per number of bounds (docs/sampled-limits.md).

``python -m smoothshaper.bench_grid_price [--cases N] [--adversarial K] [--bounds 1 .. 8]``
draws N random problems per bound count (h and every bound over six orders of magnitude, the
i-th bound scaled by 10^i so every stage matters, Ts from 1/3 to 1/3000 of the move), designs
each continuously and on the grid (the C design, ``sms_kinematic_design``), and prints mean,
99th percentile and largest price, split by whether every continuous stage lasts at least one
sample. With K > 0 it then walks K random steps (in the logarithms of h, the bounds and Ts)
from the worst problem of each class, keeping a step when the price grows: an adversarial
search near the worst seen. Nothing asserts; the figures are for reading.
"""
from __future__ import annotations

import argparse

import numpy as np

from .filters import _backend

__all__ = ["grid_price", "grid_prices", "main"]


def _designer():
    ffi, lib = _backend("double")
    L, T, cnt = ffi.new("double[8]"), ffi.new("double[8]"), ffi.new("size_t *")

    def design(h, lim, Ts):
        n = len(lim)
        for i, v in enumerate(lim):
            L[i] = v
        if lib.sms_kinematic_design(h, L, n, 0, 0.0, 0.0, Ts, T, n, cnt) != 0:
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


def grid_prices(n: int, cases: int, seed: int = 5, adversarial: int = 0) -> dict:
    """Prices of `cases` random problems with n bounds: {True: array, False: array} (True:
    every continuous stage lasts at least a sample) and the worst problem of each class
    (after `adversarial` steps of the local search) as {key: (price, h, limits, Ts)}."""
    rng = np.random.default_rng(seed)
    design = _designer()
    prices = {True: [], False: []}
    worst = {}
    for _ in range(cases):
        h = 10.0 ** rng.uniform(-3, 3)
        lim = [10.0 ** rng.uniform(-3, 3) * 10.0 ** i for i in range(n)]
        cont = design(h, lim, 0.0)
        if cont is None:
            continue
        Ts = sum(cont) / 10.0 ** rng.uniform(0.5, 3.5)
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


def report(n: int, cases: int, adversarial: int = 0, seed: int = 5) -> str:
    """One line per bound count, as the benchmark prints it."""
    res = grid_prices(n, cases, seed, adversarial)
    parts = []
    for key, label in ((True, "every stage >= Ts"), (False, "a stage < Ts")):
        pr = res[key]
        if pr.size:
            part = (f"{label} ({pr.size}): mean {pr.mean():.2f}  p99 "
                    f"{np.percentile(pr, 99):.2f}  max {pr.max():.2f}")
            if adversarial and key in res["worst"]:
                part += f"  adversarial {res['worst'][key][0]:.2f}"
            parts.append(part)
    return f"grid price in samples, {n} bound(s): " + "; ".join(parts)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m smoothshaper.bench_grid_price",
                                description=__doc__.split("\n\n")[0])
    p.add_argument("--cases", type=int, default=3000, help="random problems per bound count")
    p.add_argument("--adversarial", type=int, default=0,
                   help="local-search steps from the worst problem of each class")
    p.add_argument("--bounds", type=int, nargs="*", default=list(range(1, 9)))
    p.add_argument("--seed", type=int, default=5)
    args = p.parse_args(argv)
    for n in args.bounds:
        print(report(n, args.cases, args.adversarial, args.seed), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
