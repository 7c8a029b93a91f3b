# SPDX-License-Identifier: Apache-2.0
"""NumPy reference of the time-optimal online generator's plan.

Linear ramps of the acceleration (the polynomial and damped profiles) plan from any state to
any target state, or to a target velocity, with :mod:`smoothshaper.reference.third_order`
(step 1, the time-optimal motion; a moving target reached on the sample grid by the convex
combination of the two farthest motions of that many samples); after the target the
acceleration returns to zero at jmax and the velocity is held. Half-cosine transitions (the
trigonometric profile) plan to rest as below.

Written independently of ``c/src/trajectory/plan.c``: the motion from a state (q, v, a) to a target at
rest is built from the same three phases (velocity change to a peak velocity vp with the
acceleration back at 0, a cruise at +-vmax when the distance allows, the stop), but vp is
found by ``scipy.optimize.brentq`` and the plan is sampled on absolute float64 times, a
breakpoint on the grid (within 8 ulps of its sample count of a whole number) deciding the
side of its jump by the sample index. Used by the tests and the arrival benchmark; not on any run path.

Limits and dropped targets follow the generator's documented rules, derived here from the
formulas, not from the C code: :func:`reach` is the move that reaches vmax from rest and the
feasible region of the limits (``sms_generator_reach`` in trajectory.h); a target whose plan
has a non-finite value or lasts more than 2^52 samples is dropped (:func:`representable`): the
running plan goes on and the target is not tried again until it changes.

``shape="cosine"`` (the trigonometric profile): every transition of the acceleration is a
half cosine, a(t) = a0 + da (1 - cos(pi t/d))/2 with peak jerk jmax, evaluated here with
NumPy's sin/cos. Its durations and velocity changes are those of a linear ramp at the mean
jerk 2 jmax/pi; a transition that would take the acceleration across zero is split at zero
(a cosine lingers near its start and would carry v past the brake velocity), and a re-plan
waits for a state from which a fresh transition to zero keeps |v| <= vmax.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from . import _reach
from .reference import third_order as _to
from ._checks import (choice as _choice, finite as _finite, positive as _positive,
                      real_array as _real_array)
from .errors import ParameterError

__all__ = ["plan_to_rest", "plan_duration", "time_optimal_reference", "mean_jerk", "C3", "reach",
           "representable", "MAX_PLAN_SAMPLES", "TS_MAX", "POSITION", "VELOCITY", "STOP"]

#: Interfaces of a target (the values of ``sms_interface``).
POSITION, VELOCITY, STOP = 0, 1, 2

#: The longest plan in samples: its sample counts stay exact in a double (a saved state).
MAX_PLAN_SAMPLES = 2.0 ** 52
#: Reaching vmax may take at most this many samples: room for a reversal within a plan.
MAX_REACH_SAMPLES = 2.0 ** 50
#: Room for a reversal and the stop in the products and distances of a plan.
MARGIN = 16.0
#: The largest Ts a generator takes (``SMS_TS_MAX``, types.h): a duration is held to 2^53 Ts
#: and a move or the FMU clock sums up to 8 of them, so 2^56 Ts must stay a finite double.
TS_MAX = 2.0 ** 967


C3 = {"ramp": 1.0 / 6.0, "cosine": 0.25 - 1.0 / math.pi ** 2}
SHAPES = tuple(C3)


def mean_jerk(jmax: float, shape: str) -> float:
    """The jerk the planner works with: jmax (ramps) or 2 jmax/pi (half-cosine transitions,
    whose change of a over a duration d is 2 jmax d/pi). ParameterError naming ``jmax`` (not
    finite and > 0) or ``shape`` (not "ramp" or "cosine")."""
    jmax = _positive("jmax", jmax)
    return jmax * 2.0 / math.pi if _choice("shape", shape, SHAPES) == "cosine" else jmax


def _mean_jerk(jmax: float, shape: str) -> float:
    """:func:`mean_jerk` of checked arguments (the planner's inner loops)."""
    return jmax * 2.0 / math.pi if shape == "cosine" else jmax


def _change(v0: float, a0: float, v1: float, A: float, J: float,
            shape: str = "ramp") -> list[tuple[float, float]]:
    """(duration, jerk) pieces that take (v0, a0) to (v1, 0) in the least time within A, J.

    The acceleration first moves towards a peak ap of the sign of the remaining change, holds
    it if |ap| reached A, then returns to 0. The velocity gained when a returns to 0 at once
    is a0|a0|/(2J); the peak follows from v1 - v0 = (ap^2 - a0^2)/(2J) + ap^2/(2J) (+ hold)."""
    settle = v0 + a0 * abs(a0) / (2 * J)
    if v1 == settle:
        return [(abs(a0) / J, -math.copysign(J, a0))] if a0 else []
    s = 1.0 if v1 > settle else -1.0
    b0, dv = s * a0, s * (v1 - v0)
    if shape == "cosine" and b0 < 0:
        return [(-b0 / J, s * J)] + _change(settle, 0.0, v1, A, J, shape)
    peak = math.sqrt(max(J * dv + 0.5 * b0 * b0, 0.0))
    hold = 0.0
    if peak > A:
        peak = A
        hold = max((dv - (2 * A * A - b0 * b0) / (2 * J)) / A, 0.0)
    peak = max(peak, b0)
    return [((peak - b0) / J, s * J), (hold, 0.0), (peak / J, -s * J)]


def reach(vmax: float, amax: float, jmax: float, Ts: float, shape: str = "ramp",
          precision: str = "double") -> dict:
    """The move that reaches vmax from rest and stops, and whether the limits are feasible.

    J is the planner's jerk (:func:`mean_jerk`); the move's peak acceleration is
    ap = min(amax, sqrt(vmax J)), it lasts T = 2 (vmax/ap + ap/J) and covers
    h = vmax (vmax/ap + ap/J). For a move from any state within the bounds the planner forms
    J dv (|dv| <= 2 vmax), squares of accelerations up to ap^2, durations up to about T and
    distances up to a few times h, so the limits are feasible when, with MAX and MIN the
    largest and smallest normal numbers of the precision and eps its epsilon: every limit is
    in [MIN, MAX/16]; 16 vmax J <= MAX; T/Ts <= 2^50 (a reversal fits the plan's 2^52
    samples); ap^2 >= MIN/eps; T >= MIN; MIN/eps <= h <= MAX/16.

    Returns
    -------
    dict
        ``peak``, ``duration`` [s], ``distance``, ``samples`` (duration/Ts) and ``quantity``:
        None when feasible, else the first quantity out of range ("vmax", "vmax*jmax",
        "vmax/amax", "sqrt(vmax/jmax)" or "sqrt(pi vmax/(2 jmax))", "amax^2",
        "the duration to reach vmax", "the distance to reach vmax").
    """
    vmax, amax, jmax, Ts = (_positive(name, value) for name, value in
                            (("vmax", vmax), ("amax", amax), ("jmax", jmax), ("Ts", Ts)))
    shape = _choice("shape", shape, SHAPES)
    precision = _choice("precision", precision, ("double", "float"))
    return reach_unchecked(vmax, amax, jmax, Ts, shape, precision)


def reach_unchecked(vmax: float, amax: float, jmax: float, Ts: float, shape: str,
                    precision: str = "double") -> dict:
    """:func:`reach` of checked arguments (finite floats > 0, a shape of :data:`SHAPES`)."""
    info = np.finfo(np.float32 if precision == "float" else np.float64)
    big, least, tiny = float(info.max), float(info.tiny), float(info.tiny) / float(info.eps)
    out = dict(peak=0.0, duration=0.0, distance=0.0, samples=0.0, quantity=None)
    for name, x in (("vmax", vmax), ("amax", amax), ("jmax", jmax)):
        if not least <= x <= big / MARGIN:
            out["quantity"] = name
            return out
    J = _mean_jerk(jmax, shape)
    if not vmax * J * MARGIN <= big:
        out["quantity"] = "vmax*jmax"
        return out
    ap = math.sqrt(vmax) * math.sqrt(J)
    reached = amax < ap
    ap = amax if reached else ap
    tv, tj = vmax / ap, ap / J
    out.update(peak=ap, duration=2 * (tv + tj), distance=vmax * (tv + tj),
               samples=2 * (tv + tj) / Ts)
    if not out["samples"] <= MAX_REACH_SAMPLES:
        out["quantity"] = ("vmax/amax" if reached else
                           "sqrt(pi vmax/(2 jmax))" if shape == "cosine" else "sqrt(vmax/jmax)")
    elif not ap * ap >= tiny:
        out["quantity"] = "amax^2" if reached else "vmax*jmax"
    elif not out["duration"] >= least:
        out["quantity"] = "the duration to reach vmax"
    elif not tiny <= out["distance"] <= big / MARGIN:
        out["quantity"] = "the distance to reach vmax"
    return out


def reach_pairs(vmax: float, amax: float, jmax: float, vmin: float, amin: float, Ts: float,
                shape: str = "ramp", precision: str = "double") -> dict:
    """:func:`reach_unchecked` of asymmetric limits (checked floats, vmin and amin < 0): the
    moves that reach each velocity bound with each acceleration bound, in the order
    (vmax, amax), (vmin, amin), (vmax, amin), (vmin, amax); the first refusal with its
    quantity named after that pair (``"vmin/amin"``, ``"the distance to reach vmin"``), else
    the (vmax, amax) move. ``vmin`` or ``amin`` out of [MIN, MAX/16] in magnitude is named
    alone. The trigonometric shape takes symmetric limits only (the caller refuses it)."""
    info = np.finfo(np.float32 if precision == "float" else np.float64)
    big, least = float(info.max), float(info.tiny)
    first = reach_unchecked(vmax, amax, jmax, Ts, shape, precision)
    if first["quantity"] is not None:
        return first
    for name, x in (("vmin", vmin), ("amin", amin)):
        if not least <= -x <= big / MARGIN:
            return dict(first, quantity=name)
    for vn, an, V, A in (("vmin", "amin", -vmin, -amin), ("vmax", "amin", vmax, -amin),
                         ("vmin", "amax", -vmin, amax)):
        out = reach_unchecked(V, A, jmax, Ts, shape, precision)
        q = out["quantity"]
        if q is not None:
            out["quantity"] = q.replace("vmax", vn).replace("amax", an)
            return out
    return first


def representable(pieces, starts, Ts: float) -> bool:
    """Can the plan be formed: every duration and start value finite, each piece's values
    bounded by |q| + d (|v| + d (|a|/2 + d |j|/4)) finite, and at most 2^52 samples long?"""
    total = 0.0
    for (d, j), (q, v, a) in zip(pieces, starts):
        if not all(math.isfinite(x) for x in (d, j, q, v, a)):
            return False
        bound = abs(q) + d * (abs(v) + d * (abs(a) / 2 + d * abs(j) / 4))
        if not (math.isfinite(bound) and math.isfinite(abs(v) + d * (abs(a) + d * abs(j)))):
            return False
        total += d
    return math.isfinite(total) and total / Ts + 2 <= MAX_PLAN_SAMPLES


def _integrate(pieces, q, v, a, c3=1.0 / 6.0):
    """End state after whole pieces from (q, v, a): dq = v d + a d^2/2 + c3 j d^3 (c3 = 1/6
    for a constant jerk j, 1/4 - 1/pi^2 for a half cosine of mean jerk j)."""
    for d, j in pieces:
        if d <= 0:
            continue
        q, v, a = q + d * v + d * d * a / 2 + c3 * d ** 3 * j, v + d * a + d * d * j / 2, a + d * j
    return q, v, a


def plan_to_rest(q: float, v: float, a: float, goal: float, *, vmax: float, amax: float,
                 jmax: float, shape: str = "ramp"):
    """Pieces [(duration, jerk), ...] and the start states of the time-optimal motion from
    (q, v, a) to goal at rest. Returns (pieces, starts) with starts[i] = (q, v, a) of piece i;
    the stop is anchored on the goal (its start is the goal minus its own distance). For
    ``shape="cosine"`` the jerk of a piece is its mean jerk (peak: pi/2 times it).

    ParameterError naming the argument: ``q``, ``v``, ``a``, ``goal`` not finite; a bound not
    finite and > 0; ``|v| > vmax`` or ``|a| > amax``; ``shape``; or ``goal`` when the motion
    to it is beyond the range of a float."""
    q, v, a, goal = (_finite(name, value) for name, value in
                     (("q", q), ("v", v), ("a", a), ("goal", goal)))
    vmax, amax, jmax = (_positive(name, value) for name, value in
                        (("vmax", vmax), ("amax", amax), ("jmax", jmax)))
    shape = _choice("shape", shape, SHAPES)
    if abs(v) > vmax:
        raise ParameterError("v", f"v={v!r} exceeds vmax={vmax!r}")
    if abs(a) > amax:
        raise ParameterError("a", f"a={a!r} exceeds amax={amax!r}")
    try:
        with np.errstate(all="ignore"):
            pieces, starts = _plan_to_rest(q, v, a, goal, vmax=vmax, amax=amax, jmax=jmax,
                                           shape=shape)
        if not (all(math.isfinite(x) for piece in pieces for x in piece)
                and math.isfinite(sum(d for d, _ in pieces))
                and all(math.isfinite(x) for state in starts for x in state)):
            raise OverflowError("a duration or a state of the plan is not finite")
        return pieces, starts
    except (OverflowError, ZeroDivisionError):
        # limits out of the generator's feasible region name the limit (Ts plays no part)
        quantity = reach(vmax, amax, jmax, 1e300, shape)["quantity"]
        if quantity is not None:
            name = _reach.named(quantity, [n for n in ("vmax", "amax", "jmax") if n in quantity],
                                0.0)
            raise ParameterError(
                name, f"{name}: vmax={vmax!r}, amax={amax!r}, jmax={jmax!r}: {quantity} is out "
                "of the feasible range: no motion can be planned within them") from None
        raise ParameterError(
            "goal", f"goal={goal!r}: the motion from (q, v, a) = ({q!r}, {v!r}, {a!r}) within "
            f"vmax={vmax!r}, amax={amax!r}, jmax={jmax!r} is beyond the range of a float") from None


def _plan_to_rest(q: float, v: float, a: float, goal: float, *, vmax: float, amax: float,
                  jmax: float, shape: str = "ramp"):
    """:func:`plan_to_rest` of checked arguments (the reference generator's re-plans)."""
    D = goal - q
    if D == 0 and v == 0 and a == 0:
        return [], []
    c3 = C3[shape]
    jmax = _mean_jerk(jmax, shape)

    def dist(vp):
        first = _change(v, a, vp, amax, jmax, shape)
        stop = _change(vp, 0.0, 0.0, amax, jmax, shape)
        q1, _, _ = _integrate(first, 0.0, v, a, c3)
        q2, _, _ = _integrate(stop, 0.0, vp, 0.0, c3)
        return q1 + q2

    on_stop = False
    if D >= dist(vmax):
        vp = vmax
    elif D <= dist(-vmax):
        vp = -vmax
    else:
        # the root on the side of `after` (v when a returns to zero at once) where it lies:
        # above it the distance increases with vp; just below it a split deceleration (to vp,
        # then the stop) covers more than stopping at once, a second, slower root
        after = v + a * abs(a) / (2 * jmax)
        lo, hi = -vmax, vmax
        if -vmax < after < vmax:
            # a target at the direct stop to within the rounding of the positions: vp = after
            dA = dist(after)
            if abs(D - dA) <= 8 * np.finfo(float).eps * (abs(q) + abs(goal) + abs(dA)):
                lo = hi = after
                on_stop = True
            else:
                lo, hi = (after, vmax) if D > dA else (-vmax, after)
        try:
            vp = after if lo == hi else brentq(lambda x: dist(x) - D, lo, hi, xtol=1e-300,
                                               rtol=8.9e-16, maxiter=1000)
        except (RuntimeError, ValueError):   # a flat corner or a sign lost to rounding: bisect
            for _ in range(3000):
                mid = 0.5 * (lo + hi)
                if not lo < mid < hi:
                    break
                lo, hi = (mid, hi) if dist(mid) < D else (lo, mid)
            vp = 0.5 * (lo + hi)
        # The root's neighbour on the side that leaves a distance to cover at vp (short of D
        # for vp > 0, beyond it for vp < 0). Near `after` the distance grows like the square
        # root of vp - after, so neighbouring vp differ in distance by far more than the
        # rounding of the positions: the parts cannot meet by vp alone, and the stop
        # anchored on the goal would start that far from where the velocity change ends (a
        # jump of q). The cruise at vp below covers what is left.
        for _ in range(8):
            if vp > 0 and dist(vp) > D and vp > lo:
                vp = max(math.nextafter(vp, -math.inf), lo)
            elif vp < 0 and dist(vp) < D and vp < hi:
                vp = min(math.nextafter(vp, math.inf), hi)
            else:
                break
    first = _change(v, a, vp, amax, jmax, shape)
    stop = _change(vp, 0.0, 0.0, amax, jmax, shape)
    pieces, starts = [], []
    state = (q, v, a)
    for d, j in first:
        if d > 0:
            pieces.append((d, j))
            starts.append(state)
            state = _integrate([(d, j)], *state, c3)
    # the stop starts its own distance before the goal; the cruise at vp covers the distance
    # from the end of the velocity change to there (none when it lies on the wrong side of vp,
    # which is rounding, or when vp = after for a target at the direct stop to rounding: at a
    # small `after` covering that would crawl)
    qs, _, _ = _integrate(stop, 0.0, vp, 0.0, c3)
    cruise = (goal - qs - state[0]) / vp if vp != 0 and not on_stop else 0.0
    if cruise > 0:
        pieces.append((cruise, 0.0))
        starts.append((state[0], vp, 0.0))
    state = (goal - qs, vp, 0.0)
    for d, j in stop:
        if d > 0:
            pieces.append((d, j))
            starts.append(state)
            state = _integrate([(d, j)], *state, c3)
    return pieces, starts


def plan_duration(q, v, a, goal, *, vmax, amax, jmax, shape="ramp") -> float:
    """Duration [s] of :func:`plan_to_rest`."""
    pieces, _ = plan_to_rest(q, v, a, goal, vmax=vmax, amax=amax, jmax=jmax, shape=shape)
    return float(sum(d for d, _ in pieces))


def _ends(pieces, Ts):
    """End of each piece in samples after the plan's start, snapped onto the grid when within
    8 ulps of its sample count of a whole number (what summing the lengths can round away)."""
    out, total = [], 0.0
    for d, _ in pieces:
        total += d
        b = total / Ts
        r = math.floor(b + 0.5)
        out.append(float(r) if abs(b - r) <= 8 * np.finfo(float).eps * max(1.0, b) else b)
    return out


def _evaluate(plan, m, Ts, shape="ramp"):
    """q, v, a, j at sample m >= 0 after the plan's start (jerk: right limit at a jump); from
    its end on, q = goal + drift t and v = drift."""
    begin = 0.0
    for (d, j), (q0, v0, a0), end in zip(plan["pieces"], plan["starts"], plan["ends"]):
        if m < end:
            s = max(m * Ts - begin, 0.0)   # at its start when the breakpoint snapped onto m
            if shape == "cosine" and j != 0:
                x, w, half = math.pi * min(s / d, 1.0), d / math.pi, j * d / 2
                return (q0 + s * v0 + s * s * a0 / 2 + half * w * w * (x * x / 2 - 1 + math.cos(x)),
                        v0 + s * a0 + half * w * (x - math.sin(x)),
                        a0 + half * (1 - math.cos(x)), half / w * math.sin(x))
            return (q0 + s * (v0 + s * (a0 / 2 + s * j / 6)), v0 + s * (a0 + s * j / 2),
                    a0 + s * j, j)
        begin = end * Ts
    drift, end = plan["drift"], plan["end"]
    q = plan["goal"] + drift * (m - end) * Ts if drift != 0 and m > end else plan["goal"]
    return q, drift, 0.0, 0.0


def _rest_plan(q):
    return dict(pieces=[], starts=[], ends=[], goal=q, drift=0.0, end=0.0, arrive=0.0)


def _finish(pieces, starts, state, jmax):
    """The pieces so far, then from the target state (exact) the acceleration back to zero at
    jmax and the velocity it leaves held: (pieces, starts, goal, drift)."""
    q, v, a = state
    if a != 0:
        d, j = abs(a) / jmax, -math.copysign(jmax, a)
        pieces.append((d, j))
        starts.append((q, v, a))
        q, v, _ = _integrate([(d, j)], q, v, a)
    return pieces, starts, q, v


def _from_third_order(third, q, v, a, last, jmax, vend=0.0, aend=0.0):
    """The pieces (jerk, duration, a_start[, v]) of a third-order motion from (q, v, a) as
    (duration, jerk) pieces and their starts, then the target state `last` (exact), or the
    state reached with vend, aend (the velocity interface) when last is None."""
    pieces, starts = [], []
    for piece in third:
        j, d, a = piece[0], piece[1], piece[2]
        if len(piece) > 3:
            v = piece[3]
        pieces.append((d, j))
        starts.append((q, v, a))
        q, v, a = q + d * (v + d * (a / 2 + d * j / 6)), v + d * (a + d * j / 2), a + d * j
    return _finish(pieces, starts, last if last is not None else (q, vend, aend), jmax)


def _blend(hi, lo, lam, q, v, a, T):
    """lam hi + (1 - lam) lo, two motions of duration T from (q, v, a), on the union of their
    breakpoints: (duration, jerk) pieces and their starts."""
    cuts = set()
    for prof in (hi, lo):
        t = 0.0
        for piece in prof[:-1]:
            t += piece[1]
            if 0 < t < T:
                cuts.add(t)
    cuts = [0.0] + sorted(cuts) + [T]
    mu = 1.0 - lam
    pieces, starts = [], []
    for t0, t1 in zip(cuts[:-1], cuts[1:]):
        pa, va, aa, _ = _to.state_at(hi, v, a, t0)
        pb, vb, ab, _ = _to.state_at(lo, v, a, t0)
        ja = _to.state_at(hi, v, a, (t0 + t1) / 2)[3]
        jb = _to.state_at(lo, v, a, (t0 + t1) / 2)[3]
        pieces.append((t1 - t0, lam * ja + mu * jb))
        starts.append((q + (lam * pa + mu * pb), lam * va + mu * vb, lam * aa + mu * ab))
    return pieces, starts


def _grid_ceil(T, Ts):
    """The first whole number of samples at or above T (within 8 ulps of its count: on it)."""
    x = T / Ts
    r = math.floor(x)
    return int(r if x - r <= 8 * np.finfo(float).eps * max(x, 1.0) else r + 1)


def _plateau(v, a, vf, af, lim, hold):
    """The velocity change (v, a) -> (w, 0), w = vf - af|af|/(2 jmax) (where the target's
    acceleration was last zero), ``hold`` seconds at (w, 0), then the ramp at jmax to af: a
    motion to (vf, af) of every duration from its own without the hold on."""
    w = vf - af * abs(af) / (2 * lim.jmax)
    change = _to.velocity_change(v, a, w, 0.0, lim)
    if change is None:
        return None
    return change + [(0.0, hold, 0.0, w), (math.copysign(lim.jmax, af), abs(af) / lim.jmax, 0.0)]


def _velocity_plan(q, v, a, vf, af, tmin, lim, Ts):
    """(pieces, starts, goal, drift, N) of the velocity interface: the time-optimal change
    (N None), or with a minimum duration beyond it the first sample N at or after it at which
    a motion of N Ts exists: the midpoint of the two farthest ones, or (past the blocked
    durations) the plateau motion at the first sample at or after its own duration."""
    third = _to.velocity_change(v, a, vf, af, lim)
    if third is None:
        return None
    if tmin > sum(piece[1] for piece in third):
        n0 = _grid_ceil(tmin, Ts)
        for n in (n0, n0 + 1):
            hi = _to.farthest(v, a, vf, af, lim, n * Ts, 1)
            lo = _to.farthest(v, a, vf, af, lim, n * Ts, -1)
            if hi is not None and lo is not None:
                pieces, starts = _blend(hi[1], lo[1], 0.5, q, v, a, n * Ts)
                return _finish(pieces, starts, (q + (hi[0] + lo[0]) / 2, vf, af), lim.jmax) + (n,)
        bare = _plateau(v, a, vf, af, lim, 0.0)
        if bare is not None:
            T1 = sum(piece[1] for piece in bare)
            n = _grid_ceil(max(T1, tmin), Ts)
            third = _plateau(v, a, vf, af, lim, n * Ts - T1)
            pieces, starts = _blend(third, third, 1.0, q, v, a, n * Ts)
            p = _to.integrate(third, q, v, a)[0]
            return _finish(pieces, starts, (p, vf, af), lim.jmax) + (n,)
    return _from_third_order(third, q, v, a, None, lim.jmax, vf, af) + (None,)


def _ramp_plan(state, goal, vmax, amax, jmax, Ts, vmin=None, amin=None):
    """The plan of linear ramps from state (q, v, a) towards goal (interface, position,
    velocity, acceleration, minimum duration), or None when none is found or it cannot be
    represented. vmin, amin: the lower bounds (None: -vmax, -amax)."""
    q, v, a = state
    interface, pf, vf, af, tmin = goal
    lim = _to.Limits(vmax, amax, jmax, vmin, amin)
    N = None
    if interface == VELOCITY:
        found = _velocity_plan(q, v, a, vf, af, tmin, lim, Ts)
        if found is None:
            return None
        pieces, starts, g, drift, N = found
        arrive = N if N is not None else sum(piece[0] for piece in pieces
                                              [:len(pieces) - (1 if af != 0 else 0)]) / Ts
    else:
        found = _to.time_optimal(q, v, a, pf, vf, af, lim)
        if found is None:
            return None
        T, third, durations = found
        pieces = None
        if vf != 0 or af != 0 or tmin > T:
            # on the grid: the first whole number of samples at or after the optimum and the
            # minimum duration (or past a blocked duration, the next member's) at which a
            # motion exists
            start = max(T, tmin)
            for Tr in [start] + [d for d in durations if d > start]:
                if not math.isfinite(Tr / Ts) or Tr / Ts + 2 > MAX_PLAN_SAMPLES:
                    continue
                for n in (_grid_ceil(Tr, Ts), _grid_ceil(Tr, Ts) + 1):
                    hi = _to.farthest(v, a, vf, af, lim, n * Ts, 1)
                    lo = _to.farthest(v, a, vf, af, lim, n * Ts, -1)
                    if hi is None or lo is None:
                        continue
                    D = pf - q
                    tol = 16 * np.finfo(float).eps * (abs(q) + abs(pf) + abs(hi[0]) + abs(lo[0])
                                                      + (lim.vmax - lim.vmin) * n * Ts)
                    if not lo[0] - tol <= D <= hi[0] + tol:
                        continue
                    lam = (D - lo[0]) / (hi[0] - lo[0]) if hi[0] > lo[0] else 1.0
                    pieces, starts = _blend(hi[1], lo[1], min(max(lam, 0.0), 1.0), q, v, a, n * Ts)
                    pieces, starts, g, drift = _finish(pieces, starts, (pf, vf, af), jmax)
                    N = n
                    break
                if pieces is not None:
                    break
        if pieces is None:
            pieces, starts, g, drift = _from_third_order(third, q, v, a, (pf, vf, af), jmax)
        arrive = (N if N is not None else T / Ts)
    if not representable(pieces, starts, Ts) or not math.isfinite(g) or not math.isfinite(drift):
        return None
    ends = _ends(pieces, Ts)
    if N is not None and pieces:
        # the target exactly on sample N: the motion's last piece ends there
        k = len(pieces) - (1 if af != 0 else 0)
        ends[k - 1] = float(N)
    return dict(pieces=pieces, starts=starts, ends=ends, goal=g, drift=drift,
                end=ends[-1] if ends else 0.0, arrive=arrive)


def _cosine_plan(state, goal, vmax, amax, jmax, Ts, vmin=None, amin=None):
    """The half-cosine plan: to rest at the goal's position, or to its velocity at a = 0."""
    q, v, a = state
    interface, pf, vf, _, _ = goal
    c3 = C3["cosine"]
    Jm = _mean_jerk(jmax, "cosine")
    if interface == VELOCITY:
        pieces, starts, st = [], [], (q, v, a)
        for d, j in _change(v, a, vf, amax, Jm, "cosine"):
            if d > 0:
                pieces.append((d, j))
                starts.append(st)
                st = _integrate([(d, j)], *st, c3)
        g, drift = st[0], vf
    else:
        pieces, starts = _plan_to_rest(q, v, a, pf, vmax=vmax, amax=amax, jmax=jmax,
                                       shape="cosine")
        g, drift = pf, 0.0
    if not representable(pieces, starts, Ts):
        return None
    ends = _ends(pieces, Ts)
    return dict(pieces=pieces, starts=starts, ends=ends, goal=g, drift=drift,
                end=ends[-1] if ends else 0.0, arrive=ends[-1] if ends else 0.0)


def _can_start(v, a, vmax, jmax, shape):
    """A fresh transition of a to zero keeps |v| <= vmax (always, to rounding, for ramps). No
    tolerance: a plan from a state whose estimate is over vmax takes v that far over it."""
    if shape != "cosine":
        return True
    return abs(v + a * abs(a) / (2 * _mean_jerk(jmax, shape))) <= vmax


def canonical_target(interface, position, velocity, acceleration, *, vmax, amax, jmax,
                     shape="ramp", minimum_duration=0.0, vmin=None, amin=None, qlim=None):
    """A target (interface, position, velocity, acceleration) in canonical form (a stop as
    the velocity interface to 0, the position of a velocity target as 0), or None when it is
    invalid: the interface unknown, a value not finite, or the velocity, acceleration or
    v -+ a|a|/(2 jmax) beyond the bounds (:func:`~smoothshaper.reference.third_order.target_ok`);
    half-cosine transitions take position targets at rest and velocity targets at a = 0.
    With position limits ``qlim = (qmin, qmax)`` a target rests within them (velocity and
    acceleration 0, a position in [qmin, qmax])."""
    if interface == STOP:
        return (VELOCITY, 0.0, 0.0, 0.0, 0.0)
    if interface not in (POSITION, VELOCITY):
        return None
    if not (0 <= minimum_duration < math.inf) or (shape == "cosine" and minimum_duration != 0):
        return None
    if interface == VELOCITY:
        position = 0.0
    if not math.isfinite(position):
        return None
    if shape == "cosine" and (acceleration != 0 or (interface == POSITION and velocity != 0)):
        return None
    if qlim is not None and (velocity != 0 or acceleration != 0 or (
            interface == POSITION and not qlim[0] <= position <= qlim[1])):
        return None
    if _to.target_ok(velocity, acceleration, _to.Limits(vmax, amax, jmax, vmin, amin)) is not None:
        return None
    return (interface, float(position), float(velocity), float(acceleration),
            float(minimum_duration))


#: A re-plan under position limits from a state whose brake would cross one: not now.
WAIT = "wait"


def _extent(plan):
    """(lowest, highest) position of a ramp plan over its whole time: the ends of every piece
    and the zeros of its velocity (a quadratic in the piece's time) inside it."""
    lo = hi = plan["goal"]
    for (d, j), (q0, v0, a0) in zip(plan["pieces"], plan["starts"]):
        times = [0.0, d]
        coeffs = [j / 2, a0, v0] if j != 0 else [a0, v0]
        if any(c != 0 for c in coeffs):
            for r in np.roots(coeffs):
                if abs(r.imag) <= 1e-12 * max(abs(r.real), d) and 0 < r.real < d:
                    times.append(float(r.real))
        for t in times:
            q = q0 + t * v0 + t * t * a0 / 2 + t ** 3 * j / 6
            lo, hi = min(lo, q), max(hi, q)
    return lo, hi


def _inside(plan, qlim, tol):
    lo, hi = _extent(plan)
    return lo >= qlim[0] - tol and hi <= qlim[1] + tol


def _bounded_plan(state, goal, vmax, amax, jmax, Ts, vmin, amin, qlim):
    """The plan under position limits: the time-optimal one when it stays inside; else the
    brake to rest, a rest until the next sample, and the move from there (with what is left
    of the minimum duration, then without); WAIT when not even the brake stays inside."""
    tol = 16 * np.finfo(float).eps / 2 * (abs(qlim[0]) + abs(qlim[1]))
    direct = _ramp_plan(state, goal, vmax, amax, jmax, Ts, vmin, amin)
    if direct is None:
        return None
    if _inside(direct, qlim, tol):
        return direct
    if goal[0] == VELOCITY:
        return WAIT
    brake = _ramp_plan(state, (VELOCITY, 0.0, 0.0, 0.0, 0.0), vmax, amax, jmax, Ts, vmin, amin)
    if brake is None:
        return None
    if not _inside(brake, qlim, tol):
        return WAIT
    S = math.ceil(brake["end"])
    tmin = goal[4]
    for left in ([max(tmin - S * Ts, 0.0), 0.0] if tmin else [0.0]):
        move = _ramp_plan((brake["goal"], 0.0, 0.0), (POSITION, goal[1], 0.0, 0.0, left), vmax,
                          amax, jmax, Ts, vmin, amin)
        if move is None:
            return None
        if not _inside(move, qlim, tol):
            continue
        wait = [(S * Ts - brake["end"] * Ts, 0.0)] if S > brake["end"] else []
        return dict(pieces=brake["pieces"] + wait + move["pieces"],
                    starts=brake["starts"] + [(brake["goal"], 0.0, 0.0)] * len(wait)
                    + move["starts"],
                    ends=brake["ends"] + [float(S)] * len(wait) + [e + S for e in move["ends"]],
                    goal=move["goal"], drift=move["drift"], end=move["end"] + S,
                    arrive=move["arrive"] + S)
    return WAIT


def _run(targets, *, vmax, amax, jmax, Ts, q0=0.0, shape="ramp", velocity=None,
         acceleration=None, interface=None, start=None, minimum_duration=None, vmin=None,
         amin=None, qlim=None):
    """(out, goal, dropped): the samples, the running plan's goal at each sample (where it
    rests, or from where it drifts on), and 1 at each sample where a target was dropped.

    targets: the position at every sample (position interface; ignored for the others);
    velocity, acceleration: arrays of the same length (default 0); interface: POSITION,
    VELOCITY or STOP per sample (default POSITION). An invalid target is ignored (the held one
    kept), as a non-finite position is. start: (q, v, a, target) the generator continues
    from (its plan to target formed at the sample before the first), default at rest on q0.
    vmin, amin: the lower velocity and acceleration bounds (None: -vmax, -amax; ramps only).
    qlim: the position limits (qmin, qmax) or None (ramps only): every plan stays inside
    (:func:`_bounded_plan`), q unrounded (the generator holds its q to them)."""
    x = np.asarray(targets, dtype=np.float64)
    n = x.size
    vel = np.zeros(n) if velocity is None else np.asarray(velocity, dtype=np.float64)
    acc = np.zeros(n) if acceleration is None else np.asarray(acceleration, dtype=np.float64)
    itf = np.zeros(n, dtype=int) if interface is None else np.asarray(interface, dtype=int)
    tmin = np.zeros(n) if minimum_duration is None else np.asarray(minimum_duration, dtype=float)
    out = np.empty((n, 4))
    goals = np.empty(n)
    dropped = np.zeros(n, dtype=bool)
    make = _cosine_plan if shape == "cosine" else _ramp_plan
    if qlim is not None:
        def make(state, goal, vmax, amax, jmax, Ts, vmin, amin):
            return _bounded_plan(state, goal, vmax, amax, jmax, Ts, vmin, amin, qlim)
    if vmin is None and amin is None:
        evaluate = _evaluate
    else:
        # asymmetric limits: v and a held to their bounds (the rounding of a segment's sum of
        # terms of the larger bound's size, the generator's rule)
        lo_v = -vmax if vmin is None else vmin
        lo_a = -amax if amin is None else amin

        def evaluate(plan, m, Ts, shape):
            q, v, a, j = _evaluate(plan, m, Ts, shape)
            return q, min(max(v, lo_v), vmax), min(max(a, lo_a), amax), j
    plan, i0 = _rest_plan(float(q0)), 0
    held = goal = (POSITION, float(q0), 0.0, 0.0, 0.0)
    refused = False
    if start is not None:
        q, v, a, target = start
        goal = held = target
        new = make((q, v, a), target, vmax, amax, jmax, Ts, vmin, amin)
        if new is None:
            raise ParameterError("target", f"target={target!r}: the motion from (q, v, a) = "
                                 f"({q!r}, {v!r}, {a!r}) cannot be represented")
        plan, i0 = new, -1
    for i in range(n):
        t = canonical_target(int(itf[i]), float(x[i]), float(vel[i]), float(acc[i]), vmax=vmax,
                             amax=amax, jmax=jmax, shape=shape, minimum_duration=float(tmin[i]),
                             vmin=vmin, amin=amin, qlim=qlim)
        if t is not None and t != held:   # a new target (invalid: ignored)
            held, refused = t, False
        state = evaluate(plan, i - i0, Ts, shape)
        if held != goal and not refused and _can_start(state[1], state[2], vmax, jmax, shape):
            try:
                with np.errstate(all="ignore"):
                    new = make(state[:3], held, vmax, amax, jmax, Ts, vmin, amin)
            except (OverflowError, ValueError, ZeroDivisionError):
                new = None
            if new is WAIT:   # position limits: the running plan goes on, tried again next
                pass
            elif new is not None:
                plan, goal, i0 = new, held, i
                state = evaluate(plan, 0, Ts, shape)
            else:   # dropped: the running plan goes on; not tried again until it changes
                refused = True
                dropped[i] = True
        out[i] = state
        goals[i] = plan["goal"]
    return out, goals, dropped


def time_optimal_reference(targets, *, vmax, amax, jmax, Ts, q0=0.0,
                           shape="ramp") -> np.ndarray:
    """``(n, 4)`` q, v, a, j of the time-optimal online generator for a staircase of targets.

    Sample i is at time i Ts; before sample 0 the generator rests at ``q0``. On every sample
    whose target differs from the running plan's goal, a new plan starts from the exact state
    of the running one at that instant (half-cosine transitions: from the first such sample
    whose state allows it). A target whose plan cannot be represented (:func:`representable`:
    a non-finite value, or more than 2^52 samples) is dropped: the running plan goes on and
    the target is not tried again until it changes; a non-finite target is ignored.

    ParameterError naming ``targets`` (not a one-dimensional array of real numbers), a bound,
    ``Ts``, ``q0``, ``shape``, or the limits :func:`reach` finds infeasible."""
    x = _real_array("targets", targets, ndim=1)
    q0 = _finite("q0", q0)
    feasible = reach(vmax, amax, jmax, Ts, shape)     # checks the limits, Ts and shape
    quantity = feasible["quantity"]
    if quantity is not None:
        arguments = [n for n in ("vmax", "amax", "jmax") if n in quantity]
        name = _reach.named(quantity, arguments, feasible["duration"])
        raise ParameterError(name, f"{name}: vmax={vmax!r}, amax={amax!r}, jmax={jmax!r}, "
                             f"Ts={Ts!r}: {quantity} is out of the feasible range: no move "
                             "that reaches vmax can be planned")
    return _run(x, vmax=float(vmax), amax=float(amax), jmax=float(jmax), Ts=float(Ts), q0=q0,
                shape=_choice("shape", shape, SHAPES))[0]
