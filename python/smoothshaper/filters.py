# SPDX-License-Identifier: Apache-2.0
"""C-backed filters: :class:`Chain` and the C design / identification functions.

Everything here calls the compiled C core (``smoothshaper._core``, or ``_core_float`` with
``precision="float"``) through cffi. Arrays in and out are float64 (the float module rounds
the input to float32, filters in float32 and returns float64). Memory follows the C house
style: the Python object owns the ``sms_stage`` array and the stages' memory (a NumPy array of
``sms_memory_cell``: each stage's instance, tap table and delay line); the C ``sms_chain``
holds pointers into them, which stay valid because the object keeps both alive and never
reallocates them.

Errors: every C status maps to :class:`ParameterError` (a ``ValueError``) whose message starts
with the offending parameter's name (``Ts``, ``T``, ``sigma``, ``k``, ``wn``, ``zeta``,
``order``, ``tolerance``, ``notch_pole_zeta``, ``state``, ...). The C library validates before
it writes, and so does this module, so a failed call leaves the object as it was.
"""
from __future__ import annotations

import itertools
import math
from collections import namedtuple
from typing import Iterable, Sequence

import numpy as np

from . import stages as _stages
from ._shared import locked as _locked, new_lock as _new_lock
from .stages import Stage
from ._checks import (choice as _choice, finite as _finite, finite_signal as _signal,
                      integer as _integer, positive as _positive, real_array as _real_array,
                      show as _show)
from .errors import ParameterError

__all__ = ["Chain", "Mode", "ParameterError", "PRECISIONS", "MAX_BUFFER_REALS", "status_string",
           "raise_for_status", "design_for_mode", "identify_from_peaks", "identify_from_record",
           "notch_pole_zeta_from_bandwidth", "si_insensitivity", "si_design", "si_shaper"]

PRECISIONS = ("double", "float")
#: Largest delay line a Chain allocates (2**28 reals: 2 GiB in double); beyond it the
#: duration is rejected as a parameter error instead of failing in the allocator.
MAX_BUFFER_REALS = 1 << 28

# C status -> the parameter it names (see sms_status in c/include/smoothshaper/types.h).
_STATUS_PARAMETER = {
    -1: "argument", -2: "Ts", -3: "T", -4: "T", -5: "sigma", -6: "wn", -7: "zeta", -8: "k",
    -9: "k", -10: "order", -11: "buffer", -12: "kind", -13: "notch_pole_zeta",
    -14: "tolerance", -15: "T", -16: "wn", -17: "limits", -18: "x", -19: "state",
    -20: "bandwidth", -21: "duration",
    # a saved C state of another configuration: the status names the field, the argument is the state
    **{code: "state" for code in range(-43, -21)},
    -44: "coeffs",
    -45: "index",   # a retune of a stage whose previous switch is still in progress
    -46: "target", -47: "velocity", -48: "acceleration", -49: "interface",
    -50: "amplitudes", -51: "times", -52: "sync", -55: "Ts", -56: "qmax",
}
#: Saved Chain states start with this tag and format version, then the configuration they
#: belong to (see :meth:`Chain.get_state`).
STATE_TAG = 5459283.0          # "SMS" read as a 24-bit integer
STATE_VERSION = 1
#: Per stage, in this order, in a saved state (kind and timing as their index).
STATE_STAGE_FIELDS = ("kind", "timing", "T", "sigma", "k", "wn", "zeta", "order", "tolerance",
                      "notch_pole_zeta", "duration")
_STATE_HEAD = 5                # tag, version, precision, Ts, number of stages
_SMS_ERR_TOO_LONG = -15
_SMS_ERR_DURATION_BELOW_TS = -4
_SMS_ERR_ABOVE_NYQUIST = -16


def check_memory(parameter: str, n_reals, what: str) -> int:
    """``n_reals`` as an int, or :class:`ParameterError` naming ``parameter`` when it exceeds
    :data:`MAX_BUFFER_REALS`: a request too large is refused in O(1) with the limit stated,
    never by numpy's MemoryError (or hours of swapping)."""
    if not n_reals <= MAX_BUFFER_REALS:
        try:
            need = f"{float(n_reals):.4g}"
        except OverflowError:     # an int beyond the largest float
            need = f"more than 2^{int(n_reals).bit_length() - 1}"
        raise ParameterError(
            parameter, f"{parameter} out of range: {what} would need {need} values, "
            f"more than the limit of {MAX_BUFFER_REALS} (smoothshaper.filters.MAX_BUFFER_REALS)")
    return int(n_reals)


#: Most stages a stage list may hold (a Chain takes 16; an iterator is read no further).
MAX_STAGE_LIST = 1 << 16

_backends: dict = {}


def _backend(precision: str):
    """(ffi, lib) of the compiled module for ``precision``; imported on first use so the
    pure-Python parts of the package work without the extension."""
    if precision not in PRECISIONS:
        precision = _choice("precision", precision, PRECISIONS)
    if precision not in _backends:
        try:
            if precision == "double":
                from . import _core as mod
            else:
                from . import _core_float as mod
        except ImportError as exc:  # pragma: no cover - depends on the installation
            raise ImportError(
                f"the C extension for precision={precision!r} is not built ({exc}); "
                "install the package with `pip install -e .` from the repository root") from exc
        _backends[precision] = (mod.ffi, mod.lib)
    return _backends[precision]


def _cells(ffi, n_cells: int):
    """Zeroed memory of ``n_cells`` ``sms_memory_cell`` for a chain: the NumPy array that owns
    it (float64, so aligned for the cell's double, size_t and pointer members) and the C
    pointer into it."""
    size = ffi.sizeof("sms_memory_cell")
    if ffi.alignof("sms_memory_cell") > np.dtype(np.float64).alignment or size % 8:
        raise RuntimeError("sms_memory_cell needs an alignment float64 arrays do not give")
    memory = np.zeros(max(1, n_cells) * size // 8, dtype=np.float64)
    return memory, ffi.cast("sms_memory_cell *", ffi.from_buffer(memory))


def _real_dtype(precision: str):
    return np.float64 if precision == "double" else np.float32


def input_max(precision: str = "double") -> float:
    """Largest ``|x|`` the per-sample path takes (C ``SMS_INPUT_MAX``: 1e305 in double, 3e35 in
    float): within it every output and state value stays finite."""
    ffi, lib = _backend(precision)
    return float(lib.SMS_INPUT_MAX)


def _check_input(name: str, x: np.ndarray, precision: str, bound: float | None = None) -> None:
    """ParameterError naming ``name[i]`` for the first sample beyond ``bound`` (default
    :func:`input_max`; a chain passes its own :attr:`Chain.input_max`)."""
    limit = input_max(precision) if bound is None else bound
    bad = np.flatnonzero(np.abs(x) > limit)
    if bad.size:
        i = bad[0]
        where = f"{name}[{i}]" if x.ndim else name
        value = x[i] if x.ndim else x
        what = (f"SMS_INPUT_MAX for precision={precision!r}" if limit == input_max(precision)
                else "this chain's input_max: a heavily damped or high-gain stage")
        raise ParameterError(
            name, f"{name} out of range: {where} = {float(value)!r} exceeds {limit:g} "
            f"({what}), beyond which internal sums of the filters could overflow")


def _stage_fields(stage: Stage) -> tuple[float, ...]:
    values = {"kind": float(stage.kind_index), "timing": float(_stages.TIMINGS.index(stage.timing))}
    return tuple(values[f] if f in values else float(getattr(stage, f))
                 for f in STATE_STAGE_FIELDS)


def status_string(status: int, precision: str = "double") -> str:
    """The C library's one-line description of a status code (``sms_status_string``).

    Parameters
    ----------
    status : int
        An ``sms_status`` value (0 is ``SMS_OK``, errors are negative).
    precision : {"double", "float"}
        Which build of the C core to ask (default ``"double"``).

    Returns
    -------
    str
        The message, e.g. ``"Ts must be finite and > 0"``.

    Raises
    ------
    ParameterError
        Naming ``precision`` when it is neither ``"double"`` nor ``"float"``.
    """
    ffi, lib = _backend(precision)
    return ffi.string(lib.sms_status_string(_status_code(status))).decode()


def _status_code(status) -> int:
    """``status`` as a C int (ParameterError naming it unless an integer); a value beyond the
    C enum's range is passed as one that is "unknown status" too (cffi raised OverflowError)."""
    n = _integer("status", status)
    return n if -2 ** 31 <= n < 2 ** 31 else -2 ** 31


def _raise_status(status: int, lib, ffi, context: str, parameter: str | None = None,
                  value=None):
    parameter = parameter or _STATUS_PARAMETER.get(status, "argument")
    text = ffi.string(lib.sms_status_string(status)).decode()
    if not text.startswith(parameter + " "):
        text = f"{parameter} invalid: {text}"
    got = "" if value is None else f" (got {parameter}={_show(value)})"
    raise ParameterError(parameter, f"{text}{got}; {context}", status)


def raise_for_status(status: int, *, context: str, parameter: str | None = None, value=None,
                     precision: str = "double") -> None:
    """For C-backed wrappers: do nothing on ``SMS_OK`` (0), else raise.

    Parameters
    ----------
    status : int
        The ``sms_status`` a C call returned.
    context : str, keyword-only
        What was being done, appended to the message.
    parameter : str or None, keyword-only
        The parameter to name (default: the one the status names, e.g. ``SMS_ERR_LIMIT``
        -> ``limits``).
    value : object, keyword-only
        The offending value, shown in the message.
    precision : {"double", "float"}, keyword-only
        Which build of the C core produced the status.

    Raises
    ------
    ParameterError
        For any non-zero status, naming ``parameter``, with the C message, ``value`` and
        ``context``.
    """
    status = _status_code(status)
    if status != 0:
        ffi, lib = _backend(precision)
        _raise_status(status, lib, ffi, context, parameter, value)


def _stage_parameter(stage: Stage, status: int) -> tuple[str, object]:
    """Name and value of the stage field a status refers to (a too-long shaper is a too-low wn)."""
    parameter = _STATUS_PARAMETER.get(status, "argument")
    if status == _SMS_ERR_TOO_LONG and stage.kind not in _stages.SMOOTHERS:
        parameter = "wn"
    if status == _SMS_ERR_ABOVE_NYQUIST and stage.kind in _stages.SMOOTHERS:
        parameter = "T"     # the zero exact timing pins, k 2pi/T or k 3pi/T, is above pi/Ts
    return parameter, getattr(stage, parameter, None)


def _unsigned(name: str, value: int) -> int:
    if not 0 <= value <= 0xFFFFFFFF:
        raise ParameterError(name, f"{name} must fit an unsigned 32-bit integer, got {_show(value)}")
    return value


def _fill_config(config, stage: Stage) -> None:
    config.kind = stage.kind_index
    config.timing = _stages.TIMINGS.index(stage.timing)
    config.T = stage.T
    config.sigma = stage.sigma
    config.k = _unsigned("k", stage.k)
    config.wn = stage.wn
    config.zeta = stage.zeta
    config.order = _unsigned("order", stage.order)
    config.tolerance = stage.tolerance
    config.notch_pole_zeta = stage.notch_pole_zeta
    config.duration = stage.duration
    for i, (a, t) in enumerate(zip(stage.amplitudes, stage.times)):
        config.amplitudes[i] = a
        config.times[i] = t


def _stage_from_config(config) -> Stage:
    kind = _stages.KINDS[config.kind]
    common = dict(timing=_stages.TIMINGS[config.timing], k=config.k)
    if kind in _stages.SMOOTHERS:
        return Stage(kind, T=config.T, sigma=config.sigma, **common)
    if kind in _stages.INPUT_SMOOTHERS:
        return Stage(kind, wn=config.wn, zeta=config.zeta, **common)
    return Stage(kind, wn=config.wn, zeta=config.zeta, order=config.order,
                 tolerance=config.tolerance, notch_pole_zeta=config.notch_pole_zeta,
                 duration=config.duration, **common)


def _as_stage_list(stages) -> tuple[Stage, ...]:
    if isinstance(stages, Stage):
        stages = [stages]
    try:
        # more than any chain holds is refused below; an endless iterator is not drained
        out = tuple(itertools.islice(iter(stages), MAX_STAGE_LIST + 1))
    except TypeError:
        raise ParameterError(
            "stages", f"stages must be a Stage or a sequence of Stage, got {_show(stages)}") from None
    if len(out) > MAX_STAGE_LIST:
        raise ParameterError("stages", f"stages: more than {MAX_STAGE_LIST} stages")
    for i, s in enumerate(out):
        if not isinstance(s, Stage):
            raise ParameterError(
                f"stages[{i}]", f"stages[{i}] must be a smoothshaper.Stage, got {_show(s)}")
    return out


def _process_checked(ffi, process_f64, chain, u, precision: str, limit: float) -> np.ndarray:
    """``u`` through a chain's glue ``process_f64`` (smspy_*_process_f64, which checks every
    sample first); ParameterError naming ``u`` for a non-finite sample or one beyond ``limit``
    (then nothing is filtered)."""
    # The output: u is copied once (complex, boolean or text input is refused, not cast).
    y = np.array(_real_array("u", u, ndim=1), dtype=np.float64)
    if y.size:
        data = ffi.from_buffer("double[]", y)
        bad = process_f64(chain, data, data, y.size)
        if bad >= 0:
            if math.isfinite(y[bad]):
                _check_input("u", y, precision, limit)
            raise ParameterError("u", f"u must be finite: u[{bad}] = {float(y[bad])!r}")
    return y


def _validated_configs(stages: tuple, Ts: float, ffi, lib):
    """The C configs of ``stages`` at ``Ts``, each validated and sized by the C core, and the
    delay-line reals each needs; ParameterError naming the offending field and stage (a delay
    line beyond :data:`MAX_BUFFER_REALS` in total names ``T`` or ``wn``)."""
    n = len(stages)
    configs = ffi.new("sms_stage_config[]", n)
    need = ffi.new("size_t *")
    sizes = []
    for i, stage in enumerate(stages):
        if stage.kind in _stages.SMOOTHERS and stage.T / Ts > MAX_BUFFER_REALS:
            # Checked here because sizing a billion-sample smoother in C takes seconds.
            raise ParameterError(
                "T", f"T too long for Ts={Ts!r}: T/Ts = {stage.T / Ts:.4g} samples "
                f"exceeds {MAX_BUFFER_REALS}; stages[{i}] is {stage.kind} with T={stage.T!r}")
        try:
            _fill_config(configs[i], stage)
        except ParameterError as exc:
            raise ParameterError(exc.parameter, f"{exc}; stages[{i}] is {stage.kind}") from None
        # Validates and sizes the stage (its design is closed-form, O(1)).
        st = lib.sms_stage_buffer_size(ffi.addressof(configs, i), Ts, need)
        sizes.append(need[0])
        if st != 0:
            parameter, value = _stage_parameter(stage, st)
            hint = ""
            if st == _SMS_ERR_DURATION_BELOW_TS and "harmonic" in stage.kind:
                hint = " (the harmonic families need T >= 2 Ts)"
            if st == _SMS_ERR_ABOVE_NYQUIST and stage.kind in _stages.SMOOTHERS:
                zero = f"{stage.k}*{'3' if 'harmonic' in stage.kind else '2'}*pi/T"
                raise ParameterError(
                    "T", f"T too short for exact timing: off the sample grid it pins a zero "
                    f"at k*{zero.split('*', 1)[1]} = {zero}, which must lie below the "
                    f"Nyquist frequency pi/Ts (got T={stage.T!r}); stages[{i}] is "
                    f"{stage.kind}, Ts={Ts!r} (use a longer T, k=1, or timing='paper')",
                    st)
            _raise_status(st, lib, ffi, f"stages[{i}] is {stage.kind}, Ts={Ts!r}{hint}",
                          parameter, value)
    total = sum(sizes)
    if total > MAX_BUFFER_REALS:
        _raise_too_long(stages, Ts, sizes, total)
    return configs, sizes


def _raise_too_long(stages, Ts: float, sizes: list, total: int):
    i = max(range(len(sizes)), key=sizes.__getitem__)
    parameter = "T" if stages[i].kind in _stages.SMOOTHERS else "wn"
    raise ParameterError(
        parameter, f"{parameter} {'too long' if parameter == 'T' else 'too low'} for "
        f"Ts={Ts!r}: the chain would need a delay line of {total} samples "
        f"(more than {MAX_BUFFER_REALS}); stages[{i}] is {stages[i].kind} with "
        f"{parameter}={getattr(stages[i], parameter)!r}")


class Chain:
    """Stages in series, filtered by the C core: ``y = H_{n-1}(...H_1(H_0(u)))``.

    Parameters
    ----------
    stages : Stage or sequence of Stage
        1 to ``SMS_CHAIN_MAX_STAGES`` (16) stage descriptions (``smoothshaper.stages``).
    Ts : float
        Sample period [s], finite and > 0 (keyword-only).
    precision : {'double', 'float'}
        Which build of the C core filters the signal (keyword-only).

    The chain starts at rest at 0. Every stage has unit DC gain and realises
    ``y[n] = sum_i h[i] x[n-i]`` (notches: their biquad), so the chain is their product.

    A chain may be shared between threads: its methods hold the chain's lock, so calls run
    one at a time, each on a consistent state (docs/python.md).
    ``copy.copy``, ``copy.deepcopy`` and ``pickle`` give independent chains that continue
    bit-exactly.

    Raises
    ------
    ParameterError
        (a ``ValueError``) naming the invalid parameter, e.g. ``wn`` above the Nyquist
        frequency ``pi/Ts``.
    """

    def __init__(self, stages: Stage | Iterable[Stage], *, Ts: float, precision: str = "double"):
        self.Ts = _positive("Ts", Ts)
        self._lock = _new_lock()
        self.stages = _as_stage_list(stages)
        precision = _choice("precision", precision, PRECISIONS)
        ffi, lib = _backend(precision)
        self.precision = precision
        self._ffi, self._lib = ffi, lib
        n = len(self.stages)
        if not 1 <= n <= lib.SMS_CHAIN_MAX_STAGES:
            raise ParameterError(
                "stages", f"stages: a chain needs 1 to {lib.SMS_CHAIN_MAX_STAGES} stages, got {n}")
        configs, sizes = _validated_configs(self.stages, self.Ts, ffi, lib)
        cells = ffi.new("size_t *")
        st = lib.sms_chain_memory_size(configs, n, self.Ts, cells)
        if st != 0:
            _raise_status(st, lib, ffi, f"chain of {n} stages, Ts={self.Ts!r}")
        # Owned by this object for its whole life; the C chain points into both.
        self._memory, self._memory_c = _cells(ffi, cells[0])
        self._stage_mem = ffi.new("sms_stage[]", n)
        self._chain = ffi.new("sms_chain *")
        st = lib.sms_chain_init(self._chain, self._stage_mem, configs, n, self.Ts,
                                self._memory_c, cells[0])
        if st != 0:
            _raise_status(st, lib, ffi, f"chain of {n} stages, Ts={self.Ts!r}")
        self._input_max = float(lib.sms_chain_input_max(self._chain))

    @property
    def input_max(self) -> float:
        """Largest ``|x|`` (input sample or ``rest``) this chain keeps every output and state
        finite for (C ``sms_chain_input_max``): :func:`input_max` (``SMS_INPUT_MAX``) for most
        chains, less for a heavily damped harmonic smoother (its internal gain is about
        ``exp(-sigma*Ts)/sin(pi/N)``) or stages with large gains. :meth:`process`,
        :meth:`step` and :meth:`reset` refuse values beyond it."""
        return self._input_max

    @property
    def lag(self) -> float:
        """The chain's lag [s]: the delay it gives a constant-speed motion (its DC group
        delay, the sum of the stages' centroids; C ``sms_chain_lag``). See
        :mod:`smoothshaper.align` for centring and aligning."""
        return float(self._lib.sms_chain_lag(self._chain)) * self.Ts

    # -- filtering ------------------------------------------------------------------------

    @_locked
    def process(self, u) -> np.ndarray:
        """Filter a block of samples, continuing from the current state.

        Parameters
        ----------
        u : array_like of float, shape (n,)
            Input samples at ``Ts`` (any length, 0 included); not modified.

        Returns
        -------
        ndarray of float64, shape (n,)
            The output ``y[n] = sum_i h[i] u[n-i]`` of the chain (notches: their biquads).

        Raises
        ------
        ParameterError
            Naming ``u`` if it is not 1-D real (complex, boolean and text are refused, not cast),
            holds NaN/Inf, or a sample beyond :attr:`input_max`; the state is then untouched.
        """
        return _process_checked(self._ffi, self._lib.smspy_chain_process_f64, self._chain, u,
                                self.precision, self._input_max)

    @_locked
    def step(self, x: float) -> float:
        """Filter one sample.

        Parameters
        ----------
        x : float
            The input sample.

        Returns
        -------
        float
            The output sample.

        Raises
        ------
        ParameterError
            Naming ``x`` if it is not a finite real number or beyond :attr:`input_max`; the
            state is then untouched.
        """
        v = _finite("x", x)
        if abs(v) > self._input_max:      # the scalar test first: NumPy costs ~2 us
            _check_input("x", np.float64(v), self.precision, self._input_max)
        cell = self._ffi.new("sms_real *", v)
        self._lib.sms_chain_step(self._chain, cell)
        return float(cell[0])

    @_locked
    def reset(self, rest: float = 0.0) -> None:
        """Put every stage at rest at ``rest``, as if the input had been ``rest`` forever.

        Parameters
        ----------
        rest : float
            The rest value (default 0).

        Raises
        ------
        ParameterError
            Naming ``rest`` if it is not finite or beyond :attr:`input_max`.
        """
        v = _finite("rest", rest)
        _check_input("rest", np.float64(v), self.precision, self._input_max)
        self._lib.sms_chain_reset(self._chain, v)

    # -- state ----------------------------------------------------------------------------

    @property
    def state_size(self) -> int:
        """Number of doubles in :attr:`state` (the configuration header plus the C state)."""
        return self._header_size + self._core_state_size

    @property
    def _header_size(self) -> int:
        return _STATE_HEAD + len(STATE_STAGE_FIELDS) * len(self.stages)

    @property
    def _core_state_size(self) -> int:
        return int(self._lib.sms_chain_state_count(self._chain))

    def _header(self) -> np.ndarray:
        head = [STATE_TAG, STATE_VERSION, float(PRECISIONS.index(self.precision)), self.Ts,
                float(len(self.stages))]
        for stage in self.stages:
            head.extend(_stage_fields(stage))
        return np.array(head, dtype=np.float64)

    @_locked
    def get_state(self) -> np.ndarray:
        """The full dynamic state, tagged with the configuration it belongs to.

        Restoring it with :meth:`set_state` into this chain or an identically configured one
        continues the filtering bit-exactly.

        Returns
        -------
        ndarray of float64, shape (state_size,)
            A copy: ``[STATE_TAG, STATE_VERSION, precision (0 double, 1 float), Ts, n_stages]``,
            then per stage the :data:`STATE_STAGE_FIELDS` (kind and timing as indices), then the
            C core's state (``sms_chain_get_state``: delay lines, recursion states, indices).
        """
        out = np.zeros(self.state_size, dtype=np.float64)
        head = self._header()
        out[:head.size] = head
        if self._core_state_size:
            self._lib.sms_chain_get_state(
                self._chain, self._ffi.from_buffer("double[]", out[head.size:]))
        return out

    def _identity_mismatch(self, s: np.ndarray) -> str | None:
        """Why the header of ``s`` does not describe this chain, or None."""
        if s.size < _STATE_HEAD or s[0] != STATE_TAG:
            return "it is not a saved Chain state (no state tag; was it saved by get_state?)"
        if s[1] != STATE_VERSION:
            return (f"it has state format version {float(s[1])!r}, this library reads version "
                    f"{STATE_VERSION}")
        mine = self._header()
        if s[2] != mine[2]:
            names = {0.0: "'double'", 1.0: "'float'"}
            return (f"precision differs: the state is from precision={names.get(s[2], float(s[2]))}, "
                    f"this chain is precision={self.precision!r}")
        if s[3] != mine[3]:
            return (f"Ts differs: the state is from Ts={float(s[3])!r}, this chain has "
                    f"Ts={self.Ts!r}")
        if s[4] != mine[4]:
            return (f"the number of stages differs: the state has {float(s[4]):g}, this chain "
                    f"{len(self.stages)}")
        if s.size < mine.size:
            return "it is truncated inside its configuration header"
        for i in range(len(self.stages)):
            for j, field in enumerate(STATE_STAGE_FIELDS):
                k = _STATE_HEAD + i * len(STATE_STAGE_FIELDS) + j
                if s[k] != mine[k]:
                    theirs, ours = float(s[k]), float(mine[k])
                    if field in ("kind", "timing"):
                        table = _stages.KINDS if field == "kind" else _stages.TIMINGS
                        theirs = table[int(theirs)] if theirs in range(len(table)) else theirs
                        ours = table[int(ours)]
                    return (f"stages[{i}].{field} differs: the state is from {field}={theirs!r}, "
                            f"this chain has {field}={ours!r}")
        return None

    @_locked
    def set_state(self, state) -> None:
        """Restore a state saved by :meth:`get_state`.

        Parameters
        ----------
        state : array_like of float, shape (state_size,)
            A state of this chain or of an identically configured one.

        Raises
        ------
        ParameterError
            Naming ``state`` if it has the wrong shape, comes from another configuration (the
            message says which field differs: precision, Ts, a stage's kind, T, sigma, ...), or
            does not fit this chain; then nothing is changed.
        """
        s = np.array(_real_array("state", state), dtype=np.float64, order="C", copy=True)
        if s.ndim != 1:
            raise ParameterError("state", f"state must be a 1-D array, got shape {s.shape}")
        why = self._identity_mismatch(s)
        if why is not None:
            raise ParameterError("state", f"state is from another configuration: {why}")
        if s.size != self.state_size:
            raise ParameterError(
                "state", f"state must be a 1-D array of {self.state_size} values for this chain, "
                f"got {s.size}")
        core = s[self._header_size:]
        if not np.isfinite(core).all():
            raise ParameterError("state", "state must be finite")
        st = self._lib.sms_chain_set_state(self._chain, self._ffi.from_buffer("double[]", core),
                                           core.size)
        if st != 0:
            _raise_status(st, self._lib, self._ffi, "it was not saved from an identical chain",
                          "state")

    state = property(get_state, set_state, doc="The dynamic state (see get_state/set_state).")

    @_locked
    def copy(self) -> "Chain":
        """An independent chain with the same stages and the same current state.

        A copy of the C instances and their delay lines (nothing is designed again).

        Returns
        -------
        Chain
            The copy; filtering one does not affect the other.
        """
        ffi, lib = self._ffi, self._lib
        twin = Chain.__new__(Chain)
        twin.__dict__.update(self.__dict__)       # the description; lock and memory are new:
        twin._lock = _new_lock()
        twin._memory, twin._memory_c = _cells(ffi, int(self._chain.memory_len))
        twin._memory[:] = self._memory
        n = len(self.stages)
        twin._stage_mem = ffi.new("sms_stage[]", n)
        ffi.memmove(twin._stage_mem, self._stage_mem, ffi.sizeof("sms_stage") * n)
        twin._chain = ffi.new("sms_chain *")
        twin._chain[0] = self._chain[0]
        lib.sms_chain_rebind(twin._chain, twin._stage_mem, twin._memory_c)
        return twin

    __copy__ = copy

    def __deepcopy__(self, memo) -> "Chain":
        return self.copy()

    def __reduce__(self):
        # Pickle the description and the state, never the pointers.
        return (_restore_chain, (self.stages, self.Ts, self.precision, self.get_state()))

    # -- impulse response -----------------------------------------------------------------

    @property
    def length(self) -> int:
        """FIR length of the chain in samples (sum of the stage lengths minus stages - 1;
        IIR notches count 0)."""
        return int(self._lib.sms_chain_length(self._chain))

    @property
    def is_fir(self) -> bool:
        """True unless the chain contains a notch (IIR)."""
        return all(s.kind not in _stages.NOTCHES for s in self.stages)

    def impulse_response(self, n: int | None = None) -> np.ndarray:
        """The first ``n`` samples of the impulse response, computed by the C core on a fresh copy
        at rest (this chain's state is not touched).

        Parameters
        ----------
        n : int or None
            Number of samples, >= 0; None means :attr:`length` (required when the chain contains
            a notch).

        Returns
        -------
        ndarray of float64, shape (n,)
            ``h[0..n-1]``.

        Raises
        ------
        ParameterError
            Naming ``n`` when it is missing for an IIR chain, negative, not an integer or too
            large to allocate.
        """
        if n is None:
            if not self.is_fir:
                raise ParameterError("n", "n is required: the chain contains an IIR notch")
            n = self.length
        n = _integer("n", n, 1)
        impulse = np.zeros(check_memory("n", n, "the impulse response"))
        impulse[0] = 1.0
        twin = self.copy()
        twin.reset(0.0)
        return twin.process(impulse)

    def taps(self) -> np.ndarray:
        """The FIR taps of the whole chain.

        Returns
        -------
        ndarray of float64, shape (length,)
            The impulse response of the FIR chain (DC gain 1).

        Raises
        ------
        ParameterError
            The chain contains a notch (IIR: use :meth:`impulse_response` with ``n``).
        """
        if not self.is_fir:
            raise ParameterError("stages", "stages: taps() needs an FIR chain; it contains an "
                                 "IIR notch (use impulse_response(n))")
        return self.impulse_response(self.length)

    def __repr__(self) -> str:
        kinds = ", ".join(s.kind for s in self.stages)
        return f"Chain([{kinds}], Ts={self.Ts!r}, precision={self.precision!r})"


def _restore_chain(stages, Ts, precision, state) -> Chain:
    chain = Chain(stages, Ts=Ts, precision=precision)
    chain.set_state(state)
    return chain


# -- design and identification (C) ---------------------------------------------------------

Mode = namedtuple("Mode", "wn zeta wd sigma")
Mode.__doc__ = """A vibration mode: natural frequency wn [rad/s], damping ratio zeta, damped
frequency wd = wn sqrt(1 - zeta^2) [rad/s], decay rate sigma = -zeta wn [1/s]."""


def design_for_mode(kind: str, *, wn: float, zeta: float = 0.0, k: int = 1) -> Stage:
    """The C ``sms_design_for_mode``: a stage of ``kind`` that cancels the mode (wn, zeta).

    With ``wd = wn sqrt(1 - zeta^2)``: rectangular ``T = k 2 pi/wd``; harmonic
    ``T = k 3 pi/wd`` (k odd); damped harmonic ``sigma = -zeta wn``, ``T = k 3 pi/wd`` (k odd;
    Biagiotti, Melchiorri and Moriello, "Damped Harmonic Smoother for Trajectory Planning and
    Vibration Suppression", 2020); exponential ``sigma = -zeta wn``, ``T = k Td``; shapers and
    notches take the mode (k = 1). Same result as :func:`smoothshaper.stages.for_mode`,
    computed in C.

    Parameters
    ----------
    kind : str
        Any stage kind (any case).
    wn : float, keyword-only
        Natural frequency [rad/s], > 0.
    zeta : float, keyword-only
        Damping ratio, in [0, 1) (default 0).
    k : int, keyword-only
        Multiple of the zero placed on the mode (>= 1, default 1).

    Returns
    -------
    Stage
        The designed stage.

    Raises
    ------
    ParameterError
        Naming ``kind``, ``wn``, ``zeta`` or ``k``.
    """
    kind = _stages.kind_name(kind)
    wn_v, zeta_v = _finite("wn", wn), _finite("zeta", zeta)
    k = _integer("k", k, 1)
    if k > 0xFFFFFFFF:
        raise ParameterError("k", f"k must fit an unsigned 32-bit integer, got {_show(k)}")
    ffi, lib = _backend("double")
    config = ffi.new("sms_stage_config *")
    st = lib.sms_design_for_mode(_stages.KINDS.index(kind), wn_v, zeta_v, int(k), config)
    if st != 0:
        parameter = _STATUS_PARAMETER.get(st, "argument")
        value = {"wn": wn_v, "zeta": zeta_v, "k": k}.get(parameter)
        _raise_status(st, lib, ffi, f"designing {kind} for a mode", parameter, value)
    return _stage_from_config(config)


def si_insensitivity(*, order: int, duration: float, tolerance: float = 0.05) -> float:
    """The insensitivity I of a specified-insensitivity shaper (C
    ``sms_shaper_si_insensitivity``): its residual stays <= ``tolerance`` for mode frequencies
    within ``wd (1 +- I/2)``.

    Closed form (docs/filters.md): the equal-ripple Chebyshev design of ``order`` equally
    spaced impulses over ``duration`` damped periods (Singhose, Seering and Singer, "Input
    shaping for vibration reduction with specified insensitivity to modeling errors", 1996;
    Dolph 1946).

    Parameters
    ----------
    order : int, keyword-only
        Number of impulses: 3, 5, 7 or 9.
    duration : float, keyword-only
        Span in damped periods, in [(order - 1)/4, (order - 1)/2].
    tolerance : float, keyword-only
        Vibration tolerance V, in (0, 1) (default 0.05).

    Returns
    -------
    float
        I, the band's width relative to the damped frequency, in (0, 2).

    Raises
    ------
    ParameterError
        Naming ``order``, ``tolerance`` or ``duration``.
    """
    n = _integer("order", order)
    D, V = _finite("duration", duration), _finite("tolerance", tolerance)
    ffi, lib = _backend("double")
    out = ffi.new("double *")
    # an order beyond C's unsigned is out of range like any other: 0 gets SMS_ERR_ORDER
    st = lib.sms_shaper_si_insensitivity(n if 0 <= n <= 0xFFFFFFFF else 0, D, V, out)
    if st != 0:
        parameter = _STATUS_PARAMETER.get(st, "argument")
        _raise_status(st, lib, ffi, "si shaper", parameter,
                      {"order": n, "duration": D, "tolerance": V}.get(parameter))
    return float(out[0])


def si_design(*, insensitivity: float, tolerance: float = 0.05) -> tuple[int, float]:
    """The shortest specified-insensitivity shaper for a band (C ``sms_shaper_si_design``).

    Parameters
    ----------
    insensitivity : float, keyword-only
        I, the relative width of the band around the mode (``wd (1 +- I/2)``) over which the
        residual must stay <= ``tolerance``, in (0, 2); up to about 1.43 at V = 0.05 (9
        impulses). Below ZV's band (0.064 at V = 0.05) ZV itself is returned.
    tolerance : float, keyword-only
        Vibration tolerance V, in (0, 1) (default 0.05).

    Returns
    -------
    order : int
        Number of impulses (3, 5, 7 or 9).
    duration : float
        Span in damped periods.

    Raises
    ------
    ParameterError
        Naming ``tolerance`` or ``insensitivity`` (outside (0, 2), or wider than nine
        impulses reach).
    """
    I, V = _finite("insensitivity", insensitivity), _finite("tolerance", tolerance)
    ffi, lib = _backend("double")
    order, duration = ffi.new("unsigned *"), ffi.new("double *")
    st = lib.sms_shaper_si_design(V, I, order, duration)
    if st in (-10, -21):            # SMS_ERR_ORDER, SMS_ERR_SHAPER_DURATION: the band
        raise ParameterError(
            "insensitivity", f"insensitivity must be in (0, 2) and reachable with at most "
            f"{_stages.MAX_IMPULSES} impulses at tolerance {V!r}, got {I!r}", st)
    if st != 0:
        _raise_status(st, lib, ffi, "si design", "tolerance", V)
    return int(order[0]), float(duration[0])


def si_shaper(*, wn: float, zeta: float = 0.0, insensitivity: float,
              tolerance: float = 0.05, timing: str = "exact") -> Stage:
    """The shortest specified-insensitivity shaper for the mode (``wn``, ``zeta``) whose
    residual stays <= ``tolerance`` over ``wd (1 +- insensitivity/2)`` (:func:`si_design`).

    Parameters
    ----------
    wn : float, keyword-only
        Natural frequency [rad/s], > 0.
    zeta : float, keyword-only
        Damping ratio, in [0, 1) (default 0).
    insensitivity : float, keyword-only
        Relative width of the band, see :func:`si_design`.
    tolerance : float, keyword-only
        Vibration tolerance V, in (0, 1) (default 0.05).
    timing : {"exact", "paper"}, keyword-only
        Realisation between samples (default ``"exact"``).

    Returns
    -------
    Stage
        kind ``"si"`` with the designed order and duration.

    Raises
    ------
    ParameterError
        Naming ``wn``, ``zeta``, ``insensitivity``, ``tolerance`` or ``timing``.
    """
    order, duration = si_design(insensitivity=insensitivity, tolerance=tolerance)
    return Stage("si", wn=wn, zeta=zeta, order=order, duration=duration, tolerance=tolerance,
                 timing=timing)


def _mode(m) -> Mode:
    return Mode(float(m.wn), float(m.zeta), float(m.wd), float(m.sigma))


def identify_from_peaks(*, t1: float, p1: float, t2: float, p2: float) -> Mode:
    """Mode from two successive peaks of a free decay, measured about its final value.

    ``T0 = t2 - t1``, ``sigma = ln(p2/p1)/T0``, ``wd = 2 pi/T0`` (Biagiotti, Melchiorri and
    Moriello, "Damped Harmonic Smoother for Trajectory Planning and Vibration Suppression",
    2020, eq. 16); computed by the C ``sms_identify_from_peaks``.

    Parameters
    ----------
    t1, t2 : float, keyword-only
        Times of the two peaks [s], ``t2 > t1``.
    p1, p2 : float, keyword-only
        Their heights above the final value, ``p1 > p2 > 0``.

    Returns
    -------
    Mode
        ``(wn [rad/s], zeta, wd [rad/s], sigma [1/s])``.

    Raises
    ------
    ParameterError
        Naming ``t2`` (not later than ``t1``, or so close that the rates overflow), ``p2``
        (not ``p1 > p2 > 0``), or a value that is not finite.
    """
    values = {n: _finite(n, v) for n, v in (("t1", t1), ("p1", p1), ("t2", t2), ("p2", p2))}
    if not values["t2"] > values["t1"]:
        raise ParameterError("t2", f"t2 must be later than t1, got t1={values['t1']!r}, "
                             f"t2={values['t2']!r}")
    if not values["p1"] > values["p2"] > 0:
        raise ParameterError("p2", f"p2 must satisfy p1 > p2 > 0 (a decay), got "
                             f"p1={values['p1']!r}, p2={values['p2']!r}")
    ffi, lib = _backend("double")
    out = ffi.new("sms_mode *")
    st = lib.sms_identify_from_peaks(values["t1"], values["p1"], values["t2"], values["p2"], out)
    if st != 0:   # the checks above passed: the rates 1/(t2 - t1) overflow double
        raise ParameterError(
            "t2", f"t2 too close to t1 (t2 - t1 = {values['t2'] - values['t1']!r} s): the "
            f"frequency or decay rate of the mode would exceed the range of double", st)
    return _mode(out)


def identify_from_record(x: Sequence[float], *, Ts: float) -> Mode:
    """Mode of a sampled free decay by the C least-squares fit over the whole record
    (``sms_identify_from_record``; docs/design.md).

    Parameters
    ----------
    x : array_like of float, shape (n,)
        The decay, ``n >= 8``, at least one visible oscillation; any constant offset is fitted.
    Ts : float, keyword-only
        Sample period [s], > 0.

    Returns
    -------
    Mode
        ``(wn [rad/s], zeta, wd [rad/s], sigma [1/s])``.

    Raises
    ------
    ParameterError
        Naming ``x`` (too short, not finite, no oscillation found) or ``Ts``.
    """
    Ts_v = _positive("Ts", Ts)
    data = np.ascontiguousarray(_signal("x", x))
    ffi, lib = _backend("double")
    out = ffi.new("sms_mode *")
    st = lib.sms_identify_from_record(ffi.from_buffer("double[]", data), data.size, Ts_v, out)
    if st != 0:
        _raise_status(st, lib, ffi, f"identifying from a record of {data.size} samples, "
                      f"Ts={Ts_v!r}")
    return _mode(out)


def notch_pole_zeta_from_bandwidth(*, wn: float, zeta: float = 0.0, bandwidth: float) -> float:
    """Pole damping of a notch at ``wn`` whose -3 dB band is ``bandwidth`` wide
    (C ``sms_notch_pole_zeta_from_bandwidth``).

    Parameters
    ----------
    wn : float, keyword-only
        Notch frequency [rad/s], > 0.
    zeta : float, keyword-only
        Damping of the zeros, in [0, 1) (default 0).
    bandwidth : float, keyword-only
        Width of the -3 dB band [rad/s], > 0.

    Returns
    -------
    float
        ``notch_pole_zeta`` (> ``zeta``) for :func:`smoothshaper.stages.notch`.

    Raises
    ------
    ParameterError
        Naming ``wn``, ``zeta`` or ``bandwidth``.
    """
    args = (_finite("wn", wn), _finite("zeta", zeta), _finite("bandwidth", bandwidth))
    ffi, lib = _backend("double")
    out = ffi.new("double *")
    st = lib.sms_notch_pole_zeta_from_bandwidth(*args, out)
    wn_v, zeta_v, bw = args
    if st == -20 and bw > 0 and wn_v > 0 and 0 <= zeta_v < 1:
        # a finite, positive band refused for its size relative to wn: say which way
        wide = bw > wn_v
        raise ParameterError(
            "bandwidth", f"bandwidth = {bw!r} rad/s is too {'wide' if wide else 'narrow'} for "
            f"wn = {wn_v!r} rad/s: the pole damping (bandwidth/(2 wn), with zeta = {zeta_v!r}) "
            + ("exceeds the notch's limit" if wide else "rounds onto zeta"), st)
    if st != 0:
        parameter = _STATUS_PARAMETER.get(st, "argument")
        value = dict(zip(("wn", "zeta", "bandwidth"), args)).get(parameter)
        _raise_status(st, lib, ffi, "notch pole damping from a bandwidth", parameter, value)
    return float(out[0])
