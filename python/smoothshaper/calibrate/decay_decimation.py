# SPDX-License-Identifier: Apache-2.0
"""Long free decays fitted at the rate their content needs, in bounded memory.

The whole-record fit of :func:`.modes.decay_modes` holds a Jacobian of a dozen columns per
sample (about 100 bytes a sample: a 1e6-sample decay needed 1 GB). A decay sampled far above
its modes carries them in a small band: low-pass filtering it with a linear-phase FIR of unit
DC gain and keeping every q-th sample leaves each damped oscillation ``e^{sigma t} cos(wd t +
phi)`` a damped oscillation of the same ``sigma`` and ``wd`` (the filter acts on it as the
complex gain ``H(sigma + j wd)``, within 0.5 % of 1 in the pass band: amplitude only), and the
offset exactly. White noise of variance s^2 becomes white noise of variance about s^2 / q, so
the fit's covariance (``(J^T J)^-1 s^2`` over n / q samples) states the same uncertainty as
the full-rate fit: the noise outside the kept band carries no information on the modes
(S. M. Kay, "Fundamentals of Statistical Signal Processing: Estimation Theory", 1993,
Sec. 3.11: the Fisher information of a sinusoid in white noise). The factor keeps the new
Nyquist frequency at least :data:`NYQUIST_MARGIN` times above the highest frequency that
stands out of the record's noise floor.
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["FIT_SAMPLES", "NYQUIST_MARGIN", "content_top", "decimation_factor", "decimate",
           "fit_rate", "residual_sum"]

#: Records longer than this are fitted on a decimated copy (when their content allows it).
FIT_SAMPLES = 1 << 16
#: The decimated Nyquist frequency stays this many times above the record's content.
NYQUIST_MARGIN = 2.5
#: A frequency is content when its Welch PSD stands this many times above the median bin.
CONTENT_RATIO = 100.0
#: Model evaluations and residuals run over chunks of this many samples.
CHUNK = 1 << 16


def content_top(x: np.ndarray, Ts: float) -> float:
    """Highest frequency [Hz] whose Welch PSD (segments of 4096 samples, bounded memory) stands
    :data:`CONTENT_RATIO` times above the median bin: above it the record is noise."""
    from .spectra import welch
    spec = welch(x, Ts, nperseg=min(x.size, 4096))
    f, P = spec.f, spec.P
    floor = float(np.median(P))
    hit = np.flatnonzero(P > CONTENT_RATIO * floor)
    return float(f[hit[-1]]) if hit.size else float(f[-1])


def decimation_factor(n: int, Ts: float, f_keep: float) -> int:
    """The factor q for a record of ``n`` samples whose content ends at ``f_keep`` [Hz]: 1 for
    records of at most :data:`FIT_SAMPLES`, else the largest q keeping the new Nyquist
    frequency :data:`NYQUIST_MARGIN` times above ``f_keep``, and no more than needed to reach
    :data:`FIT_SAMPLES` samples."""
    if n <= FIT_SAMPLES or not f_keep > 0:
        return 1
    by_band = int(math.floor(0.5 / (Ts * NYQUIST_MARGIN * f_keep)))
    return max(1, min(by_band, n // FIT_SAMPLES))


def decimate(x: np.ndarray, q: int) -> tuple[np.ndarray, np.ndarray]:
    """(indices into x of the kept samples, their low-passed values): a zero-phase FIR of
    20 q + 1 taps (Hamming window, unit DC gain) applied polyphase (``scipy.signal.
    resample_poly``: no full-rate copy), the samples within the filter's half length of either
    end dropped (the filter sees the record's edges there)."""
    import scipy.signal
    taps = scipy.signal.firwin(20 * q + 1, 1.0 / q, window="hamming")
    y = scipy.signal.resample_poly(x, 1, q, window=taps)
    edge = 11                      # 10 q input samples: 10 decimated ones, and one more
    keep = np.arange(edge, y.size - edge)
    keep = keep[keep * q < x.size]
    return keep * q, y[keep]


def fit_rate(x: np.ndarray, Ts: float, band=None) -> tuple[np.ndarray, np.ndarray, int]:
    """(indices into x, values, factor q) of the record a decay fit uses: all of x (q = 1), or
    for a long record its decimated copy (the content's top, or the band's when given, kept)."""
    q = 1
    if x.size > FIT_SAMPLES:
        f_keep = content_top(x, Ts)
        if band is not None and math.isfinite(band[1]):
            f_keep = max(f_keep, float(band[1]))
        q = decimation_factor(x.size, Ts, f_keep)
    if q == 1:
        return np.arange(x.size), np.asarray(x, dtype=float), 1
    idx, y = decimate(x, q)
    return idx, y, q


def residual_sum(model, theta, x: np.ndarray, Ts: float) -> float:
    """Sum of squared residuals of ``model(theta, t)`` (values only) against every sample of x,
    evaluated in chunks of :data:`CHUNK` samples."""
    total = 0.0
    for a in range(0, x.size, CHUNK):
        b = min(x.size, a + CHUNK)
        r = model(theta, np.arange(a, b) * Ts) - x[a:b]
        total += float(r @ r)
    return total
