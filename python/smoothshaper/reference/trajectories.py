# SPDX-License-Identifier: Apache-2.0
"""Closed-form step responses (trajectories) of the continuous smoothers, height ``h``.

* harmonic: ``q(t) = h/2 (1 - cos(pi t/T))`` on [0, T];
* damped harmonic (Biagiotti et al. 2020): ``q(t) = h/(1 + e^{sigma T}) (1 + e^{sigma t}
  (sigma T/pi sin(pi t/T) - cos(pi t/T)))`` on [0, T];
* exponential: ``q(t) = h (e^{sigma t} - 1)/(e^{sigma T} - 1)`` (``h t/T`` when sigma = 0);
* chain of rectangular smoothers of lengths ``T_1..T_n`` (the time-optimal profile with n
  bounded derivatives): the distribution function of a sum of uniform variables,
  ``q^{(d)}(t) = h/((n-d)! prod T_i) sum_{J subset} (-1)^{|J|} (t - sum_{j in J} T_j)_+^{n-d}``.

All are 0 before t = 0 and h after the end of the filter.
"""
from __future__ import annotations

import itertools
import math

import numpy as np
from .._checks import (finite as _finite, finite_array as _real_array, integer as _integer,
                       positive as _positive, real_array as _any_real_array,
                       representable as _representable)
from ..errors import ParameterError

__all__ = ["harmonic_trajectory", "damped_harmonic_trajectory", "exponential_trajectory",
           "rectangular_chain_trajectory"]


#: Most moving averages :func:`rectangular_chain_trajectory` takes (a Chain's limit too).
MAX_CHAIN = 16


def _sigma(sigma) -> float:
    """A decay rate: finite and <= 0 (a stage's sigma), else ParameterError naming sigma."""
    sigma = _finite("sigma", sigma)
    if sigma > 0:
        raise ParameterError("sigma", f"sigma must be <= 0 1/s (a decaying mode), got {sigma!r}")
    return sigma


def harmonic_trajectory(t, *, T: float, h: float = 1.0) -> np.ndarray:
    """Closed-form step of height ``h`` through the harmonic smoother: ``h/2 (1 - cos(pi t/T))``
    on ``[0, T]`` (Biagiotti and Melchiorri, "Online Planning of Multi-Segment Trajectories
    with Trigonometric Blends", 2011).

    Parameters
    ----------
    t : array_like of float
        Times [s], any shape (the step is applied at t = 0).
    T : float, keyword-only
        Duration [s], > 0.
    h : float, keyword-only
        Step height [position units] (default 1).

    Returns
    -------
    ndarray of float64
        Position at ``t``, the shape of ``t`` (0 before 0, ``h`` after ``T``).

    Raises
    ------
    ParameterError
        Naming ``t``, ``T`` or ``h``.
    """
    T, h = _positive("T", T), _finite("h", h)
    tc = np.clip(_real_array("t", t), 0.0, T)
    return 0.5 * h * (1.0 - np.cos(math.pi * tc / T))


def damped_harmonic_trajectory(t, *, T: float, sigma: float, h: float = 1.0) -> np.ndarray:
    """Closed-form step of height ``h`` through the damped harmonic smoother (Biagiotti,
    Melchiorri and Moriello, "Damped Harmonic Smoother for Trajectory Planning and Vibration
    Suppression", 2020): the integral of the normalised ``e^(sigma t) sin(pi t/T)``.

    Parameters
    ----------
    t : array_like of float
        Times [s], any shape (the step is applied at t = 0).
    T : float, keyword-only
        Duration [s], > 0.
    sigma : float, keyword-only
        Decay rate [1/s], <= 0.
    h : float, keyword-only
        Step height [position units] (default 1).

    Returns
    -------
    ndarray of float64
        Position at ``t``, the shape of ``t`` (0 before 0, ``h`` after ``T``).

    Raises
    ------
    ParameterError
        Naming ``t``, ``T``, ``sigma`` or ``h``.
    """
    T, h, sigma = _positive("T", T), _finite("h", h), _sigma(sigma)
    tc = np.clip(_real_array("t", t), 0.0, T)
    x = math.pi * tc / T
    inner = np.exp(sigma * tc) * (sigma * T / math.pi * np.sin(x) - np.cos(x))
    return h / (1.0 + math.exp(sigma * T)) * (1.0 + inner)


def exponential_trajectory(t, *, T: float, sigma: float, h: float = 1.0) -> np.ndarray:
    """Closed-form step of height ``h`` through the exponential smoother:
    ``h (e^(sigma t) - 1)/(e^(sigma T) - 1)`` on ``[0, T]`` (a ramp for sigma = 0).

    Parameters
    ----------
    t : array_like of float
        Times [s], any shape (the step is applied at t = 0).
    T : float, keyword-only
        Duration [s], > 0.
    sigma : float, keyword-only
        Decay rate [1/s], <= 0.
    h : float, keyword-only
        Step height [position units] (default 1).

    Returns
    -------
    ndarray of float64
        Position at ``t``, the shape of ``t`` (0 before 0, ``h`` after ``T``).

    Raises
    ------
    ParameterError
        Naming ``t``, ``T``, ``sigma`` or ``h``.
    """
    T, h, sigma = _positive("T", T), _finite("h", h), _sigma(sigma)
    tc = np.clip(_real_array("t", t), 0.0, T)
    if sigma == 0.0:
        return h * tc / T
    return h * np.expm1(sigma * tc) / math.expm1(sigma * T)


def rectangular_chain_trajectory(t, *, T, h: float = 1.0, derivative: int = 0) -> np.ndarray:
    """Closed-form step of height ``h`` through a chain of moving averages of lengths ``T``, or
    its ``derivative``-th time derivative: the piecewise polynomial
    ``h sum_S (-1)^|S| max(t - sum(S), 0)^(n-d) / ((n-d)! prod T)`` over the subsets S of
    ``T`` (the trapezoidal / double-S trajectory as a cascade of moving averages; Biagiotti
    and Melchiorri, *Trajectory Planning for Automatic Machines and Robots*, 2008).

    Parameters
    ----------
    t : array_like of float
        Times [s], any shape (the step is applied at t = 0).
    T : sequence of float, keyword-only
        Lengths of the n moving averages [s], each > 0.
    h : float, keyword-only
        Step height [position units] (default 1).
    derivative : int, keyword-only
        d in 0..n-1 (0: position, 1: velocity, ...).

    Returns
    -------
    ndarray of float64
        The d-th derivative [units/s^d] at ``t``, the shape of ``t``.

    Raises
    ------
    ParameterError
        Naming ``t``, ``T`` / ``T[i]``, ``h`` or ``derivative``.
    """
    T_arr = np.atleast_1d(_any_real_array("T", T))
    if T_arr.ndim != 1:
        raise ParameterError("T", f"T must be one duration or a sequence of them, got shape "
                             f"{T_arr.shape}")
    Ts = [_positive(f"T[{i}]", v) for i, v in enumerate(T_arr)]
    if not Ts:
        raise ParameterError("T", "T must hold at least one duration")
    n = len(Ts)
    if n > MAX_CHAIN:      # the closed form sums 2^n terms
        raise ParameterError("T", f"T: at most {MAX_CHAIN} moving averages (the closed form sums "
                             f"2^n terms), got {n}")
    if _integer("derivative", derivative, 0) >= n:
        raise ParameterError(
            "derivative", f"derivative must be an integer in 0..{n - 1}, got {derivative!r}")
    h = _finite("h", h)
    t = _real_array("t", t)
    power = n - int(derivative)
    acc = np.zeros(t.shape)
    with np.errstate(over="ignore", invalid="ignore"):     # refused below if not finite
        for r in range(n + 1):
            for subset in itertools.combinations(Ts, r):
                acc += (-1) ** r * np.maximum(t - sum(subset), 0.0) ** power
        out = h * acc / (math.factorial(power) * math.prod(Ts))
    if derivative == 0:
        out = np.where(t >= sum(Ts), h, out)
    else:
        out = np.where(t >= sum(Ts), 0.0, out)
    return _representable("t", out, "the trajectory (a power of t overflows)")
