# SPDX-License-Identifier: Apache-2.0
"""Peaks of a sampled curve and their topographic prominence, with NumPy alone.

The definitions are ``scipy.signal.find_peaks``'s (a peak: a sample above its left neighbour
followed by equal samples and then a lower one, placed mid-plateau; its prominence: its height
above the higher of the lowest points on either side before a higher sample or the end), so
that results are the same (the tests compare them). ``scipy.signal`` is not imported for it:
it pulls ``scipy.stats`` in, about 1.5 s of CPU and 40 MiB, more than a whole calibration of a
short record takes otherwise.
"""
from __future__ import annotations

import numpy as np

__all__ = ["local_maxima", "prominences", "find_peaks"]


def local_maxima(x: np.ndarray) -> np.ndarray:
    """Indices of the local maxima of ``x`` (flat tops: the middle sample, rounded down; the
    first and last samples are never peaks)."""
    x = np.asarray(x, dtype=float)
    if x.size < 3:
        return np.zeros(0, dtype=np.intp)
    d = np.sign(np.diff(x))
    # runs of equal samples carry the sign of the step that follows them
    nz = np.flatnonzero(d)
    if nz.size == 0:
        return np.zeros(0, dtype=np.intp)
    step = d[nz]
    # a rise (into sample nz[i] + 1) followed by the next nonzero step being a fall
    rise_then_fall = np.flatnonzero((step[:-1] > 0) & (step[1:] < 0))
    left = nz[rise_then_fall] + 1                 # first sample of the top
    right = nz[rise_then_fall + 1]                # last sample of the top
    return ((left + right) // 2).astype(np.intp)


def prominences(x: np.ndarray, peaks: np.ndarray) -> np.ndarray:
    """Topographic prominence of each of ``peaks`` in ``x``."""
    x = np.asarray(x, dtype=float)
    out = np.empty(len(peaks))
    for n, p in enumerate(peaks):
        v = x[p]
        higher = np.flatnonzero(x[:p] > v)
        lo = int(higher[-1]) + 1 if higher.size else 0
        higher = np.flatnonzero(x[p + 1:] > v)
        hi = p + 1 + int(higher[0]) if higher.size else x.size
        out[n] = v - max(float(np.min(x[lo: p + 1])), float(np.min(x[p: hi])))
    return out


def find_peaks(x: np.ndarray, prominence: float = 0.0) -> tuple[np.ndarray, dict]:
    """(peaks, {"prominences": ...}) of ``x`` whose prominence is at least ``prominence``, as
    ``scipy.signal.find_peaks(x, prominence=prominence)`` returns them."""
    pk = local_maxima(x)
    prom = prominences(x, pk)
    keep = prom >= prominence
    return pk[keep], {"prominences": prom[keep]}
