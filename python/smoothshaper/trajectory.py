# SPDX-License-Identifier: Apache-2.0
"""Online multi-point generator and B-spline interpolation: C-backed classes and NumPy references.

* :class:`Generator` wraps ``sms_generator`` (docs/design.md, docs/sampled-limits.md): a
  staircase of targets in, position, velocity, acceleration and jerk out, never beyond
  ``vmax``, ``amax``, ``jmax``, each new target reached in the profile's time-optimal duration
  (the argument is in ``c/include/smoothshaper/trajectory.h``); :func:`generator_reference`
  recomputes the same trajectory independently (the plan of :mod:`smoothshaper.time_optimal`,
  then the tuned stage as a convolution with the reference taps).
* :class:`BSpline` wraps ``sms_bspline`` (Biagiotti & Melchiorri 2011b);
  :func:`bspline_reference` is the NumPy version (dense solve, ``np.convolve``). :func:`bspline_period` picks the knot
  spacing from the modes, ``T >= 2*pi/min(wn)``.
"""
from __future__ import annotations

import math
import warnings

import numpy as np

from . import _reach, _state_identity
from ._shared import Twins, locked, new_lock
from . import design as _design
from .errors import DroppedTargetWarning
from .filters import (ParameterError, _backend, _raise_status, _real_dtype, check_memory,
                      input_max)
from ._checks import (finite as _finite, finite_signal as _targets, integer as _integer,
                      real_array as _real_array, show as _show)

__all__ = ["Generator", "DroppedTargetWarning", "generator_reference", "tuned_stage", "BSpline",
           "bspline_reference", "bspline_period", "BSPLINE_MAX_DEGREE", "BSPLINE_MAX_AXES", "MultiAxisGenerator",
           "MultiAxisMove", "multi_axis_move", "phase_duration", "multi_axis_reference"]

BSPLINE_MAX_DEGREE = 7
BSPLINE_MAX_AXES = 3
# The fields of a saved state's identity after the common head (trajectory.h).
_GENERATOR_IDENTITY_FIELDS = ("vmax", "amax", "jmax", "profile", "wn", "zeta")


def _generator_error(st, lib, ffi, cfg, Ts, profile):
    """ParameterError naming the cause of a refused generator config, with the values."""
    if st in (-16, -4, -15, -3) and cfg.wn:
        raise ParameterError("wn", f"wn={cfg.wn!r} rad/s: the stage tuned to the mode cannot be "
                                   f"placed on the grid Ts={Ts!r} s (the mode is at or above "
                                   f"the Nyquist frequency pi/Ts = {math.pi / Ts:.6g} rad/s, or "
                                   "the stage spans too many samples)", st)
    if st == -17:
        raise _infeasible(lib, ffi, cfg, Ts, st)
    _raise_status(st, lib, ffi, "online generator")


def _infeasible(lib, ffi, cfg, Ts, st):
    """ParameterError for limits with which no plan can reach vmax (``sms_generator_reach``):
    the arguments and their values, the derived quantity out of range, its bound."""
    info = ffi.new("sms_generator_reach_info *")
    lib.sms_generator_reach(cfg, Ts, info)
    return _reach.refused(ffi, info, dict(vmax=cfg.vmax, amax=cfg.amax, jmax=cfg.jmax), Ts, st)


def _generator_config(ffi, vmax, amax, jmax, profile, wn, zeta):
    cfg = ffi.new("sms_generator_config *")
    cfg.vmax = _design._positive("vmax", vmax)
    cfg.amax = _design._positive("amax", amax)
    cfg.jmax = _design._positive("jmax", jmax)
    profile = _design.profile_name(profile)
    wn_, zeta_ = _design._mode(profile, wn, zeta)
    cfg.profile = _design.PROFILES.index(profile)
    cfg.wn = wn_
    cfg.zeta = zeta_
    return cfg


class Generator(_state_identity.SavedState, Twins):
    """Online multi-point trajectory generator (C core, ``sms_generator``).

    :meth:`process` takes the target (a staircase) per sample and returns position,
    velocity, acceleration and jerk: the exact values and derivatives of the continuous
    output at the sample instants, so the backward differences of the samples keep the
    bounds too (docs/sampled-limits.md). Every new target is planned time-optimally from the
    current state, for any ``Ts``: the polynomial profile in ruckig's jerk-limited duration,
    the trigonometric one with half-cosine transitions of the acceleration (jerk continuous,
    peak ``jmax``), both rounded up to the sample grid. With a mode ``wn`` the plan runs
    through the shortest stage tuned to it (exact zero, every bound kept), which adds its
    length :attr:`stage_duration`.

    Parameters
    ----------
    vmax : float, keyword-only
        Velocity bound [units/s], > 0.
    amax : float, keyword-only
        Acceleration bound [units/s^2], > 0.
    jmax : float, keyword-only
        Jerk bound [units/s^3], > 0.
    Ts : float, keyword-only
        Sample period [s], > 0.
    profile : {"polynomial", "trigonometric", "damped"}, keyword-only
        Jerk-limited (linear acceleration ramps), half-cosine acceleration transitions
        (Biagiotti and Melchiorri, "Online Planning of Multi-Segment Trajectories with
        Trigonometric Blends", 2011) or the Damped-Jerk stage (Béarée, "New Damped-Jerk
        trajectory for vibration reduction", 2014; needs ``wn``).
    wn : float or None, keyword-only
        Mode [rad/s] the plan is filtered for (a stage tuned to it, :func:`tuned_stage`).
    zeta : float, keyword-only
        Its damping ratio, in [0, 1) (default 0).
    q0 : float, keyword-only
        Initial position: the generator starts at rest there (default 0).
    precision : {"double", "float"}, keyword-only
        Which build of the C core runs it.

    Raises
    ------
    ParameterError
        Naming the parameter out of range (a bound, ``Ts``, ``profile``, ``wn``, ``zeta``,
        ``q0``, ``precision``), or limits with which no plan can reach ``vmax``: the message
        names the arguments, their values and the derived quantity out of range (e.g.
        ``sqrt(vmax/jmax) = 1e+150 s`` for ``vmax=1, jmax=1e-300``: reaching vmax would take
        more than the 2^50 samples a plan holds with room for a reversal; or a product that
        would overflow or underflow the build's floats). The feasible region is documented at
        ``sms_generator_reach`` (trajectory.h) and in docs/sampled-limits.md.

    Attributes
    ----------
    refused : bool
        True while the held target is dropped (see :meth:`process`).
    dropped : int
        Targets dropped since construction or the last :meth:`reset`.

    Notes
    -----
    A generator may be shared between threads (its methods hold its lock, so calls run one at
    a time); ``copy.copy``, ``copy.deepcopy`` and ``pickle`` give independent generators that
    continue bit-exactly (docs/python.md).
    """

    _STATE_C = "sms_generator"
    _STATE_FIELDS = _GENERATOR_IDENTITY_FIELDS
    _STATE_CHOICES = {"profile": _design.PROFILES}
    # Old names (deprecated): one name per concept, as Chain.get_state / set_state.
    _STATE_ALIASES = {"save_state": "get_state", "load_state": "set_state"}
    _STATE_DOC = dict(
        what="generator", same="``vmax``, ``amax``, ``jmax``, ``profile``, ``wn``, ``zeta``",
        example='``"state is from vmax=2.0 (this Generator: vmax=1.0)"``',
        layout="``sms_generator_get_state``: first the configuration identity "
        "(``SMS_GENERATOR_IDENTITY_COUNT`` = 11 values: state tag, format version, "
        "``sizeof(sms_real)`` (8 double, 4 float), kind (100, a generator), ``Ts``, ``vmax``, "
        "``amax``, ``jmax``, profile index in :data:`~smoothshaper.design.PROFILES`, ``wn`` "
        "(0 without a mode), ``zeta``); then target, goal, the running plan's start q, v, a "
        "and the samples since it (n = 17 without a mode); with a mode also the samples the "
        "plan has rested and the four states of the tuned stage (each with its own stage "
        "identity).")

    def __init__(self, *, vmax: float, amax: float, jmax: float, Ts: float,
                 profile: str = "polynomial", wn: float | None = None, zeta: float = 0.0,
                 q0: float = 0.0, precision: str = "double"):
        ffi, lib = _backend(precision)
        self._ffi, self._lib = ffi, lib
        self._lock = new_lock()
        self.Ts = _design._positive("Ts", Ts)
        q0 = _finite("q0", q0)
        self.precision = precision
        self._init_args = dict(vmax=vmax, amax=amax, jmax=jmax, Ts=Ts, profile=profile, wn=wn,
                               zeta=zeta, q0=q0, precision=precision)
        cfg = _generator_config(ffi, vmax, amax, jmax, profile, wn, zeta)
        need = ffi.new("size_t *")
        st = lib.sms_generator_buffer_size(cfg, self.Ts, need)
        if st != 0:
            _generator_error(st, lib, ffi, cfg, self.Ts, profile)
        check_memory("Ts", need[0], f"the generator's stage tuned to wn at Ts={self.Ts!r}")
        self._buffer = np.zeros(max(need[0], 1), dtype=_real_dtype(precision))
        self._gen = ffi.new("sms_generator *")
        st = lib.sms_generator_init(self._gen, cfg, self.Ts,
                                    ffi.from_buffer("sms_real[]", self._buffer), need[0])
        if st != 0:  # pragma: no cover - the size query validated the same arguments
            _raise_status(st, lib, ffi, "online generator")
        self.vmax, self.amax, self.jmax = cfg.vmax, cfg.amax, cfg.jmax
        self.profile, self.wn, self.zeta = _design.PROFILES[cfg.profile], cfg.wn, cfg.zeta
        self.q0 = q0
        self.reset(q0)

    @property
    def time_optimal(self) -> bool:
        """True: every profile plans each new target time-optimally (kept for inspection)."""
        return bool(self._gen.time_optimal)

    @property
    def stage_duration(self) -> float:
        """Length [s] of the stage tuned to the mode (0 without a mode): the output rests on
        a target that long (rounded up to whole samples) after the plan does."""
        return float(self._gen.stage_T)

    @property
    def tail_samples(self) -> int:
        """Taps L of the stage tuned to the mode (0 without one): the output rests exactly on
        the target L - 1 samples after the plan does."""
        return int(self._gen.stage_length)

    def _full_state(self):
        # with the diagnostics that are not part of the saved state
        return self.get_state(), {"dropped": int(self._gen.dropped),
                                  "refused": int(self._gen.refused)}

    def _set_full_state(self, state, counters) -> None:
        self.set_state(state)
        self._gen.dropped, self._gen.refused = counters["dropped"], counters["refused"]

    @locked
    def reset(self, position: float | None = None) -> None:
        """Rest at ``position``: q = position, v = a = j = 0.

        Parameters
        ----------
        position : float or None
            The rest position (default: ``q0``).

        Raises
        ------
        ParameterError
            Naming ``position`` when it is not finite.
        """
        position = self.q0 if position is None else _finite("position", position)
        self._lib.sms_generator_reset(self._gen, position)

    @locked
    def process(self, targets) -> np.ndarray:
        """Run a block of targets, one C call for the whole block.

        Parameters
        ----------
        targets : array_like of float, shape (n,)
            The target at every sample, finite.

        Returns
        -------
        ndarray of float64, shape (n, 4)
            Columns q [units], v [units/s], a [units/s^2], j [units/s^3] at the samples.
            A target whose move cannot be represented in the build's floats (a value of the
            plan would overflow, or the move would last more than 2^52 samples, e.g. 1e300
            at ``vmax=1``) is dropped: the running motion goes on and the target is not tried
            again until it changes, so the outputs stay finite and within the limits.

        Raises
        ------
        ParameterError
            Naming ``targets`` when it is not a finite real 1-D array; the state is then
            untouched.

        Warns
        -----
        DroppedTargetWarning
            Once per call in which targets were dropped, naming the last one, the position
            it was to be reached from and the count (also in :attr:`dropped`).
        """
        x = _targets("targets", targets)
        before = self._gen.dropped
        dtype = _real_dtype(self.precision)
        xin = np.ascontiguousarray(x, dtype=dtype)
        out = np.empty((x.size, 4), dtype=dtype)
        if x.size:
            self._lib.sms_generator_process(self._gen, self._ffi.from_buffer("sms_real[]", xin),
                                            x.size, self._ffi.from_buffer("sms_real[]", out))
        if self._gen.dropped != before:
            self._warn_dropped(self._gen.dropped - before)
        return out if dtype == np.float64 else out.astype(np.float64)

    @property
    def refused(self) -> bool:
        """True while the held target is dropped: its move cannot be represented (it would
        last more than 2^52 samples, or a value on the way would overflow the build's
        floats); the generator heads for its previous goal until the target changes."""
        return bool(self._gen.refused)

    @property
    def dropped(self) -> int:
        """Targets dropped since construction or the last :meth:`reset` (a diagnostic count;
        not part of the saved state)."""
        return int(self._gen.dropped)

    def _warn_dropped(self, count: int) -> None:
        g = self._gen
        target, q, goal = float(g.target), float(g.plan_q), float(g.plan.goal)
        span = abs(target - goal) / self.vmax / self.Ts if math.isfinite(target - goal) else math.inf
        what = "target" if count == 1 else f"{count} targets dropped in this block; the last"
        warnings.warn(DroppedTargetWarning(
            f"{what} {target!r}: its move cannot be represented in {self.precision} "
            f"(|target - goal|/vmax alone is {span:.3g} samples of Ts, a plan holds at most "
            f"2^52, and every value on the way must stay finite); the generator keeps its goal "
            f"{goal!r} (the running plan started at q={q!r}) until the target changes"),
            stacklevel=3)

    @locked
    def start_from(self, q: float, v: float = 0.0, a: float = 0.0, *,
                   target: float | None = None) -> None:
        """Continue from the motion state (q, v, a): the next sample plans afresh from there.

        A state set through :meth:`set_state` (its plan fields), so the generator continues
        exactly as if its own plan had brought it to (q, v, a) at the previous sample: the
        next :meth:`process` re-plans from there to its first target (the time-optimal motion
        of the profile). A tuned stage (``wn``) keeps its history: it filters the new plan
        from the next sample on, as it would after a re-plan.

        Parameters
        ----------
        q : float
            Position [units], finite.
        v : float
            Velocity [units/s], ``|v| <= vmax``.
        a : float
            Acceleration [units/s^2], ``|a| <= amax``, and able to reach zero without passing
            ``vmax``: ``|v + a|a| / (2 jmax_mean)| <= vmax`` (``jmax_mean`` = ``jmax``, or
            ``(2/pi) jmax`` for the trigonometric profile's half-cosine transitions). Each
            bound holds to the generator's own rounding, the relative ``SMS_LIMIT_RTOL`` (32 u
            of the precision, 2^-48 in double and 2^-19 in float) to which its reported v, a, j
            keep the limits, with v and a rounded to the precision: a sample the generator
            reported is always accepted.
        target : float or None
            The goal the motion heads for until the next target arrives (default: q).

        Raises
        ------
        ParameterError
            Naming ``q``, ``v``, ``a`` or ``target`` when one is not finite or the state is
            one no plan of this generator can start from; then nothing is changed.
        """
        q = _finite("q", q)
        v = _finite("v", v)
        a = _finite("a", a)
        target = q if target is None else _finite("target", target)
        # as the C check (sms_generator_check_state): the values as sms_real holds them,
        # against the limits as sms_real, to the reported values' tolerance
        real = _real_dtype(self.precision)
        tol = float(self._lib.SMS_LIMIT_RTOL)
        with np.errstate(over="ignore"):     # beyond float's range: inf, refused below
            v_real, a_real = float(real(v)), float(real(a))
        if not abs(v_real) <= float(real(self.vmax)) * (1 + tol):
            raise ParameterError("v", f"v={v!r} exceeds vmax={self.vmax!r} (beyond the "
                                 f"generator's own rounding, a relative {tol:.3g})")
        if not abs(a_real) <= float(real(self.amax)) * (1 + tol):
            raise ParameterError("a", f"a={a!r} exceeds amax={self.amax!r} (beyond the "
                                 f"generator's own rounding, a relative {tol:.3g})")
        s = self.get_state()
        plan = int(self._lib.SMS_GENERATOR_IDENTITY_COUNT)
        s[plan:plan + 6] = (target, target, q, v, a, 0.0)
        if self.tail_samples:
            s[plan + 6] = 0.0       # the plan has not rested on its goal yet
        st = self._lib.sms_generator_set_state(self._gen, self._ffi.from_buffer("double[]", s),
                                               s.size)
        if st != 0 and target != q:
            # the state itself is one a plan starts from (towards q): the target is what
            # cannot be reached in the build's floats (sms_generator_check_state writes nothing)
            probe = s.copy()
            probe[plan:plan + 2] = (q, q)
            if self._lib.sms_generator_check_state(
                    self._gen, self._ffi.from_buffer("double[]", probe), probe.size) == 0:
                raise ParameterError(
                    "target", f"target={target!r}: the move from (q, v, a) = ({q!r}, {v!r}, "
                    f"{a!r}) cannot be represented in {self.precision} (more than 2^52 samples "
                    "of Ts, or a value beyond the range of a float)", st)
        if st != 0:
            raise ParameterError(
                "a", f"(q, v, a) = ({q!r}, {v!r}, {a!r}) towards target={target!r} is not a "
                "state a plan of this generator can start from: bringing a to zero would pass "
                f"vmax={self.vmax!r}, or a value of the plan cannot be represented", st)


# ----------------------------------------------------------------------------------------------
# NumPy reference of the generator
# ----------------------------------------------------------------------------------------------

def tuned_stage(profile: str, wn: float, zeta: float):
    """The shortest stage whose zero cancels the mode, as the C generator builds it: a
    rectangular (polynomial) or exponential (damped, ``sigma = -zeta wn``) stage of one damped
    period ``2 pi/wd``, or a half sine (trigonometric; damped half sine when zeta > 0) of
    ``3 pi/wd``, ``wd = wn sqrt(1 - zeta^2)``, exact timing, k = 1 (Biagiotti, Melchiorri and
    Moriello, "Damped Harmonic Smoother for Trajectory Planning and Vibration Suppression",
    2020).

    Parameters
    ----------
    profile : {"polynomial", "trigonometric", "damped"}
        The generator's profile.
    wn : float
        Natural frequency [rad/s], > 0.
    zeta : float
        Damping ratio, in [0, 1).

    Returns
    -------
    Stage
        The tuned stage.

    Raises
    ------
    ParameterError
        Naming ``profile``, ``wn`` (not finite and > 0, or a period beyond a float) or
        ``zeta`` (not in [0, 1)).
    """
    from .stages import for_mode
    profile = _design.profile_name(profile)
    zeta = _finite("zeta", zeta)
    return for_mode(_tuned_kind(profile, zeta), wn=wn, zeta=zeta)  # checks wn, zeta, period


def _tuned_kind(profile: str, zeta: float) -> str:
    return {"polynomial": "rectangular", "damped": "exponential",
            "trigonometric": "damped_harmonic" if zeta > 0 else "harmonic"}[profile]


def generator_reference(targets, *, vmax, amax, jmax, Ts, profile="polynomial", wn=None,
                        zeta=0.0, position=0.0) -> np.ndarray:
    """NumPy reference of :class:`Generator`.

    The plan is :func:`smoothshaper.time_optimal.time_optimal_reference` (linear ramps of the
    acceleration, or half-cosine transitions for the trigonometric profile). With a mode,
    q, v, a, j are the plan's convolved with the taps of :func:`tuned_stage` from the
    reference filters (independent of the C smoother), the plan resting at ``position``
    before sample 0; once the plan has rested on its goal for all L taps, the output is
    the goal exactly. Limits and dropped targets follow the generator's documented rules as
    the reference states them (:func:`smoothshaper.time_optimal.reach`, a target whose plan
    is not representable is dropped until it changes).

    Parameters
    ----------
    targets : array_like of float, shape (n,)
        The target at every sample.
    vmax : float, keyword-only
        Velocity bound [units/s], > 0.
    amax : float, keyword-only
        Acceleration bound [units/s^2], > 0.
    jmax : float, keyword-only
        Jerk bound [units/s^3], > 0.
    Ts : float, keyword-only
        Sample period [s], > 0.
    profile : {"polynomial", "trigonometric", "damped"}, keyword-only
        Jerk-limited (linear acceleration ramps), half-cosine acceleration transitions
        (Biagiotti and Melchiorri, "Online Planning of Multi-Segment Trajectories with
        Trigonometric Blends", 2011) or the Damped-Jerk stage (Béarée, "New Damped-Jerk
        trajectory for vibration reduction", 2014; needs ``wn``).
    wn : float or None, keyword-only
        Mode [rad/s] the plan is filtered for (a stage tuned to it, :func:`tuned_stage`).
    zeta : float, keyword-only
        Its damping ratio, in [0, 1) (default 0).
    position : float, keyword-only
        Initial rest position (default 0).

    Returns
    -------
    ndarray of float64, shape (n, 4)
        q, v, a, j at the samples.

    Raises
    ------
    ParameterError
        Naming ``targets``, a bound, ``Ts``, ``profile``, ``wn`` or ``zeta``, or limits
        outside the feasible region (no move that reaches vmax can be planned).
    """
    from .time_optimal import _run, reach_unchecked
    from .reference.filtering import fir_taps_unchecked
    from .stages import _for_mode
    x = _targets("targets", targets)
    vmax = _design._positive("vmax", vmax)
    amax = _design._positive("amax", amax)
    jmax = _design._positive("jmax", jmax)
    Ts = _design._positive("Ts", Ts)
    position = _finite("position", position)
    profile = _design.profile_name(profile)
    wn_, zeta_ = _design._mode(profile, wn, zeta)
    shape = "cosine" if profile == "trigonometric" else "ramp"
    feasible = reach_unchecked(vmax, amax, jmax, Ts, shape)
    quantity = feasible["quantity"]
    if quantity is not None:   # the argument named as the Generator names it
        arguments = [n for n in ("vmax", "amax", "jmax") if n in quantity]
        raise ParameterError(_reach.named(quantity, arguments, feasible["duration"]),
                             f"vmax={vmax!r}, amax={amax!r}, jmax={jmax!r}, Ts={Ts!r}: "
                             f"{quantity} is out of the feasible range: no move "
                             "that reaches vmax can be planned")
    plan, goals, _ = _run(x, vmax=vmax, amax=amax, jmax=jmax, Ts=Ts, q0=position, shape=shape)
    if not wn_:
        return plan
    taps = fir_taps_unchecked(_for_mode(_tuned_kind(profile, zeta_), wn_, zeta_, 1), Ts)
    L = taps.size
    out = np.empty_like(plan)
    for ch in range(4):
        before = np.full(L - 1, position if ch == 0 else 0.0)
        out[:, ch] = np.convolve(np.r_[before, plan[:, ch]], taps, mode="valid")
    rest = (plan[:, 0] == goals) & np.all(plan[:, 1:] == 0.0, axis=1)   # on its goal
    quiet = L
    for m in range(x.size):
        quiet = min(quiet + 1, L) if rest[m] else 0
        if quiet >= L:
            out[m] = (plan[m, 0], 0.0, 0.0, 0.0)
    return out


# ----------------------------------------------------------------------------------------------
# B-splines
# ----------------------------------------------------------------------------------------------

def _bspline_args(degree, T, Ts, axes):
    if not 1 <= _integer("degree", degree) <= BSPLINE_MAX_DEGREE:
        raise ParameterError(
            "degree", f"degree must be an integer in 1..{BSPLINE_MAX_DEGREE}, got {degree!r}")
    if not 1 <= _integer("axes", axes) <= BSPLINE_MAX_AXES:
        raise ParameterError(
            "axes", f"axes must be an integer in 1..{BSPLINE_MAX_AXES}, got {axes!r}")
    Ts = _design._positive("Ts", Ts)
    T = _design._positive("T", T)
    if T / Ts < 1.0 - 1e-9:   # the one rule for short T (T within 1e-9 of Ts is one sample)
        raise ParameterError(
            "T", f"T must be >= Ts = {Ts!r} (one knot spacing of at least a sample), "
                 f"got {T!r}")
    return int(degree), T, Ts, int(axes)


def _via(name, via, axes=None) -> np.ndarray:
    q = _real_array(name, via)
    if q.ndim == 1:
        q = q[:, None]
    if q.ndim != 2 or q.shape[0] < 2:
        raise ParameterError(
            name, f"{name} must have shape (M,) or (M, axes) with M >= 2, got {q.shape}")
    if axes is not None and q.shape[1] != axes:
        raise ParameterError(
            name, f"{name} must have {axes} columns (one per axis), got {q.shape[1]}")
    if not np.all(np.isfinite(q)):
        raise ParameterError(name, f"{name} must be finite")
    return q


class BSpline(Twins):
    """Uniform B-spline interpolating filter on one to three axes, run by the C core
    (``sms_bspline``): a staircase of control points held ``N`` samples each, through
    ``degree`` moving averages of ``N`` samples (Biagiotti and Melchiorri, "Input Shaping via
    B-spline Filters for 3-D Trajectory
    Planning", 2011).

    Via-point i (1 <= i <= M-2) is passed at sample ``(i-1) N + k0`` after the start; the
    output rests on the last via-point from :meth:`end_sample`. Zeros of the filter lie at
    the multiples of ``2 pi / T``, so ``T = 2 pi / wn`` cancels the mode wn
    (:func:`bspline_period`).

    Parameters
    ----------
    degree : int, keyword-only
        Spline degree, 1..7.
    T : float, keyword-only
        Knot spacing [s], >= Ts; rounded to ``N`` whole samples.
    Ts : float, keyword-only
        Sample period [s], > 0.
    axes : int, keyword-only
        Number of axes, 1..3 (default 1).
    precision : {"double", "float"}, keyword-only
        Which build of the C core runs the filter.

    Raises
    ------
    ParameterError
        Naming ``degree``, ``T``, ``Ts``, ``axes`` or ``precision``; ``T`` also when the
        delay lines would exceed :data:`smoothshaper.filters.MAX_BUFFER_REALS`.

    Notes
    -----
    A B-spline filter may be shared between threads (:meth:`process` holds its lock); copies
    and pickles are independent filters (docs/python.md).
    """

    def __init__(self, *, degree: int, T: float, Ts: float, axes: int = 1,
                 precision: str = "double"):
        degree, T, Ts, axes = _bspline_args(degree, T, Ts, axes)
        ffi, lib = _backend(precision)
        self._ffi, self._lib = ffi, lib
        self._lock = new_lock()
        self._init_args = dict(degree=degree, T=T, Ts=Ts, axes=axes, precision=precision)
        need = ffi.new("size_t *")
        st = lib.sms_bspline_buffer_size(degree, axes, T, Ts, need)
        if st != 0:
            _raise_status(st, lib, ffi, "B-spline filter")
        check_memory("T", need[0], f"a degree-{degree} B-spline on {axes} axes with T/Ts = "
                     f"{T / Ts:.6g}")
        self._buffer = np.zeros(need[0], dtype=_real_dtype(precision))
        self._b = ffi.new("sms_bspline *")
        st = lib.sms_bspline_init(self._b, degree, axes, T, Ts,
                                  ffi.from_buffer("sms_real[]", self._buffer), need[0])
        if st != 0:  # pragma: no cover
            _raise_status(st, lib, ffi, "B-spline filter")
        self.degree, self.axes, self.Ts, self.precision = degree, axes, Ts, precision

    def _full_state(self):
        out = np.empty(self._lib.sms_bspline_state_count(self._b), dtype=np.float64)
        self._lib.sms_bspline_get_state(self._b, self._ffi.from_buffer("double[]", out))
        return out, {}

    def _set_full_state(self, state, counters) -> None:
        st = self._lib.sms_bspline_set_state(self._b, self._ffi.from_buffer("double[]", state),
                                             state.size)
        if st != 0:
            _raise_status(st, self._lib, self._ffi, "B-spline state")

    @property
    def N(self) -> int:
        """The knot spacing in samples, ``round(T/Ts)`` (>= 1)."""
        return int(self._b.N)

    @property
    def T(self) -> float:
        """The knot spacing realised, N Ts."""
        return self.N * self.Ts

    @property
    def k0(self) -> int:
        """Delay [samples] from a control point's step to the output passing its via-point."""
        return int(self._b.k0)

    def control_points(self, via) -> np.ndarray:
        """Control points that make the output pass through the via-points (a banded linear solve in
        the C core, ``sms_bspline_control_points``).

        Parameters
        ----------
        via : array_like of float, shape (M, axes) or (M,)
            Via-points, M >= 2, finite.

        Returns
        -------
        ndarray of float64, shape (M, axes)
            The control points (first and last equal the first and last via-point).

        Raises
        ------
        ParameterError
            Naming ``via`` (shape, axes or non-finite values).
        """
        q = _via("via", via, self.axes)
        M = q.shape[0]
        ctrl = np.empty_like(q)
        nwork = self._lib.sms_bspline_work_size(self._b, M)
        work = np.empty(max(nwork, 1))
        st = self._lib.sms_bspline_control_points(
            self._b, self._ffi.from_buffer("double[]", np.ascontiguousarray(q)), M,
            self._ffi.from_buffer("double[]", ctrl), self._ffi.from_buffer("double[]", work), nwork)
        if st != 0:  # pragma: no cover - validated above
            _raise_status(st, self._lib, self._ffi, "B-spline control points")
        limit = input_max(self.precision)
        bad = np.flatnonzero(~(np.abs(ctrl).max(axis=1) <= limit))
        if bad.size:    # the solve amplifies the via-points (by up to ~8 at degree 7)
            raise ParameterError(
                "via", f"via out of range: control point {int(bad[0])} through these via-points "
                f"would be {float(np.abs(ctrl[bad[0]]).max()):.4g}, beyond {limit:g} (the "
                f"filter's input bound for precision={self.precision!r})")
        return ctrl

    def pass_samples(self, M: int) -> np.ndarray:
        """Samples at which the via-points 1 .. M-2 are passed.

        Parameters
        ----------
        M : int
            Number of via-points.

        Returns
        -------
        ndarray of int64, shape (M - 2,)
            ``(i - 1) N + k0`` for i = 1 .. M-2.

        Raises
        ------
        ParameterError
            Naming ``M`` when it is not an integer >= 2 or the array would exceed
            :data:`smoothshaper.filters.MAX_BUFFER_REALS`.
        """
        M = _integer("M", M, 2)
        check_memory("M", M - 2, "the pass samples")
        return np.array([self._lib.sms_bspline_pass_sample(self._b, i) for i in range(1, M - 1)],
                        dtype=np.int64)

    def end_sample(self, M: int) -> int:
        """First sample from which the output rests on the last via-point.

        Parameters
        ----------
        M : int
            Number of via-points.

        Returns
        -------
        int
            ``(M - 2) N + degree (N - 1)``.

        Raises
        ------
        ParameterError
            Naming ``M`` when it is not an integer >= 2.
        """
        M = _integer("M", M, 2)
        return (M - 2) * self.N + self.degree * (self.N - 1)

    def staircase(self, control, n_samples: int) -> np.ndarray:
        """The held control points of the feeding protocol: control point ``j`` from sample
        ``(j - 1) N``, the last one held to the end.

        Parameters
        ----------
        control : array_like of float, shape (M, axes)
            Control points (:meth:`control_points`).
        n_samples : int
            Length of the staircase.

        Returns
        -------
        ndarray of float64, shape (n_samples, axes)
            The filter's input.

        Raises
        ------
        ParameterError
            Naming ``control`` (shape or non-finite values) or ``n_samples`` (not an integer
            >= 0, or beyond :data:`smoothshaper.filters.MAX_BUFFER_REALS` values).
        """
        c = _via("control", control, self.axes)
        n_samples = _integer("n_samples", n_samples, 0)
        check_memory("n_samples", n_samples * self.axes, "the staircase")
        j = np.minimum(np.arange(n_samples) // self.N + 1, c.shape[0] - 1)
        return c[j]

    @locked
    def process(self, x, rest=None, *, progress=None) -> np.ndarray:
        """Filter ``x`` after resting every axis at ``rest``.

        The samples are stepped through ``sms_bspline_step`` one at a time on pointers into one
        contiguous array (about 1 us per sample).

        Parameters
        ----------
        x : array_like of float, shape (n, axes) or (n,) for one axis
            Input samples, finite.
        rest : array_like of float, shape (axes,) or None
            Rest value of every axis before the first sample (default ``x[0]``).
        progress : callable or None, keyword-only
            Called as ``progress(samples)`` after every block of samples.

        Returns
        -------
        ndarray of float64, shape (n, axes)
            The output.

        Raises
        ------
        ParameterError
            Naming ``x`` when it is not real, not finite, empty or not of ``axes`` columns, or
            ``rest`` when it is not ``axes`` finite real values.
        """
        x = _real_array("x", x)
        if x.ndim == 1 and self.axes == 1:
            x = x[:, None]
        if x.ndim != 2 or x.shape[1] != self.axes or x.shape[0] == 0:
            raise ParameterError("x", f"x must have shape (n,) or (n, axes) with n >= 1 and "
                                 f"axes = {self.axes}, got {x.shape}")
        x = np.ascontiguousarray(x)
        if not np.all(np.isfinite(x)):
            raise ParameterError("x", "x must be finite")
        if rest is None:
            rest = x[0]
        else:
            rest = _real_array("rest", rest)
            if rest.size != self.axes or rest.ndim > 1:
                raise ParameterError("rest", f"rest must hold {self.axes} value(s), one per "
                                     f"axis, got shape {rest.shape}")
            rest = rest.reshape(self.axes)
            if not np.all(np.isfinite(rest)):
                raise ParameterError("rest", "rest must be finite")
        # beyond the C core's input bound a difference of two samples (or the float cast)
        # overflows, and the output would be inf or NaN
        limit = input_max(self.precision)
        for name, values in (("x", x), ("rest", rest)):
            bad = np.flatnonzero(np.abs(np.reshape(values, (-1, self.axes))).max(axis=1) > limit)
            if bad.size:
                where = f"x[{int(bad[0])}]" if name == "x" else "rest"
                raise ParameterError(
                    name, f"{name} out of range: {where} exceeds {limit:g} in magnitude (the "
                    f"filter's input bound for precision={self.precision!r})")
        ffi, lib, b, axes = self._ffi, self._lib, self._b, self.axes
        lib.sms_bspline_reset(b, ffi.new("sms_real[]", [float(v) for v in rest]))
        work = np.ascontiguousarray(x, dtype=_real_dtype(self.precision))
        out = np.empty_like(work)
        pin = ffi.from_buffer("sms_real[]", work)
        pout = ffi.from_buffer("sms_real[]", out)
        step = lib.sms_bspline_step
        block = 1 << 16
        for start in range(0, work.shape[0], block):
            stop = min(start + block, work.shape[0])
            for k in range(start * axes, stop * axes, axes):
                step(b, pin + k, pout + k)
            if progress is not None:
                progress(stop - start)
        return out.astype(np.float64, copy=False)

    def interpolate(self, via, *, extra: int = 0, progress=None) -> np.ndarray:
        """The output passing through the via-points: control points, staircase and filter in one
        call.

        Parameters
        ----------
        via : array_like of float, shape (M, axes) or (M,)
            Via-points, M >= 2.
        extra : int, keyword-only
            Samples appended after the output comes to rest (default 0).
        progress : callable or None, keyword-only
            As in :meth:`process`.

        Returns
        -------
        ndarray of float64, shape (end_sample + 1 + extra, axes)
            The interpolating trajectory; via-point i is met at ``pass_samples(M)[i-1]``.

        Raises
        ------
        ParameterError
            Naming ``via``, or ``extra`` (not an integer >= 0, or too many samples).
        """
        q = _via("via", via, self.axes)
        extra = _integer("extra", extra, 0)
        n = self.end_sample(q.shape[0]) + 1 + extra
        check_memory("extra", n * self.axes, "the interpolated trajectory")
        ctrl = self.control_points(q)
        return self.process(self.staircase(ctrl, n), rest=q[0], progress=progress)


def bspline_reference(via, *, degree: int, T: float, Ts: float):
    """NumPy reference of the B-spline filter: ``(control, output, pass_samples)``.

    The discrete response d of one control point held N samples then ``degree`` moving
    averages of N samples (``np.convolve``), ``k0 = floor((len(d) - 1) / 2)``,
    ``c_m = d[k0 + m N]``, and a dense solve for the control points.

    Parameters
    ----------
    via : array_like of float, shape (M, axes) or (M,)
        Via-points, M >= 2.
    degree : int, keyword-only
        Spline degree, 1..7.
    T : float, keyword-only
        Knot spacing [s], >= Ts.
    Ts : float, keyword-only
        Sample period [s], > 0.

    Returns
    -------
    control : ndarray of float64, shape (M, axes)
        Control points.
    output : ndarray of float64, shape (end_sample + 1, axes)
        The trajectory.
    pass_samples : ndarray of int64, shape (M - 2,)
        Where the inner via-points are passed.

    Raises
    ------
    ParameterError
        Naming ``via``, ``degree``, ``T`` or ``Ts``.
    """
    q = _via("via", via)
    degree, T, Ts, _ = _bspline_args(degree, T, Ts, min(q.shape[1], BSPLINE_MAX_AXES))
    # checked before int(), on T/Ts + 0.5 >= N (an overflowing N would raise there)
    check_memory("T", (degree + 1) * (T / Ts + 0.5) * (q.shape[0] + degree),
                 f"the reference B-spline with T/Ts = {T / Ts:.6g}")
    N = max(1, int(math.floor(T / Ts + 0.5)))
    d = np.ones(N)
    for _ in range(degree):
        d = np.convolve(d, np.full(N, 1.0 / N))
    k0 = (d.size - 1) // 2
    M = q.shape[0]
    n = M - 2
    ctrl = q.copy()
    if n > 0:
        A = np.zeros((n, n))
        rhs = q[1:-1].copy()
        for i in range(1, M - 1):
            for j in range(-degree - 2, M + degree + 2):
                k = k0 + (i - j) * N
                if not 0 <= k < d.size:
                    continue
                if 1 <= j <= M - 2:
                    A[i - 1, j - 1] += d[k]
                else:
                    rhs[i - 1] -= d[k] * (q[0] if j <= 0 else q[-1])
        ctrl[1:-1] = np.linalg.solve(A, rhs)
    n_out = (M - 2) * N + degree * (N - 1) + 1
    jj = np.minimum(np.arange(n_out) // N + 1, M - 1)
    x = ctrl[jj]
    kern = np.full(N, 1.0 / N)
    out = np.empty_like(x)
    for a in range(q.shape[1]):
        # rest at q[0] before sample 0: filter the deviation from it
        y = x[:, a] - q[0, a]
        for _ in range(degree):
            y = np.convolve(y, kern)[:n_out]
        out[:, a] = y + q[0, a]
    passes = np.array([(i - 1) * N + k0 for i in range(1, M - 1)], dtype=np.int64)
    return ctrl, out, passes


def bspline_period(*, wn, Ts: float) -> float:
    """Shortest knot spacing ``N Ts >= 2 pi / min(wn)``: the B-spline filter then has a zero on
    the lowest mode and input-shapes it (Biagiotti and Melchiorri, "Input Shaping via B-spline
    Filters for 3-D Trajectory
    Planning", 2011, sec. IV).

    Parameters
    ----------
    wn : float or array_like of float, keyword-only
        Mode(s) to cancel [rad/s], each finite and > 0.
    Ts : float, keyword-only
        Sample period [s], > 0.

    Returns
    -------
    float
        The knot spacing ``T`` [s], a whole number of samples.

    Raises
    ------
    ParameterError
        Naming ``wn`` or ``Ts``.
    """
    w = np.atleast_1d(_real_array("wn", wn))
    if w.size == 0 or not np.all(np.isfinite(w)) or np.any(w <= 0):
        raise ParameterError(
            "wn", "wn must be one or more finite frequencies > 0 rad/s, got "
                  f"{_show(w.item()) if w.size == 1 else w.tolist()}")
    Ts = _design._positive("Ts", Ts)
    knot = float(w.min()) * Ts          # Python floats: overflow gives inf, not a warning
    samples = 2 * math.pi / knot * (1 - 1e-12) if knot > 0 else math.inf
    if not samples <= _design.MAX_SAMPLES:
        raise ParameterError(
            "wn", f"wn = {float(w.min())!r} rad/s at Ts = {Ts!r} s: its period spans "
                  f"{samples:.4g} samples, more than the 2^52 a count holds exactly")
    return max(1.0, math.ceil(samples)) * Ts


# Coordinated multi-axis motion lives in its own module; exposed here with the other generators.
from .multi_axis import (MultiAxisGenerator, MultiAxisMove, multi_axis_move,  # noqa: E402
                         phase_duration)
from .reference.multi_axis import multi_axis_reference  # noqa: E402
