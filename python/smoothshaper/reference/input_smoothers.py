# SPDX-License-Identifier: Apache-2.0
"""Input smoothers of Klipper-derived firmware: kernels, continuous transfer and discrete taps.

D. Butyugin's polynomial kernels (dmbutyugin/klipper, branch advanced-features,
``klippy/extras/shaper_defs.py``, commit 0e5f3bb5 of 2024-10-03; also in Kalico): on the
normalised time ``u = tau/T - 1/2`` in ``[-1/2, 1/2]`` a polynomial ``P(u) = sum_k q_k u^k``
with ``P(+-1/2) = 0`` and unit area, ``g(tau) = P(tau/T - 1/2)/T`` on ``[0, T]`` (tau the
lag), ``T = t(zeta)/f``. smooth_zv, smooth_mzv and smooth_ei tabulate ``q_k`` and ``t`` as
cubics in zeta (valid for zeta in [0, 0.25]); smooth_2hump_ei (here smooth_ei2), smooth_zvd_ei
and smooth_si are constants (designed at damping 0.1).

Independent of the C core's method (which integrates by Gauss-Legendre): here every integral
is exact polynomial algebra:

* ``H_c(s) = int_0^T g e^{-s tau}`` by the Taylor series of the exponential (exact moments of
  ``P``) for ``|sT| <= 12``
  and by the closed antiderivative ``-e^{-a u} sum_j P^(j)(u)/a^(j+1)`` above;
* the linear-interpolation taps ``h_k = int g(tau) L(tau/Ts - k) dtau`` interval by interval
  from the Taylor expansion of ``P`` at each interval's start (no cancellation between
  antiderivative values);
* the exact-timing correction ``d = W C^T (C W C^T)^{-1} (target - C h)``, ``W = diag |h|``,
  rows of C: 1, k, Re and Im of ``z_p^-k``; targets: 1, the first moment over Ts, ``H_c(p)``
  at the pinned point (the damped mode; ``j wn`` for the kernels that do not read zeta).
"""
from __future__ import annotations

import functools
import math

import numpy as np
from numpy.polynomial import polynomial as P

from ..errors import ParameterError
from ..stages import INPUT_SMOOTHERS, Stage
from ._checks import check_samples, check_stage, check_Ts, on_grid

__all__ = ["smoother_kernel", "smoother_transfer", "input_smoother_taps", "pinned_pole"]

# (t-cubic, rows of q_k cubics) for the damping-dependent kernels; constants for the others,
# the source listing q_8 first (reversed here to q_0 first).
_CUBIC = {
    "smooth_zv": ([0.66471804, 0.0039585139, 0.33614293, 0.2157273], [
        [0.1418285825, -0.4423501425, 0.696114325, -1.3609939],
        [0.0, 3.5635179, -3.83613985, -6.2783295],
        [-15.50842883, 29.06586482, -12.3383868, 112.6474131],
        [0.0, -206.8822741, 52.8629899, 152.492858],
        [452.7401905, -281.3808295, -2.555613, -1175.326975],
        [0.0, 770.51281, -150.073722, -509.51816],
        [-1571.90293, 688.77989, 163.085324, 2986.0529]]),
    "smooth_mzv": ([0.85165483, 0.0183642417, 0.39000898, 0.23209004], [
        [2.239795725, -0.3957072675, -5.57438075, 0.07195255],
        [0.0, 29.10368225, -3.461668825, -22.41514],
        [-154.4864979, 92.80041407, 23.0961391, 774.3910148],
        [0.0, -1362.168729, -35.59728045, 1147.640935],
        [3870.466035, -3292.00459, 7849.3652856, -36092.1938],
        [0.0, 21476.8835, 2071.594648, -21131.4185],
        [-43110.2746, 39792.0705, -138379.754, 483530.1615],
        [0.0, -134532.955, -15615.6118, 139113.6955],
        [214526.885, -191572.8415, 791628.475, -2450648.74],
        [0.0, 274229.94, 32481.346, -286062.83],
        [-378797.98, 316954.83, -1455001.66, 4177695.0]]),
    "smooth_ei": ([0.96753911, 0.48592866, -7.2991788, 18.2075661], [
        [2.4923607, 1.1935848, -46.9202175, 127.76906],
        [0.0, 33.3731105, 103.46339, -262.7533525],
        [-166.2319578, -317.4835492, 5178.61787, -13957.64074],
        [0.0, -1914.663767, -2867.941885, 6546.52041],
        [4043.65056, 13078.06184, -149368.2255, 386432.888],
        [0.0, 30664.02555, 11115.66415, 4553.999],
        [-43879.103, -162723.6625, 1672995.285, -4352601.97],
        [0.0, -184244.5385, 56995.0041, -422243.748],
        [213582.6565, 773861.825, -7739194.35, 2.06293873e7],
        [0.0, 360348.71, -248768.99, 1264398.56],
        [-371055.41, -1248811.1, 1.24707394e7, -3.4165302e7]]),
}
_CONSTANT = {
    "smooth_ei2": (1.14875, [
        -22525.88434486782, 2524.826047114184, 10554.22832043971, -1051.778387878068,
        -1475.914693073253, 121.2177946817349, 57.95603221424528, -4.018706414213658,
        0.8375784787864095]),
    "smooth_zvd_ei": (1.475, [
        -18835.07746719777, 1914.349309746547, 8786.608981369287, -807.3061869131075,
        -1209.429748155012, 96.48879052981883, 43.1595785340444, -3.577268915175282,
        1.083220648523371]),
    "smooth_si": (1.245, [
        -6186.76006449789, 1206.747198930197, 2579.985143622855, -476.8554763069169,
        -295.546608490564, 52.69679971161049, 4.234582468800491, -2.226157642004671,
        1.267781046297883]),
}
_SERIES_LIMIT = 12.0
#: Terms of the series whose factors -x/m are formed at once (it needs about 60 for |x| <= 12).
_STEPS = 96
_INV_M = 1.0 / np.arange(1, _STEPS + 1)


def _check(stage: Stage) -> Stage:
    stage = check_stage(stage)
    if stage.kind not in INPUT_SMOOTHERS:
        raise ParameterError("kind", f"kind must be an input smoother "
                             f"({', '.join(INPUT_SMOOTHERS)}), got {stage.kind!r}")
    return stage


def _zeta(stage: Stage) -> float:
    return stage.zeta if stage.kind in _CUBIC else 0.0


def smoother_kernel(stage: Stage) -> tuple[np.ndarray, float]:
    """The kernel of an input smoother: ``P``'s coefficients ``q_0..q_n`` (unit area over
    ``[-1/2, 1/2]``) and the duration ``T`` [s].

    Parameters
    ----------
    stage : Stage
        An input smoother (:data:`smoothshaper.stages.INPUT_SMOOTHERS`).

    Returns
    -------
    q : ndarray of float64, shape (degree + 1,)
        ``g(tau) = P(tau/T - 1/2)/T`` with ``P(u) = sum_k q[k] u^k``.
    T : float
        Kernel duration [s].

    Raises
    ------
    ParameterError
        Naming ``kind`` for another kind.
    """
    stage = _check(stage)
    z = _zeta(stage)
    if stage.kind in _CUBIC:
        t, rows = _CUBIC[stage.kind]
        q = np.array([_horner(r, z) for r in rows])
        span = _horner(t, z)
    else:
        span, high_first = _CONSTANT[stage.kind]
        q = np.array(high_first[::-1])
    # P.polyint(q) is [0, q_0, q_1/2, q_2/3, ...]: its values at +-1/2 by the same Horner steps
    integral = [0.0] + [float(c) / (j + 1) for j, c in enumerate(q)]
    area = _horner(integral, 0.5) - _horner(integral, -0.5)
    return q / area, span * 2.0 * math.pi / stage.wn


def pinned_pole(stage: Stage) -> complex:
    """The point exact timing pins, ``H(e^{p Ts}) = H_c(p)``: the damped mode for smooth_zv,
    smooth_mzv, smooth_ei; ``j wn`` for the kernels that do not read zeta.

    Parameters
    ----------
    stage : Stage
        An input smoother.

    Returns
    -------
    complex
        p [1/s].

    Raises
    ------
    ParameterError
        Naming ``kind`` for another kind.
    """
    z = _zeta(_check(stage))
    return complex(-z * stage.wn, stage.wn * math.sqrt(1.0 - z * z))


def _transfer_scalar(q: np.ndarray, a: complex) -> complex:
    """``int_{-1/2}^{1/2} P(u) e^{-a (u + 1/2)} du``."""
    return complex(_transfer(q, np.array([a], dtype=complex))[0])


#: ``2^-n / (n + 1)``, the moments of u^n over [-1/2, 1/2] for even n (the same floats as
#: computed in place).
_UNIT_MOMENTS = [0.5 ** n / (n + 1) for n in range(256)]


def _moment(q, m: int) -> float:
    """``int_{-1/2}^{1/2} u^m P(u) du`` (the exact moments of u^n: 2^-n/(n+1), n even)."""
    return sum([c * (_UNIT_MOMENTS[m + j] if m + j < 256 else 0.5 ** (m + j) / (m + j + 1))
                for j, c in enumerate(q) if (m + j) % 2 == 0])


@functools.lru_cache(maxsize=256)
def _moments(q: tuple) -> list:
    """The moments of a kernel computed so far (:func:`_moments_upto` extends the list; the
    tuning asks the same kernel hundreds of times)."""
    return []


def _moments_upto(q: tuple, n: int) -> list:
    """The first ``n`` moments of a kernel (at least), the same floats as :func:`_moment`."""
    got = _moments(q)
    while len(got) < n:
        got.append(_moment(q, len(got)))
    return got


def _horner(c, u: float) -> float:
    """``P.polyval(u, c)`` for a float u: the same Horner steps on Python floats (without its
    array checks; the tuning asks this a dozen times per transfer)."""
    v = float(c[-1])
    for a in reversed(c[:-1]):
        v = float(a) + v * u
    return v


def _transfer(q: np.ndarray, a: np.ndarray) -> np.ndarray:
    """:func:`_transfer_scalar` over an array of ``a = s T``: the exponential's series with the
    exact moments of P for ``|a| <= 12``, the closed antiderivative above."""
    a = np.asarray(a, dtype=complex)
    out = np.empty(a.shape, dtype=complex)
    small = np.abs(a) <= _SERIES_LIMIT
    if small.any():
        x = a[small]
        # e^{-a (u + 1/2)} = e^{-a/2} sum_m (-a u)^m / m!, with the moments of P over
        # [-1/2, 1/2] exactly: int u^n du = 2^-n/(n+1) for even n, 0 for odd
        # -x / m formed at once, as NumPy divides by m + 0j: each part times 1 / m
        steps = np.empty((_STEPS, x.size), dtype=complex)
        steps.real = -x.real * _INV_M[:, None]
        steps.imag = -x.imag * _INV_M[:, None]
        # the terms (-x)^m / m!, term_m = term_{m-1} * steps[m-1] (one NumPy call each, the
        # products the term-by-term loop formed), as far as the largest |x| needs them (about
        # where r^m / m! falls below 1e-18); then which are taken (m <= 20, then on while some
        # |term_m| > 1e-18) at once, and their running sum over m as the loop added them (an
        # accumulation: a reduction of one column would sum pairwise): the same floats,
        # without the loop's four further NumPy calls per term
        r, need, bound = float(np.max(np.abs(x))), 0, 1.0
        while need <= 20 or bound > 1e-18:
            need += 1
            bound *= r / need
        n_terms = min(need + 2, _STEPS)
        terms = np.empty((n_terms + 1, x.size), dtype=complex)
        terms[0] = 1.0
        for m in range(1, n_terms + 1):
            np.multiply(terms[m - 1], steps[m - 1], out=terms[m])
        big = np.abs(terms[21:]).max(axis=1) > 1e-18
        if big.all():                   # not yet below (or past the factors formed at once)
            total = _series_loop(q, x, steps)
        else:
            stop = 21 + int(np.argmin(big))
            moments = _moments_upto(tuple(float(c) for c in q), stop)
            total = np.add.accumulate(terms[:stop] * np.array(moments[:stop])[:, None],
                                      axis=0)[-1]
        out[small] = total * np.exp(-x / 2)
    if (~small).any():
        # -e^{-a u} sum_j P^(j)(u)/a^(j+1) from -1/2 to 1/2, times e^{-a/2}
        x = a[~small]
        acc = np.zeros(x.shape, dtype=complex)
        deriv, power = q.astype(float), x.copy()
        e = np.exp(-x)
        while deriv.size:
            acc += (_horner(deriv, 0.5) * e - _horner(deriv, -0.5)) / power
            deriv = deriv[1:] * np.arange(1, deriv.size)     # P.polyder's products j c_j
            power = power * x
        out[~small] = -acc
    return out


def _series_loop(q, x, steps):
    """The series term by term (for an argument whose terms stay above 1e-18 past
    ``_STEPS`` of them; the tuning's stay below |x| = 12, about 60 terms)."""
    total = np.zeros(x.shape, dtype=complex)
    term = np.ones(x.shape, dtype=complex)
    m = 0
    while m <= 20 or np.abs(term).max() > 1e-18:
        total += term * _moment(q, m)
        m += 1
        term = term * (steps[m - 1] if m <= _STEPS else -x / m)
    return total


def smoother_transfer(stage: Stage, s) -> np.ndarray:
    """``H_c(s) = int_0^T g(tau) e^{-s tau} dtau`` of an input smoother.

    Parameters
    ----------
    stage : Stage
        An input smoother.
    s : array_like of complex
        Laplace variable [1/s], any shape.

    Returns
    -------
    ndarray of complex128
        ``H_c(s)``, the shape of ``s``.

    Raises
    ------
    ParameterError
        Naming ``kind`` for another kind.
    """
    q, T = smoother_kernel(stage)
    return _transfer(q, np.asarray(s, dtype=complex) * T)


def _taps_linear(q: np.ndarray, T: float, Ts: float, L: int) -> np.ndarray:
    """``h_k = int g(tau) L(tau/Ts - k) dtau``: on each interval [k Ts, (k+1) Ts] of [0, T]
    the rising and falling halves of the two triangles, from the Taylor expansion of P at
    the interval's start."""
    h = np.zeros(L)
    derivs = [q]
    while derivs[-1].size > 1:
        derivs.append(P.polyder(derivs[-1]))
    n_int = int(math.ceil(T / Ts - 1e-12))
    for k in range(n_int):
        a, b = k * Ts, min((k + 1) * Ts, T)
        if b <= a:
            continue
        u0, du = a / T - 0.5, (b - a) / T
        # int_0^du P(u0 + v) (1 - v T/Ts) dv and int_0^du P(u0 + v) (v T/Ts) dv
        whole = ramp = 0.0
        fact = 1.0
        for j, d in enumerate(derivs):
            pj = _horner(d, u0) / fact     # P.polyval's Horner steps, on floats
            whole += pj * du ** (j + 1) / (j + 1)
            ramp += pj * du ** (j + 2) / (j + 2)
            fact *= j + 1
        ramp *= T / Ts
        h[k] += whole - ramp
        if k + 1 < L:
            h[k + 1] += ramp
    return h


def input_smoother_taps(stage: Stage, *, Ts: float) -> np.ndarray:
    """Discrete taps of an input smoother at ``Ts`` (exact timing, module docstring).

    Parameters
    ----------
    stage : Stage
        An input smoother.
    Ts : float, keyword-only
        Sample period [s], > 0; the kernel must span at least 4 samples.

    Returns
    -------
    ndarray of float64, shape (L,)
        ``L = round(T/Ts) + 1`` on the sample grid, ``floor(T/Ts) + 2`` off it.

    Raises
    ------
    ParameterError
        Naming ``wn`` when the kernel spans fewer than 4 samples (or more than the reference
        holds), ``Ts`` when it is not > 0, ``kind`` for another kind.
    """
    return taps_unchecked(_check(stage), check_Ts(Ts))


def taps_unchecked(stage: Stage, Ts: float) -> np.ndarray:
    """:func:`input_smoother_taps` of an input-smoother Stage at a checked ``Ts``."""
    q, T = smoother_kernel(stage)
    mu = T / Ts
    check_samples("wn", mu + 2.0, f"the taps of {stage.kind} at wn Ts = {stage.wn * Ts:.6g}")
    if mu < 4.0:
        raise ParameterError(
            "wn", f"wn too high for Ts: the {stage.kind} kernel (T = {T!r} s) must span at "
                  f"least 4 samples, got T/Ts = {mu:.4g}")
    n = on_grid(mu)
    L = n + 1 if n is not None else int(math.floor(mu)) + 2
    h = _taps_linear(q, T, Ts, L)
    p = pinned_pole(stage)
    target_h = _transfer_scalar(q, p * T)
    moment = T * (P.polyval(0.5, P.polyint(P.polymulx(q))) - P.polyval(-0.5, P.polyint(P.polymulx(q)))
                  + 0.5)
    k = np.arange(L, dtype=float)
    zinv = np.exp(-p * Ts * k)
    C = np.vstack([np.ones(L), k, zinv.real, zinv.imag])
    target = np.array([1.0, moment / Ts, target_h.real, target_h.imag])
    w = np.abs(h)
    y = np.linalg.solve((C * w) @ C.T, target - C @ h)
    return h + w * (C.T @ y)
