# SPDX-License-Identifier: Apache-2.0
"""The multi-axis generator's per-axis plan modes against ruckig on random cases, one
campaign per synchronisation:

* ``time``: every axis lands on one common sample (ruckig's ``Synchronization.Time``);
* ``time_if_necessary``: only the axes with a moving target do (``TimeIfNecessary``);
* ``none``: each axis as fast as it can (``Synchronization.None``);
* ``per_axis``: a random mode per axis (ruckig's ``per_dof_synchronization``);
* ``minimum``: ``time`` with a minimum duration of 0 to 3 times the unstretched one.

Per case 1 to 4 axes, each with its own limits (four decades of ratios), start state
(q, v, a) and target (at rest or moving, half and half); the generator starts there
(:meth:`MultiAxisGenerator.start`) and runs past the arrival; ruckig (the ``ruckig``
package) is asked for the same motion, continuous and with its discrete durations
(``DurationDiscretization.Discrete``). Reported per campaign: the arrival in samples against
ruckig's duration rounded up to the grid (``over``; the promise: at most one sample, except
past a duration blocked for some axis, where ruckig's discrete duration plus
one is the bar), the worst reported |v|/vmax, |a|/amax, |j|/jmax of any axis, the worst
backward difference of any axis's sampled position over its bound after the rounding floor
of docs/sampled-limits.md, the synchronised axes not arriving on one sample, and each axis's
exact landing on its target state. Cases where ruckig errs are counted, not compared.

``python -m smoothshaper.bench.multi_sync [--cases N] [--precision double|float]`` prints the
table; tests/python/test_multi_axis_sync.py asserts it on fixed-seed draws.
"""
from __future__ import annotations

import math

import numpy as np

from .. import _optional
from .targets import (UNIT_ROUNDOFF, _state, campaign_main, limit_cells, over_shares,
                      ruckig_calculate, tally_limits)

__all__ = ["FEATURES", "draw_case", "run_case", "campaign", "main"]

FEATURES = ("time", "time_if_necessary", "none", "per_axis", "minimum")
MODES = ("time", "time_if_necessary", "none")


def draw_case(rng, feature: str) -> dict:
    """A random case: per axis limits, start state and target."""
    n = int(rng.integers(1, 5))
    axes = []
    for _ in range(n):
        V = 10.0 ** rng.uniform(-1, 1)
        A = V * 10.0 ** rng.uniform(-1, 2)
        J = A * 10.0 ** rng.uniform(-1, 2)
        v0, a0 = _state(rng, V, A, J, False)
        if rng.random() < 0.15:
            v0, a0 = 0.0, 0.0
        scale = V * (V / A + A / J)
        q0 = rng.uniform(-1, 1) * scale
        pf = q0 + rng.uniform(-3, 3) * scale * 10.0 ** rng.uniform(-2, 1)
        vf = af = 0.0
        if rng.random() < 0.5:
            vf, af = _state(rng, V, A, J, True)
            if rng.random() < 0.3:
                af = 0.0
        axes.append(dict(vmax=V, amax=A, jmax=J, q0=q0, v0=v0, a0=a0, position=pf,
                         velocity=vf, acceleration=af))
    mode = "time" if feature in ("minimum", "per_axis") else feature
    per_axis = [str(rng.choice(MODES)) for _ in range(n)] if feature == "per_axis" else None
    return dict(feature=feature, mode=mode, per_axis=per_axis, axes=axes,
                stretch=rng.uniform(0.0, 3.0) if feature == "minimum" else 0.0,
                log_samples=rng.uniform(1, 3.3))


def _field(case, name):
    return [ax[name] for ax in case["axes"]]


def ruckig_duration(case, Ts=None):
    """ruckig's duration for the case (continuous, or discrete with Ts), None when it errs."""
    traj = ruckig_trajectory(case, Ts)
    return None if traj is None else traj.duration


def ruckig_trajectory(case, Ts=None):
    """ruckig's trajectory for the case (continuous, or discrete with Ts), None when it errs;
    case["mode"] may also be "phase" or "independent" (ruckig's Phase and None)."""
    ruckig = _optional.require("ruckig", "the campaigns against ruckig")
    n = len(case["axes"])
    otg = ruckig.Ruckig(n, Ts) if Ts else ruckig.Ruckig(n)
    inp, traj = ruckig.InputParameter(n), ruckig.Trajectory(n)
    inp.current_position = _field(case, "q0")
    inp.current_velocity = _field(case, "v0")
    inp.current_acceleration = _field(case, "a0")
    inp.target_position = _field(case, "position")
    inp.target_velocity = _field(case, "velocity")
    inp.target_acceleration = _field(case, "acceleration")
    inp.max_velocity = _field(case, "vmax")
    inp.max_acceleration = _field(case, "amax")
    inp.max_jerk = _field(case, "jmax")
    sync = {"time": ruckig.Synchronization.Time,
            "time_if_necessary": ruckig.Synchronization.TimeIfNecessary,
            "none": ruckig.Synchronization.No,   # (ruckig's None, spelled No in Python)
            "phase": ruckig.Synchronization.Phase, "independent": ruckig.Synchronization.No}
    inp.synchronization = sync[case["mode"]]
    if case["per_axis"] is not None:
        inp.per_dof_synchronization = [sync[m] for m in case["per_axis"]]
    if case.get("minimum_duration"):
        inp.minimum_duration = case["minimum_duration"]
    return traj if ruckig_calculate(ruckig, otg, inp, traj, Ts) else None


def _synced(case):
    modes = case["per_axis"] or [case["mode"]] * len(case["axes"])
    return [m == "time" or (m == "time_if_necessary" and (ax["velocity"] != 0 or
                                                           ax["acceleration"] != 0))
            for m, ax in zip(modes, case["axes"])]


def run_case(case: dict, *, precision: str = "double") -> dict:
    """Run the case through the C generator, Ts drawn from the case's duration (10 to 2000
    samples of ruckig's)."""
    from ..multi_axis import MultiAxisGenerator
    T = ruckig_duration(case)
    if T is None:
        return dict(ruckig=None)
    if not T > 0:
        return dict(ruckig=T, trivial=True)
    Ts = T / 10.0 ** case["log_samples"]
    g = MultiAxisGenerator(vmax=_field(case, "vmax"), amax=_field(case, "amax"),
                           jmax=_field(case, "jmax"), Ts=Ts, sync=case["mode"],
                           precision=precision)
    target = dict(positions=_field(case, "position"), velocities=_field(case, "velocity"),
                  accelerations=_field(case, "acceleration"), axis_sync=case["per_axis"],
                  minimum_duration=case.get("minimum_duration", 0.0))
    g.start(_field(case, "q0"), _field(case, "v0"), _field(case, "a0"), **target)
    arrive = g.arrival
    per_axis = list(g.axis_arrival)
    n = arrive + 8
    rows = {k: np.tile(v, (n, 1)) for k, v in target.items()
            if k in ("positions", "velocities", "accelerations")}
    out = g.process_targets(rows["positions"], velocities=rows["velocities"],
                            accelerations=rows["accelerations"], axis_sync=case["per_axis"],
                            minimum_duration=target["minimum_duration"])
    real = np.float32 if precision == "float" else np.float64
    u = UNIT_ROUNDOFF[precision]
    reported, sampled, landed = [0.0] * 3, [-np.inf] * 3, True
    for i, ax in enumerate(case["axes"]):
        limits = (ax["vmax"], ax["amax"], ax["jmax"])
        for m in (1, 2, 3):
            reported[m - 1] = max(reported[m - 1],
                                  float(np.max(np.abs(out[:, i, m]))) / float(real(limits[m - 1])))
        q = np.r_[ax["q0"], out[:, i, 0]]
        S = float(np.max(np.abs(q))) + abs(ax["position"])
        for m, L in zip((1, 2, 3), limits):
            d = np.diff(q, m)[max(0, 3 - m):]
            floor = 2.0 ** m * 16 * u * S / Ts ** m
            if d.size:
                sampled[m - 1] = max(sampled[m - 1], float(np.max((np.abs(d) / Ts ** m - floor) / L)))
        k = per_axis[i] - 1
        if k < 0:
            continue
        want = (real(ax["position"]), real(ax["velocity"]), real(ax["acceleration"]))
        ok = bool(out[k, i, 0] == want[0] and out[k, i, 1] == want[1] and out[k, i, 2] == want[2])
        if not ok and want[2] != 0:
            # a return of the acceleration to zero within the grid tolerance ends on the
            # arrival sample itself: the plan's goal and drift exactly (bench.targets)
            plan = g._gen.axis[i].plan
            ok = bool(out[k, i, 0] == real(plan.goal) and out[k, i, 1] == real(plan.drift)
                      and out[k, i, 2] == 0)
        if want[1] == 0 and want[2] == 0:
            ok = ok and bool(np.all(out[k:, i, 0] == want[0]) and np.all(out[k:, i, 1:] == 0))
        landed = landed and ok
    synced = _synced(case)
    common = {per_axis[i] for i in range(len(synced)) if synced[i]}
    grid = math.ceil(T / Ts * (1 - 1e-12))
    discrete = ruckig_duration(case, Ts)
    if arrive - grid > 1:
        # ruckig's multi-axis discrete mode errs where an unsynchronised axis's own duration
        # is blocked on the grid (it does not land such an axis on a sample): that axis's
        # one-axis discrete duration is then the bar
        from .targets import _ruckig as one_axis
        for ax in case["axes"]:
            d = one_axis(dict(feature="moving", **ax), Ts)
            if d is not None and (discrete is None or d > discrete):
                discrete = d
    return dict(ruckig=T, Ts=Ts, samples=arrive, grid=grid, over=arrive - grid,
                discrete=None if discrete is None else round(discrete / Ts),
                short=arrive * Ts < case.get("minimum_duration", 0.0) * (1 - 32 * u)
                and any(synced),
                synchronised=len(common) <= 1, reported=reported, sampled=sampled,
                landed=landed)


def campaign(feature: str, n: int, *, seed: int = 1, precision: str = "double") -> dict:
    """n random cases of the feature: the summary and the cases that break a promise."""
    rng = np.random.default_rng([seed, FEATURES.index(feature), 7])
    summary = dict(feature=feature, precision=precision, cases=0, ruckig_errors=0, over=[],
                   blocked=0, beyond_blocked=0, reported=[0.0] * 3, sampled=[-np.inf] * 3,
                   not_synchronised=0, not_landed=0, failures=[])
    for _ in range(n):
        case = draw_case(rng, feature)
        if feature == "minimum":
            T0 = ruckig_duration(case)
            if T0 is None:
                summary["ruckig_errors"] += 1
                continue
            case["minimum_duration"] = case["stretch"] * T0
        r = run_case(case, precision=precision)
        if r["ruckig"] is None:
            summary["ruckig_errors"] += 1
            continue
        if r.get("trivial"):
            continue
        summary["cases"] += 1
        over = r["over"]
        if over > 1:
            # past a duration blocked for a synchronised axis: ruckig's discrete one is the bar
            summary["blocked"] += 1
            if r["discrete"] is None or r["samples"] > r["discrete"] + 1:
                summary["beyond_blocked"] += 1
                summary["failures"].append(("duration", case, r))
        else:
            summary["over"].append(over)
        if r["short"]:
            summary["failures"].append(("shorter than the minimum duration", case, r))
        tally_limits(summary, case, r, precision)
        if not r["synchronised"]:
            summary["not_synchronised"] += 1
            summary["failures"].append(("synchronisation", case, r))
    return summary


def _row(s) -> str:
    return (f"| {s['feature']} | {s['precision']} | {s['cases']} | {s['ruckig_errors']} | "
            f"{over_shares(s)} | {s['blocked']} ({s['beyond_blocked']}) | {limit_cells(s)} | "
            f"{s['not_synchronised']} | {s['not_landed']} |")


def main(argv=None) -> int:
    return campaign_main(
        argv, prog="python -m smoothshaper.bench.multi_sync", doc=__doc__, names=FEATURES,
        flag="--features", campaign=campaign, row=_row, cases=10000,
        header=["sync", "precision", "cases", "ruckig errs", "over the grid: < 0 / 0 / 1 "
                "[share]", "past a blocked duration (beyond ruckig's discrete + 1)", "reported "
                "v, a, j beyond the limit [u]", "sampled differences / bound - 1, after the "
                "floor", "not synchronised", "not landed"])


if __name__ == "__main__":
    raise SystemExit(main())
