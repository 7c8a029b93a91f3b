# SPDX-License-Identifier: Apache-2.0
"""Zero lag and aligned axes (docs/align.md): the lag of a chain, its centred output for a
planned trajectory, and several axes padded to a common lag.

Every unit-DC-gain chain delays a constant-speed motion by its lag ``D`` (its DC group delay,
the centroid of its impulse response; C ``sms_chain_config_lag``). Two uses:

* **Centred output** (:func:`centred`, :func:`advance`): when the future of the input is known
  (an offline array, a planned job, B-spline via-points), the output is advanced by ``D``:
  ``y_c(t) = y(t + D)``, so constant-speed motion passes unchanged and the final position is
  reached no later than the input's. The price is a look-ahead of ``A = ceil(D / Ts)``
  samples: the filter must see the input ``A`` samples before the output is due, so it cannot
  apply to a live input (a jog, a sensor, a closed loop), only where the input is planned.
* **Alignment** (:func:`align`, :func:`aligned`, and ``MultiAxisGenerator(align=True)``): axes
  with different chains lag differently, so a straight move at constant speed leaves the line
  by ``v |D_i - D_j|``. Each axis is padded with a fractional delay of ``D - D_i``,
  ``D = max_i D_i``, so all lag by ``D`` and constant-speed segments stay on the line.

The fractional delay (C ``sms_delay``) interpolates linearly between two samples: exact on
constant and constant-speed signals, a pure delay for whole samples.
"""
from __future__ import annotations

import math

import numpy as np

from .filters import (Chain, PRECISIONS, ParameterError, _as_stage_list, _backend, _raise_status,
                      _real_dtype, _validated_configs)
from ._checks import choice as _choice, finite_signal as _signal, positive as _positive
from ._checks import real_array as _real_array

__all__ = ["lag", "lookahead", "delay", "advance", "centred", "align", "aligned"]

#: A lag within this many samples of a whole number counts as whole (the centroid's rounding).
_WHOLE = 1e-9


def lag(stages, *, Ts: float) -> float:
    """The lag of a chain [s]: the delay it gives a constant-speed motion.

    Parameters
    ----------
    stages : Stage or sequence of Stage
        The chain (an empty sequence: 0).
    Ts : float, keyword-only
        Sample period [s], > 0.

    Returns
    -------
    float
        ``D Ts``, ``D`` the sum of the stages' DC group delays in samples (the centroid of a
        FIR stage's realised taps; ``(d2 - d0)/(1 + a1 + a2)`` for a notch).

    Raises
    ------
    ParameterError
        Naming ``Ts`` or the stage field invalid at ``Ts``.
    """
    Ts = _positive("Ts", Ts)
    stages = () if stages is None or (isinstance(stages, (list, tuple)) and not stages) \
        else _as_stage_list(stages)
    if not stages:
        return 0.0
    ffi, lib = _backend("double")
    configs, _ = _validated_configs(stages, Ts, ffi, lib)
    out = ffi.new("double *")
    st = lib.sms_chain_config_lag(configs, len(stages), Ts, out)
    if st != 0:
        _raise_status(st, lib, ffi, "the chain's lag")
    return float(out[0]) * Ts


def lookahead(lag_seconds: float, *, Ts: float) -> int:
    """Samples of look-ahead a centred output of this lag needs: ``ceil(lag/Ts)`` (a lag within
    1e-9 samples of a whole number counts as whole).

    Parameters
    ----------
    lag_seconds : float
        The lag [s], >= 0.
    Ts : float, keyword-only
        Sample period [s], > 0.

    Returns
    -------
    int
        The look-ahead ``A`` in samples.

    Raises
    ------
    ParameterError
        Naming ``lag_seconds`` (negative or not finite) or ``Ts``.
    """
    Ts = _positive("Ts", Ts)
    if not (math.isfinite(lag_seconds) and lag_seconds >= 0.0):
        raise ParameterError("lag_seconds", f"lag_seconds must be finite and >= 0, got "
                             f"{lag_seconds!r}")
    d = lag_seconds / Ts
    return int(round(d)) if abs(d - round(d)) <= _WHOLE * max(1.0, d) else int(math.ceil(d))


def delay(x, *, samples: float, rest: float | None = None, precision: str = "double"):
    """Delay a signal by a fractional number of samples (C ``sms_delay``).

    ``y[n] = x[n-m] + f (x[n-m-1] - x[n-m])``, ``m = floor(samples)``, ``f`` the fraction:
    constants pass exactly, a constant-speed signal is delayed by exactly ``samples``.

    Parameters
    ----------
    x : array_like of float, shape (n,) or (n, k)
        The signal (each column delayed alike).
    samples : float, keyword-only
        The delay, >= 0.
    rest : float or None, keyword-only
        The value before ``x[0]`` (default ``x[0]``, per column).
    precision : {"double", "float"}, keyword-only
        Which build of the C core delays it.

    Returns
    -------
    ndarray of float64, the shape of ``x``
        The delayed signal.

    Raises
    ------
    ParameterError
        Naming ``x`` (not finite, wrong shape), ``samples`` (negative, not finite or beyond
        2^40) or ``rest``.
    """
    ffi, lib = _backend(_choice("precision", precision, PRECISIONS))
    arr = _real_array("x", x)
    if arr.ndim not in (1, 2) or not np.all(np.isfinite(arr)):
        raise ParameterError("x", f"x must be a finite 1-D or 2-D signal, got shape {arr.shape}")
    cols = arr.reshape(arr.shape[0], -1)
    need = ffi.new("size_t *")
    st = lib.sms_delay_buffer_size(float(samples), need)
    if st != 0:
        raise ParameterError("samples", f"samples must be finite, >= 0 and at most 2^40, got "
                             f"{samples!r}", st)
    dtype = _real_dtype(precision)
    out = np.empty(cols.shape)
    ring = np.zeros(need[0], dtype=dtype)
    d = ffi.new("sms_delay *")
    for c in range(cols.shape[1]):
        lib.sms_delay_init(d, float(samples), ffi.from_buffer("sms_real[]", ring), need[0])
        start = cols[0, c] if cols.shape[0] else 0.0
        lib.sms_delay_reset(d, float(start if rest is None else rest))
        col = np.ascontiguousarray(cols[:, c], dtype=dtype)
        if col.size:
            lib.sms_delay_process(d, ffi.from_buffer("sms_real[]", col),
                                  ffi.from_buffer("sms_real[]", col), col.size)
        out[:, c] = col
    return out.reshape(arr.shape)


def advance(y, *, lag: float, Ts: float, precision: str = "double") -> np.ndarray:
    """Advance a computed output by ``lag`` seconds: the centred output ``y_c(t) = y(t + lag)``.

    By ``A = lookahead(lag)`` whole samples, then delayed by ``A - lag/Ts`` with the fractional
    delay, so a constant-speed output is shifted by exactly the lag. ``y`` must have been
    computed from an input that continues (at rest, or planned) at least ``A`` samples past
    the instants wanted: the last ``A`` samples of the result hold the last value of ``y``.

    Parameters
    ----------
    y : array_like of float, shape (n,) or (n, k)
        The output, sample by sample.
    lag : float, keyword-only
        The lag to remove [s], >= 0 (e.g. :func:`lag` of the chain that made ``y``).
    Ts : float, keyword-only
        Sample period [s], > 0.
    precision : {"double", "float"}, keyword-only
        Which build of the C core runs the fractional delay.

    Returns
    -------
    ndarray of float64, the shape of ``y``
        ``y`` advanced by ``lag``.

    Raises
    ------
    ParameterError
        Naming ``y``, ``lag`` or ``Ts``.
    """
    A = lookahead(lag, Ts=Ts)
    arr = np.asarray(_real_array("y", y), dtype=np.float64)
    if arr.ndim not in (1, 2):
        raise ParameterError("y", f"y must be 1-D or 2-D, got shape {arr.shape}")
    frac = max(0.0, A - lag / Ts)
    shifted = delay(arr, samples=frac, precision=precision) if frac > _WHOLE else arr.copy()
    if A == 0 or arr.shape[0] == 0:
        return shifted
    tail = np.repeat(shifted[-1:], min(A, arr.shape[0]), axis=0)
    return np.concatenate([shifted[A:], tail])[:arr.shape[0]]


def centred(stages, x, *, Ts: float, precision: str = "double") -> np.ndarray:
    """Zero-lag filtering of a planned (offline) input: ``stages`` applied to ``x`` and the
    result advanced by the chain's lag.

    The input is taken at rest at ``x[0]`` before the array and at ``x[-1]`` after it (the
    look-ahead past the end is that rest). A constant-speed segment of ``x`` comes out
    unchanged (to rounding) wherever the chain's whole window lies inside it, and the move
    ends on ``x[-1]`` no later than the input reaches it plus the chain's length minus its lag.
    The centred output starts moving up to the chain's lag before the input does: start the
    array that long before the first motion to see all of it.

    Parameters
    ----------
    stages : Stage or sequence of Stage
        The chain.
    x : array_like of float, shape (n,)
        The planned input.
    Ts : float, keyword-only
        Sample period [s], > 0.
    precision : {"double", "float"}, keyword-only
        Which build of the C core filters.

    Returns
    -------
    ndarray of float64, shape (n,)
        The centred output at the instants of ``x``.

    Raises
    ------
    ParameterError
        Naming ``x``, ``Ts`` or a stage field.
    """
    x = _signal("x", x)
    chain = Chain(stages, Ts=Ts, precision=precision)
    D = lag(stages, Ts=Ts)
    A = lookahead(D, Ts=Ts)
    if x.size == 0:
        return x.copy()
    chain.reset(x[0])
    y = chain.process(np.concatenate([x, np.full(A, x[-1])]))
    return advance(y, lag=D, Ts=Ts, precision=precision)[:x.size]


def align(stage_lists, *, Ts: float) -> tuple[float, list[float]]:
    """The common lag of several axes' chains and the delay each needs to reach it.

    Parameters
    ----------
    stage_lists : sequence
        One entry per axis: a Stage, a sequence of Stages, or None / [] for no filter.
    Ts : float, keyword-only
        Sample period [s], > 0.

    Returns
    -------
    lag : float
        ``D Ts`` [s], ``D = max_i D_i`` over the axes' lags.
    pads : list of float
        Per axis, the delay ``(D - D_i) Ts`` [s] that pads it to the common lag.

    Raises
    ------
    ParameterError
        Naming ``stage_lists`` (not a sequence, empty), ``Ts`` or a stage field.
    """
    try:
        axes = list(stage_lists)
    except TypeError:
        raise ParameterError("stage_lists", "stage_lists must be a sequence, one entry per "
                             "axis") from None
    if not axes:
        raise ParameterError("stage_lists", "stage_lists must hold at least one axis")
    lags = [lag(s, Ts=Ts) for s in axes]
    common = max(lags)
    return common, [max(0.0, common - d) for d in lags]


def aligned(stage_lists, x, *, Ts: float, centred: bool = False,
            precision: str = "double") -> tuple[np.ndarray, float]:
    """Filter every axis of ``x`` through its own chain, padded to the common lag.

    Parameters
    ----------
    stage_lists : sequence
        One entry per column of ``x`` (a Stage, a sequence of Stages, or None for none).
    x : array_like of float, shape (n, axes)
        The axes' inputs (e.g. a straight move: ``p + s(t) d``), taken at rest at ``x[0]``.
    Ts : float, keyword-only
        Sample period [s], > 0.
    centred : bool, keyword-only
        Also advance the result by the common lag (zero lag; ``x`` is a planned input, taken
        at rest at ``x[-1]`` after its end).
    precision : {"double", "float"}, keyword-only
        Which build of the C core filters.

    Returns
    -------
    y : ndarray of float64, shape (n, axes)
        Every axis lagging by the common lag (by none when ``centred``).
    lag : float
        The common lag [s].

    Raises
    ------
    ParameterError
        Naming ``x`` (shape, not finite), ``stage_lists`` (not one per axis), ``Ts`` or a stage
        field.
    """
    arr = np.asarray(_real_array("x", x), dtype=np.float64)
    if arr.ndim != 2 or not np.all(np.isfinite(arr)):
        raise ParameterError("x", f"x must be a finite (n, axes) array, got shape {arr.shape}")
    lists = list(stage_lists) if stage_lists is not None else []
    if len(lists) != arr.shape[1]:
        raise ParameterError("stage_lists", f"stage_lists must have one entry per axis "
                             f"({arr.shape[1]}), got {len(lists)}")
    common, pads = align(lists, Ts=Ts)
    A = lookahead(common, Ts=Ts) if centred else 0
    ext = np.concatenate([arr, np.repeat(arr[-1:], A, axis=0)]) if arr.size else arr
    out = np.empty(ext.shape)
    for i, (stages, pad) in enumerate(zip(lists, pads)):
        col = ext[:, i]
        if stages:
            chain = Chain(stages, Ts=Ts, precision=precision)
            chain.reset(col[0])
            col = chain.process(col)
        out[:, i] = delay(col, samples=pad / Ts, precision=precision) if col.size else col
    if centred:
        out = advance(out, lag=common, Ts=Ts, precision=precision)[:arr.shape[0]]
    return out, common
