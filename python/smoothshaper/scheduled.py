# SPDX-License-Identifier: Apache-2.0
""":class:`ScheduledShaper`: a ZV^n input shaper whose mode follows a scheduling signal
(position, payload, any measured variable) through a table (value -> wn, zeta), run by the C
core (``sms_scheduled``, ``c/include/smoothshaper/scheduled.h``; docs/scheduled.md).

At every update (every sample, or every ``update_every`` samples) its taps are those of the
fixed exact-timing ZV^n shaper of the mode the schedule maps the current value to (the pole
interpolated linearly between the table's points), over one delay line: the frozen filter's
zero sits exactly on the current mode, a schedule that holds still gives exactly the fixed
shaper, and the output changes continuously with the schedule. The NumPy oracle is
:func:`smoothshaper.reference.scheduled`.
"""
from __future__ import annotations

import math

import numpy as np

from .filters import (PRECISIONS, ParameterError, _backend, _check_input, _raise_status,
                      _real_dtype, input_max as _input_max)
from .stages import kind_name
from ._shared import Twins, locked as _locked, new_lock as _new_lock
from ._checks import (choice as _choice, finite as _finite, finite_array as _finite_array,
                      integer as _integer, positive as _positive, real_array as _real_array)

__all__ = ["ScheduledShaper", "SCHEDULED_KINDS", "schedule_table"]

#: The shapers a schedule can drive (the ZV^n family).
SCHEDULED_KINDS = ("zv", "zvd", "zvdd", "zvn")
_KIND_CODES = {"zv": 4, "zvd": 5, "zvdd": 6, "zvn": 7}
#: Where the delay line starts in a saved state (after the order, the update period, the
#: countdown, the schedule value of the taps and the ring head: sms_scheduled_get_state).
_STATE_RING = 5
_STATUS_PARAMETER = {-2: "Ts", -6: "table", -7: "table", -10: "order", -8: "update_every",
                     -12: "kind", -16: "table", -19: "table", -15: "table"}


def schedule_table(table) -> np.ndarray:
    """A schedule as an (n, 3) float64 array of rows (value, wn, zeta), checked.

    Parameters
    ----------
    table : array_like, shape (n, 3)
        Rows (scheduling value, wn [rad/s], zeta), values strictly increasing, 1 <= n <= 64.

    Returns
    -------
    ndarray of float64, shape (n, 3)
        The table.

    Raises
    ------
    ParameterError
        Naming ``table`` (shape, non-finite entries, values not strictly increasing, a wn
        not > 0 or a zeta outside [0, 1), naming the row).
    """
    t = np.array(_real_array("table", table), dtype=np.float64)
    if t.ndim != 2 or t.shape[1] != 3 or not 1 <= t.shape[0] <= 64:
        raise ParameterError("table", f"table must have 1 to 64 rows (value, wn, zeta), got "
                             f"shape {t.shape}")
    for i, (s, wn, zeta) in enumerate(t):
        if not (math.isfinite(s) and math.isfinite(wn) and math.isfinite(zeta)):
            raise ParameterError("table", f"table row {i} must be finite, got {t[i].tolist()}")
        if not wn > 0.0:
            raise ParameterError("table", f"table row {i}: wn must be > 0, got {wn!r}")
        if not 0.0 <= zeta < 1.0:
            raise ParameterError("table", f"table row {i}: zeta must be in [0, 1), got {zeta!r}")
        if i > 0 and not s > t[i - 1, 0]:
            raise ParameterError("table", f"table values must increase strictly: row {i} has "
                                 f"{s!r} after {t[i - 1, 0]!r}")
    return t


class ScheduledShaper(Twins):
    """A ZV^n shaper scheduled by a signal through a table, filtered by the C core.

    Parameters
    ----------
    kind : {"zv", "zvd", "zvdd", "zvn"}
        The shaper family (ZV^n: ``order`` for ``"zvn"``).
    table : array_like, shape (n, 3)
        Rows (value, wn [rad/s], zeta), values strictly increasing (:func:`schedule_table`);
        between rows the pole ``-zeta wn + j wn sqrt(1 - zeta^2)`` is interpolated linearly,
        beyond the ends the end rows' modes hold.
    Ts : float, keyword-only
        Sample period [s], > 0.
    order : int, keyword-only
        n of ZV^n for ``kind="zvn"`` (1..8).
    update_every : int, keyword-only
        The taps are recomputed every this many samples (default 1: every sample).
    precision : {"double", "float"}, keyword-only
        Which build of the C core filters.

    Raises
    ------
    ParameterError
        Naming ``kind``, ``table`` (with the row), ``Ts`` (or a row's mode at or above the
        Nyquist frequency, naming ``table``), ``order`` or ``update_every``.

    Notes
    -----
    A shaper may be shared between threads: its methods hold the shaper's lock, so calls run
    one at a time, each on a consistent state (docs/python.md). ``copy``, ``copy.copy``,
    ``copy.deepcopy`` and ``pickle`` give independent shapers that continue bit-exactly.
    """

    def __init__(self, kind: str, table, *, Ts: float, order: int = 1, update_every: int = 1,
                 precision: str = "double"):
        self.kind = kind_name(kind, SCHEDULED_KINDS)
        self.table = schedule_table(table)
        self.Ts = _positive("Ts", Ts)
        self.order = _integer("order", order, 1)
        self.update_every = _integer("update_every", update_every, 1)
        if self.update_every > 0xFFFFFFFF or self.order > 0xFFFFFFFF:
            raise ParameterError("update_every", "update_every and order must fit 32 bits")
        self.precision = _choice("precision", precision, PRECISIONS)
        self._lock = _new_lock()
        self._init_args = dict(kind=self.kind, table=self.table.copy(), Ts=self.Ts,
                               order=self.order, update_every=self.update_every,
                               precision=self.precision)
        self._input_max = _input_max(self.precision)
        ffi, lib = _backend(self.precision)
        self._ffi, self._lib = ffi, lib
        self._points = ffi.new("sms_schedule_point[]", self.table.shape[0])
        for i, (s, wn, zeta) in enumerate(self.table):
            self._points[i].value, self._points[i].wn, self._points[i].zeta = s, wn, zeta
        cfg = ffi.new("sms_scheduled_config *")
        cfg.kind = _KIND_CODES[self.kind]
        cfg.order = self.order
        cfg.points = self._points
        cfg.n_points = self.table.shape[0]
        cfg.update_every = self.update_every
        need = ffi.new("size_t *")
        st = lib.sms_scheduled_buffer_size(cfg, self.Ts, need)
        if st != 0:
            parameter = _STATUS_PARAMETER.get(st, "table")
            _raise_status(st, lib, ffi, f"scheduled {self.kind} shaper, Ts={self.Ts!r}",
                          parameter)
        self._ring = np.zeros(need[0], dtype=_real_dtype(self.precision))
        self._f = ffi.new("sms_scheduled *")
        st = lib.sms_scheduled_init(self._f, cfg, self.Ts, ffi.from_buffer("sms_real[]", self._ring),
                                    need[0])
        if st != 0:  # pragma: no cover - validated above
            _raise_status(st, lib, ffi, "scheduled shaper")

    @property
    def length(self) -> int:
        """The delay line L [samples]: the longest ZV^n over the table, plus one."""
        return int(self._f.len)

    @_locked
    def mode(self, s: float) -> tuple[float, float]:
        """The mode (wn [rad/s], zeta) the schedule maps ``s`` to.

        Parameters
        ----------
        s : float
            A scheduling value (finite).

        Returns
        -------
        tuple of float
            ``(wn, zeta)`` of the interpolated pole.

        Raises
        ------
        ParameterError
            Naming ``s`` when it is not finite.
        """
        v = _finite("s", s)
        wn, zeta = self._ffi.new("double *"), self._ffi.new("double *")
        self._lib.sms_scheduled_mode(self._f, v, wn, zeta)
        return float(wn[0]), float(zeta[0])

    @_locked
    def taps(self) -> np.ndarray:
        """The impulse response of the taps in use.

        Returns
        -------
        ndarray of float64, shape (length,)
            ``h[0 .. L)``.
        """
        out = np.zeros(self.length)
        self._lib.sms_scheduled_taps(self._f, self._ffi.from_buffer("double[]", out), out.size)
        return out

    @_locked
    def reset(self, rest: float = 0.0, *, s: float | None = None) -> None:
        """Rest at ``rest`` with the taps of schedule value ``s`` (default the first row's).

        Parameters
        ----------
        rest : float
            The rest value.
        s : float or None, keyword-only
            The schedule value the taps start at.

        Raises
        ------
        ParameterError
            Naming ``rest`` or ``s`` when not finite, or ``rest`` beyond ``SMS_INPUT_MAX``
            (:func:`smoothshaper.filters.input_max`).
        """
        v = _finite("rest", rest)
        _check_input("rest", np.float64(v), self.precision, self._input_max)
        sv = self.table[0, 0] if s is None else _finite("s", s)
        self._lib.sms_scheduled_reset(self._f, v, sv)

    @_locked
    def process(self, x, schedule) -> np.ndarray:
        """Filter samples, each scheduled by its value.

        Parameters
        ----------
        x : array_like of float, shape (n,)
            Input samples (finite).
        schedule : array_like of float, shape (n,) or float
            The scheduling value at every sample (a scalar: the same for all; a non-finite
            value keeps the taps in use).

        Returns
        -------
        ndarray of float64, shape (n,)
            The output.

        Raises
        ------
        ParameterError
            Naming ``x`` (not 1-D, not finite, a sample beyond ``SMS_INPUT_MAX``) or
            ``schedule`` (another length); nothing is
            filtered then.
        """
        xin = np.array(_real_array("x", x, ndim=1), dtype=np.float64)
        if not np.all(np.isfinite(xin)):
            raise ParameterError("x", "x must be finite")
        _check_input("x", xin, self.precision, self._input_max)
        sched = np.broadcast_to(np.asarray(_real_array("schedule", schedule), dtype=np.float64),
                                xin.shape) if np.ndim(schedule) == 0 else \
            np.asarray(_real_array("schedule", schedule), dtype=np.float64)
        if sched.shape != xin.shape:
            raise ParameterError("schedule", f"schedule must have the shape of x {xin.shape}, "
                                 f"got {sched.shape}")
        sched = np.ascontiguousarray(sched)
        buf = np.ascontiguousarray(xin, dtype=_real_dtype(self.precision))
        if buf.size:
            ffi = self._ffi
            self._lib.sms_scheduled_process(self._f, ffi.from_buffer("sms_real[]", buf),
                                            ffi.from_buffer("double[]", sched),
                                            ffi.from_buffer("sms_real[]", buf), buf.size)
        return buf.astype(np.float64)

    @_locked
    def step(self, x: float, s: float) -> float:
        """Filter one sample scheduled by ``s``.

        Parameters
        ----------
        x : float
            The input sample.
        s : float
            Its scheduling value.

        Returns
        -------
        float
            The output sample.

        Raises
        ------
        ParameterError
            Naming ``x`` when it is not finite or beyond ``SMS_INPUT_MAX``.
        """
        xv = _finite("x", x)
        _check_input("x", np.float64(xv), self.precision, self._input_max)
        v = self._ffi.new("sms_real *", xv)
        self._lib.sms_scheduled_step(self._f, v, float(s))
        return float(v[0])

    @_locked
    def get_state(self) -> np.ndarray:
        """The dynamic state (C ``sms_scheduled_get_state``: order, update period, countdown,
        the schedule value of the taps, the ring head, the ring).

        Returns
        -------
        ndarray of float64
            A copy; :meth:`set_state` of this shaper or one built alike restores it.
        """
        out = np.zeros(int(self._lib.sms_scheduled_state_count(self._f)))
        self._lib.sms_scheduled_get_state(self._f, self._ffi.from_buffer("double[]", out))
        return out

    @_locked
    def set_state(self, state) -> None:
        """Restore a state from :meth:`get_state`.

        Parameters
        ----------
        state : array_like of float
            The saved state.

        Raises
        ------
        ParameterError
            Naming ``state`` when it does not fit this shaper or holds a non-finite value;
            nothing changes then.
        """
        s = np.ascontiguousarray(_finite_array("state", _real_array("state", state, ndim=1)))
        beyond = np.flatnonzero(np.abs(s[_STATE_RING:]) > self._input_max)
        if beyond.size:
            i = _STATE_RING + int(beyond[0])
            raise ParameterError("state", f"state[{i}] = {float(s[i])!r} is a delay-line value "
                                 f"beyond {self._input_max:g} (SMS_INPUT_MAX), which this "
                                 f"shaper never takes as input")
        st = self._lib.sms_scheduled_set_state(self._f, self._ffi.from_buffer("double[]", s),
                                               s.size)
        if st != 0:
            _raise_status(st, self._lib, self._ffi, "it was not saved by a scheduled shaper "
                          "built alike", "state")

    def _full_state(self):
        return self.get_state(), {}

    def _set_full_state(self, state, counters) -> None:
        self.set_state(state)

    def __repr__(self) -> str:
        return (f"ScheduledShaper({self.kind!r}, table of {self.table.shape[0]} rows, "
                f"Ts={self.Ts!r}, update_every={self.update_every})")
