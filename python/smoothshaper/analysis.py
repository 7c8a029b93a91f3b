# SPDX-License-Identifier: Apache-2.0
"""Frequency-domain analysis of stages and chains: responses, residual vibration, PRV,
insensitivity and trajectory spectra. Pure NumPy/SciPy on top of ``smoothshaper.reference``.

Definitions (docs/analysis.md):

* chain transfer ``H(s) = prod_k H_k(s)``; continuous filters when ``Ts`` is None, else the
  discrete filters evaluated at ``z = e^{s Ts}`` (``frequency_response``: ``s = j w``);
* a mode ``(wn, zeta)`` has the pole ``p = -zeta wn + j wn sqrt(1-zeta^2)``;
* ``residual_vibration`` = amplitude of the oscillation left on the mode by a filtered unit
  step divided by that of the unfiltered step = ``|H(p)|`` (discrete: ``|H_d(e^{p Ts})|``,
  the command held by a zero-order hold); ``prv`` = 100 times that (seed 003, footnote 2);
* ``insensitivity``: the band of natural frequencies around ``wn_hat`` where the PRV stays at or
  below ``100 * tolerance`` (damping fixed), and its width divided by ``wn_hat`` (the
  nondimensional insensitivity of Singhose et al.).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .reference.continuous import transfer_unchecked
from .reference.filtering import coefficients_unchecked
from ._checks import (complex_array as _complex_array, finite as _finite,
                      finite_signal as _finite_signal, integer as _integer, positive as _positive,
                      real_array as _real_array, representable as _representable)
from .reference._checks import check_samples as _check_samples
from .errors import ParameterError
from .reference._checks import as_stage_list, check_Ts

__all__ = ["transfer", "ChainResponse", "frequency_response", "mode_poles", "residual_vibration",
           "prv", "prv_curve", "prv_surface", "Insensitivity", "insensitivity", "step_spectrum",
           "signal_spectrum"]


def transfer(stages, s, *, Ts: float | None = None) -> np.ndarray:
    """Transfer function of the chain at complex frequencies ``s``.

    ``H(s) = prod_k H_k(s)``: the continuous filters, or (``Ts`` given) the discrete ones at
    ``z = e^{s Ts}`` (docs/analysis.md).

    Parameters
    ----------
    stages : Stage, sequence of Stage or ChainResponse
        The chain, first stage first (a :class:`ChainResponse` reuses its taps).
    s : array_like of complex
        Laplace variable [1/s], any shape.
    Ts : float or None, keyword-only
        Sample period [s]: the discrete chain at ``z = e^{s Ts}``; None (default): the
        continuous filters.

    Returns
    -------
    ndarray of complex128
        ``H(s)``, the shape of ``s``.

    Raises
    ------
    ParameterError
        An invalid stage or chain at ``Ts``, ``Ts`` not finite and > 0, or a ChainResponse
        given with a different ``Ts``; ``s`` not finite numbers, or where ``H(s)`` is beyond
        the range of a float.
    """
    return _response(stages, Ts)(s)


# Taps of a long FIR are summed as blocks of _BLOCK-ish taps times a (points x block) matrix of
# powers of z^-1 (one BLAS product) instead of np.polyval's one NumPy call per tap: the same
# sum, ~10 ns per tap and point instead of ~1 us per tap.
_SHORT_FIR = 4096        # taps up to this: np.polyval (its loop costs less than the exponentials)
_POINT_BLOCK = 256       # points per block (bounds memory: points x sqrt(taps) complex)


def _fir_sum(taps: np.ndarray, log_zinv: np.ndarray) -> np.ndarray:
    """``sum_n taps[n] z^-n`` for ``log(z^-1) = log_zinv`` (1-D), each power ``z^-n`` computed
    directly as ``exp(n log z^-1)`` (no accumulated rounding over long filters)."""
    L = taps.size
    B = max(1, int(math.ceil(math.sqrt(L))))
    nb = -(-L // B)
    blocks = np.zeros(nb * B)
    blocks[:L] = taps
    blocks = blocks.reshape(nb, B).T                     # (B, nb): column j = taps[jB:(j+1)B]
    inner_n = np.arange(B, dtype=np.float64)
    outer_n = np.arange(nb, dtype=np.float64) * B
    out = np.empty(log_zinv.size, dtype=complex)
    for start in range(0, log_zinv.size, _POINT_BLOCK):
        lz = log_zinv[start:start + _POINT_BLOCK, None]
        V = np.exp(lz * inner_n)                         # (P, B) powers inside a block
        inner = V.real @ blocks + 1j * (V.imag @ blocks)  # (P, nb) block sums
        out[start:start + lz.shape[0]] = np.sum(inner * np.exp(lz * outer_n), axis=1)
    return out


class ChainResponse:
    """The transfer function ``s -> H(s)`` of a chain, with the discrete taps and notch
    coefficients computed once, for evaluating many points.

    Parameters
    ----------
    stages : Stage or sequence of Stage
        The chain, first stage first.
    Ts : float or None, keyword-only
        Sample period [s]: the discrete chain evaluated at ``z = e^{s Ts}``; None: the
        continuous filters.
    progress : callable or None, keyword-only
        Called as ``progress(work)`` after every block of evaluated points, with ``work`` =
        points in the block times :attr:`taps` (at least 1), so a caller can show how far a
        long evaluation has come.

    Raises
    ------
    ParameterError
        ``stages`` is not a stage list, ``Ts`` is not finite and > 0, or a stage is invalid
        at ``Ts``.

    Notes
    -----
    A FIR stage with taps ``h[n]`` contributes ``sum_n h[n] z^-n``; a notch its biquad
    ``B(z^-1) / A(z^-1)``. The cost of one call is about ``points * taps`` multiply-adds.
    """

    def __init__(self, stages, *, Ts: float | None = None, progress=None):
        self.stages = as_stage_list(stages)
        self.Ts = None if Ts is None else check_Ts(Ts)
        self.progress = progress
        self._polys = []          # (taps or numerator in powers of z^-1, denominator or None)
        if self.Ts is not None:       # the stages and Ts are checked: build, check no more
            self._polys = [coefficients_unchecked(stage, self.Ts) for stage in self.stages]
        #: Total number of FIR taps and biquad coefficients summed per point.
        self.taps = sum(p[0].size for p in self._polys)

    def __call__(self, s) -> np.ndarray:
        """``H(s)`` at complex ``s`` [1/s].

        Parameters
        ----------
        s : array_like of complex
            Laplace variable [1/s], any shape.

        Returns
        -------
        ndarray of complex128
            ``H(s)``, the shape of ``s``.

        Raises
        ------
        ParameterError
            Naming ``s`` when it is not finite numbers, or where ``H(s)`` is beyond the range
            of a float (NaN or inf, never returned).
        """
        return _representable("s", self._evaluate(_complex_array("s", s)), "H(s)")

    def _evaluate(self, s: np.ndarray) -> np.ndarray:
        """``H(s)`` at a checked complex array, unchecked result (overflow gives inf or NaN,
        without warnings: the callers refuse it naming their argument)."""
        with np.errstate(over="ignore", invalid="ignore", divide="ignore", under="ignore"):
            return self._evaluate_raw(s)

    def _evaluate_raw(self, s: np.ndarray) -> np.ndarray:
        if self.Ts is None:
            out = np.ones(s.shape, dtype=complex)
            for stage in self.stages:
                out *= transfer_unchecked(stage, s)
            return out
        flat = s.ravel()
        out = np.empty(flat.size, dtype=complex)
        for start in range(0, flat.size, _POINT_BLOCK):
            part = flat[start:start + _POINT_BLOCK]
            log_zinv = -part * self.Ts
            zinv = np.exp(log_zinv)
            h = np.ones(part.size, dtype=complex)
            for num, den in self._polys:
                if num.size > _SHORT_FIR:
                    h *= _fir_sum(num, log_zinv)
                else:
                    h *= np.polyval(num[::-1], zinv)
                if den is not None:
                    h /= np.polyval(den[::-1], zinv)
            out[start:start + part.size] = h
            if self.progress is not None:
                self.progress(max(1, part.size * self.taps))
        return out.reshape(s.shape)


def _response(stages, Ts) -> ChainResponse:
    """``stages`` itself when it already is a ChainResponse for ``Ts``, else a new one."""
    if isinstance(stages, ChainResponse):
        if Ts is not None and (stages.Ts is None or check_Ts(Ts) != stages.Ts):
            raise ParameterError("Ts", f"Ts = {Ts!r} differs from the ChainResponse's "
                                 f"Ts = {stages.Ts!r}")
        return stages
    return ChainResponse(stages, Ts=Ts)


def frequency_response(stages, w, *, Ts: float | None = None) -> np.ndarray:
    """Complex frequency response ``H(jw)`` of the chain.

    Parameters
    ----------
    stages : Stage, sequence of Stage or ChainResponse
        The chain, first stage first (a :class:`ChainResponse` reuses its taps).
    w : array_like of float
        Angular frequencies [rad/s], any shape, finite.
    Ts : float or None, keyword-only
        Sample period [s]: the discrete chain at ``z = e^{s Ts}``; None (default): the
        continuous filters.

    Returns
    -------
    ndarray of complex128
        ``H(j w)`` (discrete: ``H_d(e^{j w Ts})``), the shape of ``w``.

    Raises
    ------
    ParameterError
        An invalid stage or chain at ``Ts``, ``Ts`` not finite and > 0; ``w`` not real or not
        finite (``parameter == "w"``).
    """
    return _frequency_response(stages, _frequencies(w), Ts)


def _frequencies(w) -> np.ndarray:
    w = _real_array("w", w)
    if not np.all(np.isfinite(w)):
        raise ParameterError("w", "w must be finite")
    return w


def _frequency_response(stages, w: np.ndarray, Ts) -> np.ndarray:
    """:func:`frequency_response` at checked frequencies."""
    return _representable("w", _response(stages, Ts)._evaluate(1j * w), "H(jw)")


def mode_poles(wn, zeta) -> np.ndarray:
    """Poles ``p = -zeta wn + j wn sqrt(1 - zeta^2)`` of lightly damped modes.

    Parameters
    ----------
    wn : array_like of float
        Natural frequencies [rad/s], finite and > 0.
    zeta : array_like of float
        Damping ratios in [0, 1); broadcast against ``wn``.

    Returns
    -------
    ndarray of complex128
        The upper-half-plane pole of each mode [1/s], the broadcast shape.

    Raises
    ------
    ParameterError
        Naming ``wn`` or ``zeta`` when a value is outside its range, complex or not numeric.
    """
    return _poles(_real_array("wn", wn), _real_array("zeta", zeta))


def _poles(wn: np.ndarray, zeta: np.ndarray) -> np.ndarray:
    """:func:`mode_poles` of real arrays: their ranges checked, the poles."""
    if not np.all(np.isfinite(wn)) or np.any(wn <= 0):
        raise ParameterError("wn", "wn must be finite and > 0 rad/s")
    if not np.all(np.isfinite(zeta)) or np.any(zeta < 0) or np.any(zeta >= 1):
        raise ParameterError("zeta", "zeta must be in [0, 1)")
    return -zeta * wn + 1j * wn * np.sqrt(1.0 - zeta * zeta)


def residual_vibration(stages, *, wn, zeta=0.0, Ts: float | None = None) -> np.ndarray:
    """Residual vibration ``|H(p)|`` of the modes ``(wn, zeta)`` after the chain.

    The amplitude of the oscillation a filtered unit step leaves on the mode, divided by the
    unfiltered step's (Biagiotti, Melchiorri and Moriello, "Damped Harmonic Smoother for
    Trajectory Planning and Vibration Suppression", 2020, footnote 2; docs/analysis.md). Discrete:
    ``|H_d(e^{p Ts})|``, the command held by a zero-order hold.

    Parameters
    ----------
    stages : Stage, sequence of Stage or ChainResponse
        The chain, first stage first (a :class:`ChainResponse` reuses its taps).
    wn : array_like of float, keyword-only
        Natural frequencies [rad/s], > 0.
    zeta : array_like of float, keyword-only
        Damping ratios in [0, 1) (default 0), broadcast against ``wn``.
    Ts : float or None, keyword-only
        Sample period [s]: the discrete chain at ``z = e^{s Ts}``; None (default): the
        continuous filters.

    Returns
    -------
    ndarray of float64
        ``|H(p)|`` (1 = no reduction), the broadcast shape of ``wn`` and ``zeta``.

    Raises
    ------
    ParameterError
        An invalid stage or chain at ``Ts``, ``Ts`` not finite and > 0; ``wn`` or ``zeta`` out of
        range.
    """
    return _residual(stages, mode_poles(wn, zeta), Ts)


def _residual(stages, p: np.ndarray, Ts) -> np.ndarray:
    """:func:`residual_vibration` at checked poles."""
    H = _response(stages, Ts)
    return _representable("wn", np.abs(H._evaluate(p)), "the residual |H(p)| of the mode")


def prv(stages, *, wn, zeta=0.0, Ts: float | None = None) -> np.ndarray:
    """Percent residual vibration ``100 |H(p)|`` (see :func:`residual_vibration`).

    Parameters
    ----------
    stages : Stage, sequence of Stage or ChainResponse
        The chain, first stage first (a :class:`ChainResponse` reuses its taps).
    wn : array_like of float, keyword-only
        Natural frequencies [rad/s], > 0.
    zeta : array_like of float, keyword-only
        Damping ratios in [0, 1) (default 0).
    Ts : float or None, keyword-only
        Sample period [s]: the discrete chain at ``z = e^{s Ts}``; None (default): the
        continuous filters.

    Returns
    -------
    ndarray of float64
        PRV [%], the broadcast shape of ``wn`` and ``zeta``.

    Raises
    ------
    ParameterError
        An invalid stage or chain at ``Ts``, ``Ts`` not finite and > 0; ``wn`` or ``zeta`` out of
        range.
    """
    return 100.0 * residual_vibration(stages, wn=wn, zeta=zeta, Ts=Ts)


def prv_curve(stages, *, wn_hat: float, ratio, zeta=0.0, Ts: float | None = None) -> np.ndarray:
    """PRV [%] at ``wn = ratio * wn_hat``: the insensitivity curve of a chain designed for
    ``wn_hat`` (Biagiotti, Melchiorri and Moriello, "Damped Harmonic Smoother for Trajectory
    Planning and Vibration Suppression", 2020, Fig. 4).

    Parameters
    ----------
    stages : Stage, sequence of Stage or ChainResponse
        The chain, first stage first (a :class:`ChainResponse` reuses its taps).
    wn_hat : float, keyword-only
        Nominal natural frequency [rad/s], > 0.
    ratio : array_like of float, keyword-only
        Actual-to-nominal frequency ratios (> 0), any shape.
    zeta : array_like of float, keyword-only
        Damping ratio of the actual mode, in [0, 1) (default 0).
    Ts : float or None, keyword-only
        Sample period [s]: the discrete chain at ``z = e^{s Ts}``; None (default): the
        continuous filters.

    Returns
    -------
    ndarray of float64
        PRV [%], the shape of ``ratio``.

    Raises
    ------
    ParameterError
        An invalid stage or chain at ``Ts``, ``Ts`` not finite and > 0; ``wn_hat`` not > 0,
        ``ratio`` or ``zeta`` out of range.
    """
    wn_hat = _positive("wn_hat", wn_hat)
    ratio = _real_array("ratio", ratio)
    if not np.all(np.isfinite(ratio) & (ratio > 0)):
        raise ParameterError("ratio", "ratio must be finite and > 0")
    with np.errstate(over="ignore", under="ignore"):
        wn = ratio * wn_hat
    if not np.all(np.isfinite(wn) & (wn > 0)):
        raise ParameterError("wn_hat", f"wn_hat = {wn_hat!r} rad/s: ratio * wn_hat is beyond the "
                             "range of a float")
    return prv(stages, wn=wn, zeta=zeta, Ts=Ts)


def prv_surface(stages, *, wn, zeta, Ts: float | None = None) -> np.ndarray:
    """PRV [%] on the grid ``zeta x wn``.

    Parameters
    ----------
    stages : Stage, sequence of Stage or ChainResponse
        The chain, first stage first (a :class:`ChainResponse` reuses its taps).
    wn : array_like of float, keyword-only
        Natural frequencies [rad/s], > 0, 1-D (a scalar counts as one).
    zeta : array_like of float, keyword-only
        Damping ratios in [0, 1), 1-D.
    Ts : float or None, keyword-only
        Sample period [s]: the discrete chain at ``z = e^{s Ts}``; None (default): the
        continuous filters.

    Returns
    -------
    ndarray of float64, shape (len(zeta), len(wn))
        ``result[i, j]`` is the PRV at ``(zeta[i], wn[j])``.

    Raises
    ------
    ParameterError
        An invalid stage or chain at ``Ts``, ``Ts`` not finite and > 0; ``wn`` or ``zeta`` out of
        range.
    """
    wn = np.atleast_1d(_real_array("wn", wn))
    zeta = np.atleast_1d(_real_array("zeta", zeta))
    for name, v in (("wn", wn), ("zeta", zeta)):
        if v.ndim != 1:
            raise ParameterError(name, f"{name} must be a number or one-dimensional, got shape "
                                 f"{v.shape}")
    return 100.0 * _residual(stages, _poles(wn[None, :], zeta[:, None]), Ts)


@dataclass(frozen=True)
class Insensitivity:
    """Band of natural frequencies around ``wn_hat`` where the PRV stays at or below the
    tolerance (:func:`insensitivity`).

    Attributes
    ----------
    low, high : float
        Band edges [rad/s].
    width : float
        ``high - low`` [rad/s].
    relative_width : float
        ``width / wn_hat``, the nondimensional insensitivity of Singhose, Seering and
        Singer, "Residual vibration reduction using vector diagrams to generate shaped
        inputs", 1994.
    """
    low: float
    high: float
    width: float
    relative_width: float


def insensitivity(stages, *, wn_hat: float, zeta: float = 0.0, tolerance: float = 0.05,
                  Ts: float | None = None, span=(0.05, 4.0), points: int = 8001) -> Insensitivity:
    """The connected band of ``wn`` containing ``wn_hat`` where ``residual <= tolerance``.

    Searched on ``points`` ratios ``wn/wn_hat`` spanning ``span``, the edges refined by
    bisection (Brent) to 1e-12 in the ratio. ``tolerance`` gets a relative slack of 1e-9 so
    that a design whose residual at ``wn_hat`` equals the tolerance by construction (EI) counts
    as inside. The damping ``zeta`` is held fixed.

    Parameters
    ----------
    stages : Stage, sequence of Stage or ChainResponse
        The chain, first stage first (a :class:`ChainResponse` reuses its taps).
    wn_hat : float, keyword-only
        Nominal natural frequency [rad/s], > 0.
    zeta : float, keyword-only
        Damping ratio of the mode, in [0, 1) (default 0).
    tolerance : float, keyword-only
        Accepted residual vibration as a fraction, in (0, 1) (default 0.05 = 5 %).
    Ts : float or None, keyword-only
        Sample period [s]: the discrete chain at ``z = e^{s Ts}``; None (default): the
        continuous filters.
    span : (float, float), keyword-only
        Ratios ``wn/wn_hat`` searched, ``0 < span[0] < 1 < span[1]`` (default (0.05, 4)).
    points : int, keyword-only
        Grid points of the search (default 8001).

    Returns
    -------
    Insensitivity
        The band; width 0 (``low == high == wn_hat``) when the residual at ``wn_hat``
        exceeds the tolerance.

    Raises
    ------
    ParameterError
        ``wn_hat``, ``tolerance`` or ``span`` out of range, or ``span`` too narrow (the band
        reaches its edge); an invalid chain or ``Ts``.
    """
    from scipy.optimize import brentq

    wn_hat = _positive("wn_hat", wn_hat)
    tolerance = _finite("tolerance", tolerance)
    if not 0 < tolerance < 1:
        raise ParameterError("tolerance", f"tolerance must be in (0, 1), got {tolerance!r}")
    span_v = _real_array("span", span, ndim=1)
    if span_v.size != 2 or not 0 < span_v[0] < 1 < span_v[1]:
        raise ParameterError("span", "span must be two numbers with 0 < span[0] < 1 < span[1], "
                             f"got {span_v.tolist()}")
    lo_r, hi_r = float(span_v[0]), float(span_v[1])
    if not math.isfinite(hi_r * wn_hat):
        raise ParameterError("wn_hat", f"wn_hat = {wn_hat!r} rad/s: span[1] * wn_hat is beyond "
                             "the range of a float")
    points = _check_samples("points", _integer("points", points, 3), "the grid of ratios")
    limit = tolerance * (1 + 1e-9)

    H = _response(stages, Ts)
    zeta = _real_array("zeta", zeta)

    def excess(r):      # the grid's poles (its range checked), H(s) at them refused if not finite
        p = _poles(np.asarray(r) * wn_hat, zeta)
        return np.abs(_representable("s", H._evaluate(p), "H(s)")) - limit

    if excess(1.0) > 0:
        return Insensitivity(wn_hat, wn_hat, 0.0, 0.0)
    r = np.linspace(lo_r, hi_r, points)
    inside = excess(r) <= 0
    j = int(np.argmin(np.abs(r - 1.0)))
    if not inside[j]:                       # the grid point missed a narrow band: use 1.0
        r, inside = np.insert(r, j, 1.0), np.insert(inside, j, True)
    lo = j
    while lo > 0 and inside[lo - 1]:
        lo -= 1
    hi = j
    while hi < r.size - 1 and inside[hi + 1]:
        hi += 1
    if lo == 0 or hi == r.size - 1:
        raise ParameterError("span", f"span {span!r} is too narrow: the band reaches its edge")
    left = brentq(lambda x: float(excess(x)), r[lo - 1], r[lo], xtol=1e-12)
    right = brentq(lambda x: float(excess(x)), r[hi], r[hi + 1], xtol=1e-12)
    return Insensitivity(left * wn_hat, right * wn_hat, (right - left) * wn_hat, right - left)


def step_spectrum(stages, w, *, h: float = 1.0, derivative: int = 1,
                  Ts: float | None = None) -> np.ndarray:
    """Fourier transform of the ``derivative``-th time derivative of the chain's step response.

    Continuous: ``h (jw)^(d-1) H(jw)``; discrete (``Ts`` given): the d-th backward difference
    over Ts of the sampled response, times Ts, ``h ((1 - e^{-jw Ts})/Ts)^(d-1)
    H_d(e^{jw Ts})``: the spectra of Biagiotti and Melchiorri, "Online Planning of
    Multi-Segment Trajectories with Trigonometric Blends", 2011, Fig. 10b and 13.

    Parameters
    ----------
    stages : Stage, sequence of Stage or ChainResponse
        The chain, first stage first (a :class:`ChainResponse` reuses its taps).
    w : array_like of float
        Angular frequencies [rad/s], any shape.
    h : float, keyword-only
        Step height (default 1) [units of position].
    derivative : int, keyword-only
        Order d >= 1 of the derivative (1: velocity, 2: acceleration, ...).
    Ts : float or None, keyword-only
        Sample period [s]: the discrete chain at ``z = e^{s Ts}``; None (default): the
        continuous filters.

    Returns
    -------
    ndarray of complex128
        The spectrum [position units / s^(d-1)], the shape of ``w``.

    Raises
    ------
    ParameterError
        An invalid stage or chain at ``Ts``, ``Ts`` not finite and > 0; ``derivative`` not an
        integer >= 1, ``w`` not finite.
    """
    derivative = _integer("derivative", derivative, 1)
    h = _finite("h", h)
    w = _frequencies(w)
    H = _frequency_response(stages, w, Ts)
    with np.errstate(over="ignore", invalid="ignore", under="ignore"):
        if Ts is None:
            d = 1j * w
        else:
            d = (1 - np.exp(-1j * w * Ts)) / Ts
        try:
            dk = d ** (int(derivative) - 1)
        except OverflowError:     # an exponent beyond a float
            dk = np.full(np.shape(d), np.inf, dtype=complex)
        _representable("derivative", dk, "the derivative's factor (jw)^(derivative - 1)")
        return _representable("h", h * dk * H, "the spectrum")


def signal_spectrum(x, *, Ts: float) -> tuple[np.ndarray, np.ndarray]:
    """Sampled approximation of the continuous Fourier transform of a signal.

    ``X(w) = Ts * sum_n x[n] e^{-j w n Ts}`` on the rfft grid.

    Parameters
    ----------
    x : array_like of float, shape (n,)
        Samples, finite.
    Ts : float, keyword-only
        Sample period [s], > 0.

    Returns
    -------
    w : ndarray of float64, shape (n // 2 + 1,)
        Angular frequencies [rad/s].
    X : ndarray of complex128, shape (n // 2 + 1,)
        The transform [units of x times s].

    Raises
    ------
    ParameterError
        ``Ts`` not finite and > 0, or ``x`` not a finite real 1-D signal.
    """
    Ts = check_Ts(Ts)
    x = _finite_signal("x", x)
    if x.size == 0:
        raise ParameterError("x", "x must hold at least one sample")
    with np.errstate(over="ignore", invalid="ignore", under="ignore"):
        X = _representable("x", np.fft.rfft(x), "the DFT of x")
        X = _representable("Ts", Ts * X, "Ts times the DFT of x")
        w = _representable("Ts", 2 * math.pi * np.fft.rfftfreq(x.size, Ts),
                           "the frequency grid 2 pi k / (n Ts)")
    return w, X
