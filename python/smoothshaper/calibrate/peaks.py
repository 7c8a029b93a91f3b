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

__all__ = ["local_maxima", "prominence_data", "prominences", "peak_widths", "find_peaks"]


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


def prominence_data(x: np.ndarray, peaks: np.ndarray):
    """(prominences, left_bases, right_bases) of ``peaks`` in ``x``: each base is the lowest
    sample between the peak and the nearest higher one (or the end) on its side, the one
    nearest the peak where several are as low (``scipy.signal.peak_prominences``)."""
    x = np.asarray(x, dtype=float)
    prom = np.empty(len(peaks))
    left = np.empty(len(peaks), dtype=np.intp)
    right = np.empty(len(peaks), dtype=np.intp)
    for n, p in enumerate(peaks):
        v = x[p]
        higher = np.flatnonzero(x[:p] > v)
        lo = int(higher[-1]) + 1 if higher.size else 0
        higher = np.flatnonzero(x[p + 1:] > v)
        hi = p + 1 + int(higher[0]) if higher.size else x.size
        seg = x[lo: p + 1]
        left[n] = lo + seg.size - 1 - int(np.argmin(seg[::-1]))
        right[n] = p + int(np.argmin(x[p: hi]))
        prom[n] = v - max(float(x[left[n]]), float(x[right[n]]))
    return prom, left, right


def prominences(x: np.ndarray, peaks: np.ndarray) -> np.ndarray:
    """Topographic prominence of each of ``peaks`` in ``x``."""
    return prominence_data(x, peaks)[0]


def peak_widths(x: np.ndarray, peaks: np.ndarray, rel_height: float, prominence_data):
    """Width [samples] of each of ``peaks`` at ``rel_height`` of its prominence below it,
    between its bases, the crossings interpolated linearly (``scipy.signal.peak_widths``'s
    first output); ``prominence_data`` = (prominences, left_bases, right_bases)."""
    x = np.asarray(x, dtype=float)
    prom, lb, rb = prominence_data
    out = np.empty(len(peaks))
    for n, p in enumerate(peaks):
        h = x[p] - prom[n] * rel_height
        i = int(p)
        while lb[n] < i and h < x[i]:
            i -= 1
        left = float(i) + ((h - x[i]) / (x[i + 1] - x[i]) if x[i] < h else 0.0)
        i = int(p)
        while i < rb[n] and h < x[i]:
            i += 1
        right = float(i) - ((h - x[i]) / (x[i - 1] - x[i]) if x[i] < h else 0.0)
        out[n] = right - left
    return out


def find_peaks(x: np.ndarray, prominence: float = 0.0) -> tuple[np.ndarray, dict]:
    """(peaks, {"prominences", "left_bases", "right_bases"}) of ``x`` whose prominence is at
    least ``prominence``, as ``scipy.signal.find_peaks(x, prominence=prominence)`` returns
    them."""
    pk = local_maxima(x)
    prom, left, right = prominence_data(x, pk)
    keep = prom >= prominence
    return pk[keep], {"prominences": prom[keep], "left_bases": left[keep],
                      "right_bases": right[keep]}
