# SPDX-License-Identifier: Apache-2.0
"""Power spectra of resonance records: Welch estimates from the samples a record holds (its
contiguous segments on the uniform time grid), summed over the axes or projected onto a
direction, and the part of a spectrum that is vibration.

Welch (P. D. Welch, "The use of fast Fourier transform for the estimation of power spectra",
IEEE Trans. Audio Electroacoust. 15 (1967) 70-73): Hann window, 75 % overlap (the squared
windows then sum to a constant, so a sweep's excitation is weighted evenly over the record),
each window's mean removed, one-sided density. A window spanning a FIFO gap takes the samples
the record holds and is normalised by the window energy on them (the gap's samples are missing,
not zero); a window that is mostly gap is skipped. The windows keep their length (and the
resolution that separates modes 2 Hz apart) whatever the gaps. The estimate is written with
numpy's FFT, in batches of windows, because
``scipy.signal`` alone takes 0.9 s and 110 MiB to import, more than the established tool needs
for its whole run on a 10 s record; the arithmetic is the textbook one (the tests compare it
with ``scipy.signal.welch``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Spectrum", "segment_length", "welch", "column_spectrum", "record_spectrum", "normalize_to_excitation",
           "vibration_content",
           "energy_shares"]

#: Longest Welch segment [s]: bins finer than 0.25 Hz resolve nothing a printer has, and cost.
MAX_SEGMENT_S = 4.0
#: A window is used when at least this share of its energy falls on samples the record holds
#: (FIFO gaps of a few tens of milliseconds take a few percent of a window of seconds).
MIN_PRESENT = 0.75
#: Windows transformed at once (bounds the memory: 32 windows of 8192 samples are 2 MiB).
_BATCH = 32


@dataclass
class Spectrum:
    """A PSD (or |H|^2) on ``f`` [Hz]; ``kernel`` is the window's |W|^2 on a grid of
    ``df/oversample`` (None: point samples), ``averages`` the number of Welch windows (None:
    unknown), ``enbw_bins`` the window's equivalent noise bandwidth in bins."""
    f: np.ndarray
    P: np.ndarray
    kernel: np.ndarray | None = None
    oversample: int = 8
    averages: int | None = None
    enbw_bins: float = 1.0


def segment_length(n: int, Ts: float) -> int:
    """Welch segment length (a power of two) for a record spanning ``n`` samples of the
    uniform grid: about a fifth of it, at most :data:`MAX_SEGMENT_S`."""
    return int(2 ** math.floor(math.log2(max(16.0, min(n / 4.5, MAX_SEGMENT_S / Ts)))))


def _grid(x, segments, starts):
    """(values on the uniform grid, mask of the samples the record holds) of one column."""
    n = starts[-1] + segments[-1][1] - segments[-1][0]
    y = np.zeros(n)
    m = np.zeros(n, dtype=bool)
    for (a, b), g in zip(segments, starts):
        y[g: g + b - a] = x[a:b]
        m[g: g + b - a] = True
    return y, m


def _windows(y, m, nperseg, win, acc):
    """Add the periodograms of every window of ``y`` (mask ``m``, None: all present) holding at
    least :data:`MIN_PRESENT` of the window's energy to ``acc``, each normalised by the window
    energy on the samples it holds; returns their number."""
    hop = max(1, nperseg // 4)
    count = 1 + (y.size - nperseg) // hop
    if count <= 0:
        return 0
    w2 = win * win
    full = float(np.sum(w2))
    used = 0
    # the windows' detrended, windowed copies go into one buffer (a new array per step cost
    # more CPU time in page faults than the FFT itself: the same floats)
    buf = np.empty((min(count, _BATCH), nperseg))
    for k0 in range(0, count, _BATCH):
        k1 = min(count, k0 + _BATCH)
        shape, strides = (k1 - k0, nperseg), (hop * y.strides[0], y.strides[0])
        seg = np.lib.stride_tricks.as_strided(y[k0 * hop:], shape=shape, strides=strides,
                                              writeable=False)
        if m is None:
            out = buf[: k1 - k0]
            np.subtract(seg, seg.mean(axis=1, keepdims=True), out=out)
            seg = np.multiply(out, win, out=out)
            energy = np.full(k1 - k0, full)
        else:
            mk = np.lib.stride_tricks.as_strided(m[k0 * hop:], shape=shape,
                                                 strides=(hop * m.strides[0], m.strides[0]),
                                                 writeable=False)
            energy = mk @ w2
            keep = energy >= MIN_PRESENT * full
            if not keep.any():
                continue
            seg, mk, energy = seg[keep], mk[keep], energy[keep]
            # the mean of the samples held; a missing sample adds nothing
            mean = np.sum(seg * mk, axis=1, keepdims=True) / np.sum(mk, axis=1, keepdims=True)
            out = buf[: seg.shape[0]]
            np.subtract(seg, mean, out=out)
            np.multiply(out, mk, out=out)
            seg = np.multiply(out, win, out=out)
        X = np.fft.rfft(seg, axis=1)
        power = X.real ** 2
        power += X.imag ** 2
        power /= energy[:, None]
        acc += np.sum(power, axis=0)
        used += seg.shape[0]
    return used


def welch(x: np.ndarray, Ts: float, *, segments=None, starts=None,
          nperseg: int | None = None) -> Spectrum:
    """Welch PSD of ``x`` (one signal, or several columns whose PSDs are summed: (n,) or
    (n, k)) over its contiguous ``segments`` [(start, stop)] placed at ``starts`` on the uniform
    grid (default: all of x, contiguous).

    Windows of ``nperseg`` samples (default :func:`segment_length`) step by a quarter of it
    over the grid; a window spanning a gap takes the samples the record holds, its mean
    removed, and its periodogram is normalised by the window energy on those samples (a
    missing sample is no zero of the signal); windows holding less than :data:`MIN_PRESENT`
    of their energy are skipped. Without gaps this is ``scipy.signal.welch(x, 1/Ts,
    window="hann", nperseg=nperseg, noverlap=3 nperseg/4, detrend="constant")``."""
    x = np.asarray(x, dtype=float)
    if x.ndim == 1:
        x = x[:, None]
    if segments is None:
        segments = [(0, x.shape[0])]
    if starts is None:
        starts = [a for a, _ in segments]
    span = starts[-1] + segments[-1][1] - segments[-1][0]
    gapless = len(segments) == 1 and segments[0] == (0, x.shape[0])
    n = segment_length(span, Ts) if nperseg is None else int(nperseg)
    n = max(1, min(n, span))
    while True:
        win = np.hanning(n + 1)[:-1] if n > 1 else np.ones(1)   # periodic Hann
        acc = np.zeros(n // 2 + 1)
        used = 0
        for j in range(x.shape[1]):
            if gapless:
                used = _windows(x[:, j], None, n, win, acc)
            else:
                y, m = _grid(x[:, j], segments, starts)
                used = _windows(y, m, n, win, acc)
        if used or n <= 16:
            break
        n //= 2                       # every window mostly in gaps: shorter windows
    P = acc / (max(used, 1) / Ts)
    P[1: (n + 1) // 2] *= 2.0          # one-sided (Nyquist bin unpaired for even n)
    f = np.fft.rfftfreq(n, Ts)
    over = 4
    W = np.abs(np.fft.fft(win, n * over)) ** 2
    half = 5 * over                    # +- 5 bins: the Hann side lobes are below -55 dB
    kernel = np.r_[W[-half:], W[: half + 1]]
    kernel /= kernel.sum()
    enbw = n * np.sum(win ** 2) / np.sum(win) ** 2
    return Spectrum(f, P, kernel, over, max(used, 1), float(enbw))


def column_spectrum(record, j: int, nperseg: int | None = None) -> Spectrum:
    """The Welch PSD of column ``j`` of a raw record, computed once per record and segment
    length (the summed analysis, the spectral figure and the energy shares all read it)."""
    cache = record.column_psd
    key = (int(j), nperseg)
    if key not in cache:
        cache[key] = welch(record.signals[:, j], record.Ts, segments=record.segments,
                           starts=record.grid_starts, nperseg=nperseg)
    return cache[key]


def record_spectrum(record, columns, direction=None, nperseg: int | None = None) -> Spectrum:
    """The PSD of a raw record: the sum of the ``columns``' PSDs, or (``direction`` a vector
    over the record's columns) the PSD of the projected acceleration."""
    x = record.signals
    if direction is not None:
        d = np.asarray(direction, dtype=float)
        y = x[:, : d.size] @ d[: x.shape[1]]
        return welch(y, record.Ts, segments=record.segments, starts=record.grid_starts,
                     nperseg=nperseg)
    parts = [column_spectrum(record, j, nperseg) for j in columns]
    if len(parts) == 1:
        return parts[0]
    first = parts[0]
    return Spectrum(first.f, np.sum([s.P for s in parts], axis=0), first.kernel,
                    first.oversample, first.averages, first.enbw_bins)


def normalize_to_excitation(f, P):
    """A resonance test's PSD divided by its excitation's growth with the frequency, as the
    established tool does before it scores shapers (Klipper's ``normalize_to_frequencies``):
    ``P / (f + 0.1)``, and below 10 Hz times ``exp(1 - (10 / (f + 0.1))^2)`` (the slow
    back-and-forth of the test is no resonance). The test commands an acceleration growing with
    f (``accel_per_hz``), a print's moves do not."""
    f = np.asarray(f, dtype=float)
    out = np.asarray(P, dtype=float) / (f + 0.1)
    low = f < 10.0
    out[low] *= np.exp(1.0 - (10.0 / (f[low] + 0.1)) ** 2)
    return out


def vibration_content(f, P, band, threshold: float = 20.0) -> np.ndarray:
    """The vibration a shaper can act on, per bin: the PSD in ``band`` less ``max(P)/
    threshold`` (the established tool's rule: a shaper cannot take a vibration below a
    twentieth of the largest one further down), zero outside the band."""
    inb = (f >= band[0]) & (f <= band[1]) & (f > 0)
    S = np.zeros_like(P, dtype=float)
    if not inb.any():
        return S
    top = float(np.max(P[inb]))
    S[inb] = np.maximum(P[inb] - top / threshold, 0.0)
    return S


def energy_shares(record, band, columns=None) -> np.ndarray:
    """Each column's (of ``columns``, default all) share of the in-band PSD energy of a record
    (raw: its own Welch PSD; a table: its column)."""
    columns = range(record.signals.shape[1]) if columns is None else columns
    if record.kind == "raw":
        e = []
        for j in columns:
            s = column_spectrum(record, j)
            inb = (s.f >= band[0]) & (s.f <= band[1])
            e.append(float(np.sum(s.P[inb])))
        e = np.array(e)
    else:
        inb = (record.f >= band[0]) & (record.f <= band[1])
        e = np.array([float(np.sum(record.signals[inb, j])) for j in columns])
    total = e.sum()
    return e / total if total > 0 else e


def kaiser_kernel(beta: float = 6.0, over: int = 4, n: int = 512) -> np.ndarray:
    """|W|^2 of a Kaiser window (the established tool's Welch window, beta 6) on a grid of a
    quarter bin over +- 5 bins, normalised to sum 1: the kernel of its PSD tables."""
    win = np.kaiser(n, beta)
    W = np.abs(np.fft.fft(win, n * over)) ** 2
    half = 5 * over
    k = np.r_[W[-half:], W[: half + 1]]
    return k / k.sum()
