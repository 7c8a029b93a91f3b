# SPDX-License-Identifier: Apache-2.0
"""FIR taps of the smoothers (rectangular, harmonic, damped harmonic, exponential).

Written from ``docs/filters.md`` and ``docs/exact-mode.md``, never from the C code. Unnormalised
continuous impulse responses on ``[0, T)``:

* rectangular ``1``; harmonic ``sin(pi t/T)``; damped harmonic ``e^{sigma t} sin(pi t/T)``;
  exponential ``e^{sigma t}``.

Discrete taps (``nu = T/Ts``):

* **integer N** (``nu`` passes the integer test, either timing): ``h[i] = h_c(i Ts)/sum``,
  ``i = 0..N-1``;
* **paper timing**: ``N = max(1, round(nu))`` and the integer formulas with ``T' = N Ts``;
* **exact timing**: ``N0 = floor(nu)``, ``f = nu - N0``; base ``g[i] = h_c(i Ts)``,
  ``i = 0..N0-1``, and ``g[N0] = f h_c(N0 Ts)`` (the last sample covers only the fraction f of
  its interval inside ``[0, T)``); a correction ``d`` on taps ``N0-1, N0`` solving
  ``d[N0-1] z*^{-(N0-1)} + d[N0] z*^{-N0} = -G(z*)`` where ``z* = exp((sigma + j w*) Ts)``,
  ``w* = k 2 pi/T`` (rectangular, exponential) or ``k 3 pi/T`` (harmonic families); then
  ``h = (g + d)/sum(g + d)``. The result has ``H(1) = 1`` and ``H(z*) = 0`` to rounding,
  non-negative taps, and length ``N0 + 1``;
* **bounded timing** (rectangular, exponential): taps ``u, q, q^2, ..., q^N0, u q^(N0+1)``
  (``q = e^{sigma Ts}``) scaled to sum 1, length ``N0 + 2``. With ``z* = q e^{j phi}`` every
  term ``q^i z*^{-i}`` is ``e^{-j phi i}``, so ``H(z*) = 0`` reads
  ``u (1 + e^{-j phi (N0+1)}) = -sum_{i=1..N0} e^{-j phi i}``: one complex equation whose
  solution ``u`` is real (the end taps are the same multiple of the base shape). No tap then
  exceeds the continuous response's peak density times ``Ts``.
"""
from __future__ import annotations

import math

import numpy as np

from ..stages import SMOOTHERS, Stage
from ._checks import check_Ts, check_samples, check_stage, on_grid, round_half_up
from ..errors import ParameterError

__all__ = ["pinned_frequency", "smoother_taps"]


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
    """``w*`` [rad/s], the imaginary part of the zero that exact timing pins: ``k 2 pi / T``
    (rectangular, exponential) or ``k 3 pi / T`` (harmonic families).

    Parameters
    ----------
    stage : Stage
        A smoother stage (:class:`smoothshaper.stages.Stage`).

    Returns
    -------
    float
        ``w*`` [rad/s].

    Raises
    ------
    ParameterError
        ``stage`` is not a valid Stage.
    """
    return _pinned(check_stage(stage))


def _pinned(stage: Stage) -> float:
    per = 2.0 if stage.kind in ("rectangular", "exponential") else 3.0
    return stage.k * per * math.pi / stage.T


def _sigma(stage: Stage) -> float:
    return stage.sigma if stage.kind in ("damped_harmonic", "exponential") else 0.0


def _sampled(stage: Stage, N: int, Ts: float) -> np.ndarray:
    """Normalised samples of the stage of duration ``N Ts`` (the integer-N formula)."""
    i = np.arange(N, dtype=float)
    if stage.kind in ("harmonic", "damped_harmonic"):
        if N < 2:
            raise ParameterError(
                "T", f"T must be >= 2*Ts for the {stage.kind} family (one sample of sin(pi t/T) "
                     f"is 0), got T/Ts = {stage.T / Ts!r}")
        # sin(pi i/N) with the integer N: the sampled wave vanishes exactly at i = 0.
        g = np.sin(math.pi * i / N)
        if stage.kind == "damped_harmonic":
            g = g * np.exp(stage.sigma * i * Ts)
    else:
        g = _shape(stage.kind, i * Ts, N * Ts, _sigma(stage))
    return g / g.sum()


def smoother_taps(stage: Stage, *, Ts: float) -> np.ndarray:
    """Normalised FIR taps (DC gain 1) of a smoother stage at sample period ``Ts``.

    The sampled continuous responses of docs/filters.md: rectangular and harmonic
    (Biagiotti and Melchiorri, "Online Planning of Multi-Segment Trajectories with
    Trigonometric Blends", 2011), damped harmonic and exponential (Biagiotti, Melchiorri and
    Moriello, "Damped Harmonic Smoother for Trajectory Planning and Vibration Suppression",
    2020, eq. 10); off the sample grid, exact timing corrects the last two taps so the zero
    ``w*`` stays exact (module docstring, docs/exact-mode.md).

    Parameters
    ----------
    stage : Stage
        A smoother stage (:class:`smoothshaper.stages.Stage`).
    Ts : float, keyword-only
        Sample period [s], finite and > 0.

    Returns
    -------
    ndarray of float64, shape (L,)
        Taps ``h[0..L-1]`` summing to 1, ``L = T/Ts`` on the grid, ``floor(T/Ts) + 1`` with
        exact timing off it, ``floor(T/Ts) + 2`` with bounded timing off it, ``round(T/Ts)``
        with paper timing.

    Raises
    ------
    ParameterError
        Naming ``T`` when ``T < Ts`` (``T`` within 1e-9 of ``Ts`` is one sample; anything
        shorter is refused, never a pass-through), when a harmonic stage is shorter than
        2 Ts, or when the pinned zero lies at or above the Nyquist frequency; ``Ts`` when it
        is not > 0; ``kind`` for a non-smoother.
    """
    Ts = check_Ts(Ts)
    if stage.kind not in SMOOTHERS:
        raise ParameterError(
            "kind", f"kind must be a smoother ({', '.join(SMOOTHERS)}), got {stage.kind!r}")
    return smoother_taps_unchecked(stage, Ts)


def smoother_taps_unchecked(stage: Stage, Ts: float) -> np.ndarray:
    """:func:`smoother_taps` of a smoother Stage at a checked ``Ts``; what depends on both
    (``T >= Ts``, the number of taps, the pinned zero below Nyquist) is checked here."""
    nu = stage.T / Ts
    N = on_grid(nu)
    if nu < 1.0 and not N:   # the one rule for short T: below Ts (beyond the grid test) refused
        raise ParameterError("T", f"T must be >= Ts ({Ts!r} s), got {stage.T!r}")
    check_samples("T", nu + 1.0, f"the taps of a {stage.kind} smoother with T/Ts = {nu:.6g}")
    if N is not None:
        return _sampled(stage, N, Ts)
    if stage.timing == "paper":
        return _sampled(stage, max(1, round_half_up(nu)), Ts)
    if stage.timing == "bounded":
        return _bounded_taps(stage, nu, Ts)
    return _exact_taps(stage, nu, Ts)


def _bounded_taps(stage: Stage, nu: float, Ts: float) -> np.ndarray:
    N0 = int(math.floor(nu))
    w_star = _pinned(stage)
    if w_star * Ts >= math.pi:
        raise ParameterError(
            "T", f"T = {stage.T!r} s cannot pin its zero w* = {w_star!r} rad/s at Ts = {Ts!r} s: "
                 f"w* Ts must lie below pi (choose a longer T or a smaller k)")
    phi = w_star * Ts
    i = np.arange(1, N0 + 1, dtype=float)
    rest = complex(math.fsum(np.cos(phi * i)), -math.fsum(np.sin(phi * i)))
    u = (-rest / (1.0 + complex(math.cos(phi * (N0 + 1)), -math.sin(phi * (N0 + 1))))).real
    q = math.exp(_sigma(stage) * Ts)
    h = np.concatenate(([u], q ** i, [u * q ** (N0 + 1)]))
    return h / math.fsum(h)


def _exact_taps(stage: Stage, nu: float, Ts: float) -> np.ndarray:
    N0 = int(math.floor(nu))
    i = np.arange(N0 + 1, dtype=float)
    g = _shape(stage.kind, i * Ts, stage.T, _sigma(stage))
    g[N0] *= nu - N0
    s_star = complex(_sigma(stage), _pinned(stage))
    # The columns z*^-(N0-1), z*^-N0 are independent unless z* is real, i.e. unless the
    # pinned zero sits on a multiple of pi/Ts.
    w_star = _pinned(stage)
    if w_star * Ts >= math.pi or abs(math.sin(w_star * Ts)) < 1e-9:
        raise ParameterError(
            "T", f"T = {stage.T!r} s cannot pin its zero w* = {w_star!r} rad/s at Ts = {Ts!r} s: "
                 f"w* Ts must lie below pi (choose a longer T or a smaller k)")
    # G is small next to its terms: sum it exactly.
    terms = g * np.exp(-s_star * Ts * i)
    G = complex(math.fsum(terms.real), math.fsum(terms.imag))
    # Multiply the condition by z*^N0:  d[N0-1] z* + d[N0] = -G z*^N0 = R.
    z = np.exp(s_star * Ts)
    R = -G * np.exp(s_star * Ts * N0)
    d_first = R.imag / z.imag
    d_last = R.real - d_first * z.real
    h = g.copy()
    h[N0 - 1] += d_first
    h[N0] += d_last
    return h / math.fsum(h)
