# SPDX-License-Identifier: Apache-2.0
"""Synthetic records of plants with known modes, in all four input kinds (for tests, the
benchmark and the shipped examples).

The plant is ``plants.series(plants.mode(wn_i, zeta_i) ...)`` (commanded acceleration ->
measured acceleration), simulated exactly: ``plants.simulate_zoh`` (matrix exponential) on the
nominal grid, and each sample's state carried from its grid instant to its jittered instant by
the Taylor series of the matrix exponential over that sub-sample interval (terms to the 6th
order: below 1e-13 relative for |A| dt < 0.05).
"""
from __future__ import annotations

import math

import numpy as np

from .. import plants

__all__ = ["plant", "sweep_input", "resonance_record", "decay_record", "psd_table",
           "frequency_response", "write_csv"]


def plant(modes):
    """``modes``: [(wn [rad/s], zeta), ...] -> the series plant."""
    return plants.series(*[plants.mode(wn=wn, zeta=z) for wn, z in modes])


def _noise(y, snr_db, rng):
    return rng.normal(0.0, math.sqrt(np.mean(y ** 2)) / 10 ** (snr_db / 20), y.size)


def _at_jittered_times(p, u, Ts, jitter, rng):
    """(t, y): samples at t_k = k Ts + d_k, d_k uniform in [0, jitter Ts), u held over
    [k Ts, (k+1) Ts)."""
    n = u.size
    Ad, Bd = plants.zoh_matrices(p, Ts)
    x = np.zeros((n, p.order))
    xk = np.zeros(p.order)
    for k in range(n):
        x[k] = xk
        xk = Ad @ xk + Bd * u[k]
    d = rng.uniform(0.0, jitter * Ts, n) if jitter > 0 else np.zeros(n)
    # x(t_k + d) = x_k + sum_{m>=1} d^m/m! A^{m-1} (A x_k + B u_k)
    dx = x @ p.A.T + np.outer(u, p.B)
    term = dx * d[:, None]
    xs = x + term
    for m in range(2, 7):
        term = (term @ p.A.T) * (d[:, None] / m)
        xs = xs + term
    y = xs @ p.C + p.D * u
    return np.arange(n) * Ts + d, y


def sweep_input(fs: float, T: float, f0: float = 5.0, f1: float = 120.0,
                accel_per_hz: float = 75.0) -> np.ndarray:
    """A resonance test's commanded acceleration: a linear sine sweep f0 -> f1 [Hz] whose
    amplitude grows with the frequency (``accel_per_hz`` f), as 3-D printer firmware runs it."""
    Ts = 1.0 / fs
    t = np.arange(int(round(T * fs))) * Ts
    f = f0 + (f1 - f0) * t / T
    return accel_per_hz * f * np.sin(2 * np.pi * np.cumsum(f) * Ts)


def resonance_record(modes, *, fs=3200.0, T=None, snr_db=30.0, jitter=0.01, seed=0,
                     axes=1, offsets=(0.0, 0.0, 9810.0), f0=None, f1=None, rate=2.0):
    """(t, accel (n, axes)): the first axis is the plant's response to the sweep; further axes
    see it scaled by 0.3 and 0.05 (cross-talk), each with its own noise and offset. The sweep
    runs from f0 (default 5 Hz) to f1 (2 x the highest mode) at ``rate`` Hz/s
    unless T [s] is given: a sweep much faster than a mode's decay distorts its peak (the
    firmware's test sweeps at 1 Hz/s)."""
    rng = np.random.default_rng(seed)
    fmodes = [wn / (2 * math.pi) for wn, _ in modes]
    f0 = min(5.0, 0.5 * min(fmodes)) if f0 is None else f0
    f1 = 2.0 * max(fmodes) if f1 is None else f1
    T = (f1 - f0) / rate if T is None else T
    u = sweep_input(fs, T, f0, f1)
    t, y = _at_jittered_times(plant(modes), u, 1.0 / fs, jitter, rng)
    cols = []
    for j, scale in enumerate((1.0, 0.3, 0.05)[:axes]):
        cols.append(scale * y + _noise(y, snr_db, rng) + offsets[j])
    return t, np.column_stack(cols)


def decay_record(modes, *, fs=2000.0, T=None, snr_db=30.0, jitter=0.01, offset=0.7, seed=0):
    """(t, x): free decay of the plant after a step of the command (held), plus an offset."""
    rng = np.random.default_rng(seed)
    slowest = min(z * wn for wn, z in modes)
    T = T if T is not None else min(8.0 / slowest, 20.0)
    p = plant(modes)
    n = int(round(T * fs))
    # start from rest at 0 with the command stepped to 1: a free decay towards 1
    u = np.ones(n)
    t, y = _at_jittered_times(p, u, 1.0 / fs, jitter, rng)
    y = y - 1.0
    sd = math.sqrt(np.mean(y[: n // 4] ** 2)) / 10 ** (snr_db / 20)
    return t, y + rng.normal(0.0, sd, n) + offset


def psd_table(modes, **kw):
    """(f [Hz], PSD): the Welch PSD of a resonance record, as calibration tools write it."""
    from .modes import welch
    t, a = resonance_record(modes, **kw)
    fs = kw.get("fs", 3200.0)
    spec = welch(a[:, 0], 1.0 / fs)
    return spec.f, spec.P


def frequency_response(modes, *, f=None, snr_db=30.0, seed=0):
    """(f [Hz], |H|, phase [deg]) of the plant with multiplicative noise at ``snr_db``."""
    rng = np.random.default_rng(seed)
    f = np.linspace(2.0, 200.0, 1200) if f is None else np.asarray(f, dtype=float)
    H = plant(modes).transfer(2j * np.pi * f)
    noise = 10 ** (-snr_db / 20)
    H = H * (1 + noise * (rng.normal(size=f.size) + 1j * rng.normal(size=f.size)) / math.sqrt(2))
    return f, np.abs(H), np.rad2deg(np.unwrap(np.angle(H)))


def write_csv(path, columns, header, fmt="%.9g"):
    np.savetxt(path, np.column_stack(columns), delimiter=",", header=",".join(header),
               comments="#", fmt=fmt)
