# SPDX-License-Identifier: Apache-2.0
"""Modes (wn, zeta, uncertainty, weight) from a spectrum or a free decay.

Spectra (resonance tests, PSD tables, frequency responses): every significant peak of the
spectrum in the band is fitted by least squares (``scipy.optimize.least_squares``) on the log
scale, where the scatter of a Welch estimate is the same at every frequency, with the model

    S(f) = a r^q (1 + 4 zeta^2 r^2) / ((1 - r^2)^2 + (2 zeta r)^2) + b,    r = f / fn,

the base-excited mode (the load acceleration of ``plants.mode`` over the commanded one, squared)
times a local power law ``r^q`` for the excitation spectrum, plus a floor ``b``. For a Welch
estimate the model is first convolved with the window's spectral kernel (the expected value of a
Welch estimate is the true PSD convolved with |W(f)|^2), so a peak narrower than a few bins is
still fitted without bias. Standard deviations come from the Jacobian, ``cov = s^2 (J^T J)^-1``,
scaled by the window's equivalent noise bandwidth in bins (neighbouring Welch bins are
correlated).

Free decays: the whole record is fitted with ``c + sum_i e^{sigma_i t}(A_i cos wd_i t +
B_i sin wd_i t)``, one term per spectral peak, started from the C core's one-mode fit
(``sms_identify_from_record``); a record the model explains poorly (a sweep, noise) is refused.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .records import RecordError

__all__ = ["DECAY_MIN_R2", "Mode", "Spectrum", "welch", "spectral_modes", "decay_modes",
           "check_free_decay"]

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

    @property
    def f_hz(self) -> float:
        return self.wn / (2 * math.pi)

    def as_dict(self) -> dict:
        return {"wn": self.wn, "wn_std": self.wn_std, "zeta": self.zeta,
                "zeta_std": self.zeta_std, "f_hz": self.f_hz, "weight": self.weight}


@dataclass
class Spectrum:
    """A PSD (or |H|^2) on ``f`` [Hz]; ``kernel`` is the window's |W|^2 on a grid of
    ``df/oversample`` (None: the values are point samples), ``averages`` the number of Welch
    segments (None: unknown)."""
    f: np.ndarray
    P: np.ndarray
    kernel: np.ndarray | None = None
    oversample: int = 8
    averages: int | None = None
    enbw_bins: float = 1.0


def welch(x: np.ndarray, Ts: float, *, resolution: float | None = None) -> Spectrum:
    """Welch PSD (Hann, 75 % overlap, constant detrend) of one axis. Segment length: the
    largest power of two giving at least 4.5 record lengths' worth of segments, or the one for
    ``resolution`` [Hz]. 75 % overlap because the squared Hann windows then sum to a constant:
    a sweep's excitation is weighted evenly over the record (at 50 % it ripples by a factor 2
    with the segment hop, which biases the modal fit)."""
    import scipy.signal
    n = x.size
    if resolution is not None:
        nperseg = int(2 ** math.ceil(math.log2(1.0 / (resolution * Ts))))
    else:
        nperseg = int(2 ** math.floor(math.log2(max(16, n / 4.5))))
    nperseg = max(16, min(nperseg, n))
    f, P = scipy.signal.welch(x, fs=1.0 / Ts, window="hann", nperseg=nperseg,
                              noverlap=3 * nperseg // 4, detrend="constant", scaling="density")
    win = scipy.signal.get_window("hann", nperseg)
    over = 4
    W = np.abs(np.fft.fft(win, nperseg * over)) ** 2
    half = 5 * over                        # +- 5 bins: the Hann side lobes are below -55 dB
    kernel = np.r_[W[-half:], W[: half + 1]]
    kernel /= kernel.sum()
    segments = 1 + max(0, (n - nperseg) // (nperseg // 4))
    enbw = nperseg * np.sum(win ** 2) / np.sum(win) ** 2
    return Spectrum(f, P, kernel, over, segments, float(enbw))


def _shape(f, fn, zeta, q):
    r = f / fn
    return r ** q * (1 + 4 * zeta * zeta * r * r) / ((1 - r * r) ** 2 + (2 * zeta * r) ** 2)


class _PeakModel:
    """log S(f_bins; theta), theta = (log fn, log zeta, log a, q, log b)."""

    def __init__(self, spec: Spectrum, lo: int, hi: int, narrow: bool):
        self.f = spec.f[lo:hi]
        # a peak many bins wide is not changed by the window: skip the convolution
        self.kernel = spec.kernel if narrow else None
        if self.kernel is not None:
            df = spec.f[1] - spec.f[0]
            m = spec.oversample
            half = (spec.kernel.size - 1) // 2
            self.fine = spec.f[lo] + (np.arange((hi - lo - 1) * m + 1 + 2 * half) - half) * df / m
            self.step = m

    def __call__(self, th):
        fn, zeta, a, q, b = math.exp(th[0]), math.exp(th[1]), math.exp(th[2]), th[3], math.exp(th[4])
        if self.kernel is None:
            return np.log(a * _shape(self.f, fn, zeta, q) + b)
        fine = np.abs(self.fine)
        S = a * _shape(np.maximum(fine, 1e-12), fn, zeta, q)
        conv = np.convolve(S, self.kernel, mode="valid")[:: self.step]
        return np.log(conv + b)


def _fit_peak(spec: Spectrum, i_peak: int, lo: int, hi: int, zeta0: float):
    from scipy.optimize import least_squares
    df = spec.f[1] - spec.f[0]
    model = _PeakModel(spec, lo, hi, narrow=2 * zeta0 * spec.f[i_peak] < 25 * df)
    y = np.log(np.maximum(spec.P[lo:hi], 1e-300))
    fn0 = spec.f[i_peak]
    floor0 = max(float(np.min(spec.P[lo:hi])), 1e-30 * float(spec.P[i_peak]))
    a0 = max(float(spec.P[i_peak]) - floor0, 1e-300) * (2 * zeta0) ** 2
    th0 = np.array([math.log(fn0), math.log(zeta0), math.log(a0), 0.0, math.log(floor0)])
    lower = [math.log(spec.f[lo] if spec.f[lo] > 0 else spec.f[lo + 1]), math.log(1e-4),
             -np.inf, -6.0, -np.inf]
    upper = [math.log(spec.f[hi - 1]), math.log(0.7), np.inf, 6.0, np.inf]
    th0 = np.clip(th0, np.array(lower) + 1e-9, np.array(upper) - 1e-9)
    res = least_squares(lambda th: model(th) - y, th0, bounds=(lower, upper), method="trf",
                        x_scale="jac")
    n, k = y.size, th0.size
    ssr = float(np.sum(res.fun ** 2))
    s2 = ssr / max(1, n - k)
    # the same window without a peak: a power law plus the floor
    fw = spec.f[lo:hi]

    def null(c):
        return np.log(np.exp(c[0]) * (fw / fn0) ** c[1] + np.exp(c[2])) - y
    c0 = np.array([math.log(max(float(np.median(spec.P[lo:hi])), 1e-300)), 0.0,
                   math.log(floor0 * 1e-3)])
    ssr0 = float(np.sum(least_squares(null, c0, method="trf").fun ** 2))
    stat = (ssr0 - ssr) / (s2 * spec.enbw_bins) if s2 > 0 else math.inf
    # pinv: a floor far below the data (log b -> -inf) leaves a zero column, not an error
    cov = np.linalg.pinv(res.jac.T @ res.jac) * s2 * spec.enbw_bins
    th = res.x
    fn, zeta = math.exp(th[0]), math.exp(th[1])
    sd = np.sqrt(np.maximum(np.diag(cov), 0.0))
    if not np.all(np.isfinite(sd)):
        return None
    a, q, b = math.exp(th[2]), th[3], math.exp(th[4])
    at_edge = th[0] <= lower[0] + 1e-6 or th[0] >= upper[0] - 1e-6 or th[1] >= upper[1] - 1e-3
    grid = np.linspace(0.3 * fn, 3.0 * fn, 2000)
    weight = float(np.trapezoid(a * _shape(grid, fn, zeta, q), grid * 2 * math.pi))
    return dict(fn=fn, zeta=zeta, fn_sd=fn * sd[0], zeta_sd=zeta * sd[1], weight=weight,
                at_edge=at_edge, peak_over_floor=a / (2 * zeta) ** 2 / max(b, 1e-300), rms=math.sqrt(s2),
                stat=stat)


def spectral_modes(spec: Spectrum, band: tuple[float, float], *, path: str, column: str,
                   max_modes: int = 4) -> list[Mode]:
    """The significant modes of a spectrum in ``band`` [Hz], largest weight first.
    RecordError when there is none."""
    import scipy.signal
    f, P = spec.f, spec.P
    inband = np.flatnonzero((f >= band[0]) & (f <= band[1]) & (f > 0))
    if inband.size < 16:
        raise RecordError(path, f"only {inband.size} frequencies in the band {band[0]:.4g} to "
                          f"{band[1]:.4g} Hz: too few to fit a mode", column=column)
    i0, i1 = int(inband[0]), int(inband[-1]) + 1
    logP = np.log10(np.maximum(P[i0:i1], 1e-300))
    # candidate peaks at three smoothing scales (narrow peaks survive the finest, broad ones
    # rise above the scatter at the coarsest); each is then confirmed by its modal fit
    cands = []
    for width in (3, 9, 27):
        kern = np.hanning(width + 2)[1:-1]
        smooth = np.convolve(logP, kern / kern.sum(), mode="same")
        resid = logP - smooth
        sigma = 1.4826 * float(np.median(np.abs(resid - np.median(resid))))
        pk, props = scipy.signal.find_peaks(smooth, prominence=max(0.05, 3.0 * sigma
                                                                   / math.sqrt(width)))
        order = np.argsort(-props["prominences"])[:4]
        for o in order:
            if 2 <= pk[o] < smooth.size - 2 and all(abs(int(pk[o]) - c) > 2 for c, _ in cands):
                cands.append((int(pk[o]), width))
    if not cands:
        raise RecordError(path, f"no resonance in the band {band[0]:.4g} to {band[1]:.4g} Hz "
                          "(no peak stands above the scatter of the spectrum)", column=column)
    fits = []
    for p, width in cands:
        ip = i0 + p
        hp = _half_power_zeta(f, np.convolve(P, np.ones(width) / width, mode="same"), ip)
        span = max(4.0 * hp * f[ip], 10 * (f[1] - f[0]))
        lo = max(i0, int(np.searchsorted(f, max(f[ip] - span, f[ip] / 2))))
        hi = min(i1, int(np.searchsorted(f, min(f[ip] + span, 2 * f[ip]))) + 1)
        if hi - lo < 10:
            continue
        fit = _fit_peak(spec, ip, lo, hi, min(max(hp, 1e-3), 0.5))
        if (fit is None or fit["at_edge"] or fit["stat"] < 40.0 or fit["peak_over_floor"] < 0.3
                or fit["fn_sd"] > 0.05 * fit["fn"]):
            continue
        fits.append(fit)
    # one fit per mode: fits within each other's uncertainty or half-power band are the same
    fits.sort(key=lambda d: -d["stat"])
    kept = []
    for d in fits:
        if all(abs(d["fn"] - e["fn"]) > max(3 * (d["fn_sd"] + e["fn_sd"]),
                                            0.5 * min(d["zeta"], e["zeta"]) * e["fn"],
                                            2 * (f[1] - f[0]))
               for e in kept):
            kept.append(d)
    if not kept:
        raise RecordError(path, f"no resonance in the band {band[0]:.4g} to {band[1]:.4g} Hz "
                          "that a modal fit confirms", column=column)
    kept.sort(key=lambda d: -d["weight"])
    total = kept[0]["weight"]
    kept = [d for d in kept if d["weight"] >= 1e-3 * total][:max_modes]
    if len(kept) > 1:
        kept = _joint_fit(spec, kept, i0, i1) or kept
    return [Mode(wn=2 * math.pi * d["fn"], zeta=d["zeta"], wn_std=2 * math.pi * d["fn_sd"],
                 zeta_std=d["zeta_sd"], weight=d["weight"]) for d in kept]


class _JointModel:
    """log of a r^q prod_i shape_i(f) + b over one window: modes in series (the measured
    spectrum is the product of the modes' responses times a smooth excitation)."""

    def __init__(self, spec: Spectrum, lo: int, hi: int, n: int, narrow: bool):
        self.n = n
        self.peak = _PeakModel(spec, lo, hi, narrow)

    def spectrum(self, th, f):
        S = np.exp(th[2 * self.n]) * (f / math.exp(th[0])) ** th[2 * self.n + 1]
        for i in range(self.n):
            S = S * _shape(f, math.exp(th[2 * i]), math.exp(th[2 * i + 1]), 0.0)
        return S

    def __call__(self, th):
        b = math.exp(th[2 * self.n + 2])
        pm = self.peak
        if pm.kernel is None:
            return np.log(self.spectrum(th, pm.f) + b)
        S = self.spectrum(th, np.maximum(np.abs(pm.fine), 1e-12))
        return np.log(np.convolve(S, pm.kernel, mode="valid")[:: pm.step] + b)


def _joint_fit(spec: Spectrum, fits: list[dict], i0: int, i1: int) -> list[dict] | None:
    """Refine several modes together (each one's tail lies under the others' peaks)."""
    from scipy.optimize import least_squares
    f = spec.f
    fits = sorted(fits, key=lambda d: d["fn"])
    n = len(fits)
    lo = max(i0, int(np.searchsorted(f, fits[0]["fn"] * max(0.5, 1 - 5 * fits[0]["zeta"]))))
    hi = min(i1, int(np.searchsorted(f, fits[-1]["fn"] * min(2.0, 1 + 5 * fits[-1]["zeta"]))) + 1)
    if hi - lo < 4 * n + 4:
        return None
    df = f[1] - f[0]
    narrow = any(2 * d["zeta"] * d["fn"] < 25 * df for d in fits)
    model = _JointModel(spec, lo, hi, n, narrow)
    y = np.log(np.maximum(spec.P[lo:hi], 1e-300))
    th0 = []
    for d in fits:
        th0 += [math.log(d["fn"]), math.log(d["zeta"])]
    th0 += [0.0, 0.0, math.log(max(float(np.min(spec.P[lo:hi])) * 1e-2, 1e-300))]
    th0 = np.array(th0)
    th0[2 * n] = float(np.median(y - np.log(model.spectrum(th0, f[lo:hi]))))
    lower = [math.log(f[lo] if f[lo] > 0 else f[lo + 1]), math.log(1e-4)] * n + [-np.inf, -8, -np.inf]
    upper = [math.log(f[hi - 1]), math.log(0.7)] * n + [np.inf, 8, np.inf]
    th0 = np.clip(th0, np.array(lower) + 1e-9, np.array(upper) - 1e-9)
    try:
        res = least_squares(lambda th: model(th) - y, th0, bounds=(lower, upper), method="trf",
                            x_scale="jac", max_nfev=200 * th0.size)
    except (ValueError, FloatingPointError):
        return None
    if not res.success:
        return None
    s2 = float(np.sum(res.fun ** 2)) / max(1, y.size - th0.size)
    cov = np.linalg.pinv(res.jac.T @ res.jac) * s2 * spec.enbw_bins
    sd = np.sqrt(np.maximum(np.diag(cov), 0.0))
    out = []
    for i, d in enumerate(fits):
        fn, zeta = math.exp(res.x[2 * i]), math.exp(res.x[2 * i + 1])
        if abs(fn - d["fn"]) > 0.1 * d["fn"] or not np.all(np.isfinite(sd[2 * i: 2 * i + 2])):
            return None                     # the joint fit wandered off: keep the single fits
        out.append(dict(d, fn=fn, zeta=zeta, fn_sd=fn * sd[2 * i], zeta_sd=zeta * sd[2 * i + 1]))
    return sorted(out, key=lambda d: -d["weight"])


def _half_power_zeta(f, P, ip):
    """zeta from the half-power bandwidth around bin ip (a start value)."""
    half = P[ip] / 2
    lo = ip
    while lo > 0 and P[lo] > half:
        lo -= 1
    hi = ip
    while hi < P.size - 1 and P[hi] > half:
        hi += 1
    return max((f[hi] - f[lo]) / (2 * f[ip]), 1e-3)


# ---------------------------------------------------------------- free decays

def _decay_model(th, t, n_modes):
    c = th[0]
    out = np.full(t.shape, c)
    jac = [np.ones_like(t)]
    for i in range(n_modes):
        A, B, sigma, wd = th[1 + 4 * i: 5 + 4 * i]
        e = np.exp(sigma * t)
        co, si = np.cos(wd * t), np.sin(wd * t)
        osc = e * (A * co + B * si)
        out = out + osc
        jac += [e * co, e * si, t * osc, e * t * (-A * si + B * co)]
    return out, np.column_stack(jac)


def decay_modes(x: np.ndarray, Ts: float, *, path: str, column: str,
                band: tuple[float, float] | None = None) -> tuple[list[Mode], float]:
    """Modes of a free decay (any offset) by a whole-record least-squares fit; returns
    (modes largest first, R^2 of the fit). RecordError for a record that is not a decay."""
    from scipy.optimize import least_squares
    import scipy.signal
    from ..filters import identify_from_record, ParameterError
    t = np.arange(x.size) * Ts
    try:
        seed = identify_from_record(x, Ts=Ts)
    except (ParameterError, ValueError) as exc:
        raise RecordError(path, f"not a free decay: the one-mode fit fails ({exc})",
                          column=column) from None
    # further modes: peaks of the decay's periodogram other than the seed's
    f, P = scipy.signal.periodogram(x - np.mean(x), fs=1 / Ts, window="hann")
    peaks, _ = scipy.signal.find_peaks(np.log10(np.maximum(P, 1e-300)), prominence=1.0)
    f_lo, f_hi = band if band else (0.0, 0.45 / Ts)
    extra = [f[p] for p in sorted(peaks, key=lambda p: -P[p])
             if f_lo <= f[p] <= f_hi and abs(f[p] - seed.wd / (2 * math.pi)) > 3 / (x.size * Ts)]
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
        r2 = 1.0 - ssr / float(np.sum((x - np.mean(x)) ** 2))
        k = th0.size
        # keep a further mode only if it explains clearly more (an F-test-like margin)
        if best is None or ssr < best[1] * (1 - 10.0 * (k - best[3]) / x.size):
            best = (res, ssr, r2, k, n_modes)
    if best is None:
        raise RecordError(path, "not a free decay: the damped-oscillation fit diverges",
                          column=column)
    res, ssr, r2, k, n_modes = best
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
