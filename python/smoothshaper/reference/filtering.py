# SPDX-License-Identifier: Apache-2.0
"""Impulse responses, discrete transfer functions and the direct-convolution chain.

Explicit state (``zi`` / ``zf``): a list with one float64 array per stage, in chain order:

* FIR stage (smoother or shaper, L taps): its last ``L - 1`` inputs, oldest first
  (``zi[k][-1]`` is the input of the previous sample);
* notch stage: ``[x[n-1], x[n-2], y[n-1], y[n-2]]`` of its direct form I.

``filter_zi(stages, Ts=..., x0=v)`` is the state of a chain at rest at the value v (every
stage has DC gain 1, so every past input and output equals v); the default ``zi=None`` is the
chain at rest at 0.
"""
from __future__ import annotations

import numpy as np

from ..stages import INPUT_SMOOTHERS, NOTCHES, SMOOTHERS, Stage
from ._checks import as_stage_list, check_samples, check_stage, check_Ts
from .notch import biquad, notch_coefficients_unchecked
from .input_smoothers import taps_unchecked as input_smoother_taps_unchecked
from .shapers import shaper_taps_unchecked
from .smoothers import smoother_taps_unchecked
from .._checks import (complex_array as _complex_array, finite as _finite,
                       finite_signal as _finite_signal, integer as _integer,
                       real_array as _real_array, representable as _representable)
from ..errors import ParameterError


def impulse_response(stage: Stage, *, Ts: float, length: int | None = None) -> np.ndarray:
    """Discrete impulse response of one stage (DC gain 1).

    Parameters
    ----------
    stage : Stage
        Any stage.
    Ts : float, keyword-only
        Sample period [s], > 0.
    length : int or None, keyword-only
        Smoothers and shapers: None (default) gives all L FIR taps, a larger length pads
        zeros, a smaller one truncates. Notches (infinite response): required, >= 0.

    Returns
    -------
    ndarray of float64, shape (L,) or (length,)
        The response ``h[n]``.

    Raises
    ------
    ParameterError
        Naming ``length`` (missing for a notch, negative, not an integer or too large) or the
        stage parameter that is invalid at ``Ts``.
    """
    stage = check_stage(stage)
    if stage.kind in NOTCHES:
        if length is None:
            raise ParameterError(
                "length", "length is required for a notch (its impulse response is infinite)")
        n = _check_length(length)
        x = np.zeros(n)
        if n:
            x[0] = 1.0
        b, a = notch_coefficients_unchecked(stage, check_Ts(Ts))
        return biquad(b, a, x, np.zeros(4))[0]
    h = fir_taps_unchecked(stage, check_Ts(Ts))
    if length is None:
        return h
    n = _check_length(length)
    return np.concatenate([h, np.zeros(max(0, n - h.size))])[:n]


def fir_taps_unchecked(stage: Stage, Ts: float) -> np.ndarray:
    """All taps of a smoother or shaper Stage at a checked ``Ts`` (what depends on both is
    checked on the way)."""
    if stage.kind in SMOOTHERS:
        return smoother_taps_unchecked(stage, Ts)
    if stage.kind in INPUT_SMOOTHERS:
        return input_smoother_taps_unchecked(stage, Ts)
    return shaper_taps_unchecked(stage, Ts)


def coefficients_unchecked(stage: Stage, Ts: float):
    """``(b, a)`` of a notch, else ``(taps, None)``, for a Stage at a checked ``Ts``."""
    if stage.kind in NOTCHES:
        return notch_coefficients_unchecked(stage, Ts)
    return fir_taps_unchecked(stage, Ts), None


def _check_length(length) -> int:
    return check_samples("length", _integer("length", length, 0), "the impulse response")


def discrete_transfer(stage: Stage, z, *, Ts: float) -> np.ndarray:
    """``H(z)`` of one discrete stage: ``sum_i h[i] z^-i`` for FIR stages, ``b(z^-1)/a(z^-1)``
    for notches.

    Parameters
    ----------
    stage : Stage
        Any stage.
    z : array_like of complex
        Points of the z-plane, any shape, non-zero.
    Ts : float, keyword-only
        Sample period [s], > 0.

    Returns
    -------
    ndarray of complex128
        ``H(z)``, the shape of ``z``.

    Raises
    ------
    ParameterError
        A stage parameter invalid at ``Ts``, or ``Ts`` not > 0.
    """
    stage = check_stage(stage)
    z = _complex_array("z", z)
    if np.any(z == 0):
        raise ParameterError("z", "z must be non-zero (the transfer is in powers of 1/z)")
    Ts = check_Ts(Ts)
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        zinv = 1.0 / z
        b, a = coefficients_unchecked(stage, Ts)
        H = np.polyval(b[::-1], zinv)
        if a is not None:
            H = H / np.polyval(a[::-1], zinv)
    return _representable("z", H, "H(z)")


def filter_zi(stages, *, Ts: float, x0: float = 0.0) -> list[np.ndarray]:
    """State of the chain at rest at the value ``x0``, in the layout :func:`filter` takes.

    Parameters
    ----------
    stages : Stage or sequence of Stage
        The chain.
    Ts : float, keyword-only
        Sample period [s], > 0.
    x0 : float, keyword-only
        The rest value (default 0).

    Returns
    -------
    list of ndarray of float64
        One array per stage: the last ``L - 1`` inputs of a FIR stage of length L, or
        ``[x1, x2, y1, y2]`` of a notch, all equal to ``x0``.

    Raises
    ------
    ParameterError
        Naming ``x0`` when it is not finite, or a stage parameter invalid at ``Ts``.
    """
    x0 = _finite("x0", x0)
    stages = as_stage_list(stages)
    Ts = check_Ts(Ts)
    return _rest_state([coefficients_unchecked(stage, Ts) for stage in stages], x0)


def _rest_state(coefficients, x0: float) -> list[np.ndarray]:
    """The state at rest at ``x0`` of stages given by their :func:`coefficients_unchecked`."""
    return [np.full(4 if a is not None else b.size - 1, x0) for b, a in coefficients]


def filter(stages, x, *, Ts: float, zi=None):
    """Filter ``x`` through the chain ``stages`` at period ``Ts``: the independent NumPy oracle
    of :class:`smoothshaper.Chain` (it never calls the C code).

    Each FIR stage is a direct convolution with its taps, each notch a direct-form-I biquad.

    Parameters
    ----------
    stages : Stage or sequence of Stage
        The chain, first stage first.
    x : array_like of float, shape (n,)
        Input samples, finite.
    Ts : float, keyword-only
        Sample period [s], > 0.
    zi : list of ndarray or None, keyword-only
        None (default): the chain starts at rest at 0; else the state from
        :func:`filter_zi` or from a previous call.

    Returns
    -------
    y : ndarray of float64, shape (n,)
        The output (alone when ``zi`` is None).
    zf : list of ndarray of float64
        With ``zi`` given: the state after the last sample, so that filtering blocks one
        after the other with the returned state equals filtering at once.

    Raises
    ------
    ParameterError
        Naming ``x`` (not a finite real 1-D signal), ``zi`` / ``zi[k]`` (wrong layout),
        ``Ts`` or a stage parameter invalid at ``Ts``.
    """
    stages = as_stage_list(stages)
    Ts = check_Ts(Ts)
    x = _finite_signal("x", x)
    rest = zi is None
    coefficients = [coefficients_unchecked(stage, Ts) for stage in stages]
    expected = _rest_state(coefficients, 0.0)
    states = expected if rest else _check_zi(expected, zi)
    y = x
    final = []
    for (b, a), state in zip(coefficients, states):
        if a is not None:
            y, new = biquad(b, a, y, state)
        else:
            padded = np.concatenate([state, y])
            new = padded[padded.size - state.size:].copy()
            # np.convolve swaps its arguments when the first is shorter (empty block)
            y = np.convolve(padded, b, mode="valid") if y.size else y.copy()
        final.append(new)
    return y if rest else (y, final)


def _check_zi(expected: list[np.ndarray], zi) -> list[np.ndarray]:
    """``zi`` as copies of the arrays, the layout of ``expected`` (the rest state)."""
    try:
        items = list(zi)
    except TypeError:
        raise ParameterError("zi", "zi must be a list with one state array per stage") from None
    if len(items) != len(expected):
        raise ParameterError("zi", f"zi must hold {len(expected)} state arrays (one per stage), "
                                   f"got {len(items)}")
    out = []
    for k, (got, want) in enumerate(zip(items, expected)):
        arr = _real_array(f"zi[{k}]", got)
        if arr.shape != want.shape:
            raise ParameterError(
                f"zi[{k}]", f"zi[{k}] must have shape {want.shape}, got {arr.shape}")
        if not np.all(np.isfinite(arr)):
            raise ParameterError(f"zi[{k}]", f"zi[{k}] must be finite")
        out.append(arr.copy())
    return out


__all__ = ["impulse_response", "discrete_transfer", "filter", "filter_zi"]
