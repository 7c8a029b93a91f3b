# SPDX-License-Identifier: Apache-2.0
"""The continuous filters of docs/filters.md (normalised to DC gain 1), for analysis and closed forms.

Smoothers, with ``a = s - sigma`` (sigma = 0 for the undamped families) and
``phi(u) = (1 - e^{-u T})/u`` (``phi(0) = T``):

* rectangular / exponential: ``h(t) = e^{sigma t}/phi(-sigma)`` on [0, T),
  ``H(s) = phi(s - sigma)/phi(-sigma)``; this is ``(1 - e^{-sT})/(sT)`` for sigma = 0.
* harmonic / damped harmonic: ``h(t) = e^{sigma t} sin(pi t/T)/F(-sigma)`` on [0, T] with
  ``F(a) = int_0^T e^{-a t} sin(pi t/T) dt = (phi(a - j pi/T) - phi(a + j pi/T))/(2j)``
  ``= (pi/T)(1 + e^{-aT})/(a^2 + (pi/T)^2)``; ``H(s) = F(s - sigma)/F(-sigma)``
  (docs/filters.md). The phi form has no removable singularity at ``a = ±j pi/T``.
* shapers: ``H(s) = sum_m A_m e^{-s t_m}`` (impulses, see ``shaper_impulses``);
* input smoothers: ``H(s) = int_0^T g(tau) e^{-s tau} dtau`` of their polynomial kernel
  (``input_smoothers``);
* notches: ``(s^2 + 2 xi1 wn s + wn^2)/(s^2 + 2 xi2 wn s + wn^2)``.
"""
from __future__ import annotations

import math

import numpy as np

from ..stages import INPUT_SMOOTHERS, NOTCHES, SHAPERS, Stage
from ._checks import check_stage
from .._checks import (complex_array as _complex_array, finite_array as _finite_array,
                       representable as _representable)
from .input_smoothers import smoother_kernel, smoother_transfer
from .notch import notch_transfer_unchecked
from .shapers import shaper_transfer_unchecked
from ..errors import ParameterError

__all__ = ["continuous_transfer", "continuous_impulse_response"]


def _cexpm1(z: np.ndarray) -> np.ndarray:
    """``e^z - 1`` for complex z without cancellation near 0."""
    x, y = z.real, z.imag
    re = np.expm1(x) * np.cos(y) - 2.0 * np.sin(0.5 * y) ** 2
    return re + 1j * np.exp(x) * np.sin(y)


def _phi(u: np.ndarray, T: float) -> np.ndarray:
    """``(1 - e^{-uT})/u``, equal to T at u = 0."""
    u = np.asarray(u, dtype=complex)
    x = u * T
    # |uT| < 1e-6: the series (error < (uT)^3/24 relative) also avoids dividing by a
    # subnormal u, which overflows in complex division
    small = np.abs(x) < 1e-6
    out = np.asarray(T * (1.0 - x / 2.0 + x * x / 6.0), dtype=complex).reshape(u.shape)
    big = ~small
    out[big] = -_cexpm1(-u[big] * T) / u[big]
    return out


def _sigma(stage: Stage) -> float:
    return stage.sigma if stage.kind in ("damped_harmonic", "exponential") else 0.0


def _smoother_laplace(stage: Stage, a: np.ndarray) -> np.ndarray:
    """Laplace transform of the unnormalised shape at ``a = s - sigma``."""
    T = stage.T
    if stage.kind in ("rectangular", "exponential"):
        return _phi(a, T)
    w = math.pi / T
    return (_phi(a - 1j * w, T) - _phi(a + 1j * w, T)) / 2j


def continuous_transfer(stage: Stage, s) -> np.ndarray:
    """``H_c(s)`` of one stage (DC gain 1) at complex ``s``: the closed forms of the module
    docstring (smoothers as Laplace transforms of their normalised impulse responses,
    shapers as impulse trains, notches as rational functions).

    Parameters
    ----------
    stage : Stage
        Any stage.
    s : array_like of complex
        Laplace variable [1/s], any shape.

    Returns
    -------
    ndarray of complex128
        ``H_c(s)``, the shape of ``s``.

    Raises
    ------
    ParameterError
        ``stage`` is not a valid Stage.
    """
    stage = check_stage(stage)
    s = _complex_array("s", s)
    with np.errstate(over="ignore", invalid="ignore", divide="ignore", under="ignore"):
        H = transfer_unchecked(stage, s)
    return _representable("s", H, "H(s)")


def transfer_unchecked(stage: Stage, s: np.ndarray) -> np.ndarray:
    """:func:`continuous_transfer` of a checked stage at a finite complex array, its result
    not checked (a caller that refuses NaN or inf names its own argument)."""
    if stage.kind in SHAPERS:
        return shaper_transfer_unchecked(stage, s)
    if stage.kind in NOTCHES:
        return notch_transfer_unchecked(stage, s)
    if stage.kind in INPUT_SMOOTHERS:
        return smoother_transfer(stage, s)
    sigma = _sigma(stage)
    dc = _smoother_laplace(stage, np.array(-sigma, dtype=complex))
    return _smoother_laplace(stage, s - sigma) / dc


def continuous_impulse_response(stage: Stage, t) -> np.ndarray:
    """Normalised impulse response ``h(t)`` (integral 1) of a smoother, 0 outside ``[0, T)``.

    Parameters
    ----------
    stage : Stage
        A smoother stage (rectangular, harmonic, damped_harmonic, exponential) or an input
        smoother (its kernel ``g``, on ``[0, T]``).
    t : array_like of float
        Times [s], any shape.

    Returns
    -------
    ndarray of float64
        ``h(t)`` [1/s], the shape of ``t``.

    Raises
    ------
    ParameterError
        Naming ``stage`` for shapers (impulse trains: use ``shaper_impulses``) and notches
        (they have a Dirac part).
    """
    stage = check_stage(stage)
    if stage.kind in SHAPERS or stage.kind in NOTCHES:
        raise ParameterError(
            "stage", f"stage must be a smoother for continuous_impulse_response; {stage.kind} "
                     "has impulses (see shaper_impulses / continuous_transfer)")
    t = _finite_array("t", t)
    if stage.kind in INPUT_SMOOTHERS:
        q, T = smoother_kernel(stage)
        inside = (t >= 0) & (t <= T)
        return np.where(inside, np.polynomial.polynomial.polyval(
            np.where(inside, t, 0.0) / T - 0.5, q) / T, 0.0)
    sigma, T = _sigma(stage), stage.T
    inside = (t >= 0) & (t < T)
    tc = np.where(inside, t, 0.0)
    shape = np.exp(sigma * tc)
    if stage.kind in ("harmonic", "damped_harmonic"):
        shape = shape * np.sin(math.pi * tc / T)
    area = _smoother_laplace(stage, np.array(-sigma, dtype=complex)).real
    return np.where(inside, shape / area, 0.0)
