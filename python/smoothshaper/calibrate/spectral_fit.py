# SPDX-License-Identifier: Apache-2.0
"""Modes of a measured spectrum, and a test of whether they explain it.

Every significant peak of the spectrum in the band is fitted by least squares
(``scipy.optimize.least_squares``) on the log scale, where the scatter of a Welch estimate is
the same at every frequency, with the model

    S(f) = a r^q (1 + 4 zeta^2 r^2) / ((1 - r^2)^2 + (2 zeta r)^2) + b,    r = f / fn,

the base-excited mode (the load acceleration of ``plants.mode`` over the commanded one, squared)
times a local power law ``r^q`` for the excitation spectrum, plus a floor ``b``. For a Welch
estimate the model is first convolved with the window's spectral kernel (the expected value of a
Welch estimate is the true PSD convolved with |W(f)|^2), so a peak narrower than a few bins is
still fitted without bias. Candidate peaks come from three smoothing widths; a peak is kept when
its fit beats a peak-free power law clearly, and several modes are then refined together. A
mode fitted far narrower than its measured peak (the flat top of two modes closer than their
widths) is refitted as a pair in series and kept as one when an F-test-like margin says so
(:func:`_split_close`).
Standard deviations come from the Jacobian, ``cov = s^2 (J^T J)^-1``, scaled by the window's
equivalent noise bandwidth in bins (neighbouring Welch bins are correlated).

Goodness of fit (:func:`fit_modes`): the vibration content the fitted peaks predict
(:func:`.spectra.vibration_content`) against the measured one, both smoothed over a few
resolution bandwidths: the fraction of the measured vibration energy the fit misplaces. Below
:data:`GOF_MAX` the fit explains the spectrum, and its damping ratios and uncertainties sharpen
the figures; above, the spectrum alone ranks the candidates.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .spectra import Spectrum, vibration_content

__all__ = ["GOF_MAX", "ModalFit", "fit_modes"]

#: Largest fraction of the measured vibration energy a modal fit may misplace and still be
#: said to explain the spectrum.
GOF_MAX = 0.05


@dataclass
class ModalFit:
    """The fit of one spectrum: ``modes`` as dicts (fn [Hz], zeta, sds, weight, at_edge),
    ``model`` the fitted PSD on the spectrum's bins (NaN outside the band), ``misfit`` the
    goodness-of-fit statistic, ``explains`` whether it is below :data:`GOF_MAX`."""
    modes: list
    model: np.ndarray
    misfit: float
    explains: bool
    notes: list = field(default_factory=list)


def _smooth(x, w):
    w = max(1, int(w))
    if w <= 1 or x.size < w:
        return x
    return np.convolve(x, np.ones(w) / w, mode="same")


def fit_modes(spec: Spectrum, band) -> ModalFit:
    """Fit the peaks of ``spec`` in ``band`` [Hz] and test whether they explain it."""
    fits = _peak_fits(spec, band)
    f = spec.f
    inb = (f >= band[0]) & (f <= band[1]) & (f > 0)
    model = np.full(spec.P.shape, np.nan)
    if not fits:
        return ModalFit([], model, math.inf, False)
    fi = f[inb]
    # each peak's own model near it; the largest where they overlap
    M = np.zeros(fi.size)
    for d in fits:
        if "curve" in d:             # a close pair: their joint model over its window
            fw, Mw = d["curve"]
            near = (fi >= fw[0]) & (fi <= fw[-1])
            M[near] = np.maximum(M[near], np.interp(fi[near], fw, Mw))
            continue
        a, fn, z, q, b = d["peak"]
        # each single fit holds near its own peak only (its power law r^q is local)
        near = (fi > fn / (1 + 6 * z)) & (fi < fn * (1 + 6 * z))
        M[near] = np.maximum(M[near], a * _shape(fi[near], fn, z, q) + b)
    model[inb] = M
    S_meas = vibration_content(fi, spec.P[inb], band)
    S_mod = vibration_content(fi, M, band)
    w = max(3, int(round(3 * spec.enbw_bins)))
    a, b = _smooth(S_meas, w), _smooth(S_mod, w)
    total = float(np.sum(a))
    misfit = float(np.sum(np.abs(a - b)) / total) if total > 0 else math.inf
    lo_f, hi_f = float(fi[0]), float(fi[-1])
    for d in fits:
        d["at_edge"] = bool(d.get("at_edge")) or \
            min(d["fn"] - lo_f, hi_f - d["fn"]) < 3 * d["zeta"] * d["fn"]
        d.setdefault("weight_rsd", 0.0)
    return ModalFit(fits, model, misfit, misfit <= GOF_MAX)


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
        fn, zeta, a, q, b = (float(np.exp(np.clip(th[0], -700, 700))), float(np.exp(np.clip(th[1], -700, 700))),
                              float(np.exp(np.clip(th[2], -700, 700))), th[3], float(np.exp(np.clip(th[4], -700, 700))))
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
    with np.errstate(all="ignore"):
        res = least_squares(lambda th: model(th) - y, th0, bounds=(lower, upper), method="trf",
                            x_scale="jac", max_nfev=100 * th0.size)
    n, k = y.size, th0.size
    ssr = float(np.sum(res.fun ** 2))
    s2 = ssr / max(1, n - k)
    # the same window without a peak: a power law plus the floor
    fw = spec.f[lo:hi]

    def null(c):
        e = np.exp(np.clip(c, -700, 700))
        return np.log(np.maximum(e[0] * (fw / fn0) ** c[1] + e[2], 1e-300)) - y
    c0 = np.array([math.log(max(float(np.median(spec.P[lo:hi])), 1e-300)), 0.0,
                   math.log(floor0 * 1e-3)])
    with np.errstate(all="ignore"):
        ssr0 = float(np.sum(least_squares(null, c0, method="trf").fun ** 2))
    stat = (ssr0 - ssr) / (s2 * spec.enbw_bins) if s2 > 0 else math.inf
    # pinv: a floor far below the data (log b -> -inf) leaves a zero column, not an error
    cov = np.linalg.pinv(res.jac.T @ res.jac) * s2 * spec.enbw_bins
    th = res.x
    fn, zeta = float(np.exp(th[0])), float(np.exp(th[1]))
    sd = np.sqrt(np.maximum(np.diag(cov), 0.0))
    if not np.all(np.isfinite(sd)):
        return None
    a, q, b = float(np.exp(np.clip(th[2], -700, 700))), th[3], float(np.exp(np.clip(th[4], -700, 700)))
    at_edge = th[0] <= lower[0] + 1e-6 or th[0] >= upper[0] - 1e-6 or th[1] >= upper[1] - 1e-3
    # the mode's energy with the window's power law taken at the peak (r^q = 1): r^q holds the
    # excitation's growth and the neighbouring modes' tails near the peak only, and carried
    # out to 0.3 and 3 fn it moved weight between modes (q = +-5 beside another mode: the
    # campaign's 35/56 Hz pair came out 1 : 0.85 where its spectrum holds 1 : 0.47)
    grid = np.linspace(0.3 * fn, 3.0 * fn, 2000)
    weight = float(np.trapezoid(a * _shape(grid, fn, zeta, 0.0), grid * 2 * math.pi))
    return dict(fn=fn, zeta=zeta, fn_sd=fn * sd[0], zeta_sd=zeta * sd[1], weight=weight, a=a, q=q,
                b=b, weight_rsd=float(math.sqrt(max(cov[2, 2] + cov[1, 1] - 2 * cov[1, 2], 0.0))),
                at_edge=at_edge, peak_over_floor=a / (2 * zeta) ** 2 / max(b, 1e-300), rms=math.sqrt(s2),
                stat=stat)


def _peak_fits(spec: Spectrum, band: tuple[float, float], max_modes: int = 4) -> list[dict]:
    """The significant modes of a spectrum in ``band`` [Hz] as dicts, largest weight first
    ([] when there is none, or the band is too narrow to fit one)."""
    from .peaks import find_peaks, peak_widths    # scipy.signal's, without scipy.stats
    f, P = spec.f, spec.P
    inband = np.flatnonzero((f >= band[0]) & (f <= band[1]) & (f > 0))
    if inband.size < 10:
        return []
    i0, i1 = int(inband[0]), int(inband[-1]) + 1
    logP = np.log10(np.maximum(P[i0:i1], 1e-300))
    # candidate peaks at three smoothing scales (narrow peaks survive the finest, broad ones
    # rise above the scatter at the coarsest); each is then confirmed by its modal fit
    cands = []
    for width in (3, 9, 27):
        if width > logP.size // 2:       # a kernel longer than the band: nothing to smooth
            continue
        kern = np.hanning(width + 2)[1:-1]
        smooth = np.convolve(logP, kern / kern.sum(), mode="same")
        resid = logP - smooth
        sigma = 1.4826 * float(np.median(np.abs(resid - np.median(resid))))
        pk, props = find_peaks(smooth, prominence=max(0.05, 3.0 * sigma / math.sqrt(width)))
        order = np.argsort(-props["prominences"])[:4]
        # each peak's extent: its half-prominence width and the valleys either side (a weak
        # mode on a larger one's tail never falls to half its power: its half-power width
        # reached the larger mode and the fit went there)
        widths = peak_widths(smooth, pk, rel_height=0.5, prominence_data=(
            props["prominences"], props["left_bases"], props["right_bases"]))
        for o in order:
            if 2 <= pk[o] < smooth.size - 2 and all(abs(int(pk[o]) - c[0]) > 2 for c in cands):
                cands.append((int(pk[o]), width, i0 + int(props["left_bases"][o]),
                              i0 + int(props["right_bases"][o]), float(widths[o])))
    if not cands:
        return []
    fits = []
    df = f[1] - f[0]
    for p, width, left, right, prom_width in cands:
        ip = i0 + p
        hp = _half_power_zeta(f, np.convolve(P, np.ones(width) / width, mode="same"), ip)
        hp = min(hp, max(0.5 * prom_width * df / f[ip], 1e-3))
        span = max(4.0 * hp * f[ip], 10 * df)
        lo = max(i0, int(np.searchsorted(f, max(f[ip] - span, f[ip] / 2))), left)
        hi = min(i1, int(np.searchsorted(f, min(f[ip] + span, 2 * f[ip]))) + 1, right + 1)
        if hi - lo < 10:             # valleys closer than ten bins: the span's own window
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
        return []
    kept.sort(key=lambda d: -d["weight"])
    total = kept[0]["weight"]
    kept = [d for d in kept if d["weight"] >= 1e-3 * total][:max_modes]
    for d in kept:                  # the single fit's own peak, for the goodness of fit
        d["peak"] = (d["a"], d["fn"], d["zeta"], d["q"], d["b"])
    if len(kept) > 1:
        kept = _joint_fit(spec, kept, i0, i1) or kept
    if len(kept) < max_modes:
        kept = _split_close(spec, kept, i0, i1)
    return kept


#: A close pair replaces one mode when it lowers the window's sum of squares by this many
#: noise variances per equivalent bin (the test a peak itself passes, ``stat``).
SPLIT_STAT = 40.0


#: A single mode this much narrower than its measured peak's half-power width is tried as a pair.
FLAT_TOP = 0.25


def _split_close(spec: Spectrum, kept: list[dict], i0: int, i1: int) -> list[dict]:
    """Each mode whose peak is better explained by two modes in series close together (two
    modes 2 Hz apart, each as wide as their distance, make one flat-topped peak with no dip
    between them, which a single mode fits too narrow) is replaced by the pair."""
    f = spec.f
    df = f[1] - f[0]
    out = []
    smooth = np.convolve(spec.P, np.ones(3) / 3, mode="same")
    for d in kept:
        # the measured peak's relative half-power half-width: the pair lies within it
        ip = int(np.clip(np.searchsorted(f, d["fn"]), 1, f.size - 2))
        hp = max(_half_power_zeta(f, smooth, ip), 1.5 * df / d["fn"])
        # one window for both models (their sums of squares are compared)
        window = (max(i0, int(np.searchsorted(f, d["fn"] * (1 - 4 * hp)))),
                  min(i1, int(np.searchsorted(f, d["fn"] * (1 + 4 * hp))) + 1))
        one = _joint_fit(spec, [d], i0, i1, with_ssr=True, window=window)
        best = None
        # a flat top's signature: the single mode fits far narrower than the measured peak
        # (a lone mode's zeta is its relative half-power half-width; seed 0 of the campaign's
        # pair: 0.0045 against 0.03; a lone broad peak of a real table: 0.067 against 0.17)
        if one is not None and one[0][0]["zeta"] < FLAT_TOP * hp:
            ssr1 = one[1]
            for sep in (0.4, 0.7, 1.0):
                delta = sep * hp
                if delta >= 1.0:        # a peak as broad as its frequency: no pair below 0 Hz
                    continue
                pair = [dict(d, fn=d["fn"] * (1 - delta), zeta=hp / 2),
                        dict(d, fn=d["fn"] * (1 + delta), zeta=hp / 2)]
                two = _joint_fit(spec, pair, i0, i1, with_ssr=True, wander=max(delta, 2 * hp),
                                 window=window)
                if two is None:
                    continue
                a, b = two[0]
                # the drop in the sum of squares over the pair's residual variance (the larger
                # model's, as in an F test: the single mode's holds its misfit)
                s2p = two[2]
                stat = (ssr1 - two[1]) / (s2p * spec.enbw_bins) if s2p > 0 else math.inf
                apart = abs(b["fn"] - a["fn"]) > max(3 * (a["fn_sd"] + b["fn_sd"]), 3 * df)
                if stat > SPLIT_STAT and apart and (best is None or two[1] < best[1]):
                    best = two
        if best is None:
            out.append(d)
            continue
        pair = best[0]
        # the pair's share of the single mode's weight: each peak's height times its width
        h = np.array([p["a_peak"] * p["zeta"] * p["fn"] for p in pair])
        for p, share in zip(pair, h / h.sum()):
            p["weight"] = d["weight"] * float(share)
            p["curve"] = best[3]
            p.pop("a_peak", None)
            out.append(p)
    return sorted(out, key=lambda d: -d["weight"])


class _JointModel:
    """log of a r^q prod_i shape_i(f) + b over one window: modes in series (the measured
    spectrum is the product of the modes' responses times a smooth excitation)."""

    def __init__(self, spec: Spectrum, lo: int, hi: int, n: int, narrow: bool):
        self.n = n
        self.peak = _PeakModel(spec, lo, hi, narrow)

    def spectrum(self, th, f):
        e = np.exp(np.clip(th, -700, 700))
        S = e[2 * self.n] * (f / e[0]) ** th[2 * self.n + 1]
        for i in range(self.n):
            S = S * _shape(f, e[2 * i], e[2 * i + 1], 0.0)
        return S

    def __call__(self, th):
        b = float(np.exp(np.clip(th[2 * self.n + 2], -700, 700)))
        pm = self.peak
        if pm.kernel is None:
            return np.log(self.spectrum(th, pm.f) + b)
        S = self.spectrum(th, np.maximum(np.abs(pm.fine), 1e-12))
        return np.log(np.convolve(S, pm.kernel, mode="valid")[:: pm.step] + b)


def _joint_fit(spec: Spectrum, fits: list[dict], i0: int, i1: int, with_ssr: bool = False,
               wander: float = 0.1, window=None):
    """Refine several modes together (each one's tail lies under the others' peaks); None when
    a mode moves by more than ``wander`` (relative). With ``with_ssr``: (modes, sum of squares,
    residual variance), each mode with ``a_peak``, the model's PSD at its frequency."""
    from scipy.optimize import least_squares
    f = spec.f
    fits = sorted(fits, key=lambda d: d["fn"])
    n = len(fits)
    lo = max(i0, int(np.searchsorted(f, fits[0]["fn"] * max(0.5, 1 - 5 * fits[0]["zeta"]))))
    hi = min(i1, int(np.searchsorted(f, fits[-1]["fn"] * min(2.0, 1 + 5 * fits[-1]["zeta"]))) + 1)
    if window is not None:
        lo, hi = window
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
        with np.errstate(all="ignore"):
            res = least_squares(lambda th: model(th) - y, th0, bounds=(lower, upper),
                                method="trf", x_scale="jac", max_nfev=200 * th0.size)
    except (ValueError, FloatingPointError, OverflowError, np.linalg.LinAlgError):
        return None
    if not res.success:
        return None
    s2 = float(np.sum(res.fun ** 2)) / max(1, y.size - th0.size)
    cov = np.linalg.pinv(res.jac.T @ res.jac) * s2 * spec.enbw_bins
    sd = np.sqrt(np.maximum(np.diag(cov), 0.0))
    out = []
    for i, d in enumerate(fits):
        fn, zeta = float(np.exp(res.x[2 * i])), float(np.exp(res.x[2 * i + 1]))
        if abs(fn - d["fn"]) > wander * d["fn"] or not np.all(np.isfinite(sd[2 * i: 2 * i + 2])):
            return None                     # the joint fit wandered off: keep the single fits
        out.append(dict(d, fn=fn, zeta=zeta, fn_sd=fn * sd[2 * i], zeta_sd=zeta * sd[2 * i + 1]))
    if with_ssr:
        for d in out:
            d["a_peak"] = float(model.spectrum(res.x, np.array([d["fn"]]))[0])
        return out, float(np.sum(res.fun ** 2)), s2, (f[lo:hi].copy(), np.exp(model(res.x)))
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


