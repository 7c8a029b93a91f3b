"""Kinematic design (docs/design.md): the shortest rest-to-rest chain within bounds.

``kinematic(h=, vmax=, amax=, jmax=, higher=(), profile=, wn=, zeta=)`` calls the C design
(``sms_kinematic_configs``) and returns :class:`~smoothshaper.stages.Stage` objects whose
durations sum to the trajectory's duration. ``kinematic_reference`` is an independent pure-Python
implementation of the same design (bisection instead of the C core's regula falsi and closed
forms), used as the test oracle.

Bounds: ``vmax`` on |q'|, ``amax`` on |q''|, ``jmax`` on |q'''|, then ``higher`` for the 4th,
5th, ... derivatives (at most 8 in all). Profiles:

* ``"polynomial"``: rectangular stages (trapezoid, double-S, ...);
* ``"trigonometric"``: the last stage harmonic (modified trapezoid / double-S, seed 000 eq. 6);
* ``"damped"``: the last stage exponential, tuned to the damped mode (Damped-Jerk, Béarée 2014).

With ``wn`` given, the last stage is tuned to the mode (length ``k * 2*pi/wd``, harmonic
``k * 3*pi/wd`` with k odd) and k is the multiple giving the shortest trajectory within every
bound. Seed 001 sec. 5.2 (T3 = 2*pi/wn) is ``jmax >= amax * wn / (2*pi)`` with ``wn`` given.
"""
from __future__ import annotations

import math

from . import stages as _stages
from .filters import ParameterError, _backend, _raise_status
from .stages import Stage
from ._checks import finite as _finite, positive as _positive

PROFILES = ("polynomial", "trigonometric", "damped")
MAX_ORDER = 8
MAX_MULTIPLE = 10000


def _limits(vmax, amax, jmax, higher) -> list[float]:
    """The bounds in derivative order; a bound may be given only if all lower ones are."""
    out = [_positive("vmax", vmax)]
    names = ["amax", "jmax"] + [f"higher[{i}]" for i in range(len(tuple(higher)))]
    values = [amax, jmax] + list(higher)
    missing = None
    for name, value in zip(names, values):
        if value is None:
            missing = missing or name
            continue
        if missing is not None:
            raise ValueError(f"{missing} must be given when {name} is (bounds are consecutive "
                             "derivatives)")
        out.append(_positive(name, value))
    if len(out) > MAX_ORDER:
        raise ValueError(f"higher: at most {MAX_ORDER} bounds in all, got {len(out)}")
    return out


def _mode(profile, wn, zeta) -> tuple[float, float]:
    if profile not in PROFILES:
        raise ValueError(f"profile must be one of {', '.join(PROFILES)}; got {profile!r}")
    if wn is None:
        if profile == "damped":
            raise ValueError("wn must be given for profile='damped' (the mode the exponential "
                             "jerk stage is tuned to)")
        return 0.0, 0.0
    wn = _positive("wn", wn)
    zeta = 0.0 if zeta is None else _finite("zeta", zeta)
    if not 0.0 <= zeta < 1.0:
        raise ValueError(f"zeta must be in [0, 1), got {zeta!r}")
    return wn, zeta


def kinematic(*, h: float, vmax: float, amax: float | None = None, jmax: float | None = None,
              higher=(), profile: str = "polynomial", wn: float | None = None,
              zeta: float = 0.0) -> list[Stage]:
    """Stages of the shortest rest-to-rest chain for displacement ``h`` within the bounds.

    Returns one stage per bound (first ones rectangular, the last per ``profile``); their
    ``T`` sum to the trajectory's duration. For three bounds and ``profile="polynomial"`` this
    is the time-optimal jerk-limited trajectory (e.g. h=40, vmax=250, amax=5000, jmax=2e5:
    T = 0.16, 0.05, 0.025 s). Raises ``ValueError`` naming the offending parameter.
    """
    h = _finite("h", h)
    if h == 0:
        raise ValueError("h must be non-zero (a displacement of 0 needs no trajectory)")
    limits = _limits(vmax, amax, jmax, higher)
    wn_, zeta_ = _mode(profile, wn, zeta)
    if profile == "damped" and len(limits) < 2:
        raise ValueError("amax must be given for profile='damped' (the exponential stage is "
                         "the jerk/acceleration stage)")
    ffi, lib = _backend("double")
    n = len(limits)
    configs = ffi.new("sms_stage_config[]", n)
    count = ffi.new("size_t *")
    st = lib.sms_kinematic_configs(h, ffi.new("double[]", limits), n, PROFILES.index(profile),
                                   wn_, zeta_, configs, n, count)
    if st != 0:
        if st == -15:
            raise ParameterError("wn", f"wn: no multiple k <= {MAX_MULTIPLE} of the mode period "
                                 "meets the bounds", st)
        _raise_status(st, lib, ffi, "kinematic design")
    out = []
    for i in range(count[0]):
        c = configs[i]
        out.append(Stage(_stages.KINDS[c.kind], T=c.T, sigma=c.sigma, k=c.k))
    return out


# ----------------------------------------------------------------------------------------------
# Independent reference
# ----------------------------------------------------------------------------------------------

def _peak_density(kind: str, T: float, sigma: float) -> float:
    if kind == "harmonic":
        return math.pi / (2.0 * T)
    if kind == "exponential" and sigma < 0:
        return -sigma / -math.expm1(sigma * T)
    return 1.0 / T


class _Problem:
    """Bounds L[0..n-1] and the last stage: free (T = c X / L[-1]) or fixed (T_fixed, rho)."""

    def __init__(self, limits, c_last=1.0, T_fixed=None, rho=None):
        self.L = list(limits)
        self.n = len(limits)
        self.c = c_last
        self.T_fixed = T_fixed
        self.rho = rho

    def cap(self, k: int) -> float:
        if self.T_fixed is not None and k == self.n - 2:
            return min(self.L[k], self.L[-1] / self.rho)
        return self.L[k]

    def lengths(self, k: int, X: float) -> list[float]:
        """Lengths of stages k..n-1 for level (displacement) X."""
        if k == self.n - 1:
            return [self.T_fixed if self.T_fixed is not None else self.c * X / self.L[-1]]
        V = self.cap(k)
        rest = self.lengths(k + 1, V)
        if X / V >= sum(rest):
            return [X / V] + rest
        # bound k unreachable: the level V where X/V equals the rise duration (bisection on
        # the increasing g(V) = V * D(V); g(lam V) <= lam g(V) brackets the root)
        hi = V
        lo = V * X / (V * sum(rest))
        for _ in range(400):
            mid = math.sqrt(lo * hi) if lo > 0 else 0.5 * hi
            if mid <= lo or mid >= hi:
                break
            if mid * sum(self.lengths(k + 1, mid)) > X:
                hi = mid
            else:
                lo = mid
        rest = self.lengths(k + 1, lo)
        return [max(X / lo, sum(rest))] + rest


def kinematic_reference(*, h, vmax, amax=None, jmax=None, higher=(), profile="polynomial",
                        wn=None, zeta=0.0) -> list[Stage]:
    """Pure-Python reference of :func:`kinematic` (same contract, independent code)."""
    h = abs(_finite("h", h))
    if h == 0:
        raise ValueError("h must be non-zero")
    limits = _limits(vmax, amax, jmax, higher)
    wn_, zeta_ = _mode(profile, wn, zeta)
    last_kind = "harmonic" if profile == "trigonometric" else "rectangular"
    if wn_ == 0.0:
        prob = _Problem(limits, c_last=math.pi / 2 if last_kind == "harmonic" else 1.0)
        T = prob.lengths(0, h)
        return [Stage("rectangular", T=t) for t in T[:-1]] + [Stage(last_kind, T=T[-1])]
    sigma = 0.0
    if profile == "damped":
        last_kind, sigma = "exponential", -zeta_ * wn_
    wd = wn_ * math.sqrt(1 - zeta_ ** 2)
    Tm = (3 * math.pi if last_kind == "harmonic" else 2 * math.pi) / wd
    best = None
    for k in range(1, MAX_MULTIPLE + 1, 2 if last_kind == "harmonic" else 1):
        Tf = k * Tm
        rho = _peak_density(last_kind, Tf, sigma)
        if len(limits) == 1:
            if h * rho > limits[0]:
                continue
            uncapped = True
        else:
            uncapped = limits[-2] * rho <= limits[-1]
        T = _Problem(limits, T_fixed=Tf, rho=rho).lengths(0, h)
        if best is None or sum(T) < sum(best[1]):
            best = (k, T)
        if uncapped:
            break
    if best is None:
        raise ValueError(f"wn: no multiple k <= {MAX_MULTIPLE} of the mode period meets the bounds")
    k, T = best
    return ([Stage("rectangular", T=t) for t in T[:-1]] +
            [Stage(last_kind, T=T[-1], sigma=sigma, k=k)])


def duration(stages) -> float:
    """Total duration of a designed chain (sum of its stage lengths) [s]."""
    return float(sum(s.T for s in stages))
