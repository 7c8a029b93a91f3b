# SPDX-License-Identifier: Apache-2.0
"""Input shapers: continuous designs (amplitudes and times) and their discrete taps.

Continuous designs for the mode ``(wn, zeta)``, ``wd = wn sqrt(1-zeta^2)``, ``Td = 2 pi/wd``,
``K = exp(-zeta pi/sqrt(1-zeta^2))``:

* ZV^n (Smith 1957; Singer & Seering 1990): ``C(n,m) K^m/(1+K)^n`` at ``m Td/2``, m = 0..n.
  ZV is n = 1, ZVD n = 2, ZVDD n = 3, ``zvn`` takes ``stage.order``.
* EI (Singhose, Seering & Singer 1990/1997, undamped closed form for tolerance V):
  ``(1+V)/4, (1-V)/2, (1+V)/4`` at ``0, Td/2, Td``; the residual at the design mode is V.
* EI2, two-hump EI (Singhose, Seering & Singer 1997, undamped closed form):
  ``X = (V^2 (sqrt(1-V^2) + 1))^(1/3)``, ``A1 = A4 = (3X^2 + 2X + 3V^2)/(16X)``,
  ``A2 = A3 = 1/2 - A1`` at ``0, Td/2, Td, 3Td/2``.
* MZV (as in Klipper's shaper_defs): ``1 - 1/sqrt2, sqrt2 - 1, 1 - 1/sqrt2`` at
  ``0, 0.375 Td, 0.75 Td`` before damping.
* EI3, three-hump EI (Singhose, Porter, Tuttle & Singer 1997, undamped closed form):
  ``A1 = A5 = (1 + 3V + 2 sqrt(2V(V+1)))/16``, ``A2 = A4 = (1-V)/4``, ``A3 = (1+V)/2 - 2 A1``
  at ``m Td/2``, m = 0..4.
* GMZV, the generalised MZV of 3-D printer firmware (D. Butyugin's ``shaper_defs.py``,
  ``get_mzv_coeffs``): ``n = stage.order`` impulses at ``j D Td/(n-1)``, ``D = stage.duration``;
  amplitudes are the least-squares solution (``numpy.linalg.lstsq``) of ``sum A = 1`` and
  ``H(j wd (1 + i/tau)) = 0`` for i = 0..n-2, ``tau = D (n-2)/(n-2D-1)``. n = 3, D = 0.75 is MZV.
* SI, specified insensitivity (Singhose, Seering and Singer 1996) over ``n = 2d + 1`` equally
  spaced impulses at ``m D Td/(2d)``: with ``c = cos(w D Td/(2d))`` the response is the
  Chebyshev polynomial ``V T_d`` of the band's image ``[c_lo, c_hi]`` (Dolph 1946), unit gain
  at ``c = 1``; here the band edge solves that condition by ``scipy.optimize.brentq`` and
  ``numpy.polynomial.chebyshev`` gives the cosine coefficients (:func:`si_undamped`).
* impulses (user-defined): ``stage.amplitudes`` normalised to sum 1 at ``stage.times``; no
  mode, so no damping transformation and no exact-timing correction (the linear split alone).

Damping: every design above is an undamped amplitude set ``B_m`` at times ``t_m`` (multiples of
``Td``) carried to the damped mode by ``A_m = B_m e^{-zeta wn t_m} / sum_m B_m e^{-zeta wn t_m}``,
so that ``A_m e^{-p t_m}`` equals ``B_m e^{-j wd t_m}`` up to one common factor. For ZV^n and
MZV this is exactly the published damped form (the ``K`` powers above); for EI and EI2 it is the
same transformation applied to the closed forms (the curve fits of Singhose et al. are
approximations of an optimum, not a closed form, and are not used).

Discrete taps follow ``docs/exact-mode.md``: paper timing rounds each impulse time; exact
timing splits off-grid impulses linearly and adds the least-norm correction on the support
that pins ``H(z_p) = H_c(p)``; ZV^n is the n-fold convolution of the exact ZV.
"""
from __future__ import annotations

import functools
import math

import numpy as np

from ..stages import SHAPERS, Stage
from ._checks import check_Ts, check_samples, check_stage, on_grid, round_half_up
from ..errors import ParameterError
from .._checks import finite as _finite, positive as _positive

__all__ = ["zvn_order", "mode_pole", "shaper_impulses", "shaper_continuous_transfer", "shaper_taps",
           "si_undamped"]

_ZVN_ORDER = {"zv": 1, "zvd": 2, "zvdd": 3}


def zvn_order(stage: Stage) -> int:
    """n of ZV^n for the ZV family: 1 for zv, 2 for zvd, 3 for zvdd, ``stage.order`` for zvn.

    Parameters
    ----------
    stage : Stage
        A shaper stage (:class:`smoothshaper.stages.Stage`).

    Returns
    -------
    int
        The power n of the ZV shaper the stage equals (``stage.order`` for other kinds).

    Raises
    ------
    ParameterError
        ``stage`` is not a valid Stage.
    """
    return _ZVN_ORDER.get(check_stage(stage).kind, stage.order)


def _undamped_design(stage: Stage) -> tuple[np.ndarray, np.ndarray]:
    """Amplitudes B_m (sum 1) and times in units of the damped period Td."""
    kind = stage.kind
    if kind in ("zv", "zvd", "zvdd", "zvn"):
        return _zvn_design(_ZVN_ORDER.get(kind, stage.order))
    V = stage.tolerance
    if kind == "ei":
        return np.array([(1 + V) / 4, (1 - V) / 2, (1 + V) / 4]), np.array([0.0, 0.5, 1.0])
    if kind == "ei2":
        # X = (V^2 (sqrt(1 - V^2) + 1))^(1/3), A1 = (3 X^2 + 2 X + 3 V^2)/(16 X), rearranged so
        # that nothing underflows for a tiny V (V^2 is 0 below 1e-162).
        X = V ** (1.0 / 3.0) * V ** (1.0 / 3.0) * (math.sqrt(1 - V * V) + 1) ** (1.0 / 3.0)
        a1 = (3 * X + 2 + 3 * V * (V / X)) / 16
        return np.array([a1, 0.5 - a1, 0.5 - a1, a1]), np.array([0.0, 0.5, 1.0, 1.5])
    if kind == "mzv":
        a1 = 1 - 1 / math.sqrt(2)
        return np.array([a1, math.sqrt(2) - 1, a1]), np.array([0.0, 0.375, 0.75])
    if kind == "ei3":
        a1 = (1 + 3 * V + 2 * math.sqrt(2 * V * (V + 1))) / 16
        a2 = (1 - V) / 4
        return np.array([a1, a2, (1 + V) / 2 - 2 * a1, a2, a1]), 0.5 * np.arange(5.0)
    if kind == "gmzv":
        return gmzv_undamped(stage.order, stage.duration)
    if kind == "si":
        A, units, _ = si_undamped(stage.order, stage.duration, stage.tolerance)
        return A, units
    raise ParameterError("kind", f"kind must be a shaper ({', '.join(SHAPERS)}), got {kind!r}")


def _zvn_design(n: int) -> tuple[np.ndarray, np.ndarray]:
    """ZV^n: binomial amplitudes over 2^n, half a damped period apart."""
    B = np.array([math.comb(n, m) for m in range(n + 1)], dtype=float) / 2.0 ** n
    return B, 0.5 * np.arange(n + 1)


def gmzv_undamped(n: int, duration: float) -> tuple[np.ndarray, np.ndarray]:
    """Undamped generalised MZV: amplitudes and times of ``n`` impulses over ``duration``
    damped periods.

    Equally spaced impulses whose amplitudes solve, in the least-squares sense, unit gain and
    zero vibration at the mode and its neighbourhood (the construction behind Klipper's MZV,
    which this equals for n = 3, duration = 0.75; ZV^n insensitivity as in Singhose, Seering
    and Singer, "Residual vibration reduction using vector diagrams to generate shaped
    inputs", 1994).

    Parameters
    ----------
    n : int
        Number of impulses, 3..9.
    duration : float
        Span in damped periods, in (0.5, (n - 1)/2).

    Returns
    -------
    amplitudes : ndarray of float64, shape (n,)
        Non-negative, summing to 1.
    times : ndarray of float64, shape (n,)
        Impulse times in damped periods, from 0 to ``duration``.

    Raises
    ------
    ParameterError
        Naming ``duration`` when the least-squares amplitudes go negative (in practice
        duration < 0.5).
    """
    A, units = _gmzv_undamped(n, float(duration))
    return A.copy(), units.copy()


@functools.lru_cache(maxsize=256)
def _gmzv_undamped(n: int, duration: float):
    """:func:`gmzv_undamped`, remembered (read-only arrays): a least-squares solve the tuning
    of a damping asks at every frequency for one span."""
    units = duration * np.arange(n) / (n - 1.0)
    tau = duration * (n - 2.0) / (n - 2.0 * duration - 1.0)
    w = 2.0 * math.pi * (1.0 + np.arange(n - 1)[:, None] / tau) * units[None, :]
    M = np.vstack([np.ones(n), np.cos(w), np.sin(w)])
    f = np.zeros(M.shape[0])
    f[0] = 1.0
    A = np.linalg.lstsq(M, f, rcond=None)[0]
    if np.any(A < 0.0):
        raise ParameterError(
            "duration", f"duration {duration!r} gives a negative impulse for gmzv with {n} "
                        "impulses (the least-squares design needs duration > 0.5 damped periods)")
    A = A / A.sum()
    A.setflags(write=False)
    units.setflags(write=False)
    return A, units


def si_undamped(order: int, duration: float, tolerance: float
                ) -> tuple[np.ndarray, np.ndarray, float]:
    """Undamped specified-insensitivity shaper: ``order`` impulses over ``duration`` damped
    periods whose residual stays <= ``tolerance`` over the widest band ``wd (1 +- I/2)``.

    Singhose, Seering and Singer, "Input shaping for vibration reduction with specified
    insensitivity to modeling errors", 1996 (the problem); over equally spaced symmetric
    impulses its solution is the equal-ripple polynomial of Dolph, "A current distribution for
    broadside arrays which optimizes the relationship between beam width and side-lobe level",
    1946 (module docstring).

    Parameters
    ----------
    order : int
        3, 5, 7 or 9 impulses.
    duration : float
        Span in damped periods, in [(order - 1)/4, (order - 1)/2].
    tolerance : float
        V in (0, 1).

    Returns
    -------
    amplitudes : ndarray of float64, shape (order,)
        Non-negative, summing to 1.
    times : ndarray of float64, shape (order,)
        In damped periods, from 0 to ``duration``.
    insensitivity : float
        I, the band's width relative to the damped frequency.

    Raises
    ------
    ParameterError
        Naming ``order``, ``duration`` or ``tolerance`` when out of range.
    """
    A, units, I = _si_undamped(order, float(duration), float(tolerance))
    return A.copy(), units.copy(), I


@functools.lru_cache(maxsize=256)
def _si_undamped(order: int, duration: float, tolerance: float):
    """:func:`si_undamped`, remembered (read-only arrays): the design is a root search and
    the tuning of a damping asks the same span and tolerance at every frequency."""
    from scipy.optimize import brentq
    if order not in (3, 5, 7, 9):
        raise ParameterError("order", f"order must be 3, 5, 7 or 9 for si, got {order!r}")
    if not 0.0 < tolerance < 1.0:
        raise ParameterError("tolerance", f"tolerance must be in (0, 1), got {tolerance!r}")
    d = (order - 1) // 2
    if not 0.5 * d <= duration <= d:
        raise ParameterError(
            "duration", f"duration must be in [{0.5 * d!r}, {float(d)!r}] for si with order "
                        f"{order}, got {duration!r}")
    x1 = math.cosh(math.acosh(1.0 / tolerance) / d)
    theta_c = math.pi * duration / d          # theta = w D Td/(2d) at the mode

    def ends(I: float) -> tuple[float, float]:
        lo, hi = theta_c * (1 - I / 2), theta_c * (1 + I / 2)
        c_lo = -1.0 if hi >= math.pi else math.cos(hi)
        return c_lo, max(math.cos(lo), math.cos(hi))

    def excess(I: float) -> float:           # x(c = 1) of the band minus the unit-gain x1
        c_lo, c_hi = ends(I)
        if not c_hi > c_lo:                  # a band too narrow to register in c
            return math.inf
        return (2.0 - c_lo - c_hi) / (c_hi - c_lo) - x1

    I = brentq(excess, 1e-12, 2.0 - 1e-12, xtol=1e-15, rtol=1e-15, maxiter=500)
    c_lo, c_hi = ends(I)
    # V T_d(x) with x = (2c - c_hi - c_lo)/(c_hi - c_lo), as a Chebyshev series in c = cos(theta)
    x_of_c = np.array([-(c_hi + c_lo) / (c_hi - c_lo), 2.0 / (c_hi - c_lo)])
    R = _trimmed(np.convolve(np.array([tolerance]), _chebyshev_of_linear(d, x_of_c)))
    r = _poly2cheb(R)
    r = np.concatenate([r, np.zeros(d + 1 - r.size)])
    A = np.concatenate([r[:0:-1] / 2, [r[0]], r[1:] / 2])
    A[(A < 0) & (A >= -1e-12 * np.abs(A).max())] = 0.0     # an exact 0 at duration = d/2
    if np.any(A < 0):
        raise ParameterError("duration", f"duration {duration!r} gives a negative impulse")
    A = A / A.sum()
    units = duration * np.arange(order) / (2.0 * d)
    A.setflags(write=False)
    units.setflags(write=False)
    return A, units, float(I)


def _poly2cheb(pol: np.ndarray) -> np.ndarray:
    """``np.polynomial.chebyshev.poly2cheb(pol)`` step for step on floats: from the highest
    power down, the series times x (``chebmulx``: c_0 * 0, c_0, then c_k / 2 added one place
    up and one down) plus the next coefficient (``chebadd``), trailing zeros trimmed at every
    step as NumPy's series arithmetic trims them (the same floats, without its array checks and
    type resolution: the tuning designs an SI shaper at every step of its span)."""
    res = [0.0]
    for a in reversed(_trimmed(np.asarray(pol, dtype=float)).tolist()):
        if not (len(res) == 1 and res[0] == 0):
            half = [c / 2 for c in res[1:]]
            prd = [res[0] * 0, res[0]] + half
            for k, h in enumerate(half):
                prd[k] = prd[k] + h
            res = prd
        res[0] = res[0] + a
        n = len(res)
        while n > 1 and res[n - 1] == 0:
            n -= 1
        res = res[:n]
    return np.array(res)


def _trimmed(c: np.ndarray) -> np.ndarray:
    """Trailing exact zeros dropped, at least one coefficient kept (as NumPy's series trim)."""
    n = c.size
    while n > 1 and c[n - 1] == 0:
        n -= 1
    return c[:n]


def _series_add(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    if a.size > b.size:
        out = a.copy()
        out[:b.size] += b
    else:
        out = b.copy()
        out[:a.size] += a
    return _trimmed(out)


def _series_sub(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    if a.size > b.size:
        out = a.copy()
        out[:b.size] -= b
    else:
        out = -b
        out[:a.size] += a
    return _trimmed(out)


def _chebyshev_of_linear(d: int, line: np.ndarray) -> np.ndarray:
    """Power-series coefficients of T_d(line[0] + line[1] c): Clenshaw's recurrence for the
    basis series [0, .., 0, 1] with series arithmetic, step for step as
    ``Chebyshev.basis(d)(Polynomial(line))`` computes it (the same floats, without the
    polynomial objects: the tuning designs an SI shaper at every step of its span)."""
    one, zero = np.array([1.0]), np.array([0.0])
    x = _series_add(zero, _trimmed(np.convolve(np.array([1.0]), line)))   # its domain map
    if d == 0:
        return one
    if d == 1:
        return _series_add(zero, _trimmed(np.convolve(one, x)))
    x2 = _trimmed(np.convolve(np.array([2.0]), x))
    c0, c1 = zero, one
    for _ in range(3, d + 2):
        tmp = c0
        c0 = _series_sub(zero, c1)
        c1 = _series_add(tmp, _trimmed(np.convolve(c1, x2)))
    return _series_add(c0, _trimmed(np.convolve(c1, x)))


def mode_pole(wn: float, zeta: float) -> complex:
    """The pole ``p = -zeta wn + j wn sqrt(1 - zeta^2)`` of a lightly damped mode.

    Parameters
    ----------
    wn : float
        Natural frequency [rad/s], > 0.
    zeta : float
        Damping ratio, in [0, 1).

    Returns
    -------
    complex
        The upper-half-plane pole [1/s].

    Raises
    ------
    ParameterError
        Naming ``wn`` or ``zeta`` when out of range.
    """
    wn, zeta = _positive("wn", wn), _finite("zeta", zeta)
    if not 0.0 <= zeta < 1.0:
        raise ParameterError("zeta", f"zeta must be in [0, 1), got {zeta!r}")
    return _pole(wn, zeta)


def _pole(wn: float, zeta: float) -> complex:
    return complex(-zeta * wn, wn * math.sqrt(1.0 - zeta * zeta))


def shaper_impulses(stage: Stage) -> tuple[np.ndarray, np.ndarray]:
    """The continuous shaper as impulses: amplitudes summing to 1 at times [s] from 0.

    ZV, ZVD, ZVDD, ZV^n (Singer and Seering, "Preshaping command inputs to reduce system
    vibration", 1990; Singhose, Seering and Singer 1994), EI, two- and three-hump EI
    (Singhose, Porter, Tuttle and Singer, "Vibration reduction using multi-hump input
    shapers", 1997), MZV and the generalised MZV; damping enters as amplitudes scaled by
    ``e^(-zeta wn t)`` and times in damped periods (module docstring, docs/filters.md).

    Parameters
    ----------
    stage : Stage
        A shaper stage (:class:`smoothshaper.stages.Stage`).

    Returns
    -------
    amplitudes : ndarray of float64, shape (m,)
        Impulse amplitudes, summing to 1.
    times : ndarray of float64, shape (m,)
        Impulse times [s], ascending from 0.

    Raises
    ------
    ParameterError
        ``stage`` is not a valid shaper stage.
    """
    return impulses_unchecked(check_stage(stage))


def impulses_unchecked(stage: Stage) -> tuple[np.ndarray, np.ndarray]:
    """:func:`shaper_impulses` of a Stage (whose wn and zeta the Stage validated)."""
    if stage.kind == "impulses":
        A = np.array(stage.amplitudes, dtype=float)
        return A / math.fsum(stage.amplitudes), np.array(stage.times, dtype=float)
    return _damped(*_undamped_design(stage), _pole(stage.wn, stage.zeta))


def _damped(B: np.ndarray, units: np.ndarray, p: complex) -> tuple[np.ndarray, np.ndarray]:
    """Undamped amplitudes ``B`` at ``units`` damped periods -> the design for the pole p."""
    t = units * (2.0 * math.pi / p.imag)
    A = B * np.exp(p.real * t)
    return A / A.sum(), t


def shaper_continuous_transfer(stage: Stage, s) -> np.ndarray:
    """``H_c(s) = sum_m A_m e^(-s t_m)`` of a shaper (see :func:`shaper_impulses`).

    Parameters
    ----------
    stage : Stage
        A shaper stage (:class:`smoothshaper.stages.Stage`).
    s : array_like of complex
        Laplace variable [1/s], any shape.

    Returns
    -------
    ndarray of complex128
        ``H_c(s)``, the shape of ``s``.

    Raises
    ------
    ParameterError
        ``stage`` is not a valid shaper stage.
    """
    return shaper_transfer_unchecked(check_stage(stage), s)


def shaper_transfer_unchecked(stage: Stage, s) -> np.ndarray:
    """:func:`shaper_continuous_transfer` of a Stage."""
    A, t = impulses_unchecked(stage)
    s = np.asarray(s, dtype=complex)
    return np.tensordot(np.exp(-s[..., None] * t), A, axes=([-1], [0]))


def _check_mode(stage: Stage, Ts: float) -> None:
    if stage.wn >= math.pi / Ts:
        raise ParameterError(
            "wn", f"wn must be below the Nyquist frequency pi/Ts = {math.pi / Ts!r} "
                  f"rad/s, got {stage.wn!r}")


def _paper_taps(A: np.ndarray, t: np.ndarray, Ts: float) -> np.ndarray:
    idx = [round_half_up(tm / Ts) for tm in t]
    h = np.zeros(max(idx) + 1)
    for a, i in zip(A, idx):
        h[i] += a
    return h


def _exact_taps(A: np.ndarray, t: np.ndarray, target: complex | None, zp: complex,
                Ts: float) -> np.ndarray:
    """Linear split plus least-norm correction pinning ``H(zp) = target`` (no correction when
    ``target`` is None)."""
    placed = []                       # (index, amplitude) of the base
    split = set()
    for a, tm in zip(A, t):
        mu = tm / Ts
        m = on_grid(mu)
        if m is not None:
            placed.append((m, a))
            continue
        m0 = int(math.floor(mu))
        f = mu - m0
        placed += [(m0, a * (1.0 - f)), (m0 + 1, a * f)]
        split.update((m0, m0 + 1))
    g = np.zeros(max(i for i, _ in placed) + 1)
    for i, a in placed:
        g[i] += a
    if not split or target is None:
        return g
    support = np.array(sorted(split | {0}))
    zinv = zp ** (-np.arange(g.size, dtype=float))
    r = target - np.dot(g, zinv)
    C = np.vstack([np.ones(support.size), zinv[support].real, zinv[support].imag])
    d = C.T @ np.linalg.solve(C @ C.T, np.array([0.0, r.real, r.imag]))
    g[support] += d
    return g


def shaper_taps(stage: Stage, *, Ts: float) -> np.ndarray:
    """Discrete shaper taps (sum 1) at sample period ``Ts``.

    Paper timing rounds each impulse of :func:`shaper_impulses` to the nearest sample (as
    Singer and Seering, 1990, apply shapers in discrete time); exact timing splits each
    impulse linearly between its two neighbouring samples and adds the least-norm correction
    that keeps the residual at the sampled mode exactly at the continuous design's (zero, or
    V for EI) (module docstring, docs/exact-mode.md).

    Parameters
    ----------
    stage : Stage
        A shaper stage (:class:`smoothshaper.stages.Stage`).
    Ts : float, keyword-only
        Sample period [s], finite and > 0.

    Returns
    -------
    ndarray of float64, shape (L,)
        Taps summing to 1; ``L - 1`` is the last impulse time in samples, rounded up.

    Raises
    ------
    ParameterError
        Naming ``wn`` when the mode is at or above the Nyquist frequency ``pi/Ts``, ``Ts``
        when it is not > 0, ``kind`` for a non-shaper.
    """
    Ts = check_Ts(Ts)
    if stage.kind not in SHAPERS:
        raise ParameterError(
            "kind", f"kind must be a shaper ({', '.join(SHAPERS)}), got {stage.kind!r}")
    return shaper_taps_unchecked(stage, Ts)


def shaper_taps_unchecked(stage: Stage, Ts: float) -> np.ndarray:
    """:func:`shaper_taps` of a shaper Stage at a checked ``Ts``; what depends on both (the
    Nyquist frequency, the number of taps) is checked here."""
    if stage.kind == "impulses":                   # no mode: no Nyquist check, no correction
        A, t = impulses_unchecked(stage)
        check_samples("times", t[-1] / Ts + 2.0, "the taps of the impulses")
        return _paper_taps(A, t, Ts) if stage.timing == "paper" else \
            _exact_taps(A, t, None, 1.0, Ts)
    _check_mode(stage, Ts)
    with np.errstate(over="ignore"):               # a span beyond a float: refused below
        A, t = impulses_unchecked(stage)
        span = t[-1] / Ts                          # ZV^n: already the n-fold span
    check_samples("wn", span + 2.0, f"the taps of a {stage.kind} shaper at wn Ts = "
                  f"{stage.wn * Ts:.6g}")
    if stage.timing == "paper":
        return _paper_taps(A, t, Ts)
    p = _pole(stage.wn, stage.zeta)
    zp = np.exp(p * Ts)
    if stage.kind in ("zv", "zvd", "zvdd", "zvn"):
        zv = _exact_taps(*_damped(*_zvn_design(1), p), 0.0, zp, Ts)
        h = np.ones(1)
        for _ in range(_ZVN_ORDER.get(stage.kind, stage.order)):
            h = np.convolve(h, zv)
        return h
    target = complex(np.dot(A, np.exp(-p * t)))
    return _exact_taps(A, t, target, zp, Ts)
