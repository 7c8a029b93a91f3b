# SPDX-License-Identifier: Apache-2.0
"""Kinematic design (docs/design.md): the shortest rest-to-rest chain within bounds.

``kinematic(h=, vmax=, amax=, jmax=, higher=(), profile=, wn=, zeta=, Ts=)`` calls the C design
(``sms_kinematic_design`` / ``sms_kinematic_configs``) and returns
:class:`~smoothshaper.stages.Stage` objects whose durations sum to the trajectory's duration.
With ``Ts`` the lengths lie on that sample grid and the chain run at ``Ts`` keeps every bound
at every sample (its backward differences, docs/sampled-limits.md); without it they are the
continuous optimum. ``kinematic_lengths`` designs many problems (arrays of ``h`` and bounds)
in one C call (``sms_kinematic_design_batch``) and returns their stage lengths, bit for bit
those of ``kinematic``. ``kinematic_reference`` is an independent pure-Python implementation of
the same design (nested bisection instead of the C core's closed forms per regime), used as
the test oracle.

Bounds: ``vmax`` on ``|q'|``, ``amax`` on ``|q''|``, ``jmax`` on ``|q'''|``, then ``higher``
for the 4th, 5th, ... derivatives (at most 8 in all). Profiles:

* ``"polynomial"``: rectangular stages (trapezoid, double-S, ...);
* ``"trigonometric"``: the last stage harmonic (modified trapezoid / double-S, seed 000 eq. 6);
* ``"damped"``: the last stage exponential, tuned to the damped mode (Damped-Jerk, Béarée 2014).

With ``wn`` given, the last stage is tuned to the mode (length ``k * 2*pi/wd``, harmonic
``k * 3*pi/wd`` with k odd) and k is the multiple giving the shortest trajectory within every
bound. Seed 001 sec. 5.2 (T3 = 2*pi/wn) is ``jmax >= amax * wn / (2*pi)`` with ``wn`` given.
"""
from __future__ import annotations

import cmath
import itertools
import math

import numpy as np

from . import _kinematic_fastpath, stages as _stages
from .filters import ParameterError, _as_stage_list, _backend, _raise_status
from .stages import Stage, _unchecked_stage
from ._checks import (choice as _choice, finite as _finite, positive as _positive,
                      real_array as _real_array)

__all__ = ["PROFILES", "profile_name", "MAX_ORDER", "MAX_MULTIPLE", "kinematic",
           "kinematic_lengths", "kinematic_reference", "duration"]

PROFILES = ("polynomial", "trigonometric", "damped")
MAX_ORDER = 8
MAX_MULTIPLE = 10000


def _limits(vmax, amax, jmax, higher, convert=_positive) -> list:
    """The bounds in derivative order, each through ``convert(name, value)`` (a positive
    float; :func:`kinematic_lengths`: an array); a bound may be given only if all lower ones
    are, and there are at most MAX_ORDER."""
    try:
        # at most one bound beyond the limit is read: an endless iterator is refused, not
        # drained forever (itertools.repeat(1.0) hung)
        higher = list(itertools.islice(iter(higher), MAX_ORDER))
    except TypeError:
        raise ParameterError("higher", "higher must be a sequence of bounds, got "
                             f"{type(higher).__name__}") from None
    out = [convert("vmax", vmax)]
    names = ["amax", "jmax"] + [f"higher[{i}]" for i in range(len(higher))]
    missing = None
    for name, value in zip(names, [amax, jmax] + higher):
        if value is None:
            missing = missing or name
            continue
        if missing is not None:
            raise ParameterError(
                missing, f"{missing} must be given when {name} is (bounds are consecutive "
                         "derivatives)")
        out.append(convert(name, value))
    if len(out) > MAX_ORDER:
        more = " or more" if len(higher) == MAX_ORDER else ""    # read no further
        raise ParameterError("higher", f"higher: at most {MAX_ORDER} bounds in all, got "
                             f"{len(out)}{more}")
    return out


def profile_name(profile) -> str:
    """The canonical (lower-case) profile name.

    Parameters
    ----------
    profile : str
        ``"polynomial"``, ``"trigonometric"`` or ``"damped"``, any case.

    Returns
    -------
    str
        The name as in :data:`PROFILES`.

    Raises
    ------
    ParameterError
        Naming ``profile``.
    """
    return _choice("profile", profile, PROFILES)


def _mode(profile: str, wn, zeta) -> tuple[float, float]:
    """(wn, zeta) of the mode a design is tuned to ((0, 0): none), for a ``profile`` the
    caller has checked (:func:`profile_name`)."""
    if wn is None:
        if profile == "damped":
            raise ParameterError(
                "wn", "wn must be given for profile='damped' (the mode the exponential "
                      "jerk stage is tuned to)")
        return 0.0, 0.0
    wn = _positive("wn", wn)
    zeta = 0.0 if zeta is None else _finite("zeta", zeta)
    if not 0.0 <= zeta < 1.0:
        raise ParameterError("zeta", f"zeta must be in [0, 1), got {zeta!r}")
    return wn, zeta


#: Every stage length is a combination of the ratios h/vmax, vmax/amax, amax/jmax, ... and
#: 1/wn; the C design refuses a ratio outside [1e-60, 1e60] s (in O(1), before any iteration).
RATIO_RANGE = (1e-60, 1e60)
#: Most samples a design on a grid may span (counts stay exact in a double).
MAX_SAMPLES = 2.0 ** 52


def _names(n: int) -> list[str]:
    return ["vmax", "amax", "jmax"][:n] + [f"higher[{i}]" for i in range(max(0, n - 3))]


def _check_ratios(h: float, limits: list[float], wn: float) -> None:
    """ParameterError naming the bound (and h) whose ratio no usable duration can carry."""
    names = _names(len(limits))
    pairs = [("h", abs(h), names[0], limits[0])]
    pairs += [(names[i - 1], limits[i - 1], names[i], limits[i]) for i in range(1, len(limits))]
    for num_name, num, den_name, den in pairs:
        r = num / den
        if not RATIO_RANGE[0] <= r <= RATIO_RANGE[1]:
            what = "longer than 1e60 s" if not r <= RATIO_RANGE[1] else "shorter than 1e-60 s"
            raise ParameterError(
                den_name, f"{den_name}={den!r} with {num_name}={num!r}: {num_name}/{den_name} "
                f"= {_quotient_text(num, den)} s, a stage of the design would be {what}; "
                f"bring {den_name} and {num_name} closer together", -15 if r > 1 else -17)
    if wn and not RATIO_RANGE[0] <= 1.0 / wn <= RATIO_RANGE[1]:
        raise ParameterError("wn", f"wn = {wn!r} rad/s: the mode period 2 pi/wn is outside "
                             "[1e-60, 1e60] s", -6)


def _quotient_text(num: float, den: float) -> str:
    """num/den as text, also where the quotient overflows or underflows a double (1e+318)."""
    r = num / den
    if r != 0.0 and math.isfinite(r):
        return f"{r:.6g}"
    e = math.log10(num) - math.log10(den)
    p = math.floor(e)
    return f"{10.0 ** (e - p):.6g}e{p:+d}"


def _design_error(st: int, lib, ffi, *, h, limits, Ts, wn) -> None:
    names = _names(len(limits))
    given = ", ".join(f"{n}={v!r}" for n, v in zip(["h"] + names, [h] + limits))
    if st == -15:
        if Ts:
            modes = (f" (or no mode multiple k <= {MAX_MULTIPLE} meets the bounds)" if wn
                     else "")
            raise ParameterError("Ts", f"Ts = {Ts!r} s: the design ({given}) spans more than "
                                 f"2^52 samples{modes}", st)
        raise ParameterError("wn", f"wn: no multiple k <= {MAX_MULTIPLE} of the mode period "
                             f"meets the bounds ({given})", st)
    if st in (-16, -4) and wn:
        raise _off_grid(wn, Ts, st)
    _raise_status(st, lib, ffi, f"kinematic design ({given})")


def _off_grid(wn: float, Ts: float, st: int) -> ParameterError:
    """The error for a mode whose tuned stage the grid Ts cannot hold."""
    return ParameterError("wn", f"wn = {wn!r} rad/s: the stage tuned to the mode cannot be "
                          f"placed on the grid Ts = {Ts!r} s (its zero is at or above the "
                          f"Nyquist frequency pi/Ts = {math.pi / Ts:.6g} rad/s, or the stage "
                          "is shorter than one sample)", st)


def kinematic(*, h: float, vmax: float, amax: float | None = None, jmax: float | None = None,
              higher=(), profile: str = "polynomial", wn: float | None = None,
              zeta: float = 0.0, Ts: float | None = None) -> list[Stage]:
    """Stages of the shortest rest-to-rest chain for displacement ``h`` within the bounds
    (computed by the C ``sms_kinematic_design``).

    One stage per bound, the first ones rectangular, the last per ``profile``; their ``T``
    sum to the trajectory's duration. For three bounds and ``profile="polynomial"`` this is
    the time-optimal jerk-limited (double-S) trajectory, equal to ruckig's durations
    (e.g. h=40, vmax=250, amax=5000, jmax=2e5: T = 0.16, 0.05, 0.025 s, the values of
    Biagiotti and Melchiorri, "Online Planning of Multi-Segment Trajectories with
    Trigonometric Blends", 2011; the construction as a cascade of moving averages:
    Biagiotti and Melchiorri, *Trajectory Planning for Automatic Machines and Robots*, 2008).

    Parameters
    ----------
    h : float, keyword-only
        Displacement [position units], non-zero (its sign is the direction).
    vmax : float, keyword-only
        Bound on ``|q'|`` [units/s], > 0.
    amax : float or None, keyword-only
        Bound on ``|q''|`` [units/s^2], > 0; None: velocity bound only.
    jmax : float or None, keyword-only
        Bound on ``|q'''|`` [units/s^3], > 0 (needs ``amax``).
    higher : sequence of float, keyword-only
        Bounds on the 4th, 5th, ... derivatives (at most 8 bounds in all).
    profile : {"polynomial", "trigonometric", "damped"}, keyword-only
        Family of the last stage: rectangular (trapezoid, double-S, ...), harmonic (modified
        trapezoid / double-S; Biagiotti and Melchiorri, "Online Planning of Multi-Segment
        Trajectories with Trigonometric Blends", 2011) or exponential tuned to the damped
        mode (Damped-Jerk; Béarée, "New Damped-Jerk trajectory for vibration reduction",
        2014).
    wn : float or None, keyword-only
        Mode the last stage is tuned to [rad/s] (required for ``"damped"``): its length
        becomes ``k 2 pi/wd`` (harmonic: ``k 3 pi/wd``, k odd), k the multiple giving the
        shortest trajectory within every bound.
    zeta : float, keyword-only
        Damping ratio of that mode, in [0, 1) (default 0).
    Ts : float or None, keyword-only
        Sample period the chain will run at [s]: every stage (except one tuned to a mode,
        which keeps ``k`` mode periods and, rectangular or exponential, gets
        ``timing="bounded"``) then lasts a whole number of samples, the lengths chosen together
        so that a step of ``h`` through ``Chain(stages, Ts=Ts)`` has backward differences
        ``|diff(q, i)| / Ts**i`` within the i-th bound at every sample (an exact bound on the
        sampled differences; docs/sampled-limits.md, with the price in duration). None: the
        continuous optimum, for analysis.

    Returns
    -------
    list of Stage
        The chain, largest stage first; run at ``Ts`` off their grid (``Ts`` not given),
        exact timing can exceed a bound between samples' differences by up to about 13 %.

    Raises
    ------
    ParameterError
        Naming the offending parameter: a bound, ``h``, ``wn``, ``zeta``, ``profile``,
        ``Ts``; extreme combinations name the pair whose ratio no duration can carry (e.g.
        ``h/vmax = 1e+318 s``).
    """
    # Fast path (plain numbers, at most three bounds; _kinematic_fastpath.c): the argument
    # types tested, the C design and the Stage objects built in one C function; None where
    # it does not apply or the C design refuses, and the checked path names the argument.
    stages = _fastpath(h, vmax, amax, jmax, higher, profile, wn, zeta, Ts)
    if stages is not None:
        return stages
    return _kinematic_checked(h, vmax, amax, jmax, higher, profile, wn, zeta, Ts)


# The fast path's Python objects: the stage type and names (index == C enumeration value),
# the profiles, and the number types besides float and int that convert exactly as float()
# does (bool, complex, str and other types take the checked path, which refuses or converts
# them by name).
_kinematic_fastpath.configure(Stage, _stages._STAGE_DEFAULTS, _stages.KINDS, _stages.TIMINGS,
                              {p: i for i, p in enumerate(PROFILES)},
                              (np.float64, np.int64, np.float32))
_fastpath = _kinematic_fastpath.design
# design.kinematic as a builtin (the same docstring and signature): a call then costs no
# Python frame before the fast path; where that declines, it calls the function above.
kinematic = _kinematic_fastpath.configure_kinematic(kinematic, __name__)


def _kinematic_checked(h, vmax, amax, jmax, higher, profile, wn, zeta, Ts) -> list[Stage]:
    """The general path of :func:`kinematic`: every argument checked and named."""
    profile = profile_name(profile)
    h = _finite("h", h)
    if h == 0:
        raise ParameterError("h", "h must be non-zero (a displacement of 0 needs no trajectory)")
    limits = _limits(vmax, amax, jmax, higher)
    wn_, zeta_ = _mode(profile, wn, zeta)
    if profile == "damped" and len(limits) < 2:
        raise ParameterError(
            "amax", "amax must be given for profile='damped' (the exponential stage is "
                    "the jerk/acceleration stage)")
    Ts_ = 0.0 if Ts is None else _positive("Ts", Ts)
    ffi, lib = _backend("double")
    n = len(limits)
    count = ffi.new("size_t *")
    if Ts is None:
        T = ffi.new("double[]", n)
        st = lib.sms_kinematic_design(h, ffi.new("double[]", limits), n,
                                      PROFILES.index(profile), wn_, zeta_, 0.0, T, n, count)
        if st != 0:
            _check_ratios(h, limits, wn_)
            _design_error(st, lib, ffi, h=h, limits=limits, Ts=None, wn=wn_)
        return _continuous_stages(list(T), profile, wn_, zeta_, h, limits)
    configs = ffi.new("sms_stage_config[]", n)
    st = lib.sms_kinematic_configs(h, ffi.new("double[]", limits), n, PROFILES.index(profile),
                                   wn_, zeta_, Ts_, configs, n, count)
    if st != 0:
        _check_ratios(h, limits, wn_)
        _design_error(st, lib, ffi, h=h, limits=limits, Ts=Ts_, wn=wn_)
    return [_unchecked_stage(_stages.KINDS[c.kind], float(c.T), float(c.sigma), int(c.k),
                             _stages.TIMINGS[c.timing])
            for c in (configs[i] for i in range(n))]


def _continuous_stages(T, profile, wn, zeta, h, limits) -> list[Stage]:
    """Stage objects for continuous lengths: the last stage's family and mode multiple."""
    last, sigma, k = ("harmonic" if profile == "trigonometric" else "rectangular"), 0.0, 1
    if wn:
        wd = wn * math.sqrt(1 - zeta * zeta)
        if profile == "damped":
            last, sigma = "exponential", -zeta * wn
        Tm = (3 * math.pi if last == "harmonic" else 2 * math.pi) / wd
        k = max(1, int(round(T[-1] / Tm)))
    return ([_unchecked_stage("rectangular", t) for t in T[:-1]]
            + [_unchecked_stage(last, T[-1], sigma, k)])


def kinematic_lengths(*, h, vmax, amax=None, jmax=None, higher=(), profile: str = "polynomial",
                      wn: float | None = None, zeta: float = 0.0,
                      Ts: float | None = None) -> np.ndarray:
    """Stage lengths of many kinematic designs in one C call (``sms_kinematic_design_batch``),
    for design loops and sweeps.

    ``h`` and the bounds are arrays that broadcast together (NumPy rules; a scalar is shared by
    every problem); problem ``i`` is the design :func:`kinematic` makes for the i-th element
    of each, and its lengths equal that design's ``[s.T for s in stages]`` bit for bit.
    ``profile``, ``wn``, ``zeta`` and ``Ts`` are shared. One problem costs about what the C
    design itself costs, not a Python call and three Stage objects (docs/sampled-limits.md,
    "What it costs").

    Parameters
    ----------
    h : array_like of float, keyword-only
        Displacements [position units], each finite and non-zero.
    vmax, amax, jmax : array_like of float, keyword-only
        Bounds on the first, second and third derivative [units/s, units/s^2, units/s^3],
        each finite and > 0; ``amax`` and ``jmax`` may be None (as in :func:`kinematic`).
    higher : sequence of array_like, keyword-only
        Bounds on the 4th, 5th, ... derivatives (at most 8 bounds in all).
    profile : {"polynomial", "trigonometric", "damped"}, keyword-only
        Family of the last stage, as in :func:`kinematic`.
    wn : float or None, keyword-only
        Mode the last stage is tuned to [rad/s]: its length is then a multiple of the mode's
        period, as in :func:`kinematic` (the multiple is not returned).
    zeta : float, keyword-only
        Damping ratio of that mode, in [0, 1).
    Ts : float or None, keyword-only
        Sample period [s]: lengths on its grid, as in :func:`kinematic`; None: continuous.

    Returns
    -------
    ndarray of float64, shape ``broadcast(h, bounds).shape + (n,)``
        The n stage lengths [s] of each problem, in chain order (the stage of vmax first; n =
        number of bounds).

    Raises
    ------
    ParameterError
        Naming the parameter: a bound, ``h``, ``higher``, ``profile``, ``wn``, ``zeta``,
        ``Ts``; arrays that are not real numbers or do not broadcast; for a refused problem,
        the message :func:`kinematic` gives for it followed by the problem's position
        (``(row 12)``, or ``(index (3, 4))`` for several dimensions).
    """
    profile = profile_name(profile)
    wn_, zeta_ = _mode(profile, wn, zeta)
    h_arr = _real_array("h", h)
    bounds = _limits(vmax, amax, jmax, higher, convert=_real_array)
    n = len(bounds)
    if profile == "damped" and n < 2:
        raise ParameterError(
            "amax", "amax must be given for profile='damped' (the exponential stage is "
                    "the jerk/acceleration stage)")
    Ts_ = 0.0 if Ts is None else _positive("Ts", Ts)
    try:
        shape = np.broadcast_shapes(h_arr.shape, *(b.shape for b in bounds))
    except ValueError:
        shape = ()
        for name, a in zip(["h"] + _names(n), [h_arr] + bounds):
            try:
                shape = np.broadcast_shapes(shape, a.shape)
            except ValueError:
                raise ParameterError(name, f"{name}: shape {a.shape} does not broadcast with "
                                     f"the shape {shape} of the arguments before it") from None
    out = np.empty(shape + (n,))
    m = out.size // n
    if m == 0:
        return out
    # A scalar h, or bounds that are all scalars, are shared through a stride of 0.
    h_stride = 0 if h_arr.ndim == 0 else 1
    H = np.ascontiguousarray(np.broadcast_to(h_arr, shape if h_stride else ())).reshape(-1)
    if all(b.ndim == 0 for b in bounds):
        L, l_stride = np.array(bounds, dtype=np.float64), 0
    else:
        L, l_stride = np.empty((m, n)), n
        for k, b in enumerate(bounds):
            L[:, k] = np.broadcast_to(b, shape).reshape(-1)
    ffi, lib = _backend("double")
    index = ffi.new("size_t *")
    st = lib.sms_kinematic_design_batch(
        m, ffi.from_buffer("double[]", H), h_stride, ffi.from_buffer("double[]", L), l_stride,
        n, PROFILES.index(profile), wn_, zeta_, Ts_, ffi.from_buffer("double[]", out),
        out.size, index)
    if st != 0:
        _batch_error(st, int(index[0]), shape, float(H[index[0] * h_stride]),
                     [float(x) for x in L.reshape(-1)[index[0] * l_stride:][:n]],
                     profile, wn, zeta, Ts)
    return out


def _batch_error(st: int, i: int, shape: tuple, h: float, row: list[float], profile, wn, zeta,
                 Ts) -> None:
    """The error :func:`kinematic` raises for problem ``i`` of a batch, with its position."""
    where = ("" if not shape else f"row {i}" if len(shape) == 1     # scalars: one problem
             else f"index {tuple(int(k) for k in np.unravel_index(i, shape))}")
    n = len(row)
    try:
        _kinematic_checked(h, row[0], row[1] if n > 1 else None, row[2] if n > 2 else None,
                           tuple(row[3:]), profile, wn, zeta, Ts)
    except ParameterError as e:
        raise ParameterError(e.parameter, f"{e} ({where})" if where else str(e),
                             e.status) from None
    ffi, lib = _backend("double")
    _raise_status(st, lib, ffi, f"kinematic design ({where})" if where else "kinematic design")


# ----------------------------------------------------------------------------------------------
# Independent reference
# ----------------------------------------------------------------------------------------------

def _peak_density(kind: str, T: float, sigma: float) -> float:
    if kind == "harmonic":
        return math.pi / (2.0 * T)
    if kind == "exponential" and sigma * T < -1e-15:   # else 1/T to rounding
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


def _grid_samples(nu: float) -> int:
    """Whole samples covering nu: round(nu) within the 1e-9 integer test, else ceil; >= 1."""
    r = math.floor(nu + 0.5)
    if abs(nu - r) <= 1e-9 * max(nu, 1.0):
        return max(1, int(r))
    return int(math.ceil(nu))


def _on_grid(T: list[float], Ts: float, h: float, limits: list[float], tuned_tap=None,
             tuned_support=None, harmonic_last=False, tuned_taps=None):
    """Reference rounding to whole samples: the shortest total among
    N_k = ceil(T_k/Ts) + {-1, 0, 1} whose chain keeps every bound at every sample (ties:
    longer early stages), else the greedy N_k = max(ceil(T_k/Ts), samples below). Sufficient
    conditions, each checked directly: N_k >= sum of the samples after it (copies in the
    differences never overlap), h / (N_0 ... N_i Ts^(i+1)) <= L_i, and the top derivative
    h / (N_0 ... N_(n-2) Ts^(n-1)) * (largest tap of the last stage) / Ts <= L_(n-1).
    Still over a sample per stage: _overlap_search, whose exact tests let copies overlap,
    then +1 .. -2 from the ceilings lifted by the structure."""
    n = len(T)
    tuned = tuned_tap is not None

    def last_tap(N_last):
        if tuned:
            return tuned_tap
        if harmonic_last:
            if N_last < 2:
                return 1.0
            taps = np.sin(np.pi * np.arange(N_last) / N_last)
            return taps.max() / taps.sum()
        return 1.0 / N_last

    def support(N):
        return tuned_support if tuned else N[-1]

    def ok(N):
        if harmonic_last and N[-1] < 2:
            return False
        below = support(N)
        for i in range(n - 2, -1, -1):
            if N[i] < below:
                return False
            below += N[i]
        prod = 1.0
        for i in range(n - 1):
            prod *= N[i]
            if h / (prod * Ts ** (i + 1)) > limits[i] * (1 + 1e-12):
                return False
        return h / (prod * Ts ** (n - 1)) * last_tap(N[-1]) / Ts <= limits[-1] * (1 + 1e-12)

    # greedy (always feasible)
    N = [0] * n
    if not tuned:
        nu = T[-1] / Ts
        N[-1] = _grid_samples(nu)
        if harmonic_last:
            N[-1] = max(N[-1], 2)
            if last_tap(N[-1]) > math.pi / (2 * nu):
                N[-1] += 1
    below = support(N)
    for i in range(n - 2, -1, -1):
        N[i] = max(_grid_samples(T[i] / Ts), below)
        below += N[i]
    m = n - 1 if tuned else n
    base = [_grid_samples(T[i] / Ts) for i in range(m)]
    best = (sum(N[:m]), [-x for x in N[:m]])
    for offsets in itertools.product((-1, 0, 1), repeat=m):
        cand = [b + o for b, o in zip(base, offsets)]
        if any(c < 1 for c in cand):
            continue
        key = (sum(cand), [-x for x in cand])
        if key < best and ok(cand + ([0] if tuned else [])):
            best, N[:m] = key, cand
    # more than one sample per stage over the continuous lengths (tight stages double the
    # rounding below them): a chain without a tuned stage lets its copies overlap where the
    # exact tests allow (boxes cancelling, a half sine's top difference); still over, each
    # stage +1 .. -2 samples from its ceiling, lifted by the structure
    free_last = not tuned and n >= 2

    def overlap(best):
        if free_last and best[0] - sum(T[i] / Ts for i in range(m)) > m:
            found = _overlap_search(base, Ts, h, limits, best[0], harmonic_last)   # m == n
            if found is not None:
                N[:] = found
                return sum(found), [-x for x in found]
        return best
    best = overlap(best)
    before4 = best[0]
    if m >= 2 and best[0] - sum(T[i] / Ts for i in range(m)) > m:
        for offsets in itertools.product((1, 0, -1, -2), repeat=m):
            cand, after = [0] * m, tuned_support if tuned else 0
            for i in range(m - 1, -1, -1):
                cand[i] = max(base[i] + offsets[i], 1)
                if i + 1 < n:
                    cand[i] = max(cand[i], after)
                after += cand[i]
            if sum(cand) < best[0] and ok(cand + ([0] if tuned else [])):
                best, N[:m] = (sum(cand), [-x for x in cand]), cand
    if best[0] < before4:      # still over, with a shorter chain to beat: prunes harder
        best = overlap(best)
    # bounded taps of a tuned stage (tuned_taps) cost up to two samples of their own: its
    # boxes get the search that lets copies overlap as soon as they are over at all
    if tuned_taps is not None and m >= 1 and best[0] - sum(T[i] / Ts for i in range(m)) > 0:
        c = [_grid_samples(t / Ts) for t in T]
        found = _overlap_search(c, Ts, h, limits, best[0], tuned_taps=tuned_taps)
        if found is not None:
            N[:m] = found
    return [N[i] * Ts if N[i] else T[i] for i in range(n)]


#: Level tests the search for overlapping chains may spend per pair of first two lengths,
#: times 2^n for n bounds.
_OVERLAP_NODES = 4


def _running_count_peak(lengths) -> int:
    """Largest |c(m)|, c(m) = sum over the subsets S of lengths with sum(S) <= m of
    (-1)^|S|: the running sum of the coefficients of prod (1 - z^-N)."""
    coeff = _signed_sums(lengths)
    run = peak = 0
    for s in sorted(coeff):
        run += coeff[s]
        peak = max(peak, abs(run))
    return peak


def _signed_sums(lengths) -> dict:
    """{s: sum over the subsets S of lengths with sum(S) = s of (-1)^|S|}: the coefficients
    of prod (1 - z^-N)."""
    coeff = {0: 1}
    for x in lengths:
        nxt = dict(coeff)
        for s, v in coeff.items():
            nxt[s + x] = nxt.get(s + x, 0) - v
        coeff = nxt
    return coeff


def _tuned_peak(boxes, taps) -> float:
    """max |F(m)| over the samples, F(m) = sum_S sign_S taps[m - sigma_S] over the signed subset
    sums sigma_S of the boxes: the top difference of boxes followed by a fixed stage, in units
    of h / prod(boxes). A copy's taps are an end tap, a geometric run and an end tap, so F only
    jumps where a copy starts, enters or leaves its run, or ends, and decays (or holds) in
    between: evaluated there, directly."""
    coeff = _signed_sums(boxes)
    sums = np.array(sorted(coeff), dtype=float)
    signs = np.array([coeff[x] for x in sorted(coeff)], dtype=float)
    L = len(taps)
    at = np.unique(np.concatenate([sums + d for d in (0, 1, L - 1, L)]))
    lag = at[:, None] - sums[None, :]
    inside = (lag >= 0) & (lag < L)
    values = np.where(inside, np.asarray(taps)[np.clip(lag, 0, L - 1).astype(np.int64)], 0.0)
    return float(np.abs(values @ signs).max())


def _half_sine_peak(boxes, N: int) -> float:
    """max |f(m)| over the samples, f(m) = sum_S sign_S sin(pi (m - sigma_S)/N) over the
    signed subset sums sigma_S of the boxes: the top difference of boxes followed by a half
    sine of N samples, in units of h tan(pi/2N) / prod(boxes) (docs/sampled-limits.md). Each
    copy's sinusoid lives from sigma_S to sigma_S + N; between consecutive such points f is one
    sinusoid, whose largest magnitude on the integers of the interval lies at its ends or next
    to its extremum."""
    coeff = {s: v for s, v in _signed_sums(boxes).items() if v}
    points = sorted(set(coeff) | {s + N for s in coeff})
    w = math.pi / N
    best = 0.0
    for a, b in zip(points, points[1:]):
        # phasor of the live copies at a: f(a + t) = Im(e^(i w t) Z)
        Z = sum(v * cmath.exp(1j * w * (a - s)) for s, v in coeff.items()
                if s <= a and s + N >= b)
        t0 = N * (0.5 - cmath.phase(Z) / math.pi)
        t0 -= N * math.floor(t0 / N)
        for t in {0, b - a, math.floor(t0), math.floor(t0) + 1, math.floor(t0) + N,
                  math.floor(t0) + N + 1}:
            if 0 <= t <= b - a:
                best = max(best, abs((cmath.exp(1j * w * t) * Z).imag))
    return best


def _overlap_search(c, Ts, h, limits, best_sum, harmonic_last=False, tuned_taps=None):
    """Reference of the C core's search for chains whose stages may overlap
    (docs/sampled-limits.md): whole-sample box lengths, largest first and non-increasing, each
    level i passing h * max|count of the i largest| <= L_i Ts^i * (product of the i largest);
    a half-sine last stage (harmonic_last) of any length, the top level checked exactly
    (_half_sine_peak), or a fixed last stage of non-negative taps (tuned_taps, the boxes'
    sum compared with best_sum) whose top level is checked exactly (_tuned_peak); depth first
    within _OVERLAP_NODES * 2^n level tests per pair of first two lengths; the box lengths if
    shorter than best_sum."""
    n = len(c)
    boxes = n - 1 if tuned_taps is not None else n
    logh, logTs = math.log(h), math.log(Ts)
    logL = [math.log(x) for x in limits]
    rest_min = [0] * (boxes + 1)
    for k in range(boxes - 1, -1, -1):
        rest_min[k] = rest_min[k + 1] + max(1, c[k] - 1)
    state = {"best": best_sum, "N": None, "nodes": 0}
    N = [0] * n

    def candidates(k, logprod):
        if k == n - 1 and harmonic_last:
            e = logh - logL[k] - n * logTs - logprod
            if e > 709.0:
                return []
            x0 = max(2, math.ceil(math.pi / 2 * math.exp(e) * (1 - 1e-12)))
            return [x for x in range(x0 - 2, x0 + 4) if x >= 2]
        if k == n - 1 or ((harmonic_last or tuned_taps is not None) and k == n - 2):
            e = logh - logL[k] - (k + 1) * logTs - logprod
            if e > 709.0:
                return []
            x0 = max(1, math.ceil(math.exp(e) * (1 - 1e-12)))
            xs = [x0 + j for j in range(4)]
            if k < n - 1:     # before a half sine: also the ceiling -1 .. +1
                xs += [x for x in (c[k] - 1, c[k], c[k] + 1) if not x0 <= x <= x0 + 3]
            return xs
        prev = N[k - 1] - c[k - 1] if k else 0
        if prev in (-1, 1):
            offs = (-prev, 0, prev, 2)
        elif k == 0:
            offs = (-1, 1, 0, 2)
        else:
            offs = (-1, 0, 1, 2) if (n - 1 - k) % 2 else (0, -1, 1, 2)
        xs = [c[k] + o for o in offs]
        lift = sum(c[k + 1:])
        return xs + [x for x in (lift - 1, lift, lift + 1) if x not in xs]

    def visit(k, logprod, psum):
        if k == boxes:
            if tuned_taps is not None:
                f = _tuned_peak(N[:k], tuned_taps)
                if logh + math.log(max(f, 1e-300)) > logL[n - 1] + n * logTs + logprod + 1e-12:
                    return
            if psum < state["best"]:
                state["best"], state["N"] = psum, list(N)
            return
        sine = harmonic_last and k == n - 1
        for x in candidates(k, logprod):
            if (x < 1 or (k and x > N[k - 1] and not sine)
                    or psum + x + rest_min[k + 1] >= state["best"]):
                continue
            if k <= 1:
                state["nodes"] = 0     # each pair of first two lengths gets its own budget
            if state["nodes"] >= _OVERLAP_NODES << n:
                return
            state["nodes"] += 1
            N[k] = x
            if sine:
                f = _half_sine_peak(N[:k], x)
                if (logh + math.log(max(f, 1e-300)) + math.log(math.tan(math.pi / (2 * x)))
                        <= logL[k] + n * logTs + logprod + 1e-12):
                    visit(k + 1, logprod, psum + x)
                continue
            lp = logprod + math.log(x)
            peak = _running_count_peak(N[:k + 1])
            if logh + math.log(peak) <= logL[k] + (k + 1) * logTs + lp + 1e-12:
                visit(k + 1, lp, psum + x)

    visit(0, 0.0, 0)
    return None if state["N"] is None else state["N"][:boxes]


def _grid_span(T: list[float], Ts: float, h: float, limits: list[float]) -> float:
    """``Ts``, or the ParameterError :func:`kinematic` raises when the design would span more
    than :data:`MAX_SAMPLES` samples of it (before the reference allocates any)."""
    span = sum(T) / Ts
    if not span <= MAX_SAMPLES:
        given = ", ".join(f"{n}={v!r}" for n, v in zip(["h"] + _names(len(limits)),
                                                       [h] + limits))
        raise ParameterError("Ts", f"Ts = {Ts!r} s: the design ({given}) spans more than "
                             f"2^52 samples ({span:.4g})", -15)
    return Ts


def kinematic_reference(*, h, vmax, amax=None, jmax=None, higher=(), profile="polynomial",
                        wn=None, zeta=0.0, Ts=None) -> list[Stage]:
    """Pure-Python reference of :func:`kinematic` (same contract, independent code: nested
    bisection instead of the C core's closed forms per regime), the test oracle.

    Parameters
    ----------
    h : float, keyword-only
        Displacement [position units], non-zero (its sign is the direction).
    vmax : float, keyword-only
        Bound on ``|q'|`` [units/s], > 0.
    amax : float or None, keyword-only
        Bound on ``|q''|`` [units/s^2], > 0; None: velocity bound only.
    jmax : float or None, keyword-only
        Bound on ``|q'''|`` [units/s^3], > 0 (needs ``amax``).
    higher : sequence of float, keyword-only
        Bounds on the 4th, 5th, ... derivatives (at most 8 bounds in all).
    profile : {"polynomial", "trigonometric", "damped"}, keyword-only
        Family of the last stage: rectangular (trapezoid, double-S, ...), harmonic (modified
        trapezoid / double-S; Biagiotti and Melchiorri, "Online Planning of Multi-Segment
        Trajectories with Trigonometric Blends", 2011) or exponential tuned to the damped
        mode (Damped-Jerk; Béarée, "New Damped-Jerk trajectory for vibration reduction",
        2014).
    wn : float or None, keyword-only
        Mode the last stage is tuned to [rad/s] (required for ``"damped"``): its length
        becomes ``k 2 pi/wd`` (harmonic: ``k 3 pi/wd``, k odd), k the multiple giving the
        shortest trajectory within every bound.
    zeta : float, keyword-only
        Damping ratio of that mode, in [0, 1) (default 0).
    Ts : float or None, keyword-only
        Sample period the chain will run at [s]: every stage (except one tuned to a mode,
        which keeps ``k`` mode periods and, rectangular or exponential, gets
        ``timing="bounded"``) then lasts a whole number of samples, the lengths chosen together
        so that a step of ``h`` through ``Chain(stages, Ts=Ts)`` has backward differences
        ``|diff(q, i)| / Ts**i`` within the i-th bound at every sample (an exact bound on the
        sampled differences; docs/sampled-limits.md, with the price in duration). None: the
        continuous optimum, for analysis.

    Returns
    -------
    list of Stage
        The same chain :func:`kinematic` returns, to rounding.

    Raises
    ------
    ParameterError
        Naming the offending parameter, as :func:`kinematic`.
    """
    from .reference.filtering import impulse_response

    profile = profile_name(profile)
    h = abs(_finite("h", h))
    if h == 0:
        raise ParameterError("h", "h must be non-zero")
    limits = _limits(vmax, amax, jmax, higher)
    wn_, zeta_ = _mode(profile, wn, zeta)
    _check_ratios(h, limits, wn_)       # the C design's range, refused alike before any work
    last_kind = "harmonic" if profile == "trigonometric" else "rectangular"
    if wn_ == 0.0:
        prob = _Problem(limits, c_last=math.pi / 2 if last_kind == "harmonic" else 1.0)
        T = prob.lengths(0, h)
        if Ts is not None:
            Ts = _grid_span(T, _positive("Ts", Ts), h, limits)
            T = _on_grid(T, Ts, h, limits, harmonic_last=last_kind == "harmonic")
        return [Stage("rectangular", T=t) for t in T[:-1]] + [Stage(last_kind, T=T[-1])]
    sigma = 0.0
    if profile == "damped":
        last_kind, sigma = "exponential", -zeta_ * wn_
    wd = wn_ * math.sqrt(1 - zeta_ ** 2)
    Tm = (3 * math.pi if last_kind == "harmonic" else 2 * math.pi) / wd
    best = None
    for k in range(1, MAX_MULTIPLE + 1, 2 if last_kind == "harmonic" else 1):
        Tf = k * Tm
        if best is not None and Tf >= sum(best[1]):
            break     # the chain lasts at least its tuned stage: no longer multiple wins
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
        raise ParameterError(
            "wn", f"wn: no multiple k <= {MAX_MULTIPLE} of the mode period meets the bounds")
    k, T = best
    timing = "exact"
    if Ts is not None:
        # the tuned stage keeps its length, so its zero stays on the mode; bounded taps keep
        # its largest tap / Ts at the density the design used (a half sine's exact taps may
        # exceed it: then the design runs again with the sampled density)
        Ts = _grid_span(T, _positive("Ts", Ts), h, limits)
        timing = "exact" if last_kind == "harmonic" else "bounded"
        k0 = k
        while True:
            try:
                taps = impulse_response(Stage(last_kind, T=k * Tm, sigma=sigma, k=k,
                                              timing=timing), Ts=Ts)
            except ParameterError as exc:   # the stage's T is derived from wn, not given
                if exc.parameter != "T":
                    raise
                raise _off_grid(wn_, Ts, -16) from None
            rho = _peak_density(last_kind, k * Tm, sigma)
            peak = float(np.max(np.abs(taps))) / Ts
            raised = peak > rho * (1 + 1e-12)     # beyond rounding
            if raised:
                rho = peak
            if not (raised and len(limits) == 1 and h * rho > limits[0]):
                break
            # alone it is the velocity stage: the next multiple, whose peak is lower
            k += 2 if last_kind == "harmonic" else 1
            if k > MAX_MULTIPLE:
                raise ParameterError("wn", f"wn: no multiple k <= {MAX_MULTIPLE} of the mode "
                                     "period keeps vmax on the grid")
        if raised or k != k0:
            T = _Problem(limits, T_fixed=k * Tm, rho=rho).lengths(0, h)
        # copies one sample closer than the taps overlap only in end taps: allowed when the
        # first and last tap together stay within the bound
        support = len(taps) - (1 if taps[0] + taps[-1] <= rho * Ts else 0)
        T = _on_grid(T, Ts, h, limits, tuned_tap=rho * Ts, tuned_support=support,
                     tuned_taps=taps if timing == "bounded" and len(taps) >= 3 else None)
    return ([Stage("rectangular", T=t) for t in T[:-1]] +
            [Stage(last_kind, T=T[-1], sigma=sigma, k=k, timing=timing)])


def duration(stages) -> float:
    """Total duration of a designed chain: the sum of its stage lengths.

    Parameters
    ----------
    stages : Stage or sequence of Stage
        Smoother stages (their ``T``).

    Returns
    -------
    float
        The duration [s].

    Raises
    ------
    ParameterError
        Naming ``stages`` (or ``stages[i]``) when it is not a Stage or a sequence of them.
    """
    return float(sum(s.T for s in _as_stage_list(stages)))
