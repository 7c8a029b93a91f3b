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
from .._checks import (finite as _finite, integer as _integer, positive as _positive,
                       real_array as _real_array)
from ..errors import ParameterError

__all__ = ["harmonic_trajectory", "damped_harmonic_trajectory", "exponential_trajectory",
           "rectangular_chain_trajectory"]


def harmonic_trajectory(t, *, T: float, h: float = 1.0) -> np.ndarray:
    """Step of height ``h`` through the harmonic smoother of duration ``T`` [s]."""
    T, h = _positive("T", T), _finite("h", h)
    tc = np.clip(_real_array("t", t), 0.0, T)
    return 0.5 * h * (1.0 - np.cos(math.pi * tc / T))


def damped_harmonic_trajectory(t, *, T: float, sigma: float, h: float = 1.0) -> np.ndarray:
    """Step of height ``h`` through the damped harmonic smoother (``sigma`` <= 0 [1/s])."""
    T, h, sigma = _positive("T", T), _finite("h", h), _finite("sigma", sigma)
    tc = np.clip(_real_array("t", t), 0.0, T)
    x = math.pi * tc / T
    inner = np.exp(sigma * tc) * (sigma * T / math.pi * np.sin(x) - np.cos(x))
    return h / (1.0 + math.exp(sigma * T)) * (1.0 + inner)


def exponential_trajectory(t, *, T: float, sigma: float, h: float = 1.0) -> np.ndarray:
    """Step of height ``h`` through the exponential smoother (``sigma`` <= 0 [1/s])."""
    T, h, sigma = _positive("T", T), _finite("h", h), _finite("sigma", sigma)
    tc = np.clip(_real_array("t", t), 0.0, T)
    if sigma == 0.0:
        return h * tc / T
    return h * np.expm1(sigma * tc) / math.expm1(sigma * T)


def rectangular_chain_trajectory(t, *, T, h: float = 1.0, derivative: int = 0) -> np.ndarray:
    """Step of height ``h`` through rectangular smoothers of lengths ``T`` (a sequence) [s],
    or its ``derivative``-th time derivative (0 <= derivative < len(T))."""
    Ts = [_positive(f"T[{i}]", v) for i, v in enumerate(np.atleast_1d(T))]
    if not Ts:
        raise ParameterError("T", "T must hold at least one duration")
    n = len(Ts)
    if _integer("derivative", derivative, 0) >= n:
        raise ParameterError(
            "derivative", f"derivative must be an integer in 0..{n - 1}, got {derivative!r}")
    h = _finite("h", h)
    t = _real_array("t", t)
    power = n - int(derivative)
    acc = np.zeros(t.shape)
    for r in range(n + 1):
        for subset in itertools.combinations(Ts, r):
            acc += (-1) ** r * np.maximum(t - sum(subset), 0.0) ** power
    out = h * acc / (math.factorial(power) * math.prod(Ts))
    if derivative == 0:
        out = np.where(t >= sum(Ts), h, out)
    else:
        out = np.where(t >= sum(Ts), 0.0, out)
    return out
