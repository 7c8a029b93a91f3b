# SPDX-License-Identifier: Apache-2.0
"""Modes (wn, zeta, uncertainty, weight): the dataclass, and the fit of a free decay.

Spectra (resonance tests, PSD tables, frequency responses) are fitted in :mod:`.spectral_fit`.
Free decays: the whole record is fitted with ``c + sum_i e^{sigma_i t}(A_i cos wd_i t +
B_i sin wd_i t)``, one term per spectral peak, started from the C core's one-mode fit
(``sms_identify_from_record``); a record the model explains poorly (a sweep, noise) is refused.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .records import RecordError
from .spectra import Spectrum, welch   # noqa: F401  (re-exported: the spectra live there)

__all__ = ["DECAY_MIN_R2", "Mode", "Spectrum", "welch", "decay_modes", "check_free_decay"]

#: A free-decay fit must explain this fraction of the signal's variance.
DECAY_MIN_R2 = 0.8


@dataclass(frozen=True)
class Mode:
    """One identified mode: natural frequency ``wn`` [rad/s] and damping ratio ``zeta`` with
    their standard deviations, and ``weight``, its share of the measured vibration energy."""
    wn: float
    zeta: float
    wn_std: float
    zeta_std: float
    weight: float = 1.0
    weight_rsd: float = 0.0        # relative standard deviation of the weight
    at_edge: bool = False          # within 3 half-power widths of the band's end

    @property
    def f_hz(self) -> float:
        return self.wn / (2 * math.pi)

    def as_dict(self) -> dict:
        return {"wn": self.wn, "wn_std": self.wn_std, "zeta": self.zeta,
                "zeta_std": self.zeta_std, "f_hz": self.f_hz, "weight": self.weight,
                "at_band_edge": self.at_edge}


# ---------------------------------------------------------------- free decays

def _decay_model(th, t, n_modes, values=False):
    c = th[0]
    out = np.full(t.shape, c)
    jac = [np.ones_like(t)]
    for i in range(n_modes):
        A, B, sigma, wd = th[1 + 4 * i: 5 + 4 * i]
        e = np.exp(sigma * t)
        co, si = np.cos(wd * t), np.sin(wd * t)
        osc = e * (A * co + B * si)
        out = out + osc
        if not values:
            jac += [e * co, e * si, t * osc, e * t * (-A * si + B * co)]
    return out if values else (out, np.column_stack(jac))


def decay_modes(x: np.ndarray, Ts: float, *, path: str, column: str,
                band: tuple[float, float] | None = None) -> tuple[list[Mode], float]:
    """Modes of a free decay (any offset) by a whole-record least-squares fit; returns
    (modes largest first, R^2 of the fit). RecordError for a record that is not a decay."""
    from scipy.optimize import least_squares
    import scipy.signal
    from ..filters import identify_from_record, ParameterError
    from . import decay_decimation as dd
    full, n_full = x, x.size
    # a long record is fitted at the rate its content needs (decay_decimation: same modes,
    # same uncertainty, bounded memory); R^2 is still that of every sample
    idx, x, q = dd.fit_rate(full, Ts, band)
    t = idx * Ts
    try:
        seed = identify_from_record(x, Ts=q * Ts)
    except (ParameterError, ValueError) as exc:
        raise RecordError(path, f"not a free decay: the one-mode fit fails ({exc})",
                          column=column) from None
    # further modes: peaks of the decay's periodogram other than the seed's
    f, P = scipy.signal.periodogram(x - np.mean(x), fs=1 / (q * Ts), window="hann")
    peaks, _ = scipy.signal.find_peaks(np.log10(np.maximum(P, 1e-300)), prominence=1.0)
    f_lo, f_hi = band if band else (0.0, 0.45 / Ts)
    extra = [f[p] for p in sorted(peaks, key=lambda p: -P[p])
             if f_lo <= f[p] <= f_hi and abs(f[p] - seed.wd / (2 * math.pi)) > 3 / (n_full * Ts)]
    starts = [(seed.sigma, seed.wd)] + [(-0.02 * 2 * math.pi * fe, 2 * math.pi * fe)
                                        for fe in extra[:2]]
    best = None
    for n_modes in range(1, len(starts) + 1):
        th0 = [float(np.mean(x[-max(1, x.size // 10):]))]
        for sigma, wd in starts[:n_modes]:
            th0 += [0.0, 0.0, sigma, wd]
        th0 = np.array(th0)
        # amplitudes by linear least squares for the start frequencies
        _, J = _decay_model(th0, t, n_modes)
        cols = [0] + [j for i in range(n_modes) for j in (1 + 4 * i, 2 + 4 * i)]
        lin = np.linalg.lstsq(J[:, cols], x, rcond=None)[0]
        th0[cols] = lin
        with np.errstate(over="ignore", invalid="ignore"):
            res = least_squares(lambda th: _decay_model(th, t, n_modes)[0] - x, th0,
                                jac=lambda th: _decay_model(th, t, n_modes)[1], method="lm")
        if not np.all(np.isfinite(res.fun)):
            continue
        ssr = float(np.sum(res.fun ** 2))
        if n_modes > 1:
            # a further term must be a decaying oscillation of its own, not a fit of the noise
            amp = [math.hypot(*res.x[1 + 4 * i: 3 + 4 * i]) for i in range(n_modes)]
            sig = [res.x[3 + 4 * i] for i in range(n_modes)]
            if max(sig) >= 0 or min(amp) < 1e-2 * max(amp):
                continue
        r2 = 1.0 - ssr / float(np.sum((x - np.mean(x)) ** 2)) if q == 1 else None
        k = th0.size
        # keep a further mode only if it explains clearly more (an F-test-like margin)
        if best is None or ssr < best[1] * (1 - 10.0 * (k - best[3]) / x.size):
            best = (res, ssr, r2, k, n_modes)
    if best is None:
        raise RecordError(path, "not a free decay: the damped-oscillation fit diverges",
                          column=column)
    res, ssr, r2, k, n_modes = best
    if r2 is None:
        total = dd.residual_sum(lambda th, tt: _decay_model(th, tt, n_modes, values=True),
                                res.x, full, Ts)
        r2 = 1.0 - total / float(np.sum((full - np.mean(full)) ** 2))
    if r2 < DECAY_MIN_R2:
        raise RecordError(path, f"not a free decay: a sum of damped oscillations explains only "
                          f"{100 * max(r2, 0):.0f} % of the signal (a decay: > "
                          f"{100 * DECAY_MIN_R2:.0f} %); a resonance test or sweep is read with "
                          "--kind raw", column=column)
    s2 = ssr / max(1, x.size - k)
    try:
        with np.errstate(over="ignore", invalid="ignore"):   # a diverged fit: refused below
            cov = np.linalg.inv(res.jac.T @ res.jac) * s2
    except np.linalg.LinAlgError:
        cov = None
    if cov is None or not np.all(np.isfinite(cov)):
        raise RecordError(path, "the decay fit is degenerate (no oscillation, or one that "
                          "grows past the double range?)", column=column)
    modes = []
    for i in range(n_modes):
        A, B, sigma, wd = res.x[1 + 4 * i: 5 + 4 * i]
        if not (sigma < 0 and wd > 0):
            raise RecordError(path, "not a free decay: the fitted oscillation does not decay "
                              f"(sigma = {sigma:.4g} 1/s)", column=column)
        C = cov[3 + 4 * i: 5 + 4 * i, 3 + 4 * i: 5 + 4 * i]   # (sigma, wd)
        wn = math.hypot(sigma, wd)
        zeta = -sigma / wn
        g_wn = np.array([sigma / wn, wd / wn])
        g_z = np.array([-1 / wn + sigma * sigma / wn ** 3, sigma * wd / wn ** 3])
        wn_sd = math.sqrt(max(g_wn @ C @ g_wn, 0.0))
        z_sd = math.sqrt(max(g_z @ C @ g_z, 0.0))
        weight = (A * A + B * B) / (4 * zeta * wn)
        modes.append(Mode(wn=wn, zeta=zeta, wn_std=wn_sd, zeta_std=z_sd, weight=weight))
    modes.sort(key=lambda m: -m.weight)
    return modes, r2


def check_free_decay(x: np.ndarray, Ts: float, *, path: str, column: str = "signal") -> float:
    """R^2 of the whole-record damped-oscillation fit; RecordError when it is not a decay (used
    by ``smoothshaper identify``, so a sweep never yields a confident wrong mode)."""
    return decay_modes(x, Ts, path=path, column=column)[1]
