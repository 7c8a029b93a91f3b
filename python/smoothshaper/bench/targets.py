# SPDX-License-Identifier: Apache-2.0
"""The single-axis generator against ruckig on random cases, one campaign per feature:

* ``rest``: from any state (q, v, a) to a position at rest;
* ``moving``: to a position reached with a velocity and an acceleration (a moving target);
* ``velocity``: the velocity interface (a velocity and an acceleration, the position free);
* ``stop``: braking to rest from any state;
* ``minimum``, ``minimum_velocity``: a position target (at rest or moving) and the velocity
  interface with a minimum duration (ruckig's ``minimum_duration``), drawn as 0 to 3 times
  the unstretched optimum: the arrival never before it, within a sample of ruckig's
  stretched duration on the grid (past a blocked duration: of its discrete one);
* ``asym_rest``, ``asym_moving``, ``asym_velocity``, ``asym_stop``: the first four with
  asymmetric limits, ``vmin`` and ``amin`` (ruckig's ``min_velocity``, ``min_acceleration``)
  each 0.1 to 10 times the negated upper bound: every sample within ``[vmin, vmax]`` and
  ``[amin, amax]``.

Per case the generator starts from a random state (:meth:`Generator.start_from`) and runs
until its plan has reached the target; ruckig (the ``ruckig`` package) is asked for the same
motion, continuous and with its discrete durations (``DurationDiscretization.Discrete``).
Reported per campaign: the arrival in samples against ruckig's duration rounded up to the
grid (``over`` = our samples minus that; the promise: at most one sample, moving targets
past a blocked duration excepted, where ruckig's discrete duration is the bar), the worst
reported |v|/vmax, |a|/amax, |j|/jmax and the worst backward difference of the sampled
position over its bound after the rounding floor of docs/sampled-limits.md, the exact
landing, and the cases where ruckig errs or is slower than our continuous optimum (not time
optimal): those are counted, not compared.

``python -m smoothshaper.bench.targets [--cases N] [--precision double|float] [--seed S]``
prints the table; tests/python/test_generator_targets.py asserts it on fixed-seed draws.
"""
from __future__ import annotations

import argparse
import math

import numpy as np

from .. import _optional

__all__ = ["FEATURES", "draw_case", "run_case", "campaign", "main"]

FEATURES = ("rest", "moving", "velocity", "stop", "minimum", "minimum_velocity", "asym_rest",
            "asym_moving", "asym_velocity", "asym_stop")
# the asymmetric features: the same motions with vmin, amin drawn apart from -vmax, -amax
ASYMMETRIC = {"asym_rest": "rest", "asym_moving": "moving", "asym_velocity": "velocity",
              "asym_stop": "stop"}
# a move stretched to a minimum duration: a position target (at rest or moving), a velocity
STRETCHED = {"minimum": "moving", "minimum_velocity": "velocity"}
UNIT_ROUNDOFF = {"double": 2.0 ** -53, "float": 2.0 ** -24}


def _state(rng, V, A, J, target, Vl=None, Al=None):
    """(v, a) within the bounds whose brake velocities (forward; and backward for a target)
    lie within [Vl, V] (Vl, Al default -V, -A)."""
    Vl = -V if Vl is None else Vl
    Al = -A if Al is None else Al
    while True:
        v, a = rng.uniform(Vl, V), rng.uniform(Al, A)
        r = a * abs(a) / (2 * J)
        if Vl <= v + r <= V and (not target or Vl <= v - r <= V):
            return v, a


def draw_case(rng, feature: str) -> dict:
    """A random case: limits over four decades of ratios, the start state, the target."""
    V = 10.0 ** rng.uniform(-1, 1)
    A = V * 10.0 ** rng.uniform(-1, 2)
    J = A * 10.0 ** rng.uniform(-1, 2)
    Vl, Al = -V, -A
    if feature in ASYMMETRIC:
        Vl, Al = -V * 10.0 ** rng.uniform(-1, 1), -A * 10.0 ** rng.uniform(-1, 1)
    v0, a0 = _state(rng, V, A, J, False, Vl, Al)
    if rng.random() < 0.15:
        v0, a0 = 0.0, 0.0
    scale = max(V, -Vl) * (max(V, -Vl) / min(A, -Al) + min(A, -Al) / J)
    case = dict(feature=feature, vmax=V, amax=A, jmax=J, q0=rng.uniform(-1, 1) * scale,
                v0=v0, a0=a0, position=0.0, velocity=0.0, acceleration=0.0)
    if feature in ASYMMETRIC:
        case.update(vmin=Vl, amin=Al)
        feature = ASYMMETRIC[feature]
    if feature in STRETCHED:
        # the minimum duration: this fraction of the unstretched optimum (campaign())
        case["stretch"] = rng.uniform(0.0, 3.0)
        if feature == "minimum" and rng.random() < 0.4:
            feature = "rest"
        else:
            feature = STRETCHED[feature]
    if feature in ("rest", "moving"):
        case["position"] = case["q0"] + rng.uniform(-3, 3) * scale * 10.0 ** rng.uniform(-2, 1)
    if feature in ("moving", "velocity"):
        vf, af = _state(rng, V, A, J, True, Vl, Al)
        if feature == "moving" and rng.random() < 0.3:
            af = 0.0
        case["velocity"], case["acceleration"] = vf, af
    return case


def _ruckig(case, Ts=None):
    """ruckig's duration for the case (continuous, or discrete with Ts), None when it errs."""
    ruckig = _optional.require("ruckig", "the campaigns against ruckig")
    otg = ruckig.Ruckig(1, Ts) if Ts else ruckig.Ruckig(1)
    inp, traj = ruckig.InputParameter(1), ruckig.Trajectory(1)
    inp.current_position = [case["q0"]]
    inp.current_velocity = [case["v0"]]
    inp.current_acceleration = [case["a0"]]
    inp.max_velocity = [case["vmax"]]
    inp.max_acceleration = [case["amax"]]
    inp.max_jerk = [case["jmax"]]
    if "vmin" in case:
        inp.min_velocity = [case["vmin"]]
        inp.min_acceleration = [case["amin"]]
    inp.minimum_duration = case.get("minimum_duration") or None
    if ASYMMETRIC.get(case["feature"], case["feature"]) in ("velocity", "stop",
                                                               "minimum_velocity"):
        inp.control_interface = ruckig.ControlInterface.Velocity
    else:
        inp.target_position = [case["position"]]
    inp.target_velocity = [case["velocity"]]
    inp.target_acceleration = [case["acceleration"]]
    return traj.duration if ruckig_calculate(ruckig, otg, inp, traj, Ts) else None


def ruckig_calculate(ruckig, otg, inp, traj, Ts=None) -> bool:
    """ruckig's calculate into traj (with its discrete durations when Ts is given): True when
    it plans (Working or Finished), False when it errs."""
    if Ts:
        inp.duration_discretization = ruckig.DurationDiscretization.Discrete
    try:
        result = otg.calculate(inp, traj)
    except (RuntimeError, ValueError, ruckig.RuckigError):
        return False
    return result in (ruckig.Result.Working, ruckig.Result.Finished)


def run_case(case: dict, *, precision: str = "double", samples: float | None = None,
             reference_T: float | None = None) -> dict:
    """Run the case through the C generator. ``samples``: Ts as a fraction of the motion
    (T/Ts), default drawn from the case's own duration (10 to 2000 samples)."""
    from ..trajectory import Generator
    T = reference_T if reference_T is not None else _ruckig(case)
    if T is None:
        return dict(ruckig=None)
    if not T > 0:
        return dict(ruckig=T, trivial=True)   # already there (a stop from rest)
    nu = samples if samples is not None else 10.0 ** case.get("log_samples", 2.0)
    Ts = T / nu
    g = Generator(vmax=case["vmax"], amax=case["amax"], jmax=case["jmax"], Ts=Ts,
                  precision=precision, vmin=case.get("vmin"), amin=case.get("amin"))
    feature = ASYMMETRIC.get(case["feature"], case["feature"])
    tmin = case.get("minimum_duration", 0.0)
    # a stretched velocity change is reached exactly on its sample, as a position target is
    stretched = feature == "minimum_velocity" and tmin > case["unstretched"]
    if feature in STRETCHED:
        feature = "velocity" if feature == "minimum_velocity" else (
            "moving" if case["velocity"] != 0 or case["acceleration"] != 0 else "rest")
    if feature == "stop":
        g.start_from(case["q0"], case["v0"], case["a0"])
    elif feature == "velocity":
        g.start_from(case["q0"], case["v0"], case["a0"], interface="velocity",
                     velocity=case["velocity"], acceleration=case["acceleration"],
                     minimum_duration=tmin)
    else:
        g.start_from(case["q0"], case["v0"], case["a0"], target=case["position"],
                     velocity=case["velocity"], acceleration=case["acceleration"],
                     minimum_duration=tmin)
    arrive = g.arrival                      # samples from the start state to the target
    n = arrive + 8
    if feature == "stop":
        out = g.process(velocity=np.zeros(n), stop=True)
    elif feature == "velocity":
        out = g.process(velocity=np.full(n, case["velocity"]),
                        acceleration=np.full(n, case["acceleration"]), minimum_duration=tmin)
    else:
        out = g.process(np.full(n, case["position"]), velocity=case["velocity"],
                        acceleration=case["acceleration"], minimum_duration=tmin)
    real = np.float32 if precision == "float" else np.float64
    u = UNIT_ROUNDOFF[precision]
    limits = (case["vmax"], case["amax"], case["jmax"])
    # the lower bounds (-vmax, -amax, -jmax when symmetric): each signed value over its own
    lower = (-case.get("vmin", -case["vmax"]), -case.get("amin", -case["amax"]), case["jmax"])
    reported = [max(float(np.max(out[:, i])) / float(real(limits[i - 1])),
                    float(np.max(-out[:, i])) / float(real(lower[i - 1]))) for i in (1, 2, 3)]
    # backward differences of the samples: the start state and out, differences of order i
    # over the last i + 1 samples (the first ones need the samples before the start)
    q = np.r_[case["q0"], out[:, 0]]
    S = float(np.max(np.abs(q))) + abs(case["position"])
    sampled = []
    for i, L, Lo in zip((1, 2, 3), limits, lower):
        d = np.diff(q, i)[max(0, 3 - i):] if q.size > i else np.zeros(1)
        floor = 2.0 ** i * 16 * u * S / Ts ** i
        sampled.append(max(float(np.max((d / Ts ** i - floor) / L)),
                           float(np.max((-d / Ts ** i - floor) / Lo))) if d.size else -np.inf)
    # the target state exactly on the arrival sample, and after it
    k = arrive - 1                            # out[k] is the sample the plan arrives on
    want = (real(case["position"]), real(case["velocity"]), real(case["acceleration"]))
    if feature == "stop":
        landed = bool(out[k, 1] == 0 and out[k, 2] == 0 and np.all(out[k:, 1:] == 0))
    elif feature == "velocity" and stretched:
        landed = bool(out[k, 1] == want[1] and out[k, 2] == want[2])
    elif feature == "velocity":
        # reached between samples: from the first sample after, the velocity held exactly
        # (with an acceleration at arrival, it returns to zero first: not compared)
        landed = bool(want[2] != 0 or (np.all(out[k:, 1] == want[1])
                                       and np.all(out[k:, 2:] == 0)))
    elif feature == "rest":
        landed = bool(out[k, 0] == want[0] and np.all(out[k:, 1:] == 0)
                      and np.all(out[k:, 0] == want[0]))
    else:
        landed = bool(out[k, 0] == want[0] and out[k, 1] == want[1] and out[k, 2] == want[2])
        # A return of the acceleration to zero shorter than the grid tolerance (8 ulps of the
        # sample count, docs/sampled-limits.md) ends on the arrival sample itself: that sample
        # shows the state after it exactly (the plan's goal, the drift velocity, a = 0). In
        # float: a target acceleration below about 2e-6 jmax N Ts.
        eps = 2 * UNIT_ROUNDOFF[precision]
        if not landed and abs(want[2]) / case["jmax"] <= 8 * eps * max(arrive, 1) * Ts:
            plan = g._gen.plan
            landed = bool(out[k, 0] == real(plan.goal) and out[k, 1] == real(plan.drift)
                          and out[k, 2] == 0)
    grid = math.ceil(T / Ts * (1 - 1e-12))
    discrete = _ruckig(case, Ts) if feature == "moving" or tmin > 0 else None
    return dict(ruckig=T, Ts=Ts, samples=arrive, grid=grid, over=arrive - grid,
                # (on the grid within 8 ulps of the count, the minimum and Ts rounded to
                # the precision)
                short=arrive * Ts < tmin * (1 - 32 * u),
                discrete=None if discrete is None else round(discrete / Ts), reported=reported,
                sampled=sampled, landed=landed)


def campaign(feature: str, n: int, *, seed: int = 1, precision: str = "double") -> dict:
    """n random cases of the feature: the summary (see the module docstring) and the cases
    that break a promise (``failures``)."""
    rng = np.random.default_rng([seed, FEATURES.index(feature)])
    summary = dict(feature=feature, precision=precision, cases=0, ruckig_errors=0,
                   over=[], blocked=0, beyond_blocked=0, reported=[0.0, 0.0, 0.0],
                   sampled=[-np.inf] * 3, not_landed=0, failures=[])
    for _ in range(n):
        case = draw_case(rng, feature)
        case["log_samples"] = rng.uniform(1, 3.3)
        if feature in STRETCHED:
            T0 = _ruckig(case)
            if T0 is None:
                summary["ruckig_errors"] += 1
                continue
            case["unstretched"], case["minimum_duration"] = T0, case["stretch"] * T0
        r = run_case(case, precision=precision)
        if r["ruckig"] is None:
            summary["ruckig_errors"] += 1
            continue
        if r.get("trivial"):
            continue
        summary["cases"] += 1
        over = r["over"]
        if r["short"]:
            summary["failures"].append(("shorter than the minimum duration", case, r))
        if feature in ("moving", "asym_moving", "minimum", "minimum_velocity") and over > 1:
            # past a blocked duration: ruckig's discrete duration is the bar
            summary["blocked"] += 1
            if r["discrete"] is None or r["samples"] > r["discrete"] + 1:
                summary["beyond_blocked"] += 1
                summary["failures"].append(("duration", case, r))
        else:
            summary["over"].append(over)
            if over > 1:
                summary["failures"].append(("duration", case, r))
        tally_limits(summary, case, r, precision)
    return summary


def tally_limits(summary: dict, case: dict, r: dict, precision: str) -> None:
    """Fold one case's worst reported v, a, j (over their limits) and sampled differences
    (over their bounds, after the floor) into the summary; a value beyond 32 u or 1e-9, or an
    axis not landed, is a failure of the case (the campaigns' shared promise)."""
    u = UNIT_ROUNDOFF[precision]
    summary["reported"] = [max(a, b) for a, b in zip(summary["reported"], r["reported"])]
    summary["sampled"] = [max(a, b) for a, b in zip(summary["sampled"], r["sampled"])]
    if max(r["reported"]) > 1 + 32 * u or max(r["sampled"]) > 1 + 1e-9:
        summary["failures"].append(("limits", case, r))
    if not r["landed"]:
        summary["not_landed"] += 1
        summary["failures"].append(("landing", case, r))


def over_shares(s: dict) -> str:
    """The share of arrivals before, on and one sample after ruckig's rounded duration."""
    over = np.array(s["over"]) if s["over"] else np.zeros(1)
    return f"{np.mean(over < 0):.3f} / {np.mean(over == 0):.3f} / {np.mean(over == 1):.3f}"


def limit_cells(s: dict) -> str:
    """The table cells of a summary's worst reported values [u] and sampled differences."""
    u = UNIT_ROUNDOFF[s["precision"]]
    return (f"{', '.join(f'{(r - 1) / u:.1f}' for r in s['reported'])} | "
            f"{', '.join(f'{x - 1:.2e}' for x in s['sampled'])}")


def campaign_main(argv, *, prog: str, doc: str, header: list, names: tuple, flag: str,
                  campaign, row, cases: int) -> int:
    """The campaigns' command line: --cases, --precision, --seed and the names to run
    (``flag``); prints the table header and one row per name; 1 when any case failed."""
    p = argparse.ArgumentParser(prog=prog, description=doc.split("\n\n")[0])
    p.add_argument("--cases", type=int, default=cases, help=f"cases per {flag[2:-1]} "
                   f"(default {cases})")
    p.add_argument("--precision", choices=("double", "float"), default="double")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument(flag, nargs="+", choices=names, default=list(names), dest="names")
    args = p.parse_args(argv)
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    bad = 0
    for name in args.names:
        s = campaign(name, args.cases, seed=args.seed, precision=args.precision)
        print(row(s), flush=True)
        bad += len(s["failures"])
    return 1 if bad else 0


def _row(s) -> str:
    over = np.array(s["over"]) if s["over"] else np.zeros(1)
    return (f"| {s['feature']} | {s['precision']} | {s['cases']} | {s['ruckig_errors']} | "
            f"{np.mean(over <= 0):.3f} / {np.mean(over == 1):.3f} / {int(over.max())} | "
            f"{s['blocked']} ({s['beyond_blocked']}) | "
            f"{limit_cells(s)} | {s['not_landed']} |")


def main(argv=None) -> int:
    return campaign_main(
        argv, prog="python -m smoothshaper.bench.targets", doc=__doc__, names=FEATURES,
        flag="--features", campaign=campaign, row=_row, cases=1000,
        header=["feature", "precision", "cases", "ruckig errs", "over the grid: <= 0 / 1 / max "
                "[samples]", "past a blocked duration (beyond ruckig's discrete)", "reported "
                "v, a, j beyond the limit [u]", "sampled differences / bound - 1, after the "
                "floor", "not landed"])


if __name__ == "__main__":
    raise SystemExit(main())
