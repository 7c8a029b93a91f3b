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

__all__ = ["plant", "sweep_input", "resonance_record", "decay_record", "psd_table", "CATEGORIES",
           "klipper_sweep", "category_record", "modal_energies", "true_remaining",
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


# ---------------------------------------------------------------- real-sensor categories

#: ADXL345 at +-16 g in full resolution: 3.9 mg per LSB [mm/s^2], and its range.
ADXL_LSB = 3.9e-3 * 9806.65
ADXL_RANGE = 16 * 9806.65
TWO_PI = 2 * math.pi

#: The synthetic campaign's categories: (modes [(f Hz, zeta)], options).
CATEGORIES = {
    "adxl345 quantised": ([(48.0, 0.05)], {"quantise": True}),
    "clipped": ([(45.0, 0.03)], {"quantise": True, "overshoot": 1.5}),
    "fifo gaps": ([(52.0, 0.06)], {"gaps": True}),
    "klipper sweep": ([(41.0, 0.07)], {}),
    "three modes": ([(35.0, 0.04), (58.0, 0.06), (92.0, 0.05)], {}),
    "two modes 2 Hz apart": ([(47.0, 0.015), (49.0, 0.015)], {}),
    "zeta 0.25": ([(55.0, 0.25)], {}),
    "y mode seen on x": ([(62.0, 0.05)], {"cross": (44.0, 0.04, 0.5)}),
    "sensor rotated 45 deg": ([(50.0, 0.05)], {"rotate": 45.0}),
    "amplitude-dependent stiffness": ([(46.0, 0.05)], {"softening": 0.04}),
    "20 Hz belt mode": ([(20.0, 0.05), (55.0, 0.06)], {}),
    "mode at the sweep start": ([(12.0, 0.06)], {"f0": 10.0}),
}


def klipper_sweep(fs: float, f0: float = 5.0, f1: float = 133.0, hz_per_sec: float = 1.0,
                  accel_per_hz: float = 60.0, sweeping_accel: float = 400.0,
                  sweeping_period: float = 1.2) -> np.ndarray:
    """The commanded acceleration of Klipper's resonance test (resonance_tester.py,
    K. O'Connor and D. Butyugin): a square wave, +-accel_per_hz f for a quarter period each
    way, its frequency rising by hz_per_sec, plus a slow square wave of +-sweeping_accel over
    sweeping_period (the "sweeping" that keeps the toolhead from sticking), sampled at fs."""
    times, accels = [], []
    f, t, sign = f0, 0.0, 1.0
    while f <= f1 + 1e-6:
        seg = 0.25 / f
        for s in (sign, -sign):
            t += seg
            times.append(t)
            accels.append(s * accel_per_hz * f)
        f += 2 * seg * hz_per_sec
        sign = -sign
    times = np.array(times)
    n = int(times[-1] * fs)
    ts = np.arange(n) / fs
    idx = np.minimum(np.searchsorted(times, ts, side="right"), len(accels) - 1)
    u = np.asarray(accels)[idx]
    if sweeping_period:
        u = u + sweeping_accel * np.where((ts // (0.5 * sweeping_period)) % 2 == 0, 1.0, -1.0)
    return u


def _response(modes_hz, u, fs, rng, jitter=0.01):
    p = plant([(TWO_PI * f, z) for f, z in modes_hz])
    return _at_jittered_times(p, u, 1.0 / fs, jitter, rng)


def _normalised_excitation(f):
    """The test's excitation in the spectrum the figures score: Klipper's sweep commands an
    acceleration of accel_per_hz f at a constant rate (power ~ f^2 per Hz), then divided by
    f + 0.1 and cut below 10 Hz (:func:`.spectra.normalize_to_excitation`)."""
    out = f * f / (f + 0.1)
    low = f < 10.0
    out[low] *= np.exp(1.0 - (10.0 / (f[low] + 0.1)) ** 2)
    return out


def modal_energies(modes_hz, gain2: float = 1.0) -> list[float]:
    """Each mode's energy in the normalised spectrum a resonance test of the series plant of
    ``modes_hz`` measures: the plant's transfer split into its modes by partial fractions,
    ``G(s) = sum_i r_i/(s - p_i) + conj``, and ``gain2 int E(f) |G_i(j 2 pi f)|^2 df`` with E
    the test's normalised excitation. A mode in series behind another is seen through the
    other's roll-off: its energy is what the plant's output actually carries, not that of the
    mode alone."""
    p = plant([(TWO_PI * f, z) for f, z in modes_hz])
    lam, V = np.linalg.eig(p.A)
    res = (p.C @ V) * np.linalg.solve(V, p.B)
    fmax = 4.0 * max(f for f, _ in modes_hz)
    f = np.linspace(fmax / 40000.0, fmax, 40000)
    s = 2j * math.pi * f
    E = _normalised_excitation(f)
    out = []
    for fn, z in modes_hz:
        target = complex(-z * TWO_PI * fn, TWO_PI * fn * math.sqrt(1 - z * z))
        i = int(np.argmin(np.abs(lam - target)))
        Gi = res[i] / (s - lam[i]) + np.conj(res[i]) / (s - np.conj(lam[i]))
        out.append(gain2 * float(np.sum(E * np.abs(Gi) ** 2)) * (f[1] - f[0]))
    return out


def category_record(name: str, seed: int = 0, fs: float = 1600.0):
    """(t, accel (n, 3) [mm/s^2], true modes [(f Hz, zeta, energy)], frequency shift of the
    modes over the record) of the campaign's category ``name`` (:data:`CATEGORIES`): Klipper's sweep
    from 5 Hz (10 Hz for the mode at the sweep start) to 133 Hz at 1 Hz/s, 1 % time-stamp
    jitter, noise at 0.3 % of the signal; each category adds what it names (clipped: the
    resonance drives the sensor to 1.5 times its range). The modes are
    perturbed by the seed (+-4 % in frequency, +-20 % in damping)."""
    base, opt = CATEGORIES[name]
    rng = np.random.default_rng(seed)
    modes = [(f * (1 + rng.uniform(-0.04, 0.04)), z * (1 + rng.uniform(-0.2, 0.2)))
             for f, z in base]
    if name == "two modes 2 Hz apart":
        modes[1] = (modes[0][0] + 2.0, modes[1][1])
    u = klipper_sweep(fs, f0=opt.get("f0", 5.0))
    shift = 0.0
    if opt.get("softening"):
        # stiffness falling with the amplitude: the record is simulated in pieces, each mode's
        # frequency lowered by up to `softening` where the response is largest
        k = opt["softening"]
        t, y = _response(modes, u, fs, rng)
        env = np.convolve(np.abs(y), np.ones(int(0.2 * fs)) / int(0.2 * fs), mode="same")
        level = env / env.max()
        out = np.empty_like(y)
        piece = int(0.5 * fs)
        for a in range(0, u.size, piece):
            drop = k * float(level[a: a + piece].mean())
            m2 = [(f * (1 - drop), z) for f, z in modes]
            _, yy = _response(m2, u[max(0, a - 4 * piece): a + piece], fs, rng, jitter=0.0)
            out[a: a + piece] = yy[-min(piece, u.size - a):]
        y = out
        shift = k
    else:
        t, y = _response(modes, u, fs, rng)
    x = y
    cols = [x, 0.05 * x, 0.02 * x]
    truth = [(f, z, w) for (f, z), w in zip(modes, modal_energies(modes, 1 + 0.05 ** 2
                                                                    + 0.02 ** 2))]
    if opt.get("cross"):
        fc, zc, gain = opt["cross"]
        fc *= 1 + rng.uniform(-0.04, 0.04)
        _, yc = _response([(fc, zc)], u, fs, rng)
        cols = [x + gain * (yc - u), 0.05 * x + (yc - u), cols[2]]
        # the relative acceleration yc - u has the mode's poles and residues
        truth.append((fc, zc, modal_energies([(fc, zc)], gain ** 2 + 1.0)[0]))
    A = np.column_stack(cols)
    if opt.get("rotate"):
        r = math.radians(opt["rotate"])
        R = np.array([[math.cos(r), -math.sin(r), 0], [math.sin(r), math.cos(r), 0], [0, 0, 1]])
        A = A @ R.T
    if opt.get("overshoot"):
        # the resonance drives the sensor past its range: the peak is `overshoot` times it
        A = A * (opt["overshoot"] * ADXL_RANGE / float(np.max(np.abs(A))))
    A = A + rng.normal(0.0, 0.003 * float(np.sqrt(np.mean(A[:, 0] ** 2))), A.shape)
    A[:, 2] += 9806.65                                   # gravity on z
    if opt.get("quantise"):
        A = np.clip(np.round(A / ADXL_LSB) * ADXL_LSB, -ADXL_RANGE, ADXL_RANGE)
    if opt.get("gaps"):
        keep = np.ones(t.size, dtype=bool)
        n_missing = int(rng.uniform(0.02, 0.035) * t.size)
        while np.count_nonzero(~keep) < n_missing:
            a = int(rng.integers(0, t.size))
            keep[a: a + int(rng.uniform(0.010, 0.050) * fs)] = False
        t, A = t[keep], A[keep]
    return t, A, truth, shift


def true_remaining(A_imp, t_imp, modes, shift=0.0) -> float:
    """The remaining vibration [%] impulses (A, t [s]) leave on the true plant: the PRV
    e^{-zeta wn t_n} |sum A e^{-p t}| of each true mode (Singer and Seering), the RMS over the
    modes weighted by each one's energy in the test's normalised spectrum (``modes``: (f [Hz],
    zeta, energy) as :func:`category_record` returns them, :func:`modal_energies`), and for a
    mode whose frequency moved by up to ``shift`` over the record, the RMS over that range."""
    A = np.asarray(A_imp, dtype=float) / float(np.sum(A_imp))
    t = np.asarray(t_imp, dtype=float)
    L = float(t[np.flatnonzero(A)[-1]])
    num = den = 0.0
    for f, z, w in modes:
        fs = np.linspace(f * (1 - shift), f, 9) if shift else np.array([f])
        wn = TWO_PI * fs
        p = -z * wn + 1j * wn * math.sqrt(1 - z * z)
        R2 = np.abs(np.exp(-np.outer(p, t)) @ A) ** 2 * np.exp(-2 * z * wn * L)
        num += w * float(np.mean(R2))
        den += w
    return 100 * math.sqrt(num / den)
