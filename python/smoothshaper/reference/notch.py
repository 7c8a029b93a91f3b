# SPDX-License-Identifier: Apache-2.0
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
from ._checks import check_stage, check_Ts
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
    """``(b, a)`` of the discrete notch biquad, in powers of ``z^-1``, ``a[0] = 1``, DC gain 1.

    The notch of Bascetta, "Motion control: advanced control techniques" (lecture notes),
    discretised as in Franklin, Powell and Workman, *Digital Control of Dynamic Systems*, 3rd
    ed., 1998: Tustin pre-warped at ``wn`` (``s = c (z-1)/(z+1)``, ``c = wn/tan(wn Ts/2)``)
    or matched pole-zero mapping (``z = e^(s Ts)`` for every root; module docstring).

    Parameters
    ----------
    stage : Stage
        A notch stage (:class:`smoothshaper.stages.Stage`).
    Ts : float, keyword-only
        Sample period [s], finite and > 0.

    Returns
    -------
    b : ndarray of float64, shape (3,)
        Numerator ``[b0, b1, b2]``.
    a : ndarray of float64, shape (3,)
        Denominator ``[1, a1, a2]``: ``y[n] = b0 x[n] + b1 x[n-1] + b2 x[n-2] - a1 y[n-1] -
        a2 y[n-2]``.

    Raises
    ------
    ParameterError
        Naming ``wn`` when it is at or above the Nyquist frequency ``pi/Ts``, ``Ts`` when it
        is not > 0, ``kind`` for a non-notch.
    """
    Ts = check_Ts(Ts)
    if stage.kind not in NOTCHES:
        raise ParameterError(
            "kind", f"kind must be a notch ({', '.join(NOTCHES)}), got {stage.kind!r}")
    return notch_coefficients_unchecked(stage, Ts)


def notch_coefficients_unchecked(stage: Stage, Ts: float) -> tuple[np.ndarray, np.ndarray]:
    """:func:`notch_coefficients` of a notch Stage at a checked ``Ts`` (the Nyquist frequency
    is checked here)."""
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
    gain = a.sum() / b.sum() if b.sum() != 0.0 else math.nan
    if not math.isfinite(gain):
        # wn Ts so small that 1 - 2 r cos(th) + r^2 cancels to 0 (0/0 gave NaN taps): the
        # same ratio as |expm1(s Ts)|^2 of the roots, scaled by (wn Ts)^2, without cancellation
        gain = _matched_dc_scaled(xi2, wn, Ts) / _matched_dc_scaled(xi1, wn, Ts)
    return b * gain, a


def _matched_dc_scaled(xi: float, wn: float, Ts: float) -> float:
    """``(1 - z1)(1 - z2) / (wn Ts)^2`` of :func:`_matched_quadratic`, from expm1 of the roots
    ``s Ts`` (no cancellation, no underflow for a mode far below the sample rate)."""
    e = wn * Ts
    if xi < 1.0:
        root = complex(-xi, math.sqrt(1.0 - xi * xi)) * e
        m = complex(np.expm1(root)) / e
        return (m * m.conjugate()).real
    q = xi + math.sqrt((xi - 1.0) * (xi + 1.0))
    return (math.expm1(-e / q) / e) * (math.expm1(-e * q) / e)


def notch_continuous_transfer(stage: Stage, s) -> np.ndarray:
    """``(s^2 + 2 zeta wn s + wn^2) / (s^2 + 2 notch_pole_zeta wn s + wn^2)`` at complex ``s``.

    Parameters
    ----------
    stage : Stage
        A notch stage (:class:`smoothshaper.stages.Stage`).
    s : array_like of complex
        Laplace variable [1/s], any shape.

    Returns
    -------
    ndarray of complex128
        The transfer function, the shape of ``s``.

    Raises
    ------
    ParameterError
        ``stage`` is not a valid Stage.
    """
    return notch_transfer_unchecked(check_stage(stage), s)


def notch_transfer_unchecked(stage: Stage, s) -> np.ndarray:
    """:func:`notch_continuous_transfer` of a notch Stage."""
    s = np.asarray(s, dtype=complex)
    wn, xi1, xi2 = stage.wn, stage.zeta, stage.notch_pole_zeta
    return (s * s + 2 * xi1 * wn * s + wn * wn) / (s * s + 2 * xi2 * wn * s + wn * wn)


def biquad(b: np.ndarray, a: np.ndarray, x: np.ndarray, state: np.ndarray):
    """Direct form I biquad over ``x``, a plain loop in the difference equation's order (no
    hidden filter state).

    Parameters
    ----------
    b : array_like of float, shape (3,)
        Numerator ``[b0, b1, b2]``.
    a : array_like of float, shape (3,)
        Denominator ``[1, a1, a2]`` (``a[0]`` is not used).
    x : ndarray of float64, shape (n,)
        Input samples.
    state : array_like of float, shape (4,)
        ``[x[-1], x[-2], y[-1], y[-2]]`` before the first sample.

    Returns
    -------
    y : ndarray of float64, shape (n,)
        Output samples.
    state : ndarray of float64, shape (4,)
        The state after the last sample, in the same layout.

    Raises
    ------
    ValueError
        ``b``, ``a`` or ``state`` hold too few values (unpacking).
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
