# SPDX-License-Identifier: Apache-2.0
"""The established 3-D printer calibration's pick (Klipper's scripts/calibrate_shaper.py and
klippy/extras/shaper_calibrate.py, as published by K. O'Connor and D. Butyugin), written here
from its description for the comparison tests:

* PSD: Welch, Kaiser window (beta 6) of 2^k samples covering >= 0.5 s, 50 % overlap, mean
  removed per window; divided by (f + 0.1) and zeroed below 5 Hz ("normalize_to_frequencies").
* For each auto-tuned shaper (zv, mzv, ei, 2hump_ei, 3hump_ei, tolerance 0.05, designed with
  damping ratio 0.1) and each frequency from its minimum (21, 23, 29, 39, 48 Hz) to 150 Hz in
  0.2 Hz steps: remaining vibrations = sum(max(R psd - psd.max()/20, 0)) / sum(max(psd -
  psd.max()/20, 0)), R the shaper's residual at damping 0.075, 0.1 and 0.15 (the worst counts);
  smoothing at accel 5000, square-corner velocity 5; score = smoothing (v^1.5 + 0.2 v + 0.01).
  Per shaper: the least-vibration frequency, then the lowest score among frequencies with
  vibrations < 1.1 x that.
* Across shapers: a later one replaces the pick when its score is 20 % lower, or 5 % lower with
  10 % less smoothing.
"""
from __future__ import annotations

import math

import numpy as np
import scipy.signal

VIBRATION_REDUCTION = 20.0
DAMPING = 0.1
TEST_DAMPINGS = (0.075, 0.1, 0.15)
MIN_FREQ = {"zv": 21.0, "mzv": 23.0, "ei": 29.0, "2hump_ei": 39.0, "3hump_ei": 48.0}
OUR_KIND = {"zv": "zv", "mzv": "mzv", "ei": "ei", "2hump_ei": "ei2", "3hump_ei": "ei3"}


def shaper(name, f, dr):
    df = math.sqrt(1 - dr * dr)
    K = math.exp(-dr * math.pi / df)
    td = 1.0 / (f * df)
    v = 1.0 / VIBRATION_REDUCTION
    if name == "zv":
        return np.array([1.0, K]), np.array([0.0, 0.5 * td])
    if name == "mzv":
        K = math.exp(-0.75 * dr * math.pi / df)
        a1 = 1 - 1 / math.sqrt(2)
        return np.array([a1, (math.sqrt(2) - 1) * K, a1 * K * K]), np.array([0, .375 * td, .75 * td])
    if name == "ei":
        a1 = 0.25 * (1 + v)
        return np.array([a1, 0.5 * (1 - v) * K, a1 * K * K]), np.array([0, .5 * td, td])
    if name == "2hump_ei":
        V2 = v * v
        X = (V2 * (math.sqrt(1 - V2) + 1)) ** (1 / 3)
        a1 = (3 * X * X + 2 * X + 3 * V2) / (16 * X)
        a2 = (0.5 - a1) * K
        return np.array([a1, a2, a2 * K, a1 * K ** 3]), np.array([0, .5, 1, 1.5]) * td
    a1 = 0.0625 * (1 + 3 * v + 2 * math.sqrt(2 * (v + 1) * v))
    a2 = 0.25 * (1 - v) * K
    a3 = (0.5 * (1 + v) - 2 * a1) * K * K
    return np.array([a1, a2, a3, a2 * K * K, a1 * K ** 4]), np.array([0, .5, 1, 1.5, 2]) * td


def residual(A, T, dr, f):
    omega = 2 * math.pi * f
    W = A * np.exp(np.outer(-dr * omega, T[-1] - T))
    od = omega * math.sqrt(1 - dr * dr)
    S = (W * np.sin(np.outer(od, T))).sum(axis=1)
    C = (W * np.cos(np.outer(od, T))).sum(axis=1)
    return np.hypot(S, C) / A.sum()


def smoothing(A, T, accel=5000.0, scv=5.0):
    inv_D = 1 / A.sum()
    ts = float(np.dot(A, T)) * inv_D
    off90 = sum(a * (scv + 0.5 * accel * (t - ts)) * (t - ts) for a, t in zip(A, T) if t >= ts)
    off180 = sum(a * 0.5 * accel * (t - ts) ** 2 for a, t in zip(A, T))
    return max(off90 * inv_D * math.sqrt(2), off180 * inv_D)


def psd(t, x):
    fs = (x.size - 1) / (t[-1] - t[0])          # samples taken as uniform, like the firmware
    M = 1 << int(fs * 0.5 - 1).bit_length()
    f, P = scipy.signal.welch(x, fs=fs, window=("kaiser", 6.0), nperseg=M, noverlap=M // 2,
                              detrend="constant", scaling="density")
    P = P / (f + 0.1)
    P[f < 5.0] = 0.0
    keep = f <= 200.0
    return f[keep], P[keep]


def fit(name, f, P):
    threshold = P.max() / VIBRATION_REDUCTION
    total = np.maximum(P - threshold, 0).sum()
    results = []
    best = None
    for freq in np.arange(MIN_FREQ[name], 150.0, 0.2)[::-1]:
        A, T = shaper(name, freq, DAMPING)
        vib = max(np.maximum(residual(A, T, dr, f) * P - threshold, 0).sum() / total
                  for dr in TEST_DAMPINGS)
        sm = smoothing(A, T)
        res = dict(name=name, freq=float(freq), vibrs=vib, smoothing=sm,
                   score=sm * (vib ** 1.5 + 0.2 * vib + 0.01), duration=float(T[-1]))
        results.append(res)
        if best is None or best["vibrs"] > vib:
            best = res
    selected = best
    for res in results[::-1]:
        if res["vibrs"] < best["vibrs"] * 1.1 and res["score"] < selected["score"]:
            selected = res
    return selected


def best_shaper(t, x) -> dict:
    f, P = psd(t, x)
    best = None
    for name in ("zv", "mzv", "ei", "2hump_ei", "3hump_ei"):
        s = fit(name, f, P)
        if (best is None or s["score"] * 1.2 < best["score"]
                or (s["score"] * 1.05 < best["score"] and s["smoothing"] * 1.1 < best["smoothing"])):
            best = s
    return best
