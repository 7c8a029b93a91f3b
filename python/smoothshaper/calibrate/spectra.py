# SPDX-License-Identifier: Apache-2.0
"""Power spectra of resonance records: Welch estimates over the contiguous segments of a record,
summed over the axes or projected onto a direction, and the part of a spectrum that is
vibration.

Welch (P. D. Welch, "The use of fast Fourier transform for the estimation of power spectra",
IEEE Trans. Audio Electroacoust. 15 (1967) 70-73): Hann window, 75 % overlap (the squared
windows then sum to a constant, so a sweep's excitation is weighted evenly over the record),
each segment's mean removed, one-sided density. Windows never straddle a gap: each contiguous
segment of the record contributes its own windows and the periodograms of all of them are
averaged. The estimate is written with numpy's FFT, in batches of windows, because
``scipy.signal`` alone takes 0.9 s and 110 MiB to import, more than the established tool needs
for its whole run on a 10 s record; the arithmetic is the textbook one (the tests compare it
with ``scipy.signal.welch``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["Spectrum", "segment_length", "welch", "record_spectrum", "normalize_to_excitation",
           "vibration_content",
           "energy_shares"]

#: Longest Welch segment [s]: bins finer than 0.25 Hz resolve nothing a printer has, and cost.
MAX_SEGMENT_S = 4.0
#: Coarsest resolution accepted when gaps force short segments [Hz].
_BATCH = 64


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


def segment_length(segments, Ts: float) -> int:
    """Welch segment length (a power of two) for a record cut into ``segments``: about a fifth
    of the longest stretch (at most :data:`MAX_SEGMENT_S`), shortened until the segments at
    least that long hold 70 % of the samples."""
    lengths = np.array([b - a for a, b in segments])
    total = lengths.sum()
    n = int(2 ** math.floor(math.log2(max(16, min(lengths.max() / 4.5, MAX_SEGMENT_S / Ts)))))
    while n > 16 and lengths[lengths >= n].sum() < 0.7 * total:
        n //= 2
    return max(16, n)


def _window_sums(x, nperseg, win, out, counts):
    """Add the windowed periodograms of one contiguous stretch ``x`` to ``out``."""
    hop = nperseg // 4
    m = 1 + (x.size - nperseg) // hop
    if m <= 0:
        return 0
    for k0 in range(0, m, _BATCH):
        k1 = min(m, k0 + _BATCH)
        seg = np.lib.stride_tricks.as_strided(
            x[k0 * hop:], shape=(k1 - k0, nperseg), strides=(hop * x.strides[0], x.strides[0]),
            writeable=False)
        seg = (seg - seg.mean(axis=1, keepdims=True)) * win
        X = np.fft.rfft(seg, axis=1)
        out += np.sum(X.real ** 2 + X.imag ** 2, axis=0)
    counts[0] += m
    return m


def welch(x: np.ndarray, Ts: float, *, segments=None, nperseg: int | None = None) -> Spectrum:
    """Welch PSD of ``x`` (one signal, or several columns summed: (n,) or (n, k)) over the
    contiguous ``segments`` [(start, stop)] (default: all of x)."""
    x = np.asarray(x, dtype=float)
    if x.ndim == 1:
        x = x[:, None]
    if segments is None:
        segments = [(0, x.shape[0])]
    if nperseg is None:
        nperseg = segment_length(segments, Ts)
    nperseg = int(min(nperseg, max(b - a for a, b in segments)))
    win = np.hanning(nperseg + 1)[:-1] if nperseg > 1 else np.ones(1)   # periodic Hann
    acc = np.zeros(nperseg // 2 + 1)
    counts = [0]
    for j in range(x.shape[1]):
        c = [0]
        for a, b in segments:
            _window_sums(np.ascontiguousarray(x[a:b, j]), nperseg, win, acc, c)
        counts[0] = c[0]
    m = max(counts[0], 1)
    scale = 1.0 / ((1.0 / Ts) * np.sum(win ** 2))
    P = acc * scale / m
    P[1: (nperseg + 1) // 2] *= 2.0             # one-sided (Nyquist bin unpaired for even n)
    f = np.fft.rfftfreq(nperseg, Ts)
    over = 4
    W = np.abs(np.fft.fft(win, nperseg * over)) ** 2
    half = 5 * over                              # +- 5 bins: the Hann side lobes are below -55 dB
    kernel = np.r_[W[-half:], W[: half + 1]]
    kernel /= kernel.sum()
    enbw = nperseg * np.sum(win ** 2) / np.sum(win) ** 2
    return Spectrum(f, P, kernel, over, m, float(enbw))


def record_spectrum(record, columns, direction=None) -> Spectrum:
    """The PSD of a raw record: the sum of the ``columns``' PSDs, or (``direction`` a vector
    over the record's columns) the PSD of the projected acceleration."""
    x = record.signals
    if direction is not None:
        d = np.asarray(direction, dtype=float)
        y = x[:, : d.size] @ d[: x.shape[1]]
        return welch(y, record.Ts, segments=record.segments)
    return welch(x[:, columns], record.Ts, segments=record.segments)


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


def energy_shares(record, band) -> np.ndarray:
    """Each column's share of the in-band PSD energy of a record (raw: its own Welch PSD; a
    table: its column)."""
    if record.kind == "raw":
        e = []
        for j in range(record.signals.shape[1]):
            s = welch(record.signals[:, j], record.Ts, segments=record.segments)
            inb = (s.f >= band[0]) & (s.f <= band[1])
            e.append(float(np.sum(s.P[inb])))
        e = np.array(e)
    else:
        inb = (record.f >= band[0]) & (record.f <= band[1])
        e = np.array([float(np.sum(record.signals[inb, j])) for j in range(record.signals.shape[1])])
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
