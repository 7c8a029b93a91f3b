# SPDX-License-Identifier: Apache-2.0
"""Remaining vibration: what a filter leaves of the measured vibration, two ways.

A filter of length L with transfer H leaves, of a mode with pole p = -zeta wn + j wn
sqrt(1 - zeta^2), the fraction R = e^{-zeta wn L} |H(p)| of the vibration an unfiltered move
excites, each measured from the end of its own move (the percent residual vibration of N. C.
Singer and W. P. Seering, "Preshaping command inputs to reduce system vibration", ASME J. Dyn.
Sys. Meas. Control 112 (1990) 76-82, their eq. for V; for a discrete filter with taps h at Ts,
H(p) = sum_k h_k e^{-p k Ts}; ``analysis.residual_vibration`` refers both to t = 0 instead,
which leaves out the factor e^{-zeta wn L}). Two figures, in %:

* **measured spectrum** (:class:`SpectralObjective`): every bin of the measured PSD is taken
  as a mode at its frequency, and the figure is what the filter leaves of the PSD standing
  above a twentieth of its peak, for the worst damping ratio of a band: the established 3-D
  printer tool's estimate (Klipper's ``_estimate_remaining_vibrations``, D. Butyugin), here for
  our exact filters and over a damping band the modal fit sharpens. It holds whatever the
  spectrum holds, modal or not.
* **modal fit** (:class:`ModalObjective`): the identified modes, each weighted by its energy
  and averaged over its uncertainty, ``V = sqrt(sum_i w_i E[R_i^2] / sum_i w_i)``.

Each objective states a +-3 sd range: the modal one with every mode anywhere in its +-3 sd disc
of (wn, zeta) (the joint 3 sd region of the two) and its weight within +-3 sd; the spectral one about the same quantity,
with every bin of the vibration content a mode anywhere within the half-power width of its
frequency and over the damping band (wide: the spectrum alone does not pin the modes).
"""
from __future__ import annotations

import itertools
import math

import numpy as np

from .design_memo import impulses, smoother_R
from ..reference.continuous import transfer_unchecked
from ..stages import INPUT_SMOOTHERS, SHAPERS

__all__ = ["BOX", "pole", "ModalObjective", "SpectralObjective", "WorstOf", "taps_R2", "stages_R2"]

#: Half-width of the uncertainty box, in standard deviations, for the stated range.
BOX = 3.0
_GH_WN = np.polynomial.hermite_e.hermegauss(5)
_GH_Z = np.polynomial.hermite_e.hermegauss(3)
#: Points of a mode's +-3 sd disc in (wn, zeta), in standard deviations: the inside (the
#: centre and rings at 0.75, 1.5 and 2.25 sd), then the rim at 3 sd (32 points: a residual
#: linear in the two is under-read there by at most 1 - cos(5.6 deg) = 0.5 %).
DISC_INSIDE = [(0.0, 0.0)] + [(r * math.cos(a), r * math.sin(a)) for r, k in
                              ((0.75, 8), (1.5, 12), (2.25, 16))
                              for a in np.arange(k) * (2 * math.pi / k)]
DISC_RIM = [(BOX * math.cos(a), BOX * math.sin(a)) for a in np.arange(32) * (2 * math.pi / 32)]
DISC = DISC_INSIDE + DISC_RIM
#: Most frequency groups the spectral objective keeps (adjacent bins merged by energy).
MAX_GROUPS = 120


def pole(wn, zeta):
    wn = np.asarray(wn, dtype=float)
    zeta = np.clip(np.asarray(zeta, dtype=float), 0.0, 0.99)
    return -zeta * wn + 1j * wn * np.sqrt(1 - zeta * zeta)


def taps_R2(h: np.ndarray, Ts: float, poles: np.ndarray) -> np.ndarray:
    """|H(p)|^2 of discrete taps h at the poles."""
    poles = np.asarray(poles).ravel()
    k = np.flatnonzero(h)
    if k.size * 4 < h.size or k.size < 16:   # sparse (shapers): the powers directly
        z = np.exp(-np.outer(poles, k) * Ts)
        return np.abs(z @ h[k]) ** 2
    if poles.size > 1000:
        # dense (smoothers), many poles: Horner's rule in z^-1 = e^{-p Ts}, one tap at a time
        zinv = np.exp(-poles * Ts)
        acc = np.zeros(poles.size, dtype=complex)
        for c in h[::-1]:
            acc = acc * zinv + c
        return np.abs(acc) ** 2
    # dense (smoothers), few poles: blocks of B taps, sum_k h_k z^-k = sum_a z^-aB sum_b h_aB+b z^-b with
    # z^-1 = e^{-p Ts}: the inner sums one matrix product, Horner's rule over the blocks (a
    # tap at a time over all poles cost a NumPy call per tap: 1650 for a 0.165 s smoother)
    B = 32
    nb = -(-h.size // B)
    hb = np.zeros(nb * B)
    hb[: h.size] = h
    E = np.exp(-np.outer(poles, np.arange(B)) * Ts)
    M = np.ascontiguousarray(hb.reshape(nb, B).T)
    # (poles, nb), real products in einsum's own loops: BLAS's threads spin for products this
    # small (a complex-by-real matrix product cost ten times the CPU time of the sum itself)
    inner = np.einsum("pb,bn->pn", E.real, M) + 1j * np.einsum("pb,bn->pn", E.imag, M)
    zB = np.exp(-poles * (B * Ts))
    acc = np.zeros(poles.size, dtype=complex)
    for a in range(nb - 1, -1, -1):
        acc = acc * zB + inner[:, a]
    return np.abs(acc) ** 2


def stages_R2(stages, poles: np.ndarray) -> np.ndarray:
    """|H(p)|^2 of the continuous designs (the tuning loop: within O((wn Ts)^2) of the
    discrete filter, which the reported figures use)."""
    H = None
    for s in stages:
        if s.kind in SHAPERS:
            A, t = impulses(s)
            Hs = np.exp(-np.outer(poles, t)) @ A
        elif s.kind in INPUT_SMOOTHERS:
            Hs = smoother_R(s, poles)
        else:
            Hs = transfer_unchecked(s, poles)
        # the first stage's H itself, not 1 times it: the product's real and imaginary parts
        # are the factor's own floats (only a zero's sign could differ, which |H| drops)
        H = Hs if H is None else H * Hs
    if H is None:
        return np.ones(np.size(poles))
    return np.abs(H) ** 2


def impulses_R2(A, t, poles: np.ndarray) -> np.ndarray:
    """|sum A_i e^{-p t_i}|^2 / (sum A)^2: a firmware shaper defined by its impulses."""
    A = np.asarray(A, dtype=float)
    z = np.exp(-np.outer(poles, np.asarray(t, dtype=float)))
    return np.abs(z @ A) ** 2 / float(A.sum()) ** 2


def _from_end(R2, poles, L):
    """|H(p)|^2 referred to the end of a filter of length L: times e^{-2 zeta wn L}."""
    return R2 * np.exp(2.0 * np.real(poles) * L) if L else R2


class _PoleSet:
    """A weighted set of poles: the figure is 100 sqrt(sum w R^2)."""
    kind = ""

    def value(self, R2: np.ndarray, L: float = 0.0) -> float:
        return 100.0 * math.sqrt(max(float(self.w @ _from_end(R2, self.poles, L)), 0.0))

    def tuning_value(self, R2: np.ndarray, L: float = 0.0) -> float:
        return self.value(R2, L)

    def tuning_values(self, R2: np.ndarray, L: np.ndarray) -> np.ndarray:
        """:meth:`tuning_value` of many designs at once: ``R2`` (poles, designs), ``L``
        (designs,) [s]."""
        R2e = R2 * np.exp(2.0 * np.real(self.poles)[:, None] * np.asarray(L, float)[None, :])
        return 100.0 * np.sqrt(np.maximum(self.w @ R2e, 0.0))


class ModalObjective(_PoleSet):
    """Remaining vibration over identified modes (Gauss-Hermite nodes over each mode's
    uncertainty); ``range`` over their +-3 sd discs in (wn, zeta) (:data:`DISC`) and their
    weights within +-3 sd, widened to hold the value."""
    kind = "modal fit"

    def __init__(self, modes):
        w = np.array([m.weight for m in modes], dtype=float)
        self.mode_w = w / w.sum()
        self.mode_wsd = np.array([getattr(m, "weight_rsd", 0.0) for m in modes])
        poles, gw = [], []
        for i, m in enumerate(modes):
            for xw, ww in zip(*_GH_WN):
                for xz, wz in zip(*_GH_Z):
                    poles.append(complex(pole(max(m.wn + xw * m.wn_std, 1e-9),
                                              min(max(m.zeta + xz * m.zeta_std, 0.0), 0.99))))
                    gw.append(self.mode_w[i] * ww * wz / (2 * math.pi))
        self.poles, self.w = np.array(poles), np.array(gw)
        self.nominal = np.array([complex(pole(m.wn, m.zeta)) for m in modes])
        # each mode's (wn, zeta) anywhere in its +-3 sd disc: the joint 3 sd region of two
        # independent estimates, whose projection on any linear function of them is that
        # function's +-3 sd (the box of +-3 sd in each reaches 4.2 sd at its corners)
        box = []
        for m in modes:
            for u, v in DISC:
                box.append(complex(pole(max(m.wn + u * m.wn_std, 1e-9),
                                        min(max(m.zeta + v * m.zeta_std, 0.0), 0.99))))
        self.n_disc = len(box)
        # the value's own nodes follow the disc: the range is widened to hold the value it is
        # stated with (a mean over the uncertainty lies within its extremes but a node of the
        # quadrature may lie outside the disc: 2.86 sd in wn with 1.73 sd in zeta)
        box += poles
        self.box = np.array(box)
        self.n = len(modes)

    def nominal_value(self, R2_nominal, L: float = 0.0) -> float:
        return 100.0 * math.sqrt(float(self.mode_w @ _from_end(R2_nominal, self.nominal, L)))

    def range(self, R2_box, L: float = 0.0) -> tuple[float, float]:
        R2_box = _from_end(R2_box, self.box, L)
        disc, nodes = R2_box[: self.n_disc], R2_box[self.n_disc:]
        per_mode = disc.reshape(self.n, len(DISC))
        hi = per_mode.max(axis=1)
        # R = |H(p) e^{pL}| is the modulus of a function analytic in the pole p, and the disc
        # maps onto a region of the p plane with the rim as its edge: by the minimum modulus
        # principle R is least on the rim unless H has a zero inside. A point inside below
        # every point of the rim shows such a zero, and then the least is 0 (the grid's least
        # inside was the grid's, not the residual's: a campaign's pick left 0.009 % where the
        # grid's least was 0.0185 %)
        inside, rim = per_mode[:, : len(DISC_INSIDE)], per_mode[:, len(DISC_INSIDE):]
        lo = np.where(inside.min(axis=1) < rim.min(axis=1), 0.0, rim.min(axis=1))
        # weights anywhere in +-3 sd (relative): the extreme ratios sit at the box's corners
        w0 = self.mode_w
        spread = np.minimum(BOX * self.mode_wsd, 0.95)
        best, worst = math.inf, 0.0
        corners = itertools.product(*[(-1.0, 1.0)] * self.n) if self.n <= 6 else [np.zeros(self.n)]
        for c in corners:
            w = w0 * np.exp(np.asarray(c) * spread)
            w = w / w.sum()
            best = min(best, float(w @ lo))
            worst = max(worst, float(w @ hi))
        value = max(float(self.w @ nodes), 0.0)
        return (100 * math.sqrt(max(min(best, value), 0.0)),
                100 * math.sqrt(max(worst, value)))


class SpectralObjective(_PoleSet):
    """Remaining vibration over a measured PSD ``P`` on bins ``f`` [Hz] in the band: the
    established tool's estimate, ``max over zeta of sum_f max(R(f, zeta) P(f) - tau, 0) /
    sum_f max(P(f) - tau, 0)`` with ``tau = max(P) / 20`` (a shaper cannot take a vibration
    below a twentieth of the largest one further down), over the damping ratios ``zetas``.

    Its ``range`` is about the plant's remaining vibration (the modal quantity): every bin of
    the vibration content ``max(P - tau, 0)`` taken as a mode anywhere within ``width``
    (relative half-power half-width) of its frequency and over the damping band, energy
    weighted."""
    kind = "measured spectrum"

    def __init__(self, f, P, zetas, width=None, threshold: float = 20.0, group_hz=None):
        f = np.asarray(f, dtype=float)
        P = np.asarray(P, dtype=float)
        width = np.full(f.size, 0.08) if width is None else np.asarray(width, float)
        if group_hz and f.size > 1 and np.median(np.diff(f)) < group_hz:
            # merge neighbouring bins (power kept) to about group_hz: finer bins change the
            # figure by nothing a filter can act on, and cost
            m = max(1, int(round(group_hz / float(np.median(np.diff(f))))))
            n = f.size // m
            if n >= 8:
                f = f[: n * m].reshape(n, m).mean(axis=1)
                P = P[: n * m].reshape(n, m).mean(axis=1)
                width = width[: n * m].reshape(n, m).mean(axis=1)
        tau = float(P.max()) / threshold
        self.tau = tau
        self.den = float(np.sum(np.maximum(P - tau, 0.0)))
        # a bin under the floor adds nothing (R <= 1 for filters of positive taps): only the
        # bins above it are scored
        above = P > tau
        self.zetas = np.unique(np.clip(np.asarray(zetas, dtype=float), 0.002, 0.9))
        wn = 2 * math.pi * f[above]
        self.f, self.P = f[above], P[above]
        self.poles = pole(wn[:, None], self.zetas[None, :]).ravel()
        self.n, self.nz = self.f.size, self.zetas.size
        self.tune_S = np.maximum(self.P - tau, 0.0) / max(self.den, 1e-300)
        # the range: the vibration content down to a thousandth of the peak (every mode the
        # plant has, not only those above the figure's floor), each bin a mode anywhere within
        # its half-power width, over any damping from 0.002 to the band's highest
        keep = P > float(P.max()) / 1000.0
        S = P[keep] - float(P.max()) / 1000.0
        self.S = S / S.sum()
        wr = 2 * math.pi * f[keep]
        offs = np.linspace(-1.0, 1.0, 5)
        # the nominal damping (the estimate's) is a node, so the range holds the estimate
        zb = np.array([0.002, float(np.median(self.zetas)), self.zetas.max()])
        grid = wr[:, None, None] * (1 + offs[None, :, None] * width[keep][:, None, None])
        grid = np.broadcast_to(grid, (wr.size, offs.size, zb.size))
        self.box = pole(grid, np.broadcast_to(zb[None, None, :], grid.shape)).reshape(wr.size, -1)
        self.nominal = pole(wr, np.median(self.zetas))
        self.n_range = wr.size

    def value(self, R2, L: float = 0.0) -> float:
        R = np.sqrt(np.maximum(_from_end(R2, self.poles, L), 0.0)).reshape(self.n, self.nz)
        left = np.maximum(R * self.P[:, None] - self.tau, 0.0).sum(axis=0)
        return 100.0 * float(left.max()) / self.den if self.den > 0 else 0.0

    def tuning_value(self, R2, L: float = 0.0) -> float:
        """:meth:`value` plus a thousandth of the energy-weighted RMS of R over the same bins [%]:
        the figure is flat (zero) wherever every residual lies under its floor, and there the
        tuning should still go on to the design with the most margin.

        ``R2`` is a squared magnitude (>= 0 or NaN), so its square root needs no clip; the
        pole factors and the bins' column come from :meth:`_tuning_terms` (the same floats as
        :func:`_from_end` and ``P[:, None]``: the tuning asks thousands of times)."""
        twice_re, P_col = self._tuning_terms()
        R2e = (R2 * np.exp(twice_re * L) if L else R2).reshape(self.n, self.nz)
        left = np.maximum(np.sqrt(R2e) * P_col - self.tau, 0.0).sum(axis=0)
        v = 100.0 * float(left.max()) / self.den if self.den > 0 else 0.0
        # sum / count is what ndarray.mean computes (the same floats), without its wrapper
        mean = R2e.sum(axis=1) / self.nz
        return v + 0.1 * math.sqrt(max(float(self.tune_S @ mean), 0.0))

    def _tuning_terms(self):
        """(2 Re(poles), P as a column), computed once for the poles and bins the objective
        holds now (again if either array is replaced)."""
        memo = self.__dict__.get("_terms")
        if memo is None or memo[0] is not self.poles or memo[1] is not self.P:
            memo = (self.poles, self.P, 2.0 * np.real(self.poles), self.P[:, None])
            self._terms = memo
        return memo[2], memo[3]

    def tuning_values(self, R2: np.ndarray, L: np.ndarray) -> np.ndarray:
        """:meth:`tuning_value` of many designs at once (the tuning's grid: one matrix
        evaluation instead of a call per design): ``R2`` (poles, designs), ``L`` (designs,)
        [s]."""
        G = R2.shape[1]
        twice_re, P_col = self._tuning_terms()
        R2e = (R2 * np.exp(twice_re[:, None] * np.asarray(L, float)[None, :])
               ).reshape(self.n, self.nz, G)
        # squared magnitudes (>= 0 or NaN): no clip before the root, as in tuning_value
        left = np.maximum(np.sqrt(R2e) * P_col[:, :, None] - self.tau, 0.0).sum(axis=0)  # (nz, G)
        v = 100.0 * left.max(axis=0) / self.den if self.den > 0 else np.zeros(G)
        mean = R2e.sum(axis=1) / self.nz                                          # (n, G)
        return v + 0.1 * np.sqrt(np.maximum(self.tune_S @ mean, 0.0))

    def nominal_value(self, R2_nominal, L: float = 0.0) -> float:
        return 100.0 * math.sqrt(float(self.S @ _from_end(R2_nominal, self.nominal, L)))

    def range(self, R2_box, L: float = 0.0) -> tuple[float, float]:
        R = _from_end(R2_box, self.box.ravel(), L).reshape(self.n_range, -1)
        return (100 * math.sqrt(float(self.S @ R.min(axis=1))),
                100 * math.sqrt(float(self.S @ R.max(axis=1))))


class WorstOf:
    """The measured-spectrum figure over several data sets of one axis (a test at several
    points of the bed, Klipper's tables of several data sets): each data set scored on its own
    (its own floor, a twentieth of its own peak, and its own total), the figure the worst of
    them, as the established tool combines its data sets (``fit_shaper``: the largest remaining
    vibration over the data sets and the test dampings), not the figure of their sum, in which
    the loudest data set would hide what a shaper leaves of a quieter one.

    ``parts``: one :class:`SpectralObjective` per data set. The poles are the parts' poles one
    after the other (an ``R2`` is sliced into them); the range and the plant estimate are the
    worst part's too (the largest lower and upper bounds)."""
    kind = SpectralObjective.kind

    def __init__(self, parts):
        self.parts = list(parts)
        if not self.parts:
            raise ValueError("parts: at least one data set")

        def cut(arrays):
            sizes = [a.size for a in arrays]
            edges = np.concatenate([[0], np.cumsum(sizes)])
            return np.concatenate(arrays), [slice(int(a), int(b)) for a, b in
                                            zip(edges[:-1], edges[1:])]

        self.poles, self._p = cut([np.asarray(p.poles).ravel() for p in self.parts])
        self.box, self._b = cut([np.asarray(p.box).ravel() for p in self.parts])
        self.nominal, self._n = cut([np.asarray(p.nominal).ravel() for p in self.parts])
        self.zetas = self.parts[0].zetas

    def value(self, R2, L: float = 0.0) -> float:
        return max(p.value(R2[s], L) for p, s in zip(self.parts, self._p))

    def values(self, R2, L) -> np.ndarray:
        """:meth:`value` of many designs: ``R2`` (poles, designs), ``L`` (designs,) [s]."""
        L = np.asarray(L, float)
        return np.array([self.value(R2[:, i], float(L[i])) for i in range(L.size)])

    def tuning_value(self, R2, L: float = 0.0) -> float:
        return max(p.tuning_value(R2[s], L) for p, s in zip(self.parts, self._p))

    def tuning_values(self, R2, L) -> np.ndarray:
        return np.max([p.tuning_values(R2[s], L) for p, s in zip(self.parts, self._p)], axis=0)

    def nominal_value(self, R2_nominal, L: float = 0.0) -> float:
        return max(p.nominal_value(R2_nominal[s], L) for p, s in zip(self.parts, self._n))

    def range(self, R2_box, L: float = 0.0) -> tuple[float, float]:
        r = [p.range(R2_box[s], L) for p, s in zip(self.parts, self._b)]
        return max(a for a, _ in r), max(b for _, b in r)
