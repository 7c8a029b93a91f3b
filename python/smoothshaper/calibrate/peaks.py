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

__all__ = ["local_maxima", "prominences", "find_peaks", "peak_widths"]


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


def prominences(x: np.ndarray, peaks: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(prominences, left_bases, right_bases) of ``peaks`` in ``x``: each base is the lowest
    sample between the peak and the nearest higher sample on that side (or the end), the one
    nearest the peak among equal lows."""
    x = np.asarray(x, dtype=float)
    out = np.empty(len(peaks))
    left_bases = np.empty(len(peaks), dtype=np.intp)
    right_bases = np.empty(len(peaks), dtype=np.intp)
    for n, p in enumerate(peaks):
        v = x[p]
        higher = np.flatnonzero(x[:p] > v)
        lo = int(higher[-1]) + 1 if higher.size else 0
        higher = np.flatnonzero(x[p + 1:] > v)
        hi = p + 1 + int(higher[0]) if higher.size else x.size
        left = x[lo: p + 1]
        right = x[p: hi]
        # the last of equal lows on the left, the first on the right: nearest the peak
        left_bases[n] = lo + left.size - 1 - int(np.argmin(left[::-1]))
        right_bases[n] = p + int(np.argmin(right))
        out[n] = v - max(float(x[left_bases[n]]), float(x[right_bases[n]]))
    return out, left_bases, right_bases


def find_peaks(x: np.ndarray, prominence: float = 0.0) -> tuple[np.ndarray, dict]:
    """(peaks, {"prominences", "left_bases", "right_bases"}) of ``x`` whose prominence is at
    least ``prominence``, as ``scipy.signal.find_peaks(x, prominence=prominence)`` returns them."""
    pk = local_maxima(x)
    prom, left, right = prominences(x, pk)
    keep = prom >= prominence
    return pk[keep], {"prominences": prom[keep], "left_bases": left[keep],
                      "right_bases": right[keep]}


def peak_widths(x: np.ndarray, peaks: np.ndarray, rel_height: float,
                prominence_data: tuple[np.ndarray, np.ndarray, np.ndarray]) -> np.ndarray:
    """Width [samples] of each of ``peaks`` at ``rel_height`` of its prominence below its top,
    between its bases, the crossings interpolated linearly between samples, as
    ``scipy.signal.peak_widths(...)[0]`` returns them."""
    x = np.asarray(x, dtype=float)
    prom, left_bases, right_bases = prominence_data
    widths = np.empty(len(peaks))
    for n, p in enumerate(peaks):
        p, i_min, i_max = int(p), int(left_bases[n]), int(right_bases[n])
        height = x[p] - prom[n] * rel_height
        # left: the first sample from the peak down to its base at or below the height
        below = np.flatnonzero(x[i_min + 1: p + 1] <= height)
        i = i_min + 1 + int(below[-1]) if below.size else i_min
        left_ip = float(i)
        if x[i] < height:
            left_ip += (height - x[i]) / (x[i + 1] - x[i])
        below = np.flatnonzero(x[p: i_max] <= height)
        i = p + int(below[0]) if below.size else i_max
        right_ip = float(i)
        if x[i] < height:
            right_ip -= (height - x[i]) / (x[i - 1] - x[i])
        widths[n] = right_ip - left_ip
    return widths
