# SPDX-License-Identifier: Apache-2.0
"""The multi-axis generator's position limits (``qmin``, ``qmax`` per axis) on random cases,
in every sync mode, against ruckig where ruckig is comparable.

Per case 1 to 4 axes, each with its own limits (four decades of ratios), start state
(q, v, a) inside its position limits and a target at rest inside them; the limits are drawn
so that about half the time-optimal motions would cross one (an overshoot of the target or a
start velocity towards a near limit). Per-axis modes (``time``, ``time_if_necessary``,
``none``) start there (:meth:`MultiAxisGenerator.start`); ``phase`` and ``independent`` start
at rest at q and get a second target mid-motion (the case where they would blend). Then the
generator runs past the arrival. Reported per mode: the largest distance of any sample outside
[qmin, qmax] (the promise: 0, exactly), the worst reported |v|/vmax, |a|/amax, |j|/jmax,
the worst backward difference of any axis's sampled position over its bound after the
rounding floor of docs/sampled-limits.md, the axes not resting exactly on their targets at
the end, the start states refused (``SMS_ERR_POSITION_LIMIT``: neither the motion to the
target nor the brake stays inside).

Per-axis modes: the same start without limits is run too; where its plans stay inside
(``direct``), the limited generator must give them bit for bit. Where they cross, the limited
axis brakes, rests and moves, which is not time-optimal under the limits (a motion that turns
before it rests is shorter): those cases are counted apart with their excess over ruckig's
rounded duration (``longer``), not held to the one-sample promise.

ruckig (the pip package, 0.19.4) takes ``min_position`` / ``max_position`` but does not hold
them: it returns the unconstrained trajectory (from rest-free states it crosses them; e.g. from
q = 0, v = 1 to 0 with vmax = amax = jmax = 1 and max_position = 0.3 its trajectory peaks at
0.95 and reports Working). So the durations are compared only on the cases whose ruckig
trajectory stays inside (its ``position_extrema``): there ruckig's motion is time-optimal under
the limits too, and a direct arrival must be at most its duration rounded up to the grid plus
one sample (``over``); the cases where ruckig crosses are counted (``ruckig_crosses``), not
compared.

``python -m smoothshaper.bench.multi_position [--cases N] [--precision double|float]`` prints
the table; tests/python/test_multi_axis_position.py asserts it on fixed-seed draws.
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import ParameterError
from .targets import UNIT_ROUNDOFF, _state, campaign_main, limit_cells, over_shares, tally_limits

__all__ = ["MODES", "draw_case", "run_case", "campaign", "main"]

MODES = ("time", "time_if_necessary", "none", "phase", "independent")


def draw_case(rng, mode: str) -> dict:
    """A random case: per axis limits, position limits, start state and target."""
    n = int(rng.integers(1, 5))
    moving = mode not in ("phase", "independent")
    axes = []
    for _ in range(n):
        V = 10.0 ** rng.uniform(-1, 1)
        A = V * 10.0 ** rng.uniform(-1, 2)
        J = A * 10.0 ** rng.uniform(-1, 2)
        v0, a0 = _state(rng, V, A, J, False) if moving and rng.random() < 0.85 else (0.0, 0.0)
        scale = V * (V / A + A / J)
        q0 = rng.uniform(-1, 1) * scale
        pf = q0 + rng.uniform(-3, 3) * scale * 10.0 ** rng.uniform(-2, 1)
        second = q0 + rng.uniform(-3, 3) * scale * 10.0 ** rng.uniform(-2, 1)
        lo = min(q0, pf, second) - scale * 10.0 ** rng.uniform(-3, 1)
        hi = max(q0, pf, second) + scale * 10.0 ** rng.uniform(-3, 1)
        axes.append(dict(vmax=V, amax=A, jmax=J, q0=q0, v0=v0, a0=a0, position=pf,
                         velocity=0.0, acceleration=0.0, second=second, qmin=lo, qmax=hi))
    return dict(mode=mode, per_axis=None, axes=axes, log_samples=rng.uniform(1, 3.3),
                switch=rng.uniform(0.1, 0.9), unlimited=int(rng.integers(0, n)) if n > 1
                and rng.random() < 0.3 else None)


def _field(case, name):
    return [ax[name] for ax in case["axes"]]


def ruckig_motion(case, Ts=None):
    """ruckig's (duration, inside) for the case's first target from its start state
    (continuous, or discrete with Ts), None when it errs; inside: its position extrema within
    every limited axis's [qmin, qmax]."""
    from .multi_sync import ruckig_trajectory
    traj = ruckig_trajectory(case, Ts)
    if traj is None:
        return None
    inside = all(case["unlimited"] == i or
                 (e.min >= ax["qmin"] and e.max <= ax["qmax"])
                 for i, (e, ax) in enumerate(zip(traj.position_extrema, case["axes"])))
    return traj.duration, inside


def _limits(case):
    qmin = [None if case["unlimited"] == i else ax["qmin"] for i, ax in enumerate(case["axes"])]
    qmax = [None if case["unlimited"] == i else ax["qmax"] for i, ax in enumerate(case["axes"])]
    return qmin, qmax


def run_case(case: dict, *, precision: str = "double") -> dict:
    """Run the case through the C generator, Ts drawn from the case's duration (10 to 2000
    samples of ruckig's)."""
    from ..multi_axis import MultiAxisGenerator
    rk = ruckig_motion(case)
    if rk is None or not rk[0] > 0:
        return dict(ruckig=None)
    T, inside = rk
    Ts = T / 10.0 ** case["log_samples"]
    qmin, qmax = _limits(case)
    per_axis = case["mode"] not in ("phase", "independent")
    g = MultiAxisGenerator(vmax=_field(case, "vmax"), amax=_field(case, "amax"),
                           jmax=_field(case, "jmax"), Ts=Ts, sync=case["mode"],
                           precision=precision, qmin=qmin, qmax=qmax,
                           q0=None if per_axis else _field(case, "q0"))
    target = np.array(_field(case, "position"))
    direct = None
    if per_axis:
        try:
            g.start(_field(case, "q0"), _field(case, "v0"), _field(case, "a0"),
                    positions=target)
        except ParameterError as e:
            if e.status != g._lib.SMS_ERR_POSITION_LIMIT:
                raise
            return dict(ruckig=T, refused=True)
        free = MultiAxisGenerator(vmax=_field(case, "vmax"), amax=_field(case, "amax"),
                                  jmax=_field(case, "jmax"), Ts=Ts, sync=case["mode"],
                                  precision=precision)
        free.start(_field(case, "q0"), _field(case, "v0"), _field(case, "a0"),
                   positions=target)
        arrive = g.arrival
        n = max(arrive, free.arrival) + 8
        out = g.process_targets(np.tile(target, (n, 1)))
        final = target
        # the plans without limits: where they stay inside, the limited generator runs them
        # bit for bit (its direct plans); else it brakes, rests and moves (longer)
        unlimited = free.process_targets(np.tile(target, (n, 1)))
        direct = all(qmin[i] is None or (np.all(unlimited[:, i, 0] >= real_lo)
                                         and np.all(unlimited[:, i, 0] <= real_hi))
                     for i, (real_lo, real_hi) in enumerate(zip(
                         [x if x is None else _real(x, precision) for x in qmin],
                         [x if x is None else _real(x, precision) for x in qmax])))
        same = bool(np.array_equal(out, unlimited))
    else:
        arrive = None
        first = max(1, int(case["switch"] * T / Ts))
        final = np.array(_field(case, "second"))
        n = 4 * int(math.ceil(T / Ts)) + 8 * first + 64
        rows = np.vstack([np.tile(target, (first, 1)), np.tile(final, (n - first, 1))])
        out = g.process(rows)
        while g.busy:                      # long second moves: run on to the end
            out = np.concatenate([out, g.process(np.tile(final, (n, 1)))])
    real = np.float32 if precision == "float" else np.float64
    u = UNIT_ROUNDOFF[precision]
    reported, sampled, outside, landed = [0.0] * 3, [-np.inf] * 3, 0.0, True
    for i, ax in enumerate(case["axes"]):
        limits = (ax["vmax"], ax["amax"], ax["jmax"])
        for m in (1, 2, 3):
            reported[m - 1] = max(reported[m - 1],
                                  float(np.max(np.abs(out[:, i, m]))) / float(real(limits[m - 1])))
        if qmin[i] is not None:
            lo, hi = float(real(qmin[i])), float(real(qmax[i]))
            outside = max(outside, float(np.max(np.maximum(lo - out[:, i, 0], out[:, i, 0] - hi))))
        q = np.r_[ax["q0"], out[:, i, 0]]
        S = float(np.max(np.abs(q))) + abs(final[i])
        for m, L in zip((1, 2, 3), limits):
            d = np.diff(q, m)[max(0, 3 - m):]
            if per_axis:   # from a moving start the first differences see the state before
                d = d[3:]
            floor = 2.0 ** m * 16 * u * S / Ts ** m
            if d.size:
                sampled[m - 1] = max(sampled[m - 1], float(np.max((np.abs(d) / Ts ** m - floor) / L)))
        landed = landed and bool(out[-1, i, 0] == real(final[i]) and np.all(out[-1, i, 1:] == 0))
    r = dict(ruckig=T, Ts=Ts, outside=max(outside, 0.0), reported=reported, sampled=sampled,
             landed=landed, inside=inside, refused=False)
    if per_axis:
        grid = math.ceil(T / Ts * (1 - 1e-12))
        r.update(samples=arrive, grid=grid, over=arrive - grid, direct=direct, same=same)
    return r


def _real(x, precision):
    return float(np.float32(x) if precision == "float" else x)


def campaign(mode: str, n: int, *, seed: int = 1, precision: str = "double") -> dict:
    """n random cases of the mode: the summary and the cases that break a promise."""
    rng = np.random.default_rng([seed, MODES.index(mode), 11])
    summary = dict(mode=mode, precision=precision, cases=0, ruckig_errors=0, refused=0,
                   ruckig_crosses=0, over=[], longer=[], direct=0, outside=0.0, reported=[0.0] * 3,
                   sampled=[-np.inf] * 3, not_landed=0, failures=[])
    for _ in range(n):
        case = draw_case(rng, mode)
        r = run_case(case, precision=precision)
        if r["ruckig"] is None:
            summary["ruckig_errors"] += 1
            continue
        if r["refused"]:
            summary["refused"] += 1
            continue
        summary["cases"] += 1
        summary["outside"] = max(summary["outside"], r["outside"])
        if r["outside"] > 0:
            summary["failures"].append(("outside", case, r))
        if "over" in r:
            if r["direct"]:
                summary["direct"] += 1
                if not r["same"]:
                    summary["failures"].append(("not the plans without limits", case, r))
            if not r["inside"]:
                summary["ruckig_crosses"] += 1
            elif r["direct"]:
                summary["over"].append(r["over"])
                if r["over"] > 1:
                    summary["failures"].append(("duration", case, r))
            else:
                # ruckig's motion stays inside where ours (the stretched synchronised one)
                # crosses: brake, rest, move is longer (not time-optimal under the limits)
                summary["longer"].append(r["over"])
        tally_limits(summary, case, r, precision)
    return summary


def _row(s) -> str:
    return (f"| {s['mode']} | {s['precision']} | {s['cases']} | {s['refused']} | "
            f"{s['outside']:.3g} | {s['ruckig_errors']} | {s['ruckig_crosses']} | "
            + (f"{s['direct']} | {over_shares(s)} (max {max(s['over'], default=0)}) | "
               f"{len(s['longer'])} (max {max(s['longer'], default=0)}) | " if s["over"] else
               "- | - (from rest to rest, no duration compared) | - | ")
            + f"{limit_cells(s)} | "
            f"{s['not_landed']} |")


def main(argv=None) -> int:
    return campaign_main(
        argv, prog="python -m smoothshaper.bench.multi_position", doc=__doc__, names=MODES,
        flag="--modes", campaign=campaign, row=_row, cases=10000,
        header=["sync", "precision", "cases", "start refused", "largest distance outside",
                "ruckig errs", "ruckig crosses (not compared)", "direct (= the plans "
                "without limits, bit for bit)", "direct vs ruckig inside: over the grid: "
                "< 0 / 0 / 1 [share] (max)", "brake, rest, move where ruckig stays inside: "
                "cases (max over the grid) [samples]", "reported v, a, j beyond the limit [u]", "sampled differences "
                "/ bound - 1, after the floor", "not landed"])


if __name__ == "__main__":
    raise SystemExit(main())
