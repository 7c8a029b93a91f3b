# SPDX-License-Identifier: Apache-2.0
"""Clipped accelerometer samples: finding them, and reconstructing them from their neighbours.

A sensor driven past its range (an ADXL345 at +-16 g on a strong resonance) holds its extreme
value for a few samples of every cycle. Those samples are no measurement, but cutting them out
leaves no contiguous stretch around the resonance: every window there holds clipped cycles, so
the spectrum would lose exactly the resonance. Their values are therefore excluded and
reconstructed: within a few periods around each clipped run, the unclipped samples are fitted
by least squares with a constant and a sinusoid at the local oscillation's frequency, which
comes from the zero crossings (clipping moves no zero crossing), and the run takes the
fit's values, kept beyond the rail it sat on (the true signal was at least there). This is the
periodic-signal case of reconstructing missing samples from a signal model (A. J. E. M.
Janssen, R. N. J. Veldhuis, L. B. Vries, "Adaptive interpolation of discrete-time signals that
can be modeled as autoregressive processes", IEEE Trans. ASSP 34 (1986) 317-330).
"""
from __future__ import annotations

import numpy as np

__all__ = ["clipped_samples", "reconstruct"]

#: Harmonics of the local oscillation the reconstruction fits: one (with more, the fit to the
#: unclipped flanks alone is free to flatten its own top again).
HARMONICS = 1


def clipped_samples(x: np.ndarray) -> tuple[np.ndarray, list[int]]:
    """(mask (n, k): samples sitting on a rail, columns clipped): a column's extreme value held in
    runs, with more samples on it than on the whole next 2 % of the range (a quantised but
    unclipped signal thins out towards its extremes; a clipped one piles up there). Columns
    spanning fewer than 20 quantisation steps (a quiet axis of a 3.9 mg/LSB sensor) are not
    judged."""
    mask = np.zeros(x.shape, dtype=bool)
    cols = []
    for j in range(x.shape[1]):
        col = x[:, j]
        lo, hi = float(col.min()), float(col.max())
        span = hi - lo
        steps = np.diff(np.unique(col[:20000]))
        q = float(steps.min()) if steps.size else 0.0
        if span <= 0 or span < 20 * q:
            continue
        band = max(0.02 * span, 2.5 * q)
        hit = False
        for value, near in ((hi, col >= hi - band), (lo, col <= lo + band)):
            at = col == value
            n_at = int(np.count_nonzero(at))
            if n_at < 5:
                continue
            idx = np.flatnonzero(at)
            starts = np.flatnonzero(np.diff(np.r_[-2, idx]) != 1)
            longest = int(np.max(np.diff(np.r_[starts, idx.size])))
            if longest >= 2 and n_at > np.count_nonzero(near) - n_at:
                mask[:, j] |= at
                hit = True
        if hit:
            cols.append(j)
    return mask, cols


def _runs(mask):
    d = np.diff(np.r_[0, mask.astype(np.int8), 0])
    return np.flatnonzero(d == 1), np.flatnonzero(d == -1)


def reconstruct(x: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """``x`` (n,) with the samples under ``mask`` replaced by the local harmonic fit (see the
    module docstring); ``x`` itself is not changed."""
    out = np.array(x, dtype=float)
    if not mask.any():
        return out
    starts, stops = _runs(mask)
    centre = 0.5 * (float(np.max(x)) + float(np.min(x)))
    # zero crossings about the mid-range (clipping keeps them), to a fraction of a sample
    y = x - centre
    i = np.flatnonzero(np.sign(y[1:]) * np.sign(y[:-1]) < 0)
    cross = i + y[i] / (y[i] - y[i + 1])
    n = x.size
    for s, e in zip(starts, stops):
        near = cross[(cross > s - 300) & (cross < e + 300)]
        if near.size >= 4:
            # crossings are equally spaced by half a period: their slope over their count
            k = np.arange(near.size)
            half = float(np.polyfit(k, near, 1)[0])
        else:
            half = 4.0 * (e - s)
        period = max(4.0, 2.0 * half)
        w = int(max(2 * period, 4 * (e - s), 24))
        a, b = max(0, s - w), min(n, e + w)
        tt = np.arange(a, b, dtype=float)
        good = ~mask[a:b]
        omega = 2 * np.pi / period
        cols = [np.ones(b - a)]
        for h in range(1, HARMONICS + 1):
            cols += [np.cos(h * omega * tt), np.sin(h * omega * tt)]
        M = np.column_stack(cols)
        if np.count_nonzero(good) < 2 * M.shape[1]:
            continue                         # too little around it: keep the rail value
        coef = np.linalg.lstsq(M[good], x[a:b][good], rcond=None)[0]
        fit = M[s - a: e - a] @ coef
        rail = x[s]
        out[s:e] = np.maximum(fit, rail) if rail >= centre else np.minimum(fit, rail)
    return out
