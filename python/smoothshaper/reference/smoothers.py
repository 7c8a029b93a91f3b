"""FIR taps of the smoothers (rectangular, harmonic, damped harmonic, exponential).

Written from SPEC 3.1-3.4 and ``docs/exact-mode.md``, never from the C code. Unnormalised
continuous impulse responses on ``[0, T)``:

* rectangular ``1``; harmonic ``sin(pi t/T)``; damped harmonic ``e^{sigma t} sin(pi t/T)``;
  exponential ``e^{sigma t}``.

Discrete taps (``nu = T/Ts``):

* **integer N** (``nu`` passes the integer test, either timing): ``h[i] = h_c(i Ts)/sum``,
  ``i = 0..N-1``;
* **paper timing**: ``N = max(1, round(nu))`` and the integer formulas with ``T' = N Ts``;
* **exact timing**: ``N0 = floor(nu)``; base ``g[i] = h_c(i Ts)``, ``i = 0..N0``, ``g[N0+1] = 0``,
  normalised to sum 1; then a correction ``d`` on taps ``N0-1, N0, N0+1`` solving
  ``sum d = 0`` and ``sum d[i] z*^{-i} = -G(z*)`` where ``z* = exp((sigma + j w*) Ts)``,
  ``w* = k 2 pi/T`` (rectangular, exponential) or ``k 3 pi/T`` (harmonic families).
  The result has ``H(1) = 1`` and ``H(z*) = 0`` to rounding; length ``N0 + 2``.
"""
from __future__ import annotations

import math

import numpy as np

from ..stages import SMOOTHERS, Stage
from ._checks import check_Ts, on_grid, round_half_up


def _shape(kind: str, t: np.ndarray, T: float, sigma: float) -> np.ndarray:
    """Unnormalised continuous impulse response at times t (inside [0, T))."""
    if kind == "rectangular":
        return np.ones_like(t)
    if kind == "exponential":
        return np.exp(sigma * t)
    wave = np.sin(math.pi * t / T)
    if kind == "harmonic":
        return wave
    return np.exp(sigma * t) * wave


def pinned_frequency(stage: Stage) -> float:
    """``w*`` [rad/s], the imaginary part of the zero that exact timing pins."""
    per = 2.0 if stage.kind in ("rectangular", "exponential") else 3.0
    return stage.k * per * math.pi / stage.T


def _sigma(stage: Stage) -> float:
    return stage.sigma if stage.kind in ("damped_harmonic", "exponential") else 0.0


def _sampled(stage: Stage, N: int, Ts: float) -> np.ndarray:
    """Normalised samples of the stage of duration ``N Ts`` (the integer-N formula)."""
    i = np.arange(N, dtype=float)
    if stage.kind in ("harmonic", "damped_harmonic"):
        if N < 2:
            raise ValueError(
                f"T must be >= 2*Ts for the {stage.kind} family (one sample of sin(pi t/T) "
                f"is 0), got T/Ts = {stage.T / Ts!r}")
        # sin(pi i/N) with the integer N: the sampled wave vanishes exactly at i = 0.
        g = np.sin(math.pi * i / N)
        if stage.kind == "damped_harmonic":
            g = g * np.exp(stage.sigma * i * Ts)
    else:
        g = _shape(stage.kind, i * Ts, N * Ts, _sigma(stage))
    return g / g.sum()


def smoother_taps(stage: Stage, *, Ts: float) -> np.ndarray:
    """Normalised FIR taps (DC gain 1) of a smoother stage at sample period ``Ts`` [s].

    Raises ValueError naming ``T`` when ``T < Ts`` (beyond the integer test) or the pinned
    zero cannot be placed, ``Ts`` when it is not > 0, ``kind`` for a non-smoother.
    """
    Ts = check_Ts(Ts)
    if stage.kind not in SMOOTHERS:
        raise ValueError(f"kind must be a smoother ({', '.join(SMOOTHERS)}), got {stage.kind!r}")
    nu = stage.T / Ts
    N = on_grid(nu)
    if N is None and nu < 1.0:
        raise ValueError(f"T must be >= Ts ({Ts!r} s), got {stage.T!r}")
    if N is not None:
        return _sampled(stage, N, Ts)
    if stage.timing == "paper":
        return _sampled(stage, max(1, round_half_up(nu)), Ts)
    return _exact_taps(stage, nu, Ts)


def _cexpm1(z: complex) -> complex:
    """``e^z - 1`` for complex z without cancellation near 0."""
    return complex(math.expm1(z.real) * math.cos(z.imag) - 2.0 * math.sin(0.5 * z.imag) ** 2,
                   math.exp(z.real) * math.sin(z.imag))


def _exact_taps(stage: Stage, nu: float, Ts: float) -> np.ndarray:
    N0 = int(math.floor(nu))
    i = np.arange(N0 + 2, dtype=float)
    g = np.zeros(N0 + 2)
    g[:N0 + 1] = _shape(stage.kind, i[:N0 + 1] * Ts, stage.T, _sigma(stage))
    g /= g.sum()
    s_star = complex(_sigma(stage), pinned_frequency(stage))
    # The columns 1, z*^-i at three consecutive i are independent unless z* is real, i.e.
    # unless the pinned zero sits on a multiple of pi/Ts.
    if abs(math.sin(pinned_frequency(stage) * Ts)) < 1e-9:
        raise ValueError(
            f"T = {stage.T!r} s cannot pin its zero w* = {pinned_frequency(stage)!r} rad/s at "
            f"Ts = {Ts!r} s: w* Ts is a multiple of pi (choose T or k so that w* < pi/Ts)")
    # G is tiny next to its terms and the solve below divides by ~(w* Ts)^3: sum exactly.
    terms = g * np.exp(-s_star * Ts * i)
    G = complex(math.fsum(terms.real), math.fsum(terms.imag))
    # Eliminate d[N0] = -d[N0-1] - d[N0+1] and divide by z*^-N0:
    #   d[N0-1] (z* - 1) + d[N0+1] (1/z* - 1) = -G z*^N0,
    # with z* - 1 and 1/z* - 1 from expm1: the 3x3 system in raw powers of z* loses about
    # 1/(w* Ts)^2 in accuracy (the correction is a near second difference), this form not.
    a = _cexpm1(s_star * Ts)
    b = _cexpm1(-s_star * Ts)
    R = -G * np.exp(s_star * Ts * N0)
    det = a.real * b.imag - a.imag * b.real
    d_first = (R.real * b.imag - R.imag * b.real) / det
    d_last = (a.real * R.imag - a.imag * R.real) / det
    d = np.array([d_first, -d_first - d_last, d_last])
    support = np.arange(N0 - 1, N0 + 2)
    h = g.copy()
    h[support] += d
    return h
