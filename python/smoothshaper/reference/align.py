# SPDX-License-Identifier: Apache-2.0
"""Lags and the fractional delay by their definitions (the oracle of :mod:`smoothshaper.align`).

``lag``: the DC group delay of a chain in samples, ``sum_i i h[i]`` of each FIR stage's taps
and ``B'(1)/B(1) - A'(1)/A(1)`` of a notch's ``b, a`` (in powers of ``z^-1``), summed over
the stages. ``delay``: ``y[n] = x[n-m] + f (x[n-m-1] - x[n-m])``, by array indexing. Neither
calls the C code.
"""
from __future__ import annotations

import math

import numpy as np

from ..stages import NOTCHES
from ._checks import as_stage_list, check_Ts
from .filtering import impulse_response
from .notch import notch_coefficients
from .._checks import finite as _finite, finite_signal as _finite_signal
from ..errors import ParameterError


def lag(stages, *, Ts: float) -> float:
    """The lag of a chain [samples]: the sum of its stages' DC group delays.

    Parameters
    ----------
    stages : Stage or sequence of Stage
        The chain.
    Ts : float, keyword-only
        Sample period [s], > 0.

    Returns
    -------
    float
        ``sum_i i h[i]`` per FIR stage, ``B'(1)/B(1) - A'(1)/A(1)`` per notch, summed.

    Raises
    ------
    ParameterError
        Naming ``Ts`` or a stage field invalid at ``Ts``.
    """
    Ts = check_Ts(Ts)
    total = 0.0
    for stage in as_stage_list(stages):
        if stage.kind in NOTCHES:
            b, a = notch_coefficients(stage, Ts=Ts)
            i = np.arange(3)
            total += float(np.dot(i, b) / np.sum(b) - np.dot(i, a) / np.sum(a))
        else:
            h = impulse_response(stage, Ts=Ts)
            total += math.fsum(np.arange(h.size) * h) / math.fsum(h)
    return total


def delay(x, *, samples: float, rest: float | None = None) -> np.ndarray:
    """Delay ``x`` by ``samples`` (>= 0): ``y[n] = x[n-m] + f (x[n-m-1] - x[n-m])``, the input
    at ``rest`` (default ``x[0]``) before its first sample.

    Parameters
    ----------
    x : array_like of float, shape (n,)
        The signal, finite.
    samples : float, keyword-only
        The delay ``m + f``, finite and >= 0.
    rest : float or None, keyword-only
        The value before ``x[0]``.

    Returns
    -------
    ndarray of float64, shape (n,)
        The delayed signal.

    Raises
    ------
    ParameterError
        Naming ``x``, ``samples`` or ``rest``.
    """
    x = _finite_signal("x", x)
    d = _finite("samples", samples)
    if d < 0.0:
        raise ParameterError("samples", f"samples must be >= 0, got {d!r}")
    r = (x[0] if x.size else 0.0) if rest is None else _finite("rest", rest)
    m = int(math.floor(d))
    f = d - m
    padded = np.concatenate([np.full(m + 1, r), x])
    n = np.arange(x.size) + m + 1
    a, b = padded[n - m], padded[n - m - 1]
    return a + f * (b - a) if f else a.copy()


__all__ = ["lag", "delay"]
