# SPDX-License-Identifier: Apache-2.0
"""NumPy reference of the multi-axis online generator (the test oracle for ``sms_multi_generator``).

Written from the planning rules stated in ``c/include/smoothshaper/multi_generator.h`` and
``docs/multi-axis.md``; it never calls the C core. The structure differs on purpose: moves are
kept as absolute-time records (start time, start state, phases) and evaluated through a
generic velocity-transition formula, and the search for the first transition is written over
whole vectors. What must match to the last bit does: the arithmetic of the plan and of the
evaluation follows the C core's order, and the planner's square and cube roots are the C
core's Newton iterations (:func:`_newton_sqrt`, :func:`_newton_cbrt`; the C core uses no libm
while stepping). A sample in the last jerk phase of a transition moves its acceleration by
``jerk * dT`` when the transition's end moves by ``dT``: relative to amax, ``dT / Tj``, with
``Tj`` the jerk phase, which can be a small fraction ``rho`` of the transition. A plan that
differs in its last bits (one ulp of a root, amplified by the root search) therefore shows up
at ``eps / rho`` (up to 3.5e-13 with libm roots); with the same roots the plans agree to the
last bit and the outputs to rounding (the tests: 1e-12 of the move and of each limit).

* :func:`reach` -- the limit sets the generator can plan with (its feasible region), per axis;
* :func:`transition` -- shortest S-curve velocity change under per-axis limits;
* :func:`phase_duration` -- time-optimal phase-synchronised rest-to-rest duration;
* :func:`multi_axis_reference` -- the sampled generator output for a staircase of targets.
"""
from __future__ import annotations

import math

import numpy as np

from . import filtering as _filtering
from ._checks import check_Ts
from .. import time_optimal as _single
from .._reach import named as _named
from .._checks import finite_vector as _finite_vector, real_array as _real_array
from ..errors import ParameterError

__all__ = ["reach", "transition", "phase_duration", "multi_axis_reference"]

_EPS = np.finfo(np.float64).eps


def _reduce(x: float, base: float) -> tuple[float, float]:
    """x scaled into [1, base) by powers of base (4 for sqrt, 8 for cbrt; exact in binary
    floating point) and the factor 2^k the root is scaled back by, as the C planner does."""
    scale = 1.0
    while x >= base:
        x *= 1.0 / base
        scale *= 2
    while x < 1:
        x *= base
        scale *= 0.5
    return x, scale


def _newton_sqrt(x: float) -> float:
    """sqrt(x) as the C planner computes it: scaled into [1, 4) by powers of 4, 7 Newton
    steps from (1 + x)/2, scaled back (within an ulp of math.sqrt); 0 for x <= 0."""
    if not x > 0:
        return np.float64(0.0)  # 1/0 is then inf, as in C
    if x == math.inf:
        return x
    x, scale = _reduce(x, 4.0)
    y = (1 + x) * 0.5
    for _ in range(7):
        y = (y + x / y) * 0.5
    return y * scale


def _newton_cbrt(x: float) -> float:
    """cbrt(x), x >= 0, as the C planner computes it: scaled into [1, 8) by powers of 8, 8
    Newton steps from 1 + x/7, scaled back (within an ulp of math.cbrt); 0 for x <= 0."""
    if not x > 0:
        return np.float64(0.0)  # 1/0 is then inf, as in C
    if x == math.inf:
        return x
    x, scale = _reduce(x, 8.0)
    y = 1 + x * (1.0 / 7.0)
    for _ in range(8):
        y = (2 * y + x / (y * y)) * (1.0 / 3.0)
    return y * scale
_CAP = 2.0 ** 60  # limit/|change| ratios are capped (a conservative, lower limit)


def _ratio(lim, d) -> float:
    """min(lim/d, 2^60) as a NumPy scalar: a ratio that underflows to 0 divides like C (inf or
    nan, the plan then refuses the move) instead of raising ZeroDivisionError."""
    with np.errstate(over="ignore", under="ignore"):
        return np.float64(min(np.min(lim / d), _CAP))


def _unit_time(A: float, J: float) -> tuple[float, float]:
    """Shortest unit velocity change with acceleration A and jerk J: (duration, rho)."""
    A, J = np.float64(A), np.float64(J)  # IEEE division by an underflowed 0, as in C
    if not (A < np.finfo(np.float64).max and J < np.finfo(np.float64).max):
        return 0.0, 0.5
    if A * A <= J:
        Tj = A / J
        T = 1.0 / A + Tj
        return T, Tj / T
    Tj = 1.0 / _newton_sqrt(J)
    return 2.0 * Tj, 0.5


#: Ratios limit/change the planner forms stay this far below its cap 2^60 for the moves that
#: reach vmax, stop and reverse (|dV| up to 2 vmax, displacements up to a few h).
RATIO_BOUND = 2.0 ** 56
#: The landing is exact for displacements up to this many times h (and durations up to this
#: many times T): their unit accelerations squared stay normal, the durations squared finite.
MOVE_SPAN = 16.0


def reach(vmax, amax, jmax, Ts: float, precision: str = "double") -> dict:
    """The feasible region of the multi-axis generator: can every axis's move reach its vmax?

    Derived from the planner's arithmetic, axis by axis (the first axis out of range is
    named). With h and T the distance and the duration of axis i's move from rest to vmax_i
    and back to rest (the single-axis move with linear jerk ramps,
    :func:`smoothshaper.time_optimal.reach`), and MAX, MIN, eps the largest and smallest normal
    number of the precision and its epsilon, axis i is feasible when, in this order:

    1. the single-axis region holds (the planner forms the same products: J dv, squares of
       accelerations, durations and distances of the move to vmax);
    2. amax/vmax, jmax/vmax, amax/h, jmax/h <= 2^56: the planner turns a velocity change dV
       or a displacement d into unit limits ``amax/|dV|``, ``jmax/|d|``, capped at 2^60; the
       move to vmax, its stop and its reversal (``|dV| <= 2 vmax``, ``|d|`` up to a few h)
       stay a factor 16 below the cap, so they are never lengthened;
    3. (16 T)^2 <= MAX, (amax/(16 h))^2 >= MIN/eps and jmax/(16 h) >= MIN/eps: the landing
       squares durations and unit accelerations, and divides by the unit jerk, for
       displacements up to 16 h.

    A phase-synchronised move takes the minimum of the axes' ratios, so it adds no condition.
    Ts must be a positive number of the precision (not 0 once rounded, at most MAX).

    Parameters
    ----------
    vmax, amax, jmax : array_like, shape (axes,) or scalar
        Per-axis limits, finite and > 0 (units of axis i per s, s^2, s^3).
    Ts : float
        Sample period [s], finite and > 0.
    precision : {"double", "float"}
        The build whose numbers bound the region.

    Returns
    -------
    dict
        ``axis`` (the first refused axis, None when feasible or when ``Ts`` is refused),
        ``quantity`` (None when feasible, else the quantity out of range: ``"Ts"``, a
        quantity of :func:`smoothshaper.time_optimal.reach`, ``"amax/vmax"``,
        ``"jmax/vmax"``, ``"amax/h"``, ``"jmax/h"``, ``"the duration to reach vmax,
        squared"``, ``"(amax/h)^2"``), ``parameter`` (the argument to change: ``"Ts"`` or
        e.g. ``"jmax[1]"``, the one the MultiAxisGenerator names) and the refused axis's
        ``distance`` h and ``duration`` T (0 before they are formed).

    Raises
    ------
    ParameterError
        Naming a limit (``vmax[i]``) that is not finite and > 0, ``Ts``, or ``precision``.
    """
    if precision not in ("double", "float"):
        raise ParameterError("precision", f"precision must be 'double' or 'float', got "
                                          f"{precision!r}")
    Ts = check_Ts(Ts)
    axes = max(np.size(vmax), np.size(amax), np.size(jmax))
    vmax, amax, jmax = _limits(vmax, amax, jmax, axes)
    info = np.finfo(np.float32 if precision == "float" else np.float64)
    big, unit_tiny = float(info.max), float(info.tiny) / float(info.eps)
    out = dict(axis=None, quantity=None, parameter=None, distance=0.0, duration=0.0)
    with np.errstate(over="ignore", under="ignore"):
        rounded = float(np.float32(Ts)) if precision == "float" else Ts
    if not (rounded > 0 and Ts <= big and Ts <= _single.TS_MAX):
        out.update(quantity="Ts", parameter="Ts")
        return out
    for i in range(axes):
        v, a, j = float(vmax[i]), float(amax[i]), float(jmax[i])
        single = _single.reach(v, a, j, Ts, "ramp", precision)
        h, T = single["distance"], single["duration"]
        quantity = single["quantity"]
        if quantity is None:
            au, ju = a / (MOVE_SPAN * h), j / (MOVE_SPAN * h)
            for name, holds in (("amax/vmax", a <= RATIO_BOUND * v),
                                ("jmax/vmax", j <= RATIO_BOUND * v),
                                ("amax/h", a <= RATIO_BOUND * h),
                                ("jmax/h", j <= RATIO_BOUND * h),
                                ("the duration to reach vmax, squared",
                                 (MOVE_SPAN * T) * (MOVE_SPAN * T) <= big),
                                ("(amax/h)^2", au * au >= unit_tiny),
                                ("jmax/h", ju >= unit_tiny)):
                if not holds:
                    quantity = name
                    break
        if quantity is not None:
            arguments = [n for n in ("vmax", "amax", "jmax") if n in quantity] or \
                ["vmax", "amax", "jmax"]
            parameter = _named(quantity, arguments, T)
            out.update(axis=i, quantity=quantity, distance=h, duration=T,
                       parameter=parameter if parameter == "Ts" else f"{parameter}[{i}]")
            return out
    return out


def _limits(vmax, amax, jmax, axes: int):
    """Per-axis limits as float64 vectors of length ``axes`` (a scalar applies to every axis);
    ParameterError naming ``vmax[i]`` etc."""
    out = []
    for name, value in (("vmax", vmax), ("amax", amax), ("jmax", jmax)):
        v = _real_array(name, value)
        if v.ndim == 0:
            v = np.full(axes, float(v))
        if v.shape != (axes,):
            raise ParameterError(name, f"{name} must hold {axes} values, got shape {v.shape}")
        bad = np.flatnonzero(~(np.isfinite(v) & (v > 0)))
        if bad.size:
            raise ParameterError(f"{name}[{bad[0]}]", f"{name}[{bad[0]}] must be finite and > 0, "
                                 f"got {float(v[bad[0]])!r}")
        out.append(v)
    return out


def transition(dV, vmax, amax, jmax) -> tuple[float, float]:
    """Shortest straight velocity change ``dV`` under per-axis limits.

    Every axis follows ``v_i(t) = V_i + dV_i F(t/T)`` with one normalised S-curve ``F`` (jerk
    ``+c, 0, -c`` over the fractions ``rho, 1 - 2 rho, rho`` of ``T``); with the scaled limits
    ``A = min_i amax_i/|dV_i|``, ``J = min_i jmax_i/|dV_i|``: ``T = 1/A + A/J``,
    ``rho = (A/J)/T`` if ``A^2 <= J``, else ``T = 2/sqrt(J)``, ``rho = 1/2`` (the double-S
    velocity ramp, Biagiotti and Melchiorri 2008, "Trajectory Planning for Automatic Machines
    and Robots", section 3.4, applied to the path parameter).

    Parameters
    ----------
    dV : array_like, shape (axes,)
        Velocity change per axis [units of axis i per s]; finite.
    vmax, amax, jmax : array_like, shape (axes,) or scalar
        Per-axis limits (finite, > 0); vmax is checked but does not enter.

    Returns
    -------
    T : float
        Duration [s] (0 when dV is zero).
    rho : float
        Jerk-phase fraction in (0, 1/2].

    Raises
    ------
    ParameterError
        Naming ``dV`` or the offending limit, e.g. ``amax[2]``.
    """
    dV = _finite_vector("dV", dV)
    _, amax, jmax = _limits(vmax, amax, jmax, dV.size)
    return _transition(dV, None, amax, jmax)


def _transition(dV, vmax, amax, jmax) -> tuple[float, float]:
    """:func:`transition` without the checks (the planner's inner loop)."""
    d = np.abs(dV)
    nz = d > 0
    if not nz.any():
        return 0.0, 0.5
    return _unit_time(_ratio(amax[nz], d[nz]), _ratio(jmax[nz], d[nz]))


def _first_rho(dV, T1, amax, jmax) -> float:
    """Jerk fraction of the first transition, the change dV over T1 (multi_generator.c
    first_rho): the shortest transition's own rho when it fits T1, else the rho that
    minimises the larger of the peak ratios, A/(J T1) (at most 1/2: the shortest
    transition's jerk phase kept), for an arrival rounded onto an earlier sample."""
    d = np.abs(dV)
    nz = d > 0
    if not nz.any():
        return 0.5
    A, J = _ratio(amax[nz], d[nz]), _ratio(jmax[nz], d[nz])
    T, rho = _unit_time(A, J)
    if T <= T1:
        return rho
    return min(A / (J * T1), 0.5)


def phase_duration(delta, *, vmax, amax, jmax) -> float:
    """Time-optimal jerk-limited straight (phase-synchronised) rest-to-rest duration.

    The path parameter ``s`` in [0, 1] of ``q = start + s delta`` has the limits
    ``min_i vmax_i/|delta_i|``, ``min_i amax_i/|delta_i|``, ``min_i jmax_i/|delta_i|``; the
    duration is the closed form of the double-S for them (Biagiotti and Melchiorri 2008,
    "Trajectory Planning for Automatic Machines and Robots", section 3.4, double S velocity
    profile).

    Parameters
    ----------
    delta : array_like, shape (axes,)
        Displacement per axis; finite (all zero gives 0).
    vmax, amax, jmax : array_like, shape (axes,) or scalar
        Per-axis limits, finite and > 0 (units of axis i per s, s^2, s^3).

    Returns
    -------
    float
        Duration [s] in continuous time; inf only when it exceeds the largest double
        (computed from the path's time scales, finite for any finite duration).

    Raises
    ------
    ParameterError
        Naming ``delta`` or the offending limit, e.g. ``jmax[1]``.
    """
    d = _finite_vector("delta", delta)
    vmax, amax, jmax = _limits(vmax, amax, jmax, d.size)
    return _phase_duration(d, vmax, amax, jmax)


def _phase_duration(delta, vmax, amax, jmax) -> float:
    """:func:`phase_duration` without the checks.

    Written in the path's time scales tv = 1/V, ta = 1/sqrt(A), tj = 1/cbrt(J) (each the
    largest over the moving axes: |d_i|/vmax_i, sqrt(|d_i|/amax_i), cbrt(|d_i|/jmax_i)),
    which stay finite whenever the duration does; the double-S in units of ta then has A = 1,
    V = 1/x, J = 1/y^3 with x = tv/ta, y = tj/ta. The limits V, A, J themselves under- or
    overflow for displacements and limits far apart (|d| = 1e300 with amax = 1e-300)."""
    d = np.abs(np.asarray(delta, dtype=np.float64))
    nz = d > 0
    if not nz.any():
        return 0.0
    with np.errstate(over="ignore", under="ignore", divide="ignore", invalid="ignore"):
        dn = d[nz]
        tv = np.max(dn / np.asarray(vmax, dtype=np.float64)[nz])
        ta = np.max(np.sqrt(dn) / np.sqrt(np.asarray(amax, dtype=np.float64)[nz]))
        tj = np.max(np.cbrt(dn) / np.cbrt(np.asarray(jmax, dtype=np.float64)[nz]))
        x, y = tv / ta, tj / ta
        y3 = y * y * y                        # A/J in units of ta (= A^2/J, A = 1)
        Tv = 1.0 / x + y3 if x * y3 <= 1.0 else 2.0 * np.sqrt(y3 / x)
        if Tv < x:                            # V is reached: cruise for the rest
            return float((x + Tv) * ta)
        # V not reached: the peak velocity c solves c^2 + c A^2/J = A (acceleration limit
        # held), as 2/(r + sqrt(r^2 + 4)) with r = A^2/J; else the jerk-limited move
        c = 2.0 / (y3 + np.hypot(y3, 2.0))
        if c >= y3:
            return float(2.0 * (c + y3) * ta)
        return float(4.0 * np.cbrt(0.5) * y * ta)


def _kappa(u, T1, vmax, amax, jmax) -> float:
    """Smallest kappa = T1/2 + tau + T2/2 with tau >= 0 and |u/kappa| <= vmax: kv =
    max |u_i|/vmax_i when the cruise at u/kv leaves room for its stop (the right side
    T1/2 + T(u/kappa)/2 decreases with kappa), else the closed form of tau = 0."""
    d = np.abs(u)
    nz = d > 0
    if not nz.any():
        return T1 / 2
    kv = np.max(d[nz] / vmax[nz])
    # kv when the cruise at u/kv leaves room for the stop (tau >= 0: the move reaches a
    # vmax); decided before the unit limits limit/|u|, which underflow for long moves
    if kv >= T1 / 2 + _transition(u / kv, vmax, amax, jmax)[0] / 2:
        return kv
    kv = float(kv)
    au = _ratio(amax[nz], d[nz])
    ju = _ratio(jmax[nz], d[nz])
    b = (T1 + au / ju) / 2
    kh = (b + _newton_sqrt(b * b + 2.0 / au)) / 2
    if kh > ju / (au * au):
        c, q = T1 / 2, 1.0 / _newton_sqrt(ju)
        y = _newton_sqrt(c) + _newton_cbrt(q)
        for _ in range(100):
            y_next = y - ((y * y - c) * y - q) / (3 * y * y - c)
            if not y_next < y:
                break
            y = y_next
        kh = y * y
    return max(kh, kv)


def _candidate(D, V, T1, lim):
    """The move with first transition T1: (excess, W, tau, T2, rho2), where excess =
    T(W - V) - T1 <= 0 when the velocity change fits in T1."""
    u = D - V * (T1 / 2)
    kappa = _kappa(u, T1, *lim)
    W = u / kappa
    T2, rho2 = _transition(W, *lim)
    tau = max(kappa - T1 / 2 - T2 / 2, 0.0)
    excess = _transition(W - V, *lim)[0] - T1
    return excess, W, tau, T2, rho2


_ROOT_TOL = 2 * _EPS  # the bracket ends as neighbouring doubles


def _smallest_feasible(D, V, lo, e_lo, hi, lim) -> float:
    """Smallest T1 in [lo, hi] with excess <= 0 (excess(lo) > 0): Illinois regula falsi
    (Dowell and Jarratt 1971) with a bisection every fourth step, each new point at least a
    quarter of the tolerance inside the bracket; returns the feasible end."""
    e_hi = _candidate(D, V, hi, lim)[0]
    if not e_hi <= 0:
        return hi
    last = None  # which end moved last
    for step in range(200):
        if not hi - lo > _ROOT_TOL * hi:
            break
        x = lo + (hi - lo) / 2 if step % 4 == 3 else lo + (hi - lo) * (e_lo / (e_lo - e_hi))
        margin = 0.25 * _ROOT_TOL * hi
        x = min(max(x, lo + margin), hi - margin)
        e = _candidate(D, V, x, lim)[0]
        if e <= 0:
            hi, e_hi = x, e
            if last == "hi":
                e_lo *= 0.5
            last = "hi"
        else:
            lo, e_lo = x, e
            if last == "lo":
                e_hi *= 0.5
            last = "lo"
    return hi


_REFUSED = "refused"               # _plan: the move cannot be represented in double
_MAX_MOVE_SAMPLES = 2.0 ** 52       # longer moves are refused (exact sample counts)


def _plan(p, V, B, off, Ts, lim):
    """A move from (p, V, a = 0) to B; its first sample at move time ``off``. None: at rest;
    _REFUSED: the displacement or the duration is not finite, or the move is longer than
    2^52 samples (the target is then dropped). Within feasible limits (:func:`reach`) nothing
    else refuses a move: the landing (:func:`_kappa`) decides on the cruise bound before it
    forms the displacement's unit limits, which underflow for long moves."""
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        return _plan_unchecked(p, V, B, off, Ts, lim)


def _plan_unchecked(p, V, B, off, Ts, lim):
    D = B - p
    if not np.all(np.isfinite(D)):
        return _REFUSED
    if not V.any() and not D.any():
        return None
    lo = _transition(V, *lim)[0]
    e_lo = _candidate(D, V, lo, lim)[0]
    if e_lo > 0:
        vmax, amax, jmax = lim
        hi = _unit_time(float(np.min(amax / (2 * vmax))),
                        float(np.min(jmax / (2 * vmax))))[0] * (1 + 16 * _EPS)
        lo = _smallest_feasible(D, V, lo, e_lo, max(hi, lo), lim)
    T1 = lo
    _, W, tau, T2, rho2 = _candidate(D, V, T1, lim)
    total = T1 + tau + T2
    nu = (total - off) / Ts
    nu = nu if nu > 0 else 0.0
    if not (math.isfinite(total) and nu <= _MAX_MOVE_SAMPLES):
        return _REFUSED
    # a planned end within 2 eps after a sample arrives on it (multi_generator.c GRID_TOL)
    n_round = math.floor(nu + 0.5)
    k_end = n_round if abs(n_round - nu) <= 2 * _EPS * max(nu, 1.0) else math.floor(nu) + 1
    tau = max(tau + (k_end * Ts + off - (T1 + tau + T2)), 0.0)
    kappa = T1 / 2 + tau + T2 / 2
    u = D - V * (T1 / 2)
    W = u / kappa if kappa > 0 else np.zeros_like(u)
    rho1 = _first_rho(W - V, T1, lim[1], lim[2])
    if not (np.all(np.isfinite(W)) and np.all(np.isfinite(W - V)) and math.isfinite(tau)
            and math.isfinite(rho1) and math.isfinite(rho2)):
        return _REFUSED
    return dict(p=p.copy(), V=V.copy(), W=W, goal=B.copy(), T1=T1, rho1=rho1, tau=tau, T2=T2,
                rho2=rho2, off=off, k_end=k_end)


def _s_curve(x: float, xs: float, ys: float, rho: float):
    """(G, F, F', F'') of the normalised transition on the piece that contains the sample,
    chosen by xs and ys (x and the fraction left 1 - x, each with its breakpoints snapped):
    F' and F'' there, that piece's G and F at x itself (ys <= 0: finished). The last jerk
    phase is located and evaluated by the fraction left, never by x against ``1 - rho``,
    which rounds by half an ulp of 1, ``eps / (4 rho)`` of that phase: a sample on the
    rounded breakpoint reported F' above the peak ``ap``. The pieces continue each other to
    second order, so the position keeps the rounding of the sample's own time while the
    acceleration and jerk take the right limit."""
    ap = 1.0 / (1.0 - rho)
    if not ys > 0:
        return x - 0.5, 1.0, 0.0, 0.0
    if xs < rho:
        return ap * x * x * x / (6 * rho), ap * x * x / (2 * rho), ap * xs / rho, ap / rho
    if ys > rho:
        return ap * (x * x / 2 - rho * x / 2 + rho * rho / 6), ap * (x - rho / 2), ap, 0.0
    y = 1 - x
    return (x - 0.5 + ap * y * y * y / (6 * rho), 1 - ap * y * y / (2 * rho),
            ap * ys / rho, -ap / rho)


_SNAP = 64 * _EPS


def _snap(x, *breaks, tol=_SNAP):
    """x moved onto a breakpoint within tol (that sample then takes the right limit)."""
    for b in breaks:
        if abs(x - b) <= tol:
            x = b
    return x


def _time_left(m, k, t, Ts):
    """Time from sample k (move time t) to the end of the stop. With a cruise the plan ends on
    the arrival sample, so it is the whole number of samples left times Ts (no rounding of
    a long move's time); without one the stop follows the first transition and is counted
    from T1 (the arrival may be rounded before T1 + T2)."""
    if m["tau"] > 0:
        return (m["k_end"] - k) * Ts
    return m["T2"] - (t - m["T1"])


def _in_stop(m, left) -> bool:
    return m["T2"] > 0 and left <= m["T2"] + _SNAP * m["T2"]


def _cruise_position(m, t):
    """Position at move time t >= T1 - SNAP T1 on the cruise (or its continuation)."""
    q1 = m["p"] + (m["V"] + m["W"]) * (m["T1"] / 2)
    return q1 + m["W"] * (t - m["T1"])


def _evaluate(m, t, left):
    """(axes, 4) output of move m at move time t, time ``left`` to its end (:func:`_time_left`).
    Each phase is located by its own time and each breakpoint snapped within SNAP of its own
    phase's length; the stop is counted back from the goal, W T2 G(y) before it with y the
    fraction of the stop left (the S-curve is point-symmetric)."""
    T1, T2 = m["T1"], m["T2"]
    p, V, W = m["p"], m["V"], m["W"]
    # sums in the C core's order, left to right (so the two round alike)
    if t < T1 - _SNAP * T1:
        x = t / T1
        G, F, dF, ddF = _s_curve(x, _snap(x, m["rho1"]), _snap(1 - x, m["rho1"]), m["rho1"])
        dV = W - V
        return np.stack([p + V * t + dV * (T1 * G), V + dV * F, dV * (dF / T1),
                         dV * (ddF / (T1 * T1))], axis=-1)
    if not _in_stop(m, left):
        z = np.zeros_like(W)
        return np.stack([_cruise_position(m, t), W, z, z], axis=-1)
    y = left / T2
    xs = _snap(1 - y, 0.0, m["rho2"])
    _, _, dF, ddF = _s_curve(xs, xs, _snap(y, m["rho2"], 0.0), m["rho2"])
    Gy, Fy, _, _ = _s_curve(y, y, 1 - y, m["rho2"])
    return np.stack([m["goal"] - W * (T2 * Gy), W * Fy, -W * (dF / T2),
                     -W * (ddF / (T2 * T2))], axis=-1)


def multi_axis_reference(targets, *, vmax, amax, jmax, Ts: float, sync: str = "phase",
                         q0=None, stages=None, qmin=None, qmax=None) -> np.ndarray:
    """Sampled output of the multi-axis generator for a staircase of target vectors, written
    independently of the C code (the same plan in NumPy, then the reference filters).

    The planning rules are those of ``c/include/smoothshaper/multi_generator.h`` (moves of
    velocity transitions, cruise and stop; blending of targets that change mid-motion;
    arrival on the sample grid), written here over whole vectors.

    Parameters
    ----------
    targets : array_like, shape (n, axes)
        Target vector at each sample; finite.
    vmax, amax, jmax : array_like, shape (axes,) or scalar
        Per-axis limits, finite and > 0 (units of axis i per s, s^2, s^3).
    Ts : float
        Sample period [s], finite and > 0.
    sync : {"phase", "independent"}
        One common straight move for all axes, or one move per axis.
    q0 : array_like, shape (axes,), optional
        Rest position before the first sample (default 0).
    stages : list of Stage, or list of lists of Stage, optional
        Vibration stages for every axis, or one list per axis; each axis's q, v, a, j are
        filtered by :func:`smoothshaper.reference.filtering.filter` from rest (q at q0, the
        others at 0).
    qmin, qmax : array_like, shape (axes,), optional
        Position limits per axis (NaN or None entries: none). A target component outside
        keeps that axis's previous target; a group with a limited axis does not blend a
        changed target but starts it from rest at the arrival (multi_generator.h).

    Returns
    -------
    ndarray, shape (n, axes, 4)
        q, v, a, j of every axis at every sample.

    Raises
    ------
    ParameterError
        Naming the offending argument (``targets``, ``vmax[i]``, ``Ts``, ``sync``, ``q0``,
        or a stage's parameter).
    """
    x = _real_array("targets", targets)
    if x.ndim != 2 or x.shape[1] == 0 or not np.all(np.isfinite(x)):
        raise ParameterError("targets", f"targets must be a finite array of shape (n, axes), "
                                        f"got shape {x.shape}")
    vmax, amax, jmax = _limits(vmax, amax, jmax, x.shape[1])
    Ts = check_Ts(Ts)
    feasible = reach(vmax, amax, jmax, Ts)
    if feasible["quantity"] is not None:
        i = feasible["axis"]
        where = "" if i is None else (f"axis {i}: vmax[{i}]={float(vmax[i])!r}, "
                                      f"amax[{i}]={float(amax[i])!r}, jmax[{i}]={float(jmax[i])!r}, ")
        raise ParameterError(feasible["parameter"],
                             f"{where}Ts={Ts!r}: {feasible['quantity']} is out of the feasible "
                             f"range: no move of {'the axes' if i is None else f'axis {i}'} "
                             "that reaches its vmax can be planned")
    if sync not in ("phase", "independent"):
        raise ParameterError("sync", f"sync must be 'phase' or 'independent', got {sync!r}")
    if q0 is not None:
        q0 = _finite_vector("q0", q0)
        if q0.size != x.shape[1]:
            raise ParameterError("q0", f"q0 must hold {x.shape[1]} values, got {q0.size}")
    bounded = np.zeros(x.shape[1], dtype=bool)
    if qmin is not None or qmax is not None:
        lo = np.array([np.nan if v is None else v for v in np.broadcast_to(
            np.asarray(qmin, dtype=object), (x.shape[1],))], dtype=float)
        hi = np.array([np.nan if v is None else v for v in np.broadcast_to(
            np.asarray(qmax, dtype=object), (x.shape[1],))], dtype=float)
        bounded = np.isfinite(lo) & np.isfinite(hi)
        x = x.copy()
        for i in np.flatnonzero(bounded):   # an outside component keeps the previous target
            held = (q0[i] if q0 is not None else
                    lo[i] if lo[i] > 0 else hi[i] if hi[i] < 0 else 0.0)
            for k in range(x.shape[0]):
                if lo[i] <= x[k, i] <= hi[i]:
                    held = x[k, i]
                x[k, i] = held
        if q0 is None:
            q0 = np.where(bounded & (lo > 0), lo, np.where(bounded & (hi < 0), hi, 0.0))
    out = _profile(x, vmax=vmax, amax=amax, jmax=jmax, Ts=Ts, sync=sync, q0=q0,
                   bounded=bounded)
    if stages is None:
        return out
    axes = out.shape[1]
    per_axis = (len(stages) == axes and all(isinstance(s, (list, tuple)) for s in stages))
    lists = [list(s) for s in stages] if per_axis else [list(stages)] * axes
    rest = np.zeros(axes) if q0 is None else np.asarray(q0, dtype=np.float64)
    for i, lst in enumerate(lists):
        for m in range(4):
            if lst:
                zi = _filtering.filter_zi(lst, Ts=Ts, x0=rest[i] if m == 0 else 0.0)
                out[:, i, m] = _filtering.filter(lst, out[:, i, m], Ts=Ts, zi=zi)[0]
    return out


def _profile(targets, *, vmax, amax, jmax, Ts, sync, q0, bounded=None) -> np.ndarray:
    """The generator's profile before any stage (see :func:`multi_axis_reference`)."""
    x = np.asarray(targets, dtype=np.float64)
    n, axes = x.shape
    vmax, amax, jmax = (np.asarray(v, dtype=np.float64).reshape(axes) for v in (vmax, amax, jmax))
    groups = [np.arange(axes)] if sync == "phase" else [np.array([i]) for i in range(axes)]
    rest = np.zeros(axes) if q0 is None else np.asarray(q0, dtype=np.float64).copy()
    out = np.zeros((n, axes, 4))
    for idx in groups:
        lim = (vmax[idx], amax[idx], jmax[idx])
        blends = bounded is None or not np.any(bounded[idx])   # position limits: no blend
        position = rest[idx].copy()  # where the group rests when no move runs
        move, k, seen, pending = None, 0, 0.0, False
        refused = None  # a target whose move was refused: not tried again while it is held
        for s in range(n):
            B = x[s, idx]
            if refused is not None and not np.array_equal(B, refused):
                refused = None
            t = 0.0
            if move is not None:
                k += 1
                if k >= move["k_end"]:
                    position, move = move["goal"], None
                else:
                    t = move["off"] + k * Ts
            goal = position if move is None else move["goal"]
            if np.array_equal(B, goal) or refused is not None:
                pending = False
            elif not pending:
                pending, seen = True, t
            if pending:
                if move is None:
                    new = _plan(position, np.zeros(len(idx)), B, 0.0, Ts, lim)
                    if new is _REFUSED:  # the target is dropped
                        refused = B.copy()
                    else:
                        move, k = new, 0
                        if move is None:
                            position = B.copy()
                    pending = False
                    t = 0.0
                elif t >= move["T1"] and blends:
                    # blend at the end of the first transition, or where the target came in
                    # the cruise (at this very sample: before the stop by _evaluate's rule);
                    # never before T1, or the new move's first sample would be taken at tr
                    tr = max(seen, move["T1"])
                    if not seen > move["T1"]:
                        before_stop = True
                    elif seen < t:
                        before_stop = seen <= move["T1"] + move["tau"]
                    else:
                        before_stop = not _in_stop(move, _time_left(move, k, t, Ts))
                    if before_stop:
                        new = _plan(_cruise_position(move, tr), move["W"].copy(), B,
                                    max(t - tr, 0.0), Ts, lim)
                        pending = False
                        if new is _REFUSED:  # the running move goes on
                            refused = B.copy()
                        else:
                            move, k = new, 0
                            if move is None:
                                position = B.copy()
                            elif move["k_end"] == 0:
                                position, move = move["goal"], None
                            t = 0.0 if move is None else move["off"]
            if move is not None and move["k_end"] == 0:
                position, move = move["goal"], None
            if move is None:
                out[s, idx, 0] = position
                out[s, idx, 1:] = 0.0
            else:
                out[s, idx] = _evaluate(move, t, _time_left(move, k, t, Ts))
    return out
