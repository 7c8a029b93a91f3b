"""Notch stage as one biquad (``docs/filters.md``, ``docs/exact-mode.md``).

Continuous: ``G(s) = (s^2 + 2 xi1 wn s + wn^2)/(s^2 + 2 xi2 wn s + wn^2)`` with ``xi1 = zeta``
(zero damping) and ``xi2 = notch_pole_zeta`` (pole damping), ``xi2 > xi1``.

* ``notch_tustin``: bilinear transform pre-warped at wn, ``s = c (z-1)/(z+1)``,
  ``c = wn/tan(wn Ts/2)``, so the discrete notch centre is exactly at wn.
* ``notch_matched``: zeros at ``exp(s Ts)`` for the numerator roots (the sampled mode
  ``e^{p Ts}`` when zeta is the mode damping), poles likewise (real when xi2 >= 1),
  gain such that ``H(1) = 1``.

Coefficients are returned as ``b = [b0, b1, b2]``, ``a = [1, a1, a2]`` in powers of ``z^-1``:
``y[n] = b0 x[n] + b1 x[n-1] + b2 x[n-2] - a1 y[n-1] - a2 y[n-2]``.
"""
from __future__ import annotations

import math

import numpy as np

from ..stages import NOTCHES, Stage
from ._checks import check_Ts
from ..errors import ParameterError

__all__ = ["notch_coefficients", "notch_continuous_transfer", "biquad"]


def _tustin_quadratic(xi: float, wn: float, c: float) -> np.ndarray:
    """(s^2 + 2 xi wn s + wn^2)(z+1)^2 at s = c (z-1)/(z+1), in powers of z^-1."""
    return np.array([c * c + 2 * xi * wn * c + wn * wn,
                     2 * (wn * wn - c * c),
                     c * c - 2 * xi * wn * c + wn * wn])


def _matched_quadratic(xi: float, wn: float, Ts: float) -> np.ndarray:
    """(1 - z1 z^-1)(1 - z2 z^-1) with z1,2 = exp(s1,2 Ts), s1,2 roots of s^2+2 xi wn s+wn^2."""
    r = math.exp(-xi * wn * Ts)
    if xi < 1.0:
        twice_re = 2.0 * r * math.cos(wn * math.sqrt(1.0 - xi * xi) * Ts)
    else:
        twice_re = 2.0 * r * math.cosh(wn * math.sqrt(xi * xi - 1.0) * Ts)
    return np.array([1.0, -twice_re, r * r])


def notch_coefficients(stage: Stage, *, Ts: float) -> tuple[np.ndarray, np.ndarray]:
    """``(b, a)`` of the discrete notch (``a[0] = 1``, DC gain 1); ``wn < pi/Ts`` required."""
    Ts = check_Ts(Ts)
    if stage.kind not in NOTCHES:
        raise ParameterError(
            "kind", f"kind must be a notch ({', '.join(NOTCHES)}), got {stage.kind!r}")
    wn, xi1, xi2 = stage.wn, stage.zeta, stage.notch_pole_zeta
    if wn >= math.pi / Ts:
        raise ParameterError(
            "wn", f"wn must be below the Nyquist frequency pi/Ts = {math.pi / Ts!r} "
                  f"rad/s, got {wn!r}")
    if stage.kind == "notch_tustin":
        c = wn / math.tan(wn * Ts / 2.0)
        b = _tustin_quadratic(xi1, wn, c)
        a = _tustin_quadratic(xi2, wn, c)
        return b / a[0], a / a[0]
    b = _matched_quadratic(xi1, wn, Ts)
    a = _matched_quadratic(xi2, wn, Ts)
    return b * (a.sum() / b.sum()), a


def notch_continuous_transfer(stage: Stage, s) -> np.ndarray:
    s = np.asarray(s, dtype=complex)
    wn, xi1, xi2 = stage.wn, stage.zeta, stage.notch_pole_zeta
    return (s * s + 2 * xi1 * wn * s + wn * wn) / (s * s + 2 * xi2 * wn * s + wn * wn)


def biquad(b: np.ndarray, a: np.ndarray, x: np.ndarray, state: np.ndarray):
    """Direct form I over ``x`` from ``state = [x1, x2, y1, y2]``; returns ``(y, new_state)``.

    A plain loop: same operation order as the difference equation, no hidden filter state.
    """
    b0, b1, b2 = (float(v) for v in b)
    a1, a2 = float(a[1]), float(a[2])
    x1, x2, y1, y2 = (float(v) for v in state)
    y = np.empty(x.size)
    for n, xn in enumerate(x.tolist()):
        yn = b0 * xn + b1 * x1 + b2 * x2 - a1 * y1 - a2 * y2
        y[n] = yn
        x2, x1, y2, y1 = x1, xn, y1, yn
    return y, np.array([x1, x2, y1, y2])
