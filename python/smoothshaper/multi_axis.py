# SPDX-License-Identifier: Apache-2.0
"""Coordinated multi-axis motion: the C-backed online generator and the offline design.

* :class:`MultiAxisGenerator` wraps ``sms_multi_generator``: target vectors of shape
  (n, axes) in, (n, axes, 4) position, velocity, acceleration and jerk out; every axis within
  its own ``vmax[i]``, ``amax[i]``, ``jmax[i]`` at every sample. ``sync="phase"`` (default)
  moves all axes on one straight line, starting and arriving on the same sample with the
  time-optimal duration under every axis's limits; ``sync="independent"`` runs each axis
  time-optimally on its own. Targets changing mid-motion are blended (docs/multi-axis.md).
* :func:`multi_axis_move` designs one rest-to-rest move offline for a target vector.
* The independent NumPy reference is :func:`smoothshaper.reference.multi_axis.multi_axis_reference`.
"""
from __future__ import annotations

import itertools
import math
import warnings
from dataclasses import dataclass

import numpy as np

from . import _kinematic_fastpath, _reach, _state_identity
from ._shared import Twins, locked, new_lock
from .errors import DroppedTargetWarning
from .filters import MAX_STAGE_LIST, ParameterError, _backend, _fill_config, _real_dtype
from .reference import multi_axis as _ref
from ._checks import (finite_vector as _finite_vector, positive as _positive,
                      real_array as _real_array, show as _show)

__all__ = ["SYNC_MODES", "PER_AXIS_SYNC_MODES", "MultiAxisGenerator", "MultiAxisMove", "phase_duration", "multi_axis_move"]

#: Indices are the C ``sms_sync`` values. "time", "time_if_necessary" and "none" plan each
#: axis from any state to any target state (:meth:`MultiAxisGenerator.process_targets`).
SYNC_MODES = ("phase", "independent", "time", "time_if_necessary", "none")
#: The modes that plan each axis on its own (ruckig's Time, TimeIfNecessary, None).
PER_AXIS_SYNC_MODES = ("time", "time_if_necessary", "none")
_MAX_AXES = 8   # SMS_MULTI_MAX_AXES: the identity has a slot for each, used or not
#: The most values (samples x axes x 4) a multi_axis_move profile holds: 1 GiB of float64.
_MAX_MOVE_VALUES = 2 ** 27

# The fields of a saved state's identity after the common head (multi_generator.h).
_MULTI_IDENTITY_FIELDS = ("axes", "sync") + tuple(
    f"{name}[{i}]" for i in range(_MAX_AXES)
    for name in ("vmax", "amax", "jmax", "n_stages", "qmin", "qmax"))


def _axis_position_limits(qmin, qmax, axes: int, precision: str) -> list:
    """Per axis (qmin, qmax) as the C config takes them ((0, 0): none), from None, or a
    sequence of one value (or None) per axis for each; errors name ``qmin[i]``/``qmax[i]``."""
    from ._checks import position_limits
    real = _real_dtype(precision)
    if qmin is None and qmax is None:
        return [(0.0, 0.0)] * axes
    seqs = {}
    for name, x in (("qmin", qmin), ("qmax", qmax)):
        if x is None:
            raise ParameterError(name, f"{name} must be given with "
                                 f"{'qmax' if name == 'qmin' else 'qmin'} (one value or None "
                                 "per axis; both None: no position limits)")
        x = [x] * axes if np.ndim(x) == 0 else list(x)
        if len(x) != axes:
            raise ParameterError(name, f"{name} must hold one value (or None) per axis "
                                 f"({axes}), got {len(x)}")
        seqs[name] = x
    out = []
    for i, (lo, hi) in enumerate(zip(seqs["qmin"], seqs["qmax"])):
        try:
            out.append(position_limits(lo, hi, "polynomial", real, precision))
        except ParameterError as e:
            raise ParameterError(f"{e.parameter}[{i}]",
                                 f"{e.parameter}[{i}] (axis {i}): {e}", e.status) from None
    return out


def _limit_vector(name: str, values, axes: int | None) -> np.ndarray:
    """Per-axis limits as a float64 vector; ParameterError naming ``name[i]``."""
    v = np.atleast_1d(_real_array(name, values))
    if v.ndim != 1 or v.size == 0:
        raise ParameterError(name, f"{name} must be a value or a non-empty vector, got shape "
                             f"{v.shape}")
    if axes is not None and v.size == 1:
        v = np.full(axes, v[0])
    if axes is not None and v.size != axes:
        raise ParameterError(name, f"{name} has {v.size} values for {axes} axes")
    for i, x in enumerate(v):
        if not (math.isfinite(x) and x > 0):
            raise ParameterError(f"{name}[{i}]", f"{name}[{i}] must be finite and > 0, got {float(x)!r}")
    return v


def _limits(vmax, amax, jmax, axes=None):
    # each checked alone first, so that a malformed bound is named, not the axis count it implies
    v, a, j = (_limit_vector(name, value, None)
               for name, value in (("vmax", vmax), ("amax", amax), ("jmax", jmax)))
    if axes is None:
        axes = max(x.size for x in (v, a, j))
    return tuple(_per_axis(name, x, axes) for name, x in (("vmax", v), ("amax", a), ("jmax", j)))


def _per_axis(name: str, v: np.ndarray, axes: int) -> np.ndarray:
    """A checked limit vector (:func:`_limit_vector`) for ``axes`` axes: a single value
    applies to every axis."""
    if v.size == 1:
        return np.full(axes, v[0])
    if v.size != axes:
        raise ParameterError(name, f"{name} has {v.size} values for {axes} axes")
    return v


def _sync(sync: str) -> str:
    s = str(sync).lower()
    if s not in SYNC_MODES:
        raise ParameterError("sync", f"sync must be one of {SYNC_MODES}, got {sync!r}")
    return s


def _infeasible(lib, ffi, cfg, Ts, st):
    """ParameterError for an axis whose limits let no move reach its vmax
    (``sms_multi_generator_reach``): the axis's arguments as ``vmax[i]=...``, the derived
    quantity out of range, its value and bound."""
    info, axis = ffi.new("sms_generator_reach_info *"), ffi.new("size_t *")
    lib.sms_multi_generator_reach(cfg, Ts, info, axis)
    i = axis[0]
    return _reach.refused(ffi, info, dict(vmax=cfg.vmax[i], amax=cfg.amax[i], jmax=cfg.jmax[i]),
                          Ts, st, axis=i)


class MultiAxisGenerator(_state_identity.SavedState, Twins):
    """Online multi-axis generator (C core ``sms_multi_generator``, up to ``MAX_AXES`` axes).

    :meth:`process` takes targets of shape (n, axes) and returns (n, axes, 4): q, v, a, j of
    each axis at each sample (the exact values of the continuous profile; after vibration
    stages, the filtered ones). With ``sync="phase"`` every move is the time-optimal
    jerk-limited straight line whose path parameter obeys ``min_i limit_i/|delta_i|``, all
    axes arriving together (the phase synchronisation ruckig offers); ``"independent"``
    moves each axis time-optimally on its own (docs/multi-axis.md).

    Parameters
    ----------
    vmax, amax, jmax : float or sequence of float, keyword-only
        Velocity [units/s], acceleration [units/s^2] and jerk [units/s^3] bounds, one per
        axis (a scalar applies to every axis), each > 0.
    Ts : float, keyword-only
        Sample period [s], > 0.
    sync : {"phase", "independent", "time", "time_if_necessary", "none"}, keyword-only
        Coordination of the axes (default ``"phase"``). The last three plan each axis from
        its exact state (q, v, a) to a target state (position, velocity, acceleration,
        :meth:`process_targets`, :meth:`start`): ``"time"`` lands every axis on one common
        sample (curved paths), ``"time_if_necessary"`` only the axes whose target moves,
        ``"none"`` each axis as fast as it can (ruckig's Time, TimeIfNecessary, None).
    q0 : sequence of float or None, keyword-only
        Initial rest position per axis (default 0).
    stages : list of Stage, list of lists of Stage, or None, keyword-only
        Vibration stages applied to every axis, or one list per axis (different lists bend
        straight lines and give a warning); each axis's q, v, a, j pass through its own copy
        of the chain in the C core.
    align : bool, keyword-only
        Pad every axis with a fractional delay to the common lag of the axes' stages (C
        ``config.align``; :attr:`lag` reports it), so that straight moves stay on the line at
        constant speed whatever stages the axes carry (docs/align.md); no warning then.
    precision : {"double", "float"}, keyword-only
        Which build of the C core runs it.
    qmin, qmax : sequence of (float or None), or None, keyword-only
        Position limits per axis (ruckig's min_position, max_position), finite with
        ``qmin[i] < qmax[i]``, or None for an axis without them (both None: none). Every
        sample's position of such an axis lies in ``[qmin[i], qmax[i]]`` exactly, in every
        sync mode. Its targets rest inside (a position outside is refused naming
        ``qmin``/``qmax``, or kept from before by :meth:`process`; a target velocity or
        acceleration other than 0 is refused). "phase" and "independent" then start a
        changed target from rest at the arrival instead of blending it; the per-axis modes
        plan such an axis by :class:`TrajectoryGenerator`'s rule (its time-optimal motion
        when it stays inside, else brake, rest, move), docs/multi-axis.md "Position limits".

    Raises
    ------
    ParameterError
        Naming the offending argument, e.g. ``vmax[2]``, ``Ts``, ``sync``, ``q0``,
        ``qmin[1]`` or a
        stage's parameter; also for limits with which no move of an axis can reach its vmax
        (``sms_multi_generator_reach``, docs/multi-axis.md "Feasible limits"), naming the
        axis, its values and the quantity out of range.

    Notes
    -----
    A generator may be shared between threads (its methods hold its lock, so calls run one at
    a time); ``copy.copy``, ``copy.deepcopy`` and ``pickle`` give independent generators that
    continue bit-exactly (docs/python.md).
    """

    _STATE_C = "sms_multi_generator"
    _STATE_FIELDS = _MULTI_IDENTITY_FIELDS
    _STATE_CHOICES = {"sync": SYNC_MODES}
    _STATE_DOC = dict(
        what="generator", same="axes, ``vmax``, ``amax``, ``jmax``, ``sync``, vibration stages",
        example='``"state is from vmax[1]=2.0 (this MultiAxisGenerator: vmax[1]=1.0)"``, or '
        "which field of a vibration stage",
        layout="``sms_multi_generator_get_state``: first the configuration identity "
        "(``SMS_MULTI_IDENTITY_COUNT`` = 55 values: state tag, format version, "
        "``sizeof(sms_real)``, kind (102), ``Ts``, the number of axes, the sync index in "
        ":data:`SYNC_MODES`, then for each of the 8 axis slots ``vmax``, ``amax``, ``jmax`` "
        "the number of vibration stages, ``qmin`` and ``qmax`` (0, 0: none), 0 beyond "
        "``axes``); then per axis target, "
        "goal, start position, start and cruise velocity, the running moves and the "
        "vibration stages' states.")

    MAX_AXES = _MAX_AXES

    def __init__(self, *, vmax, amax, jmax, Ts: float, sync: str = "phase", q0=None,
                 stages=None, align: bool = False, precision: str = "double",
                 qmin=None, qmax=None):
        ffi, lib = _backend(precision)
        self._ffi, self._lib = ffi, lib
        self._lock = new_lock()
        self.vmax, self.amax, self.jmax = _limits(vmax, amax, jmax)
        self.axes = self.vmax.size
        if not 1 <= self.axes <= lib.SMS_MULTI_MAX_AXES:
            raise ParameterError("vmax", f"1 to {lib.SMS_MULTI_MAX_AXES} axes supported, "
                                         f"got {self.axes}")
        self.Ts = _positive("Ts", Ts)
        self.sync = _sync(sync)
        self.precision = precision
        if not isinstance(align, (bool, np.bool_)):
            raise ParameterError("align", f"align must be True or False, got {_show(align)}")
        self.align = bool(align)
        self.stages = self._stage_lists(stages)
        cfg = ffi.new("sms_multi_generator_config *")
        cfg.n_axes = self.axes
        for i in range(self.axes):
            cfg.vmax[i], cfg.amax[i], cfg.jmax[i] = self.vmax[i], self.amax[i], self.jmax[i]
        cfg.sync = SYNC_MODES.index(self.sync)
        cfg.align = int(self.align)
        limits = _axis_position_limits(qmin, qmax, self.axes, precision)
        for i, (lo, hi) in enumerate(limits):
            cfg.qmin[i], cfg.qmax[i] = lo, hi
        self.qmin = tuple(lo if (lo, hi) != (0.0, 0.0) else None for lo, hi in limits)
        self.qmax = tuple(hi if (lo, hi) != (0.0, 0.0) else None for lo, hi in limits)
        self._bounded = any(x is not None for x in self.qmin)
        self._configs = []  # kept alive: the config points into them
        for i, lst in enumerate(self.stages):
            if lst:
                configs = ffi.new("sms_stage_config[]", len(lst))
                for k, stage in enumerate(lst):
                    _fill_config(configs[k], stage)
                self._configs.append(configs)
                cfg.stages[i], cfg.n_stages[i] = configs, len(lst)
        n_structs, n_cells, bad = ffi.new("size_t *"), ffi.new("size_t *"), ffi.new("size_t *")
        st = lib.sms_multi_generator_memory(cfg, self.Ts, n_structs, n_cells, bad)
        if st != 0:
            text = ffi.string(lib.sms_status_string(st)).decode()
            if st in (lib.SMS_ERR_LIMIT, lib.SMS_ERR_SAMPLE_PERIOD_RANGE):
                raise _infeasible(lib, ffi, cfg, self.Ts, st)
            if self.stages[bad[0]]:
                raise ParameterError("stages", f"stages of axis {bad[0]} rejected: {text}", st)
            raise ParameterError("Ts", f"Ts = {self.Ts!r} rejected: {text}", st)
        # Owned by this object for its whole life: the C generator points into both.
        self._stage_mem = ffi.new("sms_stage[]", max(1, n_structs[0]))
        self._memory = ffi.new("sms_memory_cell[]", max(1, n_cells[0]))
        self._gen = ffi.new("sms_multi_generator *")
        st = lib.sms_multi_generator_init(self._gen, cfg, self.Ts, self._stage_mem, n_structs[0],
                                          self._memory, n_cells[0], bad)
        if st != 0:  # the size query above validated everything
            raise ParameterError("stages", ffi.string(lib.sms_status_string(st)).decode(), st)
        self._init_args = dict(vmax=self.vmax, amax=self.amax, jmax=self.jmax, Ts=self.Ts,
                               sync=self.sync, stages=self.stages, precision=precision,
                               qmin=self.qmin if self._bounded else None,
                               qmax=self.qmax if self._bounded else None)
        self.reset(q0)

    def _full_state(self):
        # with the diagnostics that are not part of the saved state
        return self.get_state(), {"dropped": int(self._gen.dropped),
                                  "refused": [int(self._gen.move[i].refused)
                                              for i in range(self.axes)],
                                  "plan_refused": int(self._gen.plan_refused)}

    def _set_full_state(self, state, counters) -> None:
        self.set_state(state)
        self._gen.dropped = counters["dropped"]
        for i, refused in enumerate(counters["refused"]):
            self._gen.move[i].refused = refused
        self._gen.plan_refused = counters.get("plan_refused", 0)

    def _stage_lists(self, stages) -> list[list]:
        """One list of stage descriptions per axis (validated: errors name the parameter)."""
        if stages is None:
            return [[] for _ in range(self.axes)]
        from .stages import Stage
        if isinstance(stages, Stage):
            stages = [stages]
        if not isinstance(stages, (list, tuple)):
            try:
                stages = list(itertools.islice(iter(stages), MAX_STAGE_LIST + 1))
            except TypeError:
                raise ParameterError("stages", "stages must be a sequence of Stage, or one "
                                     f"per axis, got {_show(stages)}") from None
        per_axis = (isinstance(stages, (list, tuple)) and len(stages) == self.axes
                    and all(isinstance(s, (list, tuple)) for s in stages))
        lists = [list(s) for s in stages] if per_axis else [list(stages)] * self.axes
        if any(lst != lists[0] for lst in lists):
            warnings.warn("different vibration stages per axis bend straight lines: the axes "
                          "are smoothed differently (in the accelerations; with align=True "
                          "constant-speed segments stay on the line)" if self.align else
                          "different vibration stages per axis bend straight lines: the axes "
                          "are delayed and smoothed differently (align=True keeps "
                          "constant-speed segments on the line)", stacklevel=3)
        from .filters import Chain
        for lst in {id(lst): lst for lst in lists if lst}.values():
            Chain(lst, Ts=self.Ts, precision=self.precision)  # validates, naming the parameter
        return lists

    @locked
    def reset(self, q0=None) -> None:
        """Rest at ``q0`` on every axis (v = a = j = 0).

        Parameters
        ----------
        q0 : sequence of float or None
            One position per axis (default 0).

        Raises
        ------
        ParameterError
            Naming ``q0`` (wrong length, not finite, or outside an axis's position limits).
        """
        if q0 is None:
            q = np.array([lo if lo is not None and lo > 0 else hi if hi is not None and hi < 0
                          else 0.0 for lo, hi in zip(self.qmin, self.qmax)])
        else:
            q = np.atleast_1d(_real_array("q0", q0)).astype(np.float64)
            if q.ndim != 1 or q.size not in (1, self.axes):
                raise ParameterError("q0", f"q0 must hold one value or one per axis "
                                     f"({self.axes}), got shape {q.shape}")
            q = np.broadcast_to(q, (self.axes,)).copy()
            bad = np.flatnonzero(~np.isfinite(q))
            if bad.size:
                raise ParameterError("q0", f"q0[{bad[0]}] must be finite, got {float(q[bad[0]])!r}")
            for i, (lo, hi) in enumerate(zip(self.qmin, self.qmax)):
                if lo is not None and not lo <= q[i] <= hi:
                    raise ParameterError("q0", f"q0[{i}] = {float(q[i])!r} is outside "
                                         f"[qmin[{i}], qmax[{i}]] = [{lo!r}, {hi!r}]")
        self.q0 = q
        self._init_args["q0"] = q.copy()         # where a copy's reset() returns to
        buf = np.ascontiguousarray(q, dtype=_real_dtype(self.precision))
        self._lib.sms_multi_generator_reset(self._gen, self._ffi.from_buffer("sms_real[]", buf))

    @locked
    def process(self, targets) -> np.ndarray:
        """Run a block of target vectors.

        Parameters
        ----------
        targets : array_like of float, shape (n, axes)
            The target of every axis at every sample; a 1-D array is n samples of one axis
            (axes == 1) or one sample of every axis.

        Returns
        -------
        ndarray of float64, shape (n, axes, 4)
            q, v, a, j of each axis at each sample.

            A target vector whose move cannot be represented (a displacement that is not
            finite, more than 2^52 samples, or a duration in seconds that overflows the
            precision) is dropped: the axes (of its group) keep their goals and it is not
            tried again until it changes (:attr:`refused`, :attr:`dropped`). Nothing else
            drops a move within feasible limits, however long (docs/multi-axis.md).

        Raises
        ------
        ParameterError
            Naming ``targets`` (shape or non-finite values); the state is then untouched.

        Warns
        -----
        DroppedTargetWarning
            Once per call in which targets were dropped, naming the count and the held
            targets of the axes that are refused.
        """
        x = _real_array("targets", targets)
        if x.ndim == 1:
            x = x.reshape(-1, 1) if self.axes == 1 else x.reshape(1, -1)
        if x.ndim != 2 or x.shape[1] != self.axes:
            raise ParameterError("targets", f"targets must have shape (n, {self.axes}), "
                                            f"got {np.shape(targets)}")
        bad = np.argwhere(~np.isfinite(x))
        if bad.size:
            raise ParameterError("targets", f"targets must be finite: targets[{bad[0][0]}, "
                                            f"{bad[0][1]}] = {float(x[tuple(bad[0])])!r}")
        if self._bounded:
            self._check_inside(x, "targets")
        dtype = _real_dtype(self.precision)
        xin = np.ascontiguousarray(x, dtype=dtype)
        out = np.empty((x.shape[0], self.axes, 4), dtype=dtype)
        before = self._gen.dropped
        self._lib.sms_multi_generator_process(self._gen, self._ffi.from_buffer("sms_real[]", xin),
                                              x.shape[0], self._ffi.from_buffer("sms_real[]", out))
        if self._gen.dropped != before:
            held = {f"target[{i}]": float(self._gen.target[i])
                    for i, r in enumerate(self.refused) if r}
            warnings.warn(DroppedTargetWarning(
                f"{self._gen.dropped - before} target vector(s) dropped in this block (a move "
                f"longer than 2^52 samples or a value that overflows {self.precision}); "
                f"refused now: {held or 'none'}; the axes keep their goals until the target "
                "changes"), stacklevel=2)
        return out.astype(np.float64)

    def _check_inside(self, x, name) -> None:
        """ParameterError naming qmin or qmax for the first entry of x (n, axes) outside its
        axis's position limits."""
        for i, (lo, hi) in enumerate(zip(self.qmin, self.qmax)):
            if lo is None:
                continue
            out = np.flatnonzero((x[:, i] < lo) | (x[:, i] > hi))
            if out.size:
                k = out[0]
                side = "qmin" if x[k, i] < lo else "qmax"
                raise ParameterError(side, f"{name}[{k}, {i}] = {float(x[k, i])!r} is outside "
                                     f"[qmin[{i}], qmax[{i}]] = [{lo!r}, {hi!r}] of axis {i}",
                                     self._lib.SMS_ERR_POSITION_LIMIT)

    def _target_dtype(self) -> np.dtype:
        ffi, real = self._ffi, _real_dtype(self.precision)
        names = ("position", "velocity", "acceleration", "sync", "minimum_duration")
        formats = [(real, _MAX_AXES)] * 3 + [(np.intc, _MAX_AXES), real]
        return np.dtype({"names": list(names), "formats": formats,
                         "offsets": [ffi.offsetof("sms_multi_target", n) for n in names],
                         "itemsize": ffi.sizeof("sms_multi_target")})

    def _targets(self, positions, velocities, accelerations, axis_sync, minimum_duration):
        """The C target vectors of a block, checked as ``sms_multi_generator_check_target``
        checks them (ParameterError naming the array and its entry)."""
        real = _real_dtype(self.precision)
        p = _real_array("positions", positions)
        if p.ndim == 1:
            p = p.reshape(-1, 1) if self.axes == 1 else p.reshape(1, -1)
        if p.ndim != 2 or p.shape[1] != self.axes:
            raise ParameterError("positions", f"positions must have shape (n, {self.axes}), "
                                              f"got {np.shape(positions)}")
        arrays = {"positions": p}
        for name, x in (("velocities", velocities), ("accelerations", accelerations)):
            if x is None:
                arrays[name] = np.zeros_like(p)
                continue
            x = _real_array(name, x)
            try:
                arrays[name] = np.broadcast_to(x.reshape(p.shape) if x.size == p.size else x,
                                               p.shape)
            except ValueError:
                raise ParameterError(name, f"{name} must have the shape of positions "
                                           f"{p.shape}, got {np.shape(x)}") from None
        pr, vr, ar = (np.asarray(arrays[k], dtype=real) for k in
                      ("positions", "velocities", "accelerations"))
        vmax, amax, jmax = (np.asarray(x, dtype=real) for x in (self.vmax, self.amax, self.jmax))
        with np.errstate(all="ignore"):
            reach = ar * np.abs(ar) / (real(2) * jmax)
            checks = (("positions", ~np.isfinite(pr), "must be finite"),
                      ("velocities", ~(np.abs(vr) <= vmax), "must be finite and within vmax"),
                      ("accelerations", ~(np.abs(ar) <= amax) | ~(np.abs(vr - reach) <= vmax)
                       | ~(np.abs(vr + reach) <= vmax),
                       "must be finite, within amax and keep v -+ a|a|/(2 jmax) within vmax"))
        for name, bad, rule in checks:
            where = np.argwhere(bad)
            if where.size:
                k, i = where[0]
                raise ParameterError(f"{name}[{k}, {i}]",
                                     f"{name}[{k}, {i}] {rule} of axis {i}, got "
                                     f"{float(arrays[name][k, i])!r}")
        if self._bounded:
            self._check_inside(p, "positions")
            for name, x in (("velocities", vr), ("accelerations", ar)):
                for i, lo in enumerate(self.qmin):
                    moving = np.flatnonzero(x[:, i] != 0) if lo is not None else []
                    if len(moving):
                        raise ParameterError(f"{name}[{moving[0]}, {i}]",
                                             f"{name}[{moving[0]}, {i}] must be 0: axis {i} "
                                             "has position limits (a target drifting on would "
                                             "leave them)")
        if self.sync not in PER_AXIS_SYNC_MODES:
            moving = np.argwhere((vr != 0) | (ar != 0))
            if moving.size:
                raise ParameterError("velocities", f'sync="{self.sync}" plans positions at '
                                     "rest only: velocities and accelerations must be 0 (use "
                                     'sync="time", "time_if_necessary" or "none")')
        codes = np.zeros(_MAX_AXES, dtype=np.intc)
        if axis_sync is not None:
            modes = [axis_sync] * self.axes if isinstance(axis_sync, str) else list(axis_sync)
            if len(modes) != self.axes:
                raise ParameterError("axis_sync", f"axis_sync must hold one mode per axis "
                                     f"({self.axes}), got {len(modes)}")
            for i, m in enumerate(modes):
                if m is None:
                    continue
                if self.sync not in PER_AXIS_SYNC_MODES or str(m).lower() not in PER_AXIS_SYNC_MODES:
                    raise ParameterError(f"axis_sync[{i}]", f"axis_sync[{i}] must be None or one "
                                         f"of {PER_AXIS_SYNC_MODES} (with a per-axis sync mode "
                                         f"of the generator), got {m!r}")
                codes[i] = SYNC_MODES.index(str(m).lower())
        md = float(minimum_duration)
        if not (math.isfinite(md) and 0 <= md <= 2.0 ** 50 * self.Ts) or (
                md != 0 and self.sync not in PER_AXIS_SYNC_MODES):
            raise ParameterError("minimum_duration", "minimum_duration must be finite, >= 0 "
                                 "and below 2^50 samples (with a per-axis sync mode), got "
                                 f"{minimum_duration!r}")
        t = np.zeros(p.shape[0], dtype=self._target_dtype())
        t["position"][:, :self.axes] = pr
        t["velocity"][:, :self.axes] = vr
        t["acceleration"][:, :self.axes] = ar
        t["sync"][:] = codes
        t["minimum_duration"] = md
        return t

    @locked
    def process_targets(self, positions, *, velocities=None, accelerations=None,
                        axis_sync=None, minimum_duration: float = 0.0) -> np.ndarray:
        """Run a block of target states (C ``sms_multi_generator_process_targets``).

        With sync "time", "time_if_necessary" or "none", on every sample whose target differs
        from the one before, every axis re-plans from its exact state there to its target
        (position, velocity, acceleration) with the single-axis planner of
        :meth:`TrajectoryGenerator.process_targets`; the synchronised axes (sync "time", or
        "time_if_necessary" with a moving target) arrive together, exactly on the first
        sample at or after every axis's own optimum (the axes of "none" aside) and
        ``minimum_duration`` at which each of them can (docs/multi-axis.md). Every sample
        holds every axis's limits; each axis lands exactly on its target.

        Parameters
        ----------
        positions : array_like of float, shape (n, axes)
        velocities, accelerations : array_like of float, shape (n, axes), or None (0)
            Target velocity and acceleration per axis and sample: ``|v| <= vmax``,
            ``|a| <= amax`` and ``v -+ a|a|/(2 jmax)`` within ``+-vmax``. Only 0 with sync
            "phase" or "independent".
        axis_sync : str or sequence of (str or None), or None, keyword-only
            Per-axis choice among "time", "time_if_necessary", "none" (None: the
            generator's mode), for the whole block.
        minimum_duration : float, keyword-only
            Least duration [s] of the synchronised axes' moves (0: as fast as possible).

        Returns
        -------
        ndarray of float64, shape (n, axes, 4)

        Raises
        ------
        ParameterError
            Naming the array and entry (``velocities[k, i]``), ``axis_sync[i]`` or
            ``minimum_duration``; the state is then untouched.
        """
        t = self._targets(positions, velocities, accelerations, axis_sync, minimum_duration)
        dtype = _real_dtype(self.precision)
        out = np.empty((t.shape[0], self.axes, 4), dtype=dtype)
        before = self._gen.dropped
        self._lib.sms_multi_generator_process_targets(
            self._gen, self._ffi.cast("sms_multi_target *", self._ffi.from_buffer(t)),
            t.shape[0], self._ffi.from_buffer("sms_real[]", out))
        if self._gen.dropped != before:
            warnings.warn(DroppedTargetWarning(
                f"{self._gen.dropped - before} target vector(s) dropped in this block (a move "
                f"longer than 2^52 samples, a value that overflows {self.precision}, or no "
                "common duration); the axes keep their plans until the target changes"),
                stacklevel=2)
        return out.astype(np.float64)

    @locked
    def start(self, q, v, a, *, positions=None, velocities=None, accelerations=None,
              axis_sync=None, minimum_duration: float = 0.0) -> None:
        """Continue from the motion state (q[i], v[i], a[i]) of every axis (C
        ``sms_multi_generator_start``; sync "time", "time_if_necessary" or "none"): the
        generator is there now, on the first sample of the plans to the target (one row of
        :meth:`process_targets`' arguments; ``positions=None``: every axis brakes to rest at
        once), and the next sample is the plans' next.

        Parameters
        ----------
        q, v, a : sequence of float
            Position, velocity and acceleration of every axis now: ``|v| <= vmax``,
            ``|a| <= amax`` and ``|v + a|a|/(2 jmax)| <= vmax``.
        positions, velocities, accelerations, axis_sync, minimum_duration : keyword-only
            The target, as one row of :meth:`process_targets` (``positions=None``: a stop).

        Raises
        ------
        ParameterError
            Naming ``q[i]``, ``v[i]``, ``a[i]`` (not finite, beyond the limits, or a state
            no plan can start from: ``|v + a|a|/(2 jmax)| > vmax``), ``sync`` (a mode that
            plans no state), or the target's entry; the state is then untouched.
        """
        if self.sync not in PER_AXIS_SYNC_MODES:
            raise ParameterError("sync", f'start() needs sync "time", "time_if_necessary" or '
                                         f'"none", this generator has "{self.sync}"')
        real = _real_dtype(self.precision)
        state = []
        for name, x in (("q", q), ("v", v), ("a", a)):
            x = np.atleast_1d(_real_array(name, x)).astype(np.float64)
            if x.shape != (self.axes,):
                raise ParameterError(name, f"{name} must hold one value per axis ({self.axes}),"
                                           f" got shape {x.shape}")
            state.append(np.ascontiguousarray(x, dtype=real))
        t = None
        if positions is not None:
            t = self._targets(np.reshape(positions, (1, -1)),
                              None if velocities is None else np.reshape(velocities, (1, -1)),
                              None if accelerations is None else np.reshape(accelerations, (1, -1)),
                              axis_sync, minimum_duration)
        axis = self._ffi.new("size_t *")
        ptrs = [self._ffi.from_buffer("sms_real[]", x) for x in state]
        st = self._lib.sms_multi_generator_start(
            self._gen, *ptrs,
            self._ffi.NULL if t is None else self._ffi.cast("sms_multi_target *",
                                                          self._ffi.from_buffer(t)), axis)
        if st == self._lib.SMS_ERR_POSITION_LIMIT:
            i = axis[0]
            qi, vi, ai = (float(x[i]) for x in state)
            lo, hi = self.qmin[i], self.qmax[i]
            side = ("qmin" if qi < lo else "qmax" if qi > hi else
                    "qmax" if vi > 0 or (vi == 0 and ai > 0) else "qmin")
            where = ("is outside" if not lo <= qi <= hi else
                     "cannot be brought to rest (nor moved to its target) within")
            raise ParameterError(side, f"q[{i}] = {qi!r} (v = {vi!r}, a = {ai!r}) of axis {i} "
                                 f"{where} [qmin[{i}], qmax[{i}]] = [{lo!r}, {hi!r}]: it "
                                 f"would pass {side}[{i}]", st)
        if st != 0:
            i = axis[0]
            name = {self._lib.SMS_ERR_TARGET_POSITION: "q", self._lib.SMS_ERR_TARGET_VELOCITY: "v",
                    self._lib.SMS_ERR_TARGET_ACCELERATION: "a"}.get(st)
            text = self._ffi.string(self._lib.sms_status_string(st)).decode()
            if name is None:
                raise ParameterError("positions", f"positions: the motion from this state "
                                     f"cannot be formed ({text})", st)
            raise ParameterError(f"{name}[{i}]", f"{name}[{i}] = {float(state['qva'.index(name)][i])!r}"
                                 f" of axis {i} rejected: {text}", st)

    @property
    def arrival(self) -> int:
        """Samples from the last one output until every axis has reached its target state
        (per-axis sync modes; 0 once reached, and always 0 in the others)."""
        return int(self._lib.sms_multi_generator_arrival(self._gen))

    @property
    def axis_arrival(self) -> tuple:
        """Per axis, samples until it reaches its target state (C
        ``sms_multi_generator_axis_arrival``; the synchronised axes all give :attr:`arrival`)."""
        return tuple(int(self._lib.sms_multi_generator_axis_arrival(self._gen, i))
                     for i in range(self.axes))

    @property
    def lag(self) -> float:
        """The output's lag [s]: the common lag of every axis with ``align=True``, else the
        largest axis's (C ``sms_multi_generator_lag``); 0 without stages."""
        return float(self._lib.sms_multi_generator_lag(self._gen))

    @property
    def refused(self) -> tuple:
        """Per axis, True while its held target is dropped (all axes together in phase
        synchronisation, each axis alone when independent)."""
        if self.sync in PER_AXIS_SYNC_MODES:
            return (bool(self._gen.plan_refused),) * self.axes
        phase = self.sync == "phase"
        return tuple(bool(self._gen.move[0 if phase else i].refused) for i in range(self.axes))

    @property
    def dropped(self) -> int:
        """Target vectors (of a group) dropped since construction or the last :meth:`reset`
        (a diagnostic count; not part of the saved state)."""
        return int(self._gen.dropped)

    @property
    def busy(self) -> bool:
        """True while any axis moves or waits for a new target."""
        return bool(self._lib.sms_multi_generator_busy(self._gen))


@dataclass(frozen=True)
class MultiAxisMove:
    """An offline rest-to-rest move (:func:`multi_axis_move`).

    Attributes
    ----------
    T : float
        Continuous time-optimal duration [s].
    N : int
        Samples until arrival (``ceil(T/Ts)`` for sync="phase").
    Ts : float
        Sample period [s].
    profile : ndarray of float64, shape (N + 1, axes, 4)
        q, v, a, j from the step at which the target is applied to the arrival.
    """
    T: float
    N: int
    Ts: float
    profile: np.ndarray


def phase_duration(delta, *, vmax, amax, jmax) -> float:
    """Time-optimal phase-synchronised rest-to-rest duration for a displacement vector
    (continuous time): the jerk-limited straight move whose path parameter has the limits
    ``min_i vmax_i/|delta_i|``, ``min_i amax_i/|delta_i|``, ``min_i jmax_i/|delta_i|`` (the
    double-S of Biagiotti and Melchiorri, *Trajectory Planning for Automatic Machines and
    Robots*, 2008).

    Parameters
    ----------
    delta : array_like of float, shape (axes,)
        Displacement of every axis.
    vmax, amax, jmax : float or sequence of float, keyword-only
        Velocity [units/s], acceleration [units/s^2] and jerk [units/s^3] bounds, one per
        axis (a scalar applies to every axis), each > 0.

    Returns
    -------
    float
        The duration [s] (0 for no displacement).

    Raises
    ------
    ParameterError
        Naming a bound (``vmax[i]``, ...) or ``delta``; ``delta`` also when the duration
        exceeds the largest double (``delta = [1e300]`` with ``vmax = 1e-300``).

    Notes
    -----
    The C core's ``sms_multi_phase_duration``. Plain numbers (a list or tuple per argument,
    or one number for every axis) take a fast path that checks them in C (about as long as
    ruckig's ``calculate`` of the same move, ``python -m smoothshaper.bench``); anything else,
    and every refused value, runs the checks that name the argument. Limits more than 2^200
    away from the displacement use the NumPy reference's time-scale form instead, which
    stays finite there.
    """
    T = _kinematic_fastpath.phase_duration(delta, vmax, amax, jmax)
    if T is not None:
        return T
    d = _finite_vector("delta", delta)
    v, a, j = _limits(vmax, amax, jmax, d.size)
    T = _kinematic_fastpath.phase_duration(d.tolist(), v.tolist(), a.tolist(), j.tolist())
    if T is None:
        T = _ref._phase_duration(d, v, a, j)
    if not math.isfinite(T):
        raise ParameterError("delta", "delta is too long for these limits: the move lasts more "
                             "than the largest double (1.8e308 s)")
    return T


def multi_axis_move(start, target, *, vmax, amax, jmax, Ts: float, sync: str = "phase",
                    precision: str = "double") -> MultiAxisMove:
    """Rest-to-rest design from ``start`` to ``target``: the sampled phase-synchronised (or
    independent) time-optimal move, run through :class:`MultiAxisGenerator`.

    Parameters
    ----------
    start, target : array_like of float, shape (axes,)
        Rest positions before and after.
    vmax, amax, jmax : float or sequence of float, keyword-only
        Velocity [units/s], acceleration [units/s^2] and jerk [units/s^3] bounds, one per
        axis (a scalar applies to every axis), each > 0.
    Ts : float, keyword-only
        Sample period [s], > 0.
    sync : {"phase", "independent"}, keyword-only
        Coordination of the axes (default ``"phase"``).
    precision : {"double", "float"}, keyword-only
        Which build of the C core runs it.

    Returns
    -------
    MultiAxisMove
        Duration, samples and profile of the move.

    Raises
    ------
    ParameterError
        Naming ``target`` (not a vector the length of ``start``, or a move whose profile
        would hold more than 2^27 values), a bound, ``Ts``, ``sync``.
    """
    s, t = _finite_vector("start", start), _finite_vector("target", target)
    if s.shape != t.shape:
        raise ParameterError("target", f"start and target must be vectors of the same length, "
                                       f"got {s.shape} and {t.shape}")
    vmax, amax, jmax = _limits(vmax, amax, jmax, s.size)   # a scalar: every axis
    gen = MultiAxisGenerator(vmax=vmax, amax=amax, jmax=jmax, Ts=Ts, sync=sync, q0=s,
                             precision=precision)
    d = t - s                   # finite: start, target and the limits are checked above
    if gen.sync == "phase":
        T = _ref._phase_duration(d, gen.vmax, gen.amax, gen.jmax)
    else:
        T = max(_ref._phase_duration(d[i:i + 1], gen.vmax[i:i + 1], gen.amax[i:i + 1],
                                     gen.jmax[i:i + 1]) for i in range(d.size))
    Ts = gen.Ts
    samples = T / Ts * (1 + 1e-12)
    if not samples * d.size * 4 <= _MAX_MOVE_VALUES:      # O(1), before any array
        raise ParameterError("target", f"target: the move from start lasts {T:.3g} s = "
                             f"{samples:.3g} samples of Ts = {Ts:.3g} s; its profile of "
                             f"{d.size} axes would hold more than {_MAX_MOVE_VALUES:.3g} values")
    n = int(math.ceil(samples)) + 2
    prof = gen.process(np.tile(t, (n, 1)))
    arrived = np.all(prof[:, :, 0] == t, axis=1) & np.all(prof[:, :, 1:] == 0, axis=(1, 2))
    N = int(np.argmax(arrived))
    return MultiAxisMove(T=T, N=N, Ts=Ts, profile=prof[:N + 1])
