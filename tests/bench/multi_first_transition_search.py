# SPDX-License-Identifier: Apache-2.0
"""Adversarial search for the multi-axis generator's first transition (docs/multi-axis.md, "What
is guaranteed at the samples"): how far above amax_i and jmax_i can the planned first
transition of a move from a cruise go, in units of u (the unit roundoff of the build)?

A move starts from (p, V) with zero acceleration (a blend during a cruise). The search puts the
C generator (through the Python binding) into a cruise at any V by a crafted saved state and
plans from there, then reads the plan (V, W, T1, rho1) from the saved state and computes the
peaks of its first transition, |W_i - V_i| / ((1 - rho1) T1) and |W_i - V_i| / (rho1 (1 - rho1)
T1^2), in extended precision; the limits as the build holds them.

Two families, each searched by scipy.optimize.differential_evolution and by random draws, for
2 to 4 axes (and 1), in float and double:

- "free": log-uniform limits per axis (amax/vmax over 1e-2..1e2, jmax/amax over 1e-1..1e4),
  start velocities within the limits, targets within +-4 times each axis's distance to reach
  vmax, Ts from 1e-8 to 10 times the move to vmax (the arrival rounded up onto the grid
  lowers the peaks by about Ts over the move);
- "snap": the arrival rounded onto an earlier sample (a planned end within 2 eps after a
  sample, multi_generator.c GRID_TOL), where the raised cruise velocity raises the first
  transition most: a cruise velocity W with one axis at vmax, the start V, the cruise a few eps
  of the move, and Ts chosen so that the planned end lies just after a sample.

usage: python tests/bench/multi_first_transition_search.py [--quick] [--seed N] [--maxiter N]
[--draws N] (about 40 s on this 2-core machine, --quick 5 s; prints the worst case of each
family, precision and number of axes). Runs on the installed or in-place smoothshaper; needs
scipy. tests/python/test_multi_axis.py draws the snap family with hypothesis.
"""
from __future__ import annotations

import argparse
import math
import time

import numpy as np

from smoothshaper.multi_axis import MultiAxisGenerator

UNIT = {"double": 2.0 ** -53, "float": 2.0 ** -24}
REAL = {"double": np.float64, "float": np.float32}
MOVE_FIELDS = 12


class Planner:
    """One generator (limits, Ts, precision); plan(V0, target) plans from a cruise at V0."""

    def __init__(self, vmax, amax, jmax, Ts, precision):
        self.g = MultiAxisGenerator(vmax=vmax, amax=amax, jmax=jmax, Ts=Ts, precision=precision)
        self.precision = precision
        self.R = REAL[precision]
        self.n = self.g.axes
        self.identity = int(self.g._lib.SMS_MULTI_IDENTITY_COUNT)
        self.blank = self.g.get_state()
        R = self.R
        self.limits = [np.asarray(x, dtype=R).astype(np.longdouble)
                       for x in (self.g.vmax, self.g.amax, self.g.jmax)]

    def plan(self, V0, target):
        """The move planned from a cruise at V0 (p = 0 at the blend) towards target: dict of
        V, W, T1, rho1, tau, T2, k_end (as sms_real holds them) and its first sample (axes,
        4: q, v, a, j at the start of the first jerk phase), or None if refused."""
        n, a, R = self.n, self.identity, self.R
        V0 = np.asarray(V0, dtype=R).astype(float)
        Ts = float(R(self.g.Ts))
        p0 = -(V0.astype(R) * R(Ts)).astype(float)   # the blend adds V0 Ts: p = 0 exactly
        s = self.blank.copy()
        s[a:a + n] = target
        s[a + n:a + 2 * n] = p0                      # goal: differs from the target
        s[a + 2 * n:a + 3 * n] = p0
        s[a + 3 * n:a + 4 * n] = V0
        s[a + 4 * n:a + 5 * n] = V0
        m = a + 5 * n
        # a cruise at V0 (T1 = 0, long tau, no stop yet): the next sample blends from it
        s[m:m + MOVE_FIELDS] = [0.0, 0.5, 1e9, 0.0, 0.5, 0.0, 0.0, 0, 2 ** 50, 1, 0, 0]
        try:
            self.g.set_state(s)
        except ValueError:
            return None
        first = self.g.process(np.asarray(target, dtype=float)[None, :])[0]
        s = self.g.get_state()
        T1, rho1, tau, T2, rho2, off, seen, k, k_end, active = s[m:m + 10]
        if not active:
            return None
        return dict(V=s[a + 3 * n:a + 4 * n], W=s[a + 4 * n:a + 5 * n], T1=T1, rho1=rho1,
                    tau=tau, T2=T2, k_end=k_end, first=first)

    def peaks(self, f):
        """(v, a, j) of the planned first transition: the largest ratio to the limit, minus 1,
        in u (extended precision)."""
        L = np.longdouble
        vmax, amax, jmax = self.limits
        V, W = f["V"].astype(L), f["W"].astype(L)
        T1, r = L(f["T1"]), L(f["rho1"])
        if not T1 > 0:
            return (-math.inf,) * 3
        d = np.abs(W - V)
        u = UNIT[self.precision]
        v = np.max(np.maximum(np.abs(V), np.abs(W)) / vmax)
        a = np.max(d / ((1 - r) * T1) / amax)
        j = np.max(d / (r * (1 - r) * T1 * T1) / jmax)
        return tuple(float((x - 1) / L(u)) for x in (v, a, j))


def reach(vmax, amax, jmax):
    """Duration and distance of each axis's move from rest to vmax and back."""
    ap = np.minimum(amax, np.sqrt(vmax * jmax))
    T = 2 * (vmax / ap + ap / jmax)
    return T, vmax * T / 2


def limits_of(x, n):
    """Per-axis limits from the search vector: vmax 1e-1..1e1, amax/vmax 1e-2..1e2,
    jmax/amax 1e-1..1e4 (log10 in x)."""
    vmax = 10.0 ** x[0:n]
    amax = vmax * 10.0 ** x[n:2 * n]
    jmax = amax * 10.0 ** x[2 * n:3 * n]
    return vmax, amax, jmax


def free_bounds(n):
    return ([(-1, 1)] * n + [(-2, 2)] * n + [(-1, 4)] * n + [(-1, 1)] * n + [(-4, 4)] * n
            + [(-8, 1)])


def free_case(x, n, precision):
    """(planner, V0, target) of a free search vector."""
    vmax, amax, jmax = limits_of(x, n)
    V0 = x[3 * n:4 * n] * vmax
    T, h = reach(vmax, amax, jmax)
    target = x[4 * n:5 * n] * h
    Ts = 10.0 ** x[5 * n] * float(np.max(T))
    return Planner(vmax, amax, jmax, Ts, precision), V0, target


def snap_bounds(n):
    # limits; V0/vmax; W direction (the largest |W_i|/vmax_i becomes 1); cruise as a multiple
    # of eps of kappa (log2); samples N (log10); where the end lies in the 2 eps window
    return ([(-1, 1)] * n + [(-2, 2)] * n + [(-1, 4)] * n + [(-1, 1)] * n + [(-1, 1)] * n
            + [(-2, 4), (2, 6), (-1, 1)])


def snap_case(x, n, precision):
    """snap_case_of() with degenerate vectors (overflowing or vanishing ratios) giving None."""
    with np.errstate(all="ignore"):
        case = snap_case_of(x, n, precision)
    if case is None or not (math.isfinite(case[0].g.Ts) and np.all(np.isfinite(case[2]))):
        return None
    return case


def snap_case_of(x, n, precision):
    """(planner, V0, target) of a snap search vector, or None: the target of the move from V0
    whose candidate cruises at W for tau, and Ts that puts its planned end `where` of the way
    into the window of 2 eps after sample N (where < 0: that far before it, rounded up)."""
    R = REAL[precision]
    eps = R(2 * UNIT[precision])
    vmax, amax, jmax = limits_of(x, n)
    V0 = x[3 * n:4 * n] * vmax
    w = x[4 * n:5 * n]
    if not np.max(np.abs(w)) > 0:
        return None
    W = w / np.max(np.abs(w) / vmax)
    probe = Planner(vmax, amax, jmax, 1e-3, precision)

    def T_of(d):   # the shortest transition of the change d (phase-synchronised)
        d = np.abs(d)
        if not np.any(d > 0):
            return 0.0
        A = np.min(amax[d > 0] / d[d > 0])
        J = np.min(jmax[d > 0] / d[d > 0])
        return 1 / A + A / J if A * A <= J else 2 / math.sqrt(J)
    T1, T2 = max(T_of(V0), T_of(W - V0)), T_of(W)   # the candidate's, about
    kappa0 = T1 / 2 + T2 / 2
    tau = float(2.0 ** x[5 * n]) * float(eps) * kappa0
    target = V0 * T1 / 2 + W * (kappa0 + tau)
    f = probe.plan(V0, target)
    if f is None:
        return None
    # the candidate's total as the C planner forms it (kappa = kv: the move cruises at vmax)
    T1r, T2r = R(f["T1"]), R(f["T2"])
    Vr = np.asarray(V0, dtype=R)
    u = np.asarray(target, dtype=R) - Vr * (T1r / R(2))
    kv = np.max(np.abs(u) / vmax.astype(R))
    tau_c = kv - T1r / R(2) - T2r / R(2)
    if not tau_c > 0:
        return None
    total = (T1r + tau_c) + T2r
    N = round(10.0 ** x[5 * n + 1])
    Ts = float(total) / (N * (1 + x[5 * n + 2] * 2 * float(eps)))
    return Planner(vmax, amax, jmax, Ts, precision), V0, target


FAMILIES = {"free": (free_bounds, free_case), "snap": (snap_bounds, snap_case)}


def search(family, n, precision, seed, maxiter, draws):
    """The worst case (dict: score = max of the a and j peaks in u, v, a, j, x, the plan)
    of `draws` random vectors and a differential evolution of `maxiter` generations."""
    from scipy.optimize import differential_evolution
    bounds_of, case_of = FAMILIES[family]
    bounds = bounds_of(n)
    best = {"score": -math.inf}

    def score(x):
        try:
            case = case_of(np.asarray(x), n, precision)
        except ValueError:           # limits the generator refuses (ParameterError)
            return 1e9
        if case is None:
            return 1e9
        planner, V0, target = case
        f = planner.plan(V0, target)
        if f is None:
            return 1e9
        v, a, j = planner.peaks(f)
        worst = max(a, j)
        if worst > best["score"]:
            best.update(score=worst, v=v, a=a, j=j, x=np.array(x), T1=f["T1"],
                        rho1=f["rho1"], tau=f["tau"], k_end=f["k_end"], Ts=planner.g.Ts)
        return -worst

    rng = np.random.default_rng(seed)
    lo, hi = np.array(bounds).T
    for _ in range(draws):
        score(lo + (hi - lo) * rng.random(lo.size))
    differential_evolution(score, bounds, seed=seed, maxiter=maxiter, popsize=12, tol=0,
                           polish=False, init="sobol")
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="fewer evaluations (about a minute)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--maxiter", type=int, default=40, help="generations of each search")
    ap.add_argument("--draws", type=int, default=2000, help="random vectors before each search")
    args = ap.parse_args()
    maxiter, draws = (4, 200) if args.quick else (args.maxiter, args.draws)
    print(f"{'family':6} {'precision':9} {'axes':>4} {'v [u]':>8} {'a [u]':>8} {'j [u]':>8}"
          f"  {'s':>5}  worst case (T1, rho1, tau, k_end, Ts)")
    overall = -math.inf
    for precision in ("double", "float"):
        for family in ("free", "snap"):
            for n in (1, 2, 3, 4):
                t0 = time.perf_counter()
                b = search(family, n, precision, args.seed + n, maxiter, draws)
                overall = max(overall, b["score"])
                print(f"{family:6} {precision:9} {n:4d} {b.get('v', math.nan):8.2f} "
                      f"{b.get('a', math.nan):8.2f} {b.get('j', math.nan):8.2f}  "
                      f"{time.perf_counter() - t0:5.0f}  T1={b.get('T1', math.nan):.6g} "
                      f"rho1={b.get('rho1', math.nan):.4g} tau={b.get('tau', math.nan):.3g} "
                      f"k_end={b.get('k_end', math.nan):.0f} Ts={b.get('Ts', math.nan):.6g}",
                      flush=True)
    print(f"worst first-transition peak over all: {overall:.2f} u above the limit")


if __name__ == "__main__":
    main()
