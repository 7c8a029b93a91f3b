# SPDX-License-Identifier: Apache-2.0
"""The established 3-D printer calibration, re-implemented from its published formulas for the
comparison tests: Klipper's ``scripts/calibrate_shaper.py`` with ``klippy/extras/
shaper_calibrate.py`` and ``shaper_defs.py`` (K. O'Connor, D. Butyugin; Klipper3d/klipper,
2026-08). Nothing here is their code; each step follows their definitions:

* Reading (``parse_log``): a file whose first non-comment line does not start with ``freq,`` is
  a raw record (``np.loadtxt``, time + 3 axes); a PSD table whose header starts with
  ``freq,psd_x,psd_y,psd_z,psd_xyz`` is one data set (its ``psd_xyz`` column); any other
  ``freq,...`` header holds one data set per column up to ``shapers:``. Tables without
  ``,shapers:`` in the header are normalised (below), also the old ones that already were.
* Raw record -> PSD: sampling rate N / (t_N - t_1) (stamps taken as uniform), segment
  M = 2^ceil(log2(0.5 fs)), Kaiser window beta 6, 50 % overlap, each segment's mean removed,
  one-sided density; the sum over the three axes.
* Normalisation: PSD / (f + 0.1), and below 10 Hz times exp(1 - (10 / (f + 0.1))^2).
* Remaining vibrations of a shaper (A, T) at test damping dr over the bins f <= 200 Hz:
  ``sum(max(R psd - max(psd)/20, 0)) / sum(max(psd - max(psd)/20, 0))`` with R the residual
  ``|sum A_i e^{-dr w (T_n - T_i)} e^{j wd T_i}| / sum A`` (their ``_estimate_shaper``); the
  largest over dr = 0.075, 0.1, 0.15 counts.
* Smoothing at accel 5000, scv 5; score = smoothing (v^1.5 + 0.2 v + 0.01); suggested max
  accel: the largest accel whose smoothing stays <= 0.12 (bisection).
* Per shaper (zv, mzv, ei, 2hump_ei, 3hump_ei, designed at damping 0.1): frequencies from its
  minimum (21, 23, 29, 39, 48 Hz) to 150 Hz in 0.2 Hz steps, scanned downwards; the best is the
  least-vibration one, the pick the lowest score among those with vibrations below
  1.1 x best + 0.0005.
* Across shapers: a later one replaces the pick when its score is 20 % lower, or 5 % lower with
  10 % less smoothing; then any of its frequencies with both less vibration and less smoothing
  than the pick replaces it; a ZV pick gives way to the first other shaper with vibrations
  10 % lower.
"""
from __future__ import annotations

import csv
import math

import numpy as np

VIBRATION_REDUCTION = 20.0
DAMPING = 0.1
TEST_DAMPINGS = (0.075, 0.1, 0.15)
MAX_FREQ = 200.0
MAX_SHAPER_FREQ = 150.0
SHAPERS = ("zv", "mzv", "ei", "2hump_ei", "3hump_ei")
MIN_FREQ = {"zv": 21.0, "mzv": 23.0, "zvd": 29.0, "ei": 29.0, "2hump_ei": 39.0, "3hump_ei": 48.0}
#: Largest damping ratio the firmware accepts per shaper (shaper_defs.py).
MAX_DAMPING = {"zv": 0.99, "mzv": 0.99, "zvd": 0.99, "ei": 0.4, "2hump_ei": 0.3, "3hump_ei": 0.2}


# ---------------------------------------------------------------- shaper definitions

def _mzv(freq, dr, n=3, t=0.75):
    """Generalised MZV: n impulses over t damped periods; amplitudes: the least-squares
    (pseudo-inverse) solution of sum A = 1 and zero residual at (1 + i/tau) times the design
    frequency, i = 0..n-2, tau = t (n-2)/(n-2t-1)."""
    tau = t * (n - 2.0) / (n - 2.0 * t - 1.0)
    Tn = np.arange(n) * t / (n - 1.0)
    rows = [np.ones(n)]
    for i in range(n - 1):
        w = 2 * math.pi * (1 + i / tau) * Tn
        rows += [np.cos(w), np.sin(w)]
    M = np.array(rows)
    F = np.zeros(M.shape[0])
    F[0] = 1.0
    A = np.linalg.pinv(M) @ F
    df = math.sqrt(1 - dr * dr)
    K = math.exp(-2.0 * t * dr * math.pi / ((n - 1.0) * df))
    td = 1.0 / (freq * df)
    return A * K ** np.arange(n), Tn * td


def _expansion(freq, dr, t, a):
    """Impulses whose times (in periods) and amplitudes are cubic polynomials in dr."""
    T = np.array([np.polyval(row[::-1], dr) for row in t]) / freq
    A = np.array([np.polyval(row[::-1], dr) for row in a])
    return A, T


_EI2_T = [[0., 0., 0., 0.], [0.49890, 0.16270, -0.54262, 6.16180],
          [0.99748, 0.18382, -1.58270, 8.17120], [1.49920, -0.09297, -0.28338, 1.85710]]
_EI2_A = [[0.16054, 0.76699, 2.26560, -1.22750], [0.33911, 0.45081, -2.58080, 1.73650],
          [0.34089, -0.61533, -0.68765, 0.42261], [0.15997, -0.60246, 1.00280, -0.93145]]
_EI3_T = [[0., 0., 0., 0.], [0.49974, 0.23834, 0.44559, 12.4720],
          [0.99849, 0.29808, -2.36460, 23.3990], [1.49870, 0.10306, -2.01390, 17.0320],
          [1.99960, -0.28231, 0.61536, 5.40450]]
_EI3_A = [[0.11275, 0.76632, 3.29160, -1.44380], [0.23698, 0.61164, -2.57850, 4.85220],
          [0.30008, -0.19062, -2.14560, 0.13744], [0.23775, -0.73297, 0.46885, -2.08650],
          [0.11244, -0.45439, 0.96382, -1.46000]]


def shaper(name, freq, dr=DAMPING):
    """(A, T [s]) of the firmware's shaper ``name`` at ``freq`` [Hz] and damping ``dr``."""
    df = math.sqrt(1 - dr * dr)
    K = math.exp(-dr * math.pi / df)
    td = 1.0 / (freq * df)
    if name == "zv":
        return np.array([1.0, K]), np.array([0.0, 0.5 * td])
    if name == "zvd":
        return np.array([1.0, 2 * K, K * K]), np.array([0.0, 0.5 * td, td])
    if name == "mzv":
        return _mzv(freq, dr)
    if name == "ei":
        v = 1.0 / VIBRATION_REDUCTION
        a1 = (0.24968 + 0.24961 * v) + ((0.80008 + 1.23328 * v) + (0.49599 + 3.17316 * v) * dr) * dr
        a3 = (0.25149 + 0.21474 * v) + ((-0.83249 + 1.41498 * v) + (0.85181 - 4.90094 * v) * dr) * dr
        t2 = 0.4999 + (((0.46159 + 8.57843 * v) * v) + (((4.26169 - 108.644 * v) * v)
                                                       + ((1.75601 + 336.989 * v) * v) * dr) * dr) * dr
        return np.array([a1, 1.0 - a1 - a3, a3]), np.array([0.0, t2 * td, td])
    if name == "2hump_ei":
        return _expansion(freq, dr, _EI2_T, _EI2_A)
    if name == "3hump_ei":
        return _expansion(freq, dr, _EI3_T, _EI3_A)
    raise ValueError(name)


# ---------------------------------------------------------------- reading

class Dataset:
    """One PSD data set: bins [Hz] and the (normalised) summed PSD."""

    def __init__(self, freq, psd):
        self.freq, self.psd = np.asarray(freq, float), np.asarray(psd, float)


def normalize(freq, psd):
    psd = psd / (freq + 0.1)
    low = freq < 10.0
    psd[low] *= np.exp(-(10.0 / (freq[low] + 0.1)) ** 2 + 1.0)
    return psd


def _window_psd(x, fs, M):
    w = np.kaiser(M, 6.0)
    step = M - M // 2
    n = (x.size - M // 2) // step
    seg = np.lib.stride_tricks.as_strided(x, shape=(M, n), strides=(x.strides[0],
                                                                    step * x.strides[0]))
    seg = w[:, None] * (seg - seg.mean(axis=0))
    X = np.fft.rfft(seg, axis=0)
    P = (X.real ** 2 + X.imag ** 2) / (w ** 2).sum() / fs
    P[1:-1] *= 2.0
    return np.fft.rfftfreq(M, 1.0 / fs), P.mean(axis=-1)


def raw_psd(data):
    """(freq, psd_sum, [px, py, pz]) of a raw record ``data`` (n, 4), before normalisation."""
    N = data.shape[0]
    fs = N / (data[-1, 0] - data[0, 0])
    M = 1 << int(fs * 0.5 - 1).bit_length()
    if N <= M:
        raise ValueError("record shorter than one segment")
    parts = [_window_psd(np.ascontiguousarray(data[:, j]), fs, M) for j in (1, 2, 3)]
    f = parts[0][0]
    return f, sum(p for _, p in parts), [p for _, p in parts]


def load(path) -> list[Dataset]:
    with open(path) as fh:
        header = ""
        for header in fh:
            if not header.startswith("#"):
                break
    if not header.startswith("freq,"):
        data = np.loadtxt(path, comments="#", delimiter=",")
        f, psd, _ = raw_psd(data)
        return [Dataset(f, normalize(f, psd))]
    data = np.genfromtxt(path, dtype=np.float64, skip_header=1, comments="#", delimiter=",",
                         filling_values=0.0)
    if header.startswith("freq,psd_x,psd_y,psd_z,psd_xyz"):
        sets = [Dataset(data[:, 0], data[:, 4])]
    else:
        names = next(csv.reader([header.strip()]))
        sets = []
        for i, name in enumerate(names[1:]):
            if name == "shapers:":
                break
            sets.append(Dataset(data[:, 0], data[:, i + 1]))
    if ",shapers:" not in header:
        sets = [Dataset(d.freq, normalize(d.freq, d.psd.copy())) for d in sets]
    return sets


# ---------------------------------------------------------------- figures

def residual(A, T, dr, f):
    """The firmware's residual ratio R(f) of impulses (A, T) at damping dr."""
    A, T = np.asarray(A, float), np.asarray(T, float)
    omega = 2 * math.pi * np.asarray(f, float)
    W = A * np.exp(np.outer(-dr * omega, T[-1] - T))
    od = omega * math.sqrt(1 - dr * dr)
    S = (W * np.sin(np.outer(od, T))).sum(axis=1)
    C = (W * np.cos(np.outer(od, T))).sum(axis=1)
    return np.hypot(S, C) / A.sum()


def _bins(ds, max_freq=MAX_FREQ):
    keep = ds.freq <= max_freq
    return ds.freq[keep], ds.psd[keep]


def remaining(A, T, datasets, dampings=TEST_DAMPINGS, max_freq=MAX_FREQ) -> float:
    """The firmware's own estimate of the vibrations impulses (A, T) leave (a fraction): the
    worst over the test dampings and the data sets."""
    worst = 0.0
    for ds in datasets:
        f, psd = _bins(ds, max_freq)
        thr = psd.max() / VIBRATION_REDUCTION
        total = np.maximum(psd - thr, 0).sum()
        for dr in dampings:
            left = np.maximum(residual(A, T, dr, f) * psd - thr, 0).sum()
            worst = max(worst, left / total)
    return worst


def smoothing(A, T, accel=5000.0, scv=5.0):
    A, T = np.asarray(A, float), np.asarray(T, float)
    inv_D = 1.0 / A.sum()
    ts = float(A @ T) * inv_D
    after = T >= ts
    d = T - ts
    off90 = float(np.sum((A * (scv + 0.5 * accel * d) * d)[after])) * inv_D * math.sqrt(2)
    off180 = float(np.sum(A * 0.5 * accel * d * d)) * inv_D
    return max(off90, off180)


def max_accel(A, T, scv=5.0, target=0.12):
    ok = lambda a: smoothing(A, T, a, scv) <= target      # noqa: E731
    left = right = 1.0
    if not ok(1e-9):
        return 0.0
    while not ok(left):
        right = left
        left *= 0.5
    if right == left:
        while ok(right):
            right *= 2.0
    while right - left > 1e-8:
        mid = 0.5 * (left + right)
        if ok(mid):
            left = mid
        else:
            right = mid
    return left


def _fit(name, datasets):
    results = []
    best = None
    for freq in np.arange(MIN_FREQ[name], MAX_SHAPER_FREQ, 0.2)[::-1]:
        A, T = shaper(name, float(freq))
        vib = remaining(A, T, datasets)
        sm = smoothing(A, T)
        res = dict(name=name, freq=float(freq), vibrs=vib, smoothing=sm,
                   score=sm * (vib ** 1.5 + 0.2 * vib + 0.01), duration=float(T[-1]), A=A, T=T)
        results.append(res)
        if best is None or best["vibrs"] > vib:
            best = res
    selected = best
    for res in results[::-1]:
        if res["vibrs"] < best["vibrs"] * 1.1 + 0.0005 and res["score"] < selected["score"]:
            selected = res
    return selected, results


def best_shaper(datasets) -> dict:
    """The firmware's recommendation on ``datasets`` (see :func:`load`): a dict with name,
    freq, vibrs (its own estimate, a fraction), smoothing, score, duration [s], A, T and
    max_accel."""
    best = None
    tuned = []
    for name in SHAPERS:
        s, results = _fit(name, datasets)
        if (best is None or s["score"] * 1.2 < best["score"]
                or (s["score"] * 1.05 < best["score"] and s["smoothing"] * 1.1 < best["smoothing"])):
            best = s
        for r in results[::-1]:
            if r["vibrs"] < best["vibrs"] and r["smoothing"] < best["smoothing"]:
                best = s = r
        tuned.append(s)
    if best["name"] == "zv":
        for s in tuned:
            if s["name"] != "zv" and s["vibrs"] * 1.1 < best["vibrs"]:
                best = s
                break
    best = dict(best, max_accel=max_accel(best["A"], best["T"]))
    return best


def taps_as_impulses(h, Ts):
    """(A, T) of a discrete filter's taps h at sample period Ts (the nonzero taps)."""
    h = np.asarray(h, float)
    k = np.flatnonzero(h)
    return h[k], (k - k[0]) * Ts
