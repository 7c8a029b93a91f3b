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
from ._checks import position_limits as _checked_position_limits
from ._checks import (finite as _finite, finite_signal as _targets, integer as _integer,
                      real_array as _real_array, show as _show)

__all__ = ["Generator", "DroppedTargetWarning", "generator_reference", "tuned_stage", "BSpline",
           "bspline_reference", "bspline_period", "BSPLINE_MAX_DEGREE", "BSPLINE_MAX_AXES", "MultiAxisGenerator",
           "MultiAxisMove", "multi_axis_move", "phase_duration", "multi_axis_reference"]

BSPLINE_MAX_DEGREE = 7
BSPLINE_MAX_AXES = 3
# The fields of a saved state's identity after the common head (trajectory.h).
_GENERATOR_IDENTITY_FIELDS = ("vmax", "amax", "jmax", "profile", "wn", "zeta", "vmin", "amin",
                              "qmin", "qmax")


def _generator_error(st, lib, ffi, cfg, Ts, profile):
    """ParameterError naming the cause of a refused generator config, with the values."""
    if st in (-16, -4, -15, -3) and cfg.wn:
        raise ParameterError("wn", f"wn={cfg.wn!r} rad/s: the stage tuned to the mode cannot be "
                                   f"placed on the grid Ts={Ts!r} s (the mode is at or above "
                                   f"the Nyquist frequency pi/Ts = {math.pi / Ts:.6g} rad/s, or "
                                   "the stage spans too many samples)", st)
    if st in (-17, -55):
        raise _infeasible(lib, ffi, cfg, Ts, st)
    _raise_status(st, lib, ffi, "online generator")


def _infeasible(lib, ffi, cfg, Ts, st):
    """ParameterError for limits with which no plan can reach vmax (``sms_generator_reach``):
    the arguments and their values, the derived quantity out of range, its bound."""
    info = ffi.new("sms_generator_reach_info *")
    lib.sms_generator_reach(cfg, Ts, info)
    return _reach.refused(ffi, info, dict(vmax=cfg.vmax, amax=cfg.amax, jmax=cfg.jmax,
                                          vmin=cfg.vmin or -cfg.vmax,
                                          amin=cfg.amin or -cfg.amax), Ts, st)


def _lower_bound(name, value, upper, upper_name, profile):
    """A lower bound (vmin, amin): None is the symmetric -upper; else finite and < 0, and
    only with the linear-ramp profiles (the half-cosine plans are symmetric)."""
    if value is None:
        return None
    x = _finite(name, value)
    if not x < 0:
        raise ParameterError(name, f"{name}={value!r} must be < 0 (the lower bound; "
                                   f"{upper_name} is the upper one)")
    if profile == "trigonometric" and x != -upper:
        raise ParameterError(name, f"{name}={value!r}: the trigonometric profile takes symmetric "
                                   f"limits only ({name} None or -{upper_name})")
    return x


def _position_limits(qmin, qmax, profile, precision="double"):
    """(qmin, qmax) as the C config takes them (:func:`._checks.position_limits`)."""
    return _checked_position_limits(qmin, qmax, profile, _real_dtype(precision), precision)


def _generator_config(ffi, vmax, amax, jmax, profile, wn, zeta, vmin=None, amin=None,
                      qmin=None, qmax=None, precision="double"):
    cfg = ffi.new("sms_generator_config *")
    cfg.vmax = _design._positive("vmax", vmax)
    cfg.amax = _design._positive("amax", amax)
    cfg.jmax = _design._positive("jmax", jmax)
    profile = _design.profile_name(profile)
    wn_, zeta_ = _design._mode(profile, wn, zeta)
    cfg.profile = _design.PROFILES.index(profile)
    cfg.wn = wn_
    cfg.zeta = zeta_
    lo_v = _lower_bound("vmin", vmin, cfg.vmax, "vmax", profile)
    lo_a = _lower_bound("amin", amin, cfg.amax, "amax", profile)
    cfg.vmin = 0.0 if lo_v is None else lo_v
    cfg.amin = 0.0 if lo_a is None else lo_a
    cfg.qmin, cfg.qmax = _position_limits(qmin, qmax, profile, precision)
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
    vmin, amin : float or None, keyword-only
        Lower velocity and acceleration bounds (ruckig's ``min_velocity``,
        ``min_acceleration``), finite and < 0; None (default): ``-vmax``, ``-amax``. The
        velocity then stays within ``[vmin, vmax]`` and the acceleration within
        ``[amin, amax]`` at every sample (docs/design.md, "Asymmetric limits"). Linear-ramp
        profiles only (polynomial, damped).
    qmin, qmax : float or None, keyword-only
        Position limits (ruckig's ``min_position``, ``max_position``): both finite with
        ``qmin < qmax``, or both None (default: none). Every sample's position then lies in
        ``[qmin, qmax]`` exactly. Targets must rest inside (a position outside, or a target
        velocity or acceleration other than 0, is refused naming ``qmin``/``qmax``, or
        ``velocity``/``acceleration``); :meth:`start_from` refuses a state whose brake to
        rest would cross a limit; a re-plan whose time-optimal motion would cross one brakes
        to rest first and then moves (docs/design.md, "Position limits"). Linear-ramp
        profiles only. The generator starts at ``q0``, which must lie inside.

    Raises
    ------
    ParameterError
        Naming the parameter out of range (a bound, ``Ts``, ``profile``, ``wn``, ``zeta``,
        ``q0``, ``precision``, ``vmin``, ``amin``, ``qmin``, ``qmax``), or limits with which no plan can reach ``vmax``: the message
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
        what="generator", same="``vmax``, ``amax``, ``jmax``, ``profile``, ``wn``, ``zeta``, "
        "``vmin``, ``amin``, ``qmin``, ``qmax``",
        example='``"state is from vmax=2.0 (this Generator: vmax=1.0)"``',
        layout="``sms_generator_get_state``: first the configuration identity "
        "(``SMS_GENERATOR_IDENTITY_COUNT`` = 15 values: state tag, format version, "
        "``sizeof(sms_real)`` (8 double, 4 float), kind (100, a generator), ``Ts``, ``vmax``, "
        "``amax``, ``jmax``, profile index in :data:`~smoothshaper.design.PROFILES`, ``wn`` "
        "(0 without a mode), ``zeta``, ``vmin``, ``amin`` (in effect: ``-vmax``, ``-amax`` "
        "when symmetric), ``qmin``, ``qmax`` (0, 0 without position limits)); then the target and the goal of the running plan, "
        "each as position, velocity, acceleration, interface (0 position, 1 velocity; a "
        "stop is the velocity interface to 0) and minimum duration, the running plan's start "
        "q, v, a and the samples since it (n = 29 without a mode; the offsets are ``SMS_GENERATOR_STATE_*`` "
        "of trajectory.h); with a mode also the samples the plan has rested and the four "
        "states of the tuned stage (each with its own stage identity).")

    def __init__(self, *, vmax: float, amax: float, jmax: float, Ts: float,
                 profile: str = "polynomial", wn: float | None = None, zeta: float = 0.0,
                 q0: float = 0.0, precision: str = "double", vmin: float | None = None,
                 amin: float | None = None, qmin: float | None = None,
                 qmax: float | None = None):
        ffi, lib = _backend(precision)
        self._ffi, self._lib = ffi, lib
        self._lock = new_lock()
        self.Ts = _design._positive("Ts", Ts)
        q0 = _finite("q0", q0)
        self.precision = precision
        self._init_args = dict(vmax=vmax, amax=amax, jmax=jmax, Ts=Ts, profile=profile, wn=wn,
                               zeta=zeta, q0=q0, precision=precision, vmin=vmin, amin=amin,
                               qmin=qmin, qmax=qmax)
        cfg = _generator_config(ffi, vmax, amax, jmax, profile, wn, zeta, vmin, amin, qmin, qmax,
                                precision)
        if (cfg.qmin or cfg.qmax) and not cfg.qmin <= q0 <= cfg.qmax:
            raise ParameterError("q0", f"q0={q0!r} is outside [qmin, qmax] = [{cfg.qmin!r}, "
                                       f"{cfg.qmax!r}]")
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
        # the lower bounds in effect (-vmax, -amax when symmetric)
        self.vmin = cfg.vmin if cfg.vmin != 0 else -cfg.vmax
        self.amin = cfg.amin if cfg.amin != 0 else -cfg.amax
        # the position limits (None without)
        bounded = cfg.qmin != 0 or cfg.qmax != 0
        self.qmin = cfg.qmin if bounded else None
        self.qmax = cfg.qmax if bounded else None
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
            Naming ``position`` when it is not finite, or outside ``[qmin, qmax]``.
        """
        position = self.q0 if position is None else _finite("position", position)
        if self.qmin is not None and not self.qmin <= position <= self.qmax:
            raise ParameterError("position", f"position={position!r} is outside [qmin, qmax] = "
                                             f"[{self.qmin!r}, {self.qmax!r}]")
        self._lib.sms_generator_reset(self._gen, position)

    @locked
    def process(self, targets=None, *, velocity=None, acceleration=None, interface=None,
                stop=None, minimum_duration=None) -> np.ndarray:
        """Run a block of targets, one C call for the whole block.

        With ``targets`` alone, each sample's target is a position to reach and rest on (a
        staircase). ``velocity`` and ``acceleration`` give the state at arrival (a moving
        target: the output reaches the position with that velocity and acceleration exactly
        on a sample, then its acceleration returns to zero at ``jmax`` and the velocity is
        held). ``interface="velocity"`` (the default when ``targets`` is omitted) asks for
        the velocity alone: reached in the least time, the position free. ``stop`` brakes to
        rest at once where it is True. Every sample keeps every limit either way
        (docs/sampled-limits.md).

        Parameters
        ----------
        targets : array_like of float, shape (n,), optional
            The target position at every sample, finite (ignored where the interface is
            "velocity" or ``stop`` holds).
        velocity : float or array_like of float, shape (n,), keyword-only
            Velocity at arrival (position interface) or the velocity to reach (velocity
            interface) [units/s], default 0: ``|velocity| <= vmax``.
        acceleration : float or array_like of float, shape (n,), keyword-only
            Acceleration at arrival [units/s^2], default 0: ``|acceleration| <= amax`` and
            ``velocity -+ acceleration|acceleration|/(2 jmax)`` within ``+-vmax`` (the
            velocity on the way in and after, where the acceleration is zero). The
            trigonometric profile takes position targets at rest and velocity targets with
            acceleration 0 only.
        interface : {"position", "velocity"} or array_like of them, shape (n,), keyword-only
            What each target asks for (default "position" with ``targets``, "velocity"
            without).
        stop : bool or array_like of bool, shape (n,), keyword-only
            Where True, brake to rest at once (the velocity interface to 0).
        minimum_duration : float or array_like of float, shape (n,), keyword-only
            Least duration [s] of the move to each target (ruckig's ``minimum_duration``),
            default 0 (as fast as the limits allow): finite, >= 0, below 2^50 samples of
            ``Ts``; 0 for the trigonometric profile. A new target (any field changed) starts
            its move on its sample; the target state is then reached exactly on the first
            sample N after it with ``N Ts`` at least both this and the time-optimal
            duration at which a motion within the limits exists (a blocked duration is
            skipped to the next that has one; docs/design.md, "A minimum duration").

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
            Naming ``targets``, ``velocity``, ``acceleration``, ``interface``, ``stop`` or
            ``minimum_duration`` (with the first offending sample) when an array is not of
            the block's length or a value is out of range; the state is then untouched.

        Warns
        -----
        DroppedTargetWarning
            Once per call in which targets were dropped, naming the last one, the position
            it was to be reached from and the count (also in :attr:`dropped`).
        """
        rest_only = (velocity is None and acceleration is None and interface is None and
                     stop is None and minimum_duration is None)
        if targets is None and rest_only:
            raise ParameterError("targets", "targets must be given (positions), or velocity "
                                 "for the velocity interface")
        before = self._gen.dropped
        dtype = _real_dtype(self.precision)
        if rest_only:
            x = _targets("targets", targets)
            n = x.size
            if self.qmin is not None:
                self._check_inside(x)
            xin = np.ascontiguousarray(x, dtype=dtype)
            out = np.empty((n, 4), dtype=dtype)
            if n:
                self._lib.sms_generator_process(
                    self._gen, self._ffi.from_buffer("sms_real[]", xin), n,
                    self._ffi.from_buffer("sms_real[]", out))
        else:
            block = self._target_block(targets, velocity, acceleration, interface, stop,
                                       minimum_duration)
            n = block.size
            out = np.empty((n, 4), dtype=dtype)
            if n:
                self._lib.sms_generator_process_targets(
                    self._gen, self._ffi.cast("sms_target *", self._ffi.from_buffer(block)), n,
                    self._ffi.from_buffer("sms_real[]", out))
        if self._gen.dropped != before:
            self._warn_dropped(self._gen.dropped - before)
        return out if dtype == np.float64 else out.astype(np.float64)

    def _target_block(self, targets, velocity, acceleration, interface, stop,
                      minimum_duration=None) -> np.ndarray:
        """The sms_target array of a block, every target checked by the C core (its status
        names the field, the index the sample)."""
        fields = (targets, velocity, acceleration, interface, stop, minimum_duration)
        sizes = [np.size(x) for x in fields if x is not None and np.ndim(x) > 0]
        n = sizes[0] if sizes else 1
        names = ("targets", "velocity", "acceleration", "interface", "stop", "minimum_duration")
        for name, x in zip(names, fields):
            if x is not None and np.ndim(x) > 0 and np.size(x) != n:
                raise ParameterError(name, f"{name} must have the block's length {n} (or be a "
                                     f"scalar), got {np.size(x)} values")

        def column(name, x, default):
            if x is None:
                return np.full(n, default, dtype=np.float64)
            if np.ndim(x) == 0:
                return np.full(n, _finite(name, x))
            return _targets(name, x)
        pos = column("targets", targets, 0.0)
        vel = column("velocity", velocity, 0.0)
        acc = column("acceleration", acceleration, 0.0)
        tmin = column("minimum_duration", minimum_duration, 0.0)
        if interface is None:
            codes = np.full(n, 0 if targets is not None else 1, dtype=np.int32)
        else:
            names_ = np.asarray(interface, dtype=object).reshape(-1)
            codes = np.empty(names_.size, dtype=np.int32)
            for i, value in enumerate(names_):
                if value not in ("position", "velocity"):
                    raise ParameterError("interface", f"interface must be \"position\" or "
                                         f"\"velocity\", got {_show(value)}" +
                                         (f" at sample {i}" if np.ndim(interface) else ""))
                codes[i] = 0 if value == "position" else 1
            codes = np.broadcast_to(codes, (n,)).copy()
            if targets is None and np.any(codes == 0):
                raise ParameterError("targets", "targets (positions) must be given where the "
                                     "interface is \"position\"")
        if stop is not None:
            halt = np.asarray(stop)
            if halt.dtype != np.bool_:
                raise ParameterError("stop", f"stop must be a bool or an array of bools, got "
                                     f"{halt.dtype}")
            codes[np.broadcast_to(halt, (n,))] = 2
        real = _real_dtype(self.precision)
        block = np.zeros(n, dtype=_target_dtype(real))
        with np.errstate(over="ignore"):      # beyond float's range: inf, refused below
            block["position"] = pos.astype(real)
            block["velocity"] = vel.astype(real)
            block["acceleration"] = acc.astype(real)
            block["minimum_duration"] = tmin.astype(real)
        block["interface"] = codes
        index = self._ffi.new("size_t *")
        st = self._lib.sms_generator_check_targets(
            self._gen, self._ffi.cast("sms_target *", self._ffi.from_buffer(block)), n, index)
        if st != 0:
            i = int(index[0])
            if st == -56:
                side = "qmin" if pos[i] < self.qmin else "qmax"
                raise ParameterError(side, f"targets at sample {i}: the position {pos[i]!r} is "
                                     f"outside [qmin, qmax] = [{self.qmin!r}, {self.qmax!r}] "
                                     f"({'below qmin' if side == 'qmin' else 'above qmax'})", st)
            field = {-3: ("minimum_duration",), -46: ("targets",), -47: ("velocity",),
                     -48: ("acceleration",), -49: ("interface",)}[st]
            raise ParameterError(field[0], _target_message(
                self, field[0], i, float(pos[i]), float(vel[i]), float(acc[i]), int(codes[i]),
                float(tmin[i])), st)
        return block

    def _check_inside(self, x) -> None:
        """ParameterError naming qmin or qmax for the first target position outside them."""
        bad = np.flatnonzero((x < self.qmin) | (x > self.qmax))
        if bad.size:
            i = int(bad[0])
            side = "qmin" if x[i] < self.qmin else "qmax"
            raise ParameterError(side, f"targets at sample {i}: the position {float(x[i])!r} is "
                                 f"outside [qmin, qmax] = [{self.qmin!r}, {self.qmax!r}] "
                                 f"({'below qmin' if side == 'qmin' else 'above qmax'})", -56)

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

    @property
    def arrival(self) -> int:
        """Samples from the last one output until the one on which the running plan reaches
        its target state (0 once reached)."""
        return int(self._lib.sms_generator_arrival(self._gen))

    def _warn_dropped(self, count: int) -> None:
        g = self._gen
        target, q, goal = float(g.target.position), float(g.plan_q), float(g.plan.goal)
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
                   target: float | None = None, velocity: float = 0.0,
                   acceleration: float = 0.0, interface: str | None = None,
                   minimum_duration: float = 0.0) -> None:
        """Continue from the motion state (q, v, a): the generator is there now, on the first
        sample of its plan to the target, and the next :meth:`process` goes on from there
        (re-planning when its first target differs).

        A tuned stage (``wn``) keeps its history: it filters the new plan from the next
        sample on, as it would after a re-plan.

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
        target : float or None, keyword-only
            The position the motion heads for until the next target arrives; None (the
            default, with ``interface`` None): brake to rest at once.
        velocity, acceleration : float, keyword-only
            The target's velocity and acceleration at arrival (or the velocity to reach with
            ``interface="velocity"``), as for :meth:`process`.
        interface : {"position", "velocity"} or None, keyword-only
            Default "position" when ``target`` is given; with neither, a stop.
        minimum_duration : float, keyword-only
            Least duration [s] of the motion to the target, as for :meth:`process`
            (default 0; ignored for a stop).

        Raises
        ------
        ParameterError
            Naming ``qmin`` or ``qmax`` (position limits) when ``q`` or the target lies
            outside them or neither the motion to the target nor the brake to rest stays
            inside; naming ``q``, ``v``, ``a``, ``target``, ``velocity``, ``acceleration``,
            ``interface`` or ``minimum_duration`` when one is not finite or out of range, or the state is one no plan
            of this generator can start from; ``target`` also when the motion to it cannot be
            represented in the build's floats. Nothing is changed then.
        """
        q = _finite("q", q)
        v = _finite("v", v)
        a = _finite("a", a)
        ffi, lib = self._ffi, self._lib
        t = ffi.new("sms_target *")
        if interface is None:
            interface = "position" if target is not None else None
        if interface is None:
            t.interface = 2
        elif interface in ("position", "velocity"):
            if interface == "position":
                if target is None:
                    raise ParameterError("target", "target must be given for the position "
                                         "interface")
                t.position = _finite("target", target)
            t.velocity = _finite("velocity", velocity)
            t.acceleration = _finite("acceleration", acceleration)
            t.minimum_duration = _finite("minimum_duration", minimum_duration)
            t.interface = 0 if interface == "position" else 1
        else:
            raise ParameterError("interface", f"interface must be \"position\", \"velocity\" or "
                                 f"None, got {_show(interface)}")
        with np.errstate(over="ignore"):      # beyond float's range: inf, refused by C
            st = lib.sms_generator_start(self._gen, q, v, a, t)
        if st == 0:
            return
        tol = float(lib.SMS_LIMIT_RTOL)
        if st == -46:
            raise ParameterError("q", f"q={q!r} must be finite", st)
        if st == -47 and not lib.sms_generator_check_target(self._gen, t) == -47:
            raise ParameterError("v", f"v={v!r} is outside {_velocity_bounds(self)} (beyond "
                                 f"the generator's own rounding, a relative {tol:.3g})", st)
        if st == -48 and not lib.sms_generator_check_target(self._gen, t) == -48:
            raise ParameterError(
                "a", f"(q, v, a) = ({q!r}, {v!r}, {a!r}) is not a state a plan of this generator "
                f"can start from: a outside {_acceleration_bounds(self)}, or bringing a to zero "
                f"would leave {_velocity_bounds(self)} (beyond the generator's own rounding, a "
                f"relative {tol:.3g})", st)
        if st == -56:
            if lib.sms_generator_check_target(self._gen, t) == -56:
                side = "qmin" if t.position < self.qmin else "qmax"
                raise ParameterError(side, f"target={float(t.position)!r} is outside [qmin, "
                                     f"qmax] = [{self.qmin!r}, {self.qmax!r}]", st)
            side = ("qmin" if q < self.qmin else "qmax" if q > self.qmax else
                    "qmax" if v > 0 or (v == 0 and a > 0) else "qmin")
            if not self.qmin <= q <= self.qmax:
                raise ParameterError(side, f"q={q!r} is outside [qmin, qmax] = [{self.qmin!r}, "
                                     f"{self.qmax!r}]", st)
            raise ParameterError(side, f"(q, v, a) = ({q!r}, {v!r}, {a!r}): neither the "
                                 "time-optimal motion to the target nor the brake to rest (the "
                                 f"stop, at the limits) stays within [qmin, qmax] = "
                                 f"[{self.qmin!r}, {self.qmax!r}]: it would pass {side}", st)
        if st in (-3, -47, -48, -49):
            name = {-3: "minimum_duration", -47: "velocity", -48: "acceleration",
                    -49: "interface"}[st]
            raise ParameterError(name, _target_message(
                self, name, None, float(t.position), float(t.velocity), float(t.acceleration),
                int(t.interface), float(t.minimum_duration)), st)
        raise ParameterError(
            "target", f"target: the move from (q, v, a) = ({q!r}, {v!r}, {a!r}) cannot be "
            f"represented in {self.precision} (more than 2^52 samples of Ts, or a value beyond "
            "the range of a float)", st)


def _target_dtype(real):
    """NumPy's layout of sms_target for the precision (C alignment)."""
    return np.dtype([("position", real), ("velocity", real), ("acceleration", real),
                     ("interface", np.int32), ("minimum_duration", real)], align=True)


def _velocity_bounds(g) -> str:
    """The velocity bounds as a message names them: +-vmax, or [vmin, vmax]."""
    if g.vmin == -g.vmax:
        return f"+-vmax = +-{g.vmax!r}"
    return f"[vmin, vmax] = [{g.vmin!r}, {g.vmax!r}]"


def _acceleration_bounds(g) -> str:
    """The acceleration bounds as a message names them: +-amax, or [amin, amax]."""
    if g.amin == -g.amax:
        return f"+-amax = +-{g.amax!r}"
    return f"[amin, amax] = [{g.amin!r}, {g.amax!r}]"


def _target_message(g, name, i, position, velocity, acceleration, code, minimum_duration=0.0):
    """Why the generator refuses a target's field, with the values and the limits."""
    at = "" if i is None else f" at sample {i}"
    if name == "minimum_duration":
        if g.profile == "trigonometric" and minimum_duration >= 0:
            return (f"minimum_duration{at}: {minimum_duration!r}: the trigonometric profile "
                    "does not stretch a move (minimum_duration 0)")
        return (f"minimum_duration{at}: {minimum_duration!r} must be finite, >= 0 and below "
                f"2^50 samples of Ts = {g.Ts!r}")
    if name == "targets":
        return f"targets{at}: the position {position!r} must be finite"
    if name == "interface":
        return f"interface{at}: {code!r} is not position, velocity or stop"
    bounded = getattr(g, "qmin", None) is not None
    if bounded and name in ("velocity", "acceleration") and \
            (velocity if name == "velocity" else acceleration) != 0:
        value = velocity if name == "velocity" else acceleration
        return (f"{name}{at}: {value!r}: with position limits [qmin, qmax] = [{g.qmin!r}, "
                f"{g.qmax!r}] a target rests ({name} 0; a motion moving on after it would leave "
                "them)")
    if name == "velocity":
        if g.profile == "trigonometric" and velocity != 0 and math.isfinite(velocity) \
                and abs(velocity) <= g.vmax:
            return (f"velocity{at}: {velocity!r}: the trigonometric profile plans position "
                    "targets at rest only (velocity 0)")
        return f"velocity{at}: {velocity!r} must be finite and within {_velocity_bounds(g)}"
    if g.profile == "trigonometric" and acceleration != 0:
        return (f"acceleration{at}: {acceleration!r}: the trigonometric profile holds no "
                "acceleration at a target (acceleration 0)")
    reach = acceleration * abs(acceleration) / (2 * g.jmax) if math.isfinite(acceleration) else 0
    return (f"acceleration{at}: {acceleration!r} must be finite, within "
            f"{_acceleration_bounds(g)}, "
            f"and keep velocity -+ acceleration|acceleration|/(2 jmax) = {velocity - reach!r}, "
            f"{velocity + reach!r} within {_velocity_bounds(g)} (the velocity where the "
            "acceleration was zero on the way in and where it returns to zero after)")


# ----------------------------------------------------------------------------------------------
# NumPy reference of the generator
# ----------------------------------------------------------------------------------------------

def _reference_targets(targets, velocity, acceleration, interface, stop, *, vmax, amax, jmax,
                       profile, minimum_duration=None, vmin=None, amin=None):
    """(positions, velocities, accelerations, interface codes, minimum durations) of a block,
    checked as the reference states the rules
    (:func:`smoothshaper.reference.third_order.target_ok`)."""
    from .reference import third_order as _to
    if (velocity is None and acceleration is None and interface is None and stop is None
            and minimum_duration is None):
        x = _targets("targets", targets)
        return x, None, None, None, None
    arrays = [a for a in (targets, velocity, acceleration, interface, stop, minimum_duration)
              if a is not None and np.ndim(a) > 0]
    n = np.size(arrays[0]) if arrays else 1
    pos = np.zeros(n) if targets is None else np.broadcast_to(
        _targets("targets", np.atleast_1d(targets)), (n,))
    vel = np.zeros(n) if velocity is None else np.broadcast_to(
        _targets("velocity", np.atleast_1d(velocity)), (n,))
    acc = np.zeros(n) if acceleration is None else np.broadcast_to(
        _targets("acceleration", np.atleast_1d(acceleration)), (n,))
    tmin = np.zeros(n) if minimum_duration is None else np.broadcast_to(
        _targets("minimum_duration", np.atleast_1d(minimum_duration)), (n,))
    if interface is None:
        codes = np.full(n, 0 if targets is not None else 1)
    else:
        names = np.broadcast_to(np.asarray(interface, dtype=object), (n,))
        if not all(name in ("position", "velocity") for name in names):
            raise ParameterError("interface", 'interface must be "position" or "velocity"')
        codes = np.array([0 if name == "position" else 1 for name in names])
    if stop is not None:
        codes = np.where(np.broadcast_to(np.asarray(stop, dtype=bool), (n,)), 2, codes)
    lim = _to.Limits(_design._positive("vmax", vmax), _design._positive("amax", amax),
                     _design._positive("jmax", jmax), vmin, amin)
    trig = _design.profile_name(profile) == "trigonometric"
    for i in range(n):
        if codes[i] == 2:
            continue
        if not tmin[i] >= 0 or (trig and tmin[i] != 0):
            raise ParameterError("minimum_duration", f"minimum_duration at sample {i}: "
                                 f"{tmin[i]!r} must be >= 0 (0 for the trigonometric profile)")
        bad = _to.target_ok(float(vel[i]), float(acc[i]), lim)
        if trig and bad is None and (acc[i] != 0 or (codes[i] == 0 and vel[i] != 0)):
            bad = "velocity" if acc[i] == 0 else "acceleration"
        if bad is not None:
            raise ParameterError(bad, f"{bad} at sample {i}: (velocity, acceleration) = "
                                 f"({vel[i]!r}, {acc[i]!r}) is not a target of these limits")
    return np.asarray(pos, dtype=float), np.asarray(vel), np.asarray(acc), codes, np.asarray(tmin)


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


def generator_reference(targets=None, *, vmax, amax, jmax, Ts, profile="polynomial", wn=None,
                        zeta=0.0, position=0.0, velocity=None, acceleration=None,
                        interface=None, stop=None, minimum_duration=None, vmin=None,
                        amin=None, qmin=None, qmax=None) -> np.ndarray:
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
    targets : array_like of float, shape (n,), optional
        The target position at every sample.
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
    velocity, acceleration, interface, stop, minimum_duration : keyword-only
        As for :meth:`Generator.process`.
    vmin, amin : float or None, keyword-only
        Lower velocity and acceleration bounds, as for :class:`Generator` (None: ``-vmax``,
        ``-amax``); the feasible region then covers the moves that reach each velocity bound
        with each acceleration bound (:func:`smoothshaper.time_optimal.reach_pairs`).
    qmin, qmax : float or None, keyword-only
        Position limits, as for :class:`Generator`: targets outside them, or not at rest, are
        ignored (the held one kept); each plan is the time-optimal one when its extremes (the
        zeros of each piece's velocity) stay inside, else the brake to rest, a rest until the
        next sample and the move from there. The reference does not hold q to the limits:
        its samples show the plan's rounding (docs/design.md, "Position limits").

    Returns
    -------
    ndarray of float64, shape (n, 4)
        q, v, a, j at the samples.

    Raises
    ------
    ParameterError
        Naming ``targets``, a bound, ``Ts``, ``profile``, ``wn``, ``zeta``, ``velocity``,
        ``acceleration``, ``interface`` or ``stop``, or limits outside the feasible region
        (no move that reaches vmax can be planned).
    """
    from .time_optimal import TS_MAX, _run, reach_pairs, reach_unchecked
    from .reference.filtering import fir_taps_unchecked
    from .stages import _for_mode
    vmax = _design._positive("vmax", vmax)
    amax = _design._positive("amax", amax)
    jmax = _design._positive("jmax", jmax)
    profile = _design.profile_name(profile)
    vmin = _lower_bound("vmin", vmin, vmax, "vmax", profile)
    amin = _lower_bound("amin", amin, amax, "amax", profile)
    qlo, qhi = _position_limits(qmin, qmax, profile)
    qlim = (qlo, qhi) if (qlo or qhi) else None
    if qlim is not None and not qlo <= _finite("position", position) <= qhi:
        raise ParameterError("position", f"position={position!r} is outside [qmin, qmax] = "
                                         f"[{qlo!r}, {qhi!r}]")
    columns = _reference_targets(targets, velocity, acceleration, interface, stop, vmax=vmax,
                                 amax=amax, jmax=jmax, profile=profile,
                                 minimum_duration=minimum_duration, vmin=vmin, amin=amin)
    x = columns[0]
    Ts = _design._positive("Ts", Ts)
    position = _finite("position", position)
    wn_, zeta_ = _design._mode(profile, wn, zeta)
    shape = "cosine" if profile == "trigonometric" else "ramp"
    if not Ts <= TS_MAX:      # checked before the limits, as the Generator does
        raise ParameterError("Ts", f"Ts={Ts!r}, vmax={vmax!r}, amax={amax!r}, jmax={jmax!r}: "
                                   f"Ts is above {TS_MAX:.6g} = 2^967, the largest a generator "
                                   "takes (2^56 Ts, its longest time sum, must stay finite)")
    if vmin is None and amin is None:
        feasible = reach_unchecked(vmax, amax, jmax, Ts, shape)
    else:
        feasible = reach_pairs(vmax, amax, jmax, -vmax if vmin is None else vmin,
                               -amax if amin is None else amin, Ts, shape)
    quantity = feasible["quantity"]
    if quantity is not None:   # the argument named as the Generator names it
        arguments = [n for n in _reach.LIMITS if n in quantity]
        raise ParameterError(_reach.named(quantity, arguments, feasible["duration"]),
                             f"vmax={vmax!r}, amax={amax!r}, jmax={jmax!r}, Ts={Ts!r}: "
                             f"{quantity} is out of the feasible range: no move "
                             "that reaches vmax can be planned")
    plan, goals, _ = _run(x, vmax=vmax, amax=amax, jmax=jmax, Ts=Ts, q0=position, shape=shape,
                          velocity=columns[1], acceleration=columns[2], interface=columns[3],
                          minimum_duration=columns[4], vmin=vmin, amin=amin, qlim=qlim)
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
