# SPDX-License-Identifier: Apache-2.0
"""Candidate filters for a set of measured modes: tuning, figures of merit, recommendation.

Remaining vibration (docs/calibrate.md). A filter with taps h at sample period Ts leaves, of a
mode with pole p = -zeta wn + j wn sqrt(1 - zeta^2), the fraction R(wn, zeta) = |sum_k h_k
e^{-p k Ts}| of the vibration an unfiltered move excites (the percent residual vibration of
Singer & Seering 1990, for the discrete filter). Over the identified modes, weighted by their
share w_i of the measured vibration energy and averaged over each mode's uncertainty (Gauss-
Hermite nodes over wn ~ N(wn_i, sd_wn) and zeta ~ N(zeta_i, sd_zeta)):

    V = sqrt( sum_i w_i E[R(wn, zeta)^2] / sum_i w_i ).

Each candidate's design frequency (and damping, and for the generalised MZV its duration) is
tuned to minimise V (Nelder-Mead), subject to the delay and smoothing limits. The stated
uncertainty of V is the range of the same sum with each mode anywhere in its +-3 sd box.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..reference import impulse_response, shaper_impulses
from ..reference.continuous import transfer_unchecked
from ..stages import Stage, for_mode, shaper
from .modes import Mode
from .._checks import positive as _positive

__all__ = ["FIRMWARE_NAMES", "BOX", "Reference", "Candidate", "chain_taps", "Objective",
           "duration", "Family", "families", "continuity", "smoothing", "move_peaks", "class_name",
           "tune", "evaluate", "recommend", "firmware_lines"]

#: Stage families whose impulse response integrates a step once (+1) or twice (+2).
_SMOOTHING_ORDER = {"rectangular": 1, "exponential": 1, "harmonic": 2, "damped_harmonic": 2}
#: Shaper kinds 3-D printer firmware knows (Klipper [input_shaper] shaper_type names).
FIRMWARE_NAMES = {"zv": "zv", "mzv": "mzv", "zvd": "zvd", "ei": "ei", "ei2": "2hump_ei",
                  "ei3": "3hump_ei"}
#: Half-width of the uncertainty box, in standard deviations, for the stated range.
BOX = 3.0
_GH_WN = np.polynomial.hermite_e.hermegauss(5)
_GH_Z = np.polynomial.hermite_e.hermegauss(3)


@dataclass
class Reference:
    """The reference move for the figures of merit: acceleration ``accel`` and square-corner
    velocity ``corner_velocity`` (length units of the record, e.g. mm/s^2 and mm/s), a
    rest-to-rest move of ``distance``, filters at sample period ``Ts`` [s]."""
    Ts: float = 1e-4
    accel: float = 3000.0
    corner_velocity: float = 5.0
    distance: float = 10.0

    def __post_init__(self):
        # each a finite number > 0, named (None or NaN reached run() or the figures)
        for name in ("Ts", "accel", "corner_velocity", "distance"):
            object.__setattr__(self, name, _positive(name, getattr(self, name)))


@dataclass
class Candidate:
    name: str
    stages: list[Stage]
    vibration: float = math.nan            # [%], band RMS
    vibration_range: tuple[float, float] = (math.nan, math.nan)
    vibration_nominal: float = math.nan    # [%] at the identified modes
    length: float = 0.0                    # impulse-response length [s]
    lag: float = 0.0                       # centroid [s]
    smoothing: float = 0.0                 # corner rounding, length units
    peak_accel: float = 0.0
    peak_jerk: float = 0.0
    continuity: str = ""
    meets: bool = True
    reasons: list[str] = field(default_factory=list)

    def as_dict(self) -> dict:
        from dataclasses import asdict
        return {"name": self.name, "stages": [asdict(s) for s in self.stages],
                "vibration": self.vibration, "vibration_range": list(self.vibration_range),
                "vibration_nominal": self.vibration_nominal, "delay": {
                    "length": self.length, "centroid": self.lag},
                "smoothing": self.smoothing, "peak_accel": self.peak_accel,
                "peak_jerk": None if math.isinf(self.peak_jerk) else self.peak_jerk,
                "jerk_bounded": not math.isinf(self.peak_jerk),
                "continuity": self.continuity, "meets_limits": self.meets,
                "limit_violations": self.reasons}


def chain_taps(stages: list[Stage], Ts: float) -> np.ndarray:
    h = np.ones(1)
    for s in stages:
        h = np.convolve(h, impulse_response(s, Ts=Ts))
    return h


class Objective:
    """Remaining vibration of taps over the modes, nominal, band-averaged and +-3 sd range."""

    def __init__(self, modes: list[Mode], Ts: float):
        self.Ts = Ts
        w = np.array([m.weight for m in modes], dtype=float)
        self.w = w / w.sum()
        poles, gw, idx = [], [], []
        box, box_idx = [], []
        for i, m in enumerate(modes):
            for xw, ww in zip(*_GH_WN):
                for xz, wz in zip(*_GH_Z):
                    wn = max(m.wn + xw * m.wn_std, 1e-9)
                    z = min(max(m.zeta + xz * m.zeta_std, 0.0), 0.99)
                    poles.append(_pole(wn, z))
                    gw.append(ww * wz / (2 * math.pi))
                    idx.append(i)
            for wn in np.linspace(m.wn - BOX * m.wn_std, m.wn + BOX * m.wn_std, 9):
                for z in (m.zeta - BOX * m.zeta_std, m.zeta, m.zeta + BOX * m.zeta_std):
                    box.append(_pole(max(wn, 1e-9), min(max(z, 0.0), 0.99)))
                    box_idx.append(i)
        self.poles, self.gw, self.idx = np.array(poles), np.array(gw), np.array(idx)
        self.box, self.box_idx = np.array(box), np.array(box_idx)
        self.nominal = np.array([_pole(m.wn, m.zeta) for m in modes])
        self.n = len(modes)

    def _R2(self, h, poles):
        k = np.flatnonzero(h)
        if k.size * 4 < h.size:                  # sparse (shapers): the powers directly
            z = np.exp(-np.outer(poles, k) * self.Ts)
            return np.abs(z @ h[k]) ** 2
        zinv = np.exp(-poles * self.Ts)          # dense (smoothers): powers by running product
        z = np.empty((poles.size, h.size), dtype=complex)
        z[:, 0] = 1.0
        z[:, 1:] = zinv[:, None]
        np.cumprod(z, axis=1, out=z)
        return np.abs(z @ h) ** 2

    def band_continuous(self, stages) -> float:
        """``band`` for the continuous designs (the tuning loop: cheap, and within
        O((wn Ts)^2) of the discrete filter, which the reported figures use)."""
        H = np.ones(self.poles.size, dtype=complex)
        for s in stages:
            H *= transfer_unchecked(s, self.poles)    # valid stages, finite poles
        per = np.bincount(self.idx, np.abs(H) ** 2 * self.gw, minlength=self.n)
        return 100 * math.sqrt(float(self.w @ per))

    def band(self, h) -> float:
        R2 = self._R2(h, self.poles) * self.gw
        per = np.bincount(self.idx, R2, minlength=self.n)
        return 100 * math.sqrt(float(self.w @ per))

    def nominal_value(self, h) -> float:
        return 100 * math.sqrt(float(self.w @ self._R2(h, self.nominal)))

    def range(self, h) -> tuple[float, float]:
        R2 = self._R2(h, self.box)
        lo = np.array([R2[self.box_idx == i].min() for i in range(self.n)])
        hi = np.array([R2[self.box_idx == i].max() for i in range(self.n)])
        return 100 * math.sqrt(float(self.w @ lo)), 100 * math.sqrt(float(self.w @ hi))


_ZVN_ORDER = {"zv": lambda s: 1, "zvd": lambda s: 2, "zvdd": lambda s: 3,
              "zvn": lambda s: s.order}


def duration(stages, Ts: float) -> float:
    """Impulse-response length (L - 1) Ts of the discrete chain [s], without building it: a
    smoother of duration T spans floor(T/Ts) samples, a shaper whose last impulse is at t
    spans ceil(t/Ts) (exact timing splits it onto the next sample)."""
    n = 0
    for s in stages:
        if s.kind in _SMOOTHING_ORDER:
            n += math.floor(s.T / Ts + 1e-9)
        elif s.kind in _ZVN_ORDER:      # exact ZV^n: n convolved exact ZVs
            n += _ZVN_ORDER[s.kind](s) * math.ceil(float(shaper_impulses(
                s.with_(kind="zv"))[1][-1]) / Ts - 1e-9)
        else:
            n += math.ceil(float(shaper_impulses(s)[1][-1]) / Ts - 1e-9)
    return n * Ts


def _pole(wn, zeta):
    return complex(-zeta * wn, wn * math.sqrt(1 - zeta * zeta))


# ---------------------------------------------------------------- families

@dataclass
class Family:
    """A candidate family: ``build(params)`` -> stages, params = per slot (wn, zeta) [+ extra]."""
    name: str
    slots: int
    build: object
    extra: tuple = ()          # (start, low, high) of extra parameters


def _shaper(kind, **kw):
    return lambda p: [shaper(kind, wn=p[0], zeta=p[1], **kw)]


def _gmzv(n):
    return lambda p: [shaper("gmzv", wn=p[0], zeta=p[1], order=n, duration=p[2])]


def _smoother(kind):
    return lambda p: [for_mode(kind, wn=p[0], zeta=p[1])]


def families(n_modes: int) -> list[Family]:
    out = [Family(k, 1, _shaper(k)) for k in ("zv", "mzv", "zvd", "zvdd", "ei", "ei2", "ei3")]
    out.append(Family("zvn (n=4)", 1, _shaper("zvn", order=4)))
    out.append(Family("gmzv (n=4)", 1, _gmzv(4), extra=((1.0, 0.55, 1.45),)))
    out.append(Family("gmzv (n=5)", 1, _gmzv(5), extra=((1.3, 0.6, 1.95),)))
    out += [Family(k, 1, _smoother(k)) for k in ("harmonic", "damped_harmonic", "exponential")]
    out.append(Family("rectangular*zv", 1, lambda p: [for_mode("rectangular", wn=p[0], zeta=p[1]),
                                                      shaper("zv", wn=p[0], zeta=p[1])]))
    if n_modes >= 2:
        for a, b in (("zv", "zv"), ("mzv", "mzv"), ("zvd", "zvd"), ("mzv", "zv"), ("ei", "ei")):
            out.append(Family(f"{a}+{b}", 2, lambda p, a=a, b=b: [
                shaper(a, wn=p[0], zeta=p[1]), shaper(b, wn=p[2], zeta=p[3])]))
    return out


# ---------------------------------------------------------------- figures of merit

def continuity(stages: list[Stage]) -> int:
    """Continuity class of a filtered step: -1 (position jumps), 0, 1, ..."""
    return -1 + sum(_SMOOTHING_ORDER.get(s.kind, 0) for s in stages)


def smoothing(h: np.ndarray, ref: Reference) -> float:
    """Corner rounding: the largest distance between the filtered path and the commanded one
    at a 90-degree corner taken at ``corner_velocity`` with deceleration/acceleration ``accel``,
    and how far short of the turning point a 180-degree reversal (speed 0) turns."""
    Ts, A, vc = ref.Ts, ref.accel, ref.corner_velocity
    L = h.size
    t = (np.arange(-2 * L - 2, 2 * L + 2)) * Ts
    x = np.where(t < 0, vc * t - 0.5 * A * t * t, 0.0)
    y = np.where(t < 0, 0.0, vc * t + 0.5 * A * t * t)
    xf = np.convolve(x, h)[: t.size]
    yf = np.convolve(y, h)[: t.size]
    sl = slice(L, None)                     # past the start-up transient of the window
    d1 = np.hypot(np.maximum(xf[sl], 0.0), yf[sl])
    d2 = np.hypot(xf[sl], np.minimum(yf[sl], 0.0))
    dev90 = float(np.max(np.minimum(d1, d2)))
    r = -0.5 * A * t * t
    rf = np.convolve(r, h)[: t.size]
    dev180 = float(-np.max(rf[sl]))
    return max(dev90, dev180)


def move_peaks(h: np.ndarray, stages: list[Stage], ref: Reference) -> tuple[float, float]:
    """Peak |acceleration| and |jerk| of the rest-to-rest reference move (triangular velocity
    at ``accel`` over ``distance``) after the filter; jerk is inf when the filtered move's
    acceleration jumps (continuity class below C2)."""
    Ts, A = ref.Ts, ref.accel
    T = math.sqrt(ref.distance / A)
    n = int(math.ceil(2 * T / Ts)) + 1
    t = np.arange(n + h.size + 4) * Ts
    q = np.where(t < T, 0.5 * A * t * t,
                 np.where(t < 2 * T, ref.distance - 0.5 * A * (2 * T - t) ** 2, ref.distance))
    qf = np.convolve(q, h)[: t.size]
    acc = np.diff(qf, 2) / Ts ** 2
    peak_a = float(np.max(np.abs(acc)))
    if continuity(stages) + 2 < 2:
        return peak_a, math.inf
    return peak_a, float(np.max(np.abs(np.diff(acc)))) / Ts


def class_name(k: int) -> str:
    return "discontinuous" if k < 0 else f"C{k}"


# ---------------------------------------------------------------- tuning

def tune(family: Family, modes: list[Mode], objective: Objective, ref: Reference,
         max_delay: float | None, max_smoothing: float | None) -> Candidate | None:
    """The family's design minimising the band-averaged remaining vibration within limits."""
    from scipy.optimize import minimize
    from ..filters import ParameterError
    anchors = [modes[min(i, len(modes) - 1)] for i in range(family.slots)]
    nyq = math.pi / ref.Ts

    def params(u):
        p = []
        for i, m in enumerate(anchors):
            p += [m.wn * math.exp(u[2 * i]), u[2 * i + 1]]
        return p + list(u[2 * family.slots:])

    def clip_penalty(u):
        pen = 0.0
        for i in range(family.slots):
            pen += max(0.0, abs(u[2 * i]) - 0.7) + max(0.0, -u[2 * i + 1]) \
                + max(0.0, u[2 * i + 1] - 0.6)
        for j, (_, lo, hi) in enumerate(family.extra):
            v = u[2 * family.slots + j]
            pen += max(0.0, lo - v) + max(0.0, v - hi)
        return pen

    cache = {}

    def design(u):
        key = tuple(np.round(u, 12))
        if key not in cache:
            try:
                p = params(u)
                if any(p[2 * i] >= 0.95 * nyq for i in range(family.slots)):
                    raise ValueError("above Nyquist")
                stages = family.build(p)
                cache[key] = (stages, duration(stages, ref.Ts))
            except (ValueError, ParameterError):
                cache[key] = None
        return cache[key]

    def cost(u):
        pen = clip_penalty(u)
        if pen > 0:
            return 1e3 * (1 + pen)
        d = design(u)
        if d is None:
            return 1e3
        stages, length = d
        v = objective.band_continuous(stages)
        if max_delay is not None:
            excess = length / max_delay - 1
            if excess > 1e-9:               # any violation costs more than any V [%]
                v += 1e3 * (1 + excess)
        if max_smoothing is not None:
            excess = smoothing(chain_taps(stages, ref.Ts), ref) / max_smoothing - 1
            if excess > 0:
                v += 1e3 * (1 + excess)
        return v

    starts = []
    base = []
    for m in anchors:
        base += [0.0, min(m.zeta, 0.5)]
    base += [e[0] for e in family.extra]
    starts.append(np.array(base))
    if max_delay is not None:
        # shorter designs (higher frequency) when the nominal one is too long: the one that
        # just fits (the duration scales as 1/wn) and two others
        d0 = design(np.array(base))
        fit = math.log(d0[1] / max_delay) + 0.01 if d0 is not None and d0[1] > 0 else 0.0
        for scale in sorted({min(max(fit, 0.0), 0.69), 0.3, 0.6}):
            u = np.array(base)
            for i in range(family.slots):
                u[2 * i] = scale
            starts.append(u)
    best = None
    for u0 in starts:
        simplex = [u0] + [u0 + np.eye(u0.size)[j] * (0.05 if j % 2 == 0 or j >= 2 * family.slots
                                                   else 0.03) for j in range(u0.size)]
        res = minimize(cost, u0, method="Nelder-Mead",
                       options={"initial_simplex": np.array(simplex), "xatol": 1e-5,
                                "fatol": 1e-4, "maxiter": 300 * u0.size})
        if best is None or res.fun < best.fun:
            best = res
    d = design(best.x)
    if d is None:
        return None
    stages = d[0]
    h = chain_taps(stages, ref.Ts)
    return evaluate(family.name, stages, h, objective, ref, max_delay, max_smoothing)


def evaluate(name: str, stages: list[Stage], h: np.ndarray, objective: Objective,
             ref: Reference, max_delay: float | None, max_smoothing: float | None) -> Candidate:
    c = Candidate(name, list(stages))
    c.vibration = objective.band(h)
    c.vibration_range = objective.range(h)
    c.vibration_nominal = objective.nominal_value(h)
    c.length = (h.size - 1) * ref.Ts
    c.lag = float(np.dot(np.arange(h.size), h) / h.sum()) * ref.Ts
    c.smoothing = smoothing(h, ref)
    c.peak_accel, c.peak_jerk = move_peaks(h, stages, ref)
    c.continuity = class_name(continuity(stages))
    if max_delay is not None and c.length > max_delay * (1 + 1e-9):
        c.reasons.append(f"delay {c.length:.4g} s > {max_delay:.4g} s")
    if max_smoothing is not None and c.smoothing > max_smoothing * (1 + 1e-9):
        c.reasons.append(f"smoothing {c.smoothing:.4g} > {max_smoothing:.4g}")
    c.meets = not c.reasons
    return c


def recommend(candidates: list[Candidate]) -> Candidate | None:
    """Least remaining vibration among those within the limits; within 0.05 percentage points
    the shorter one."""
    ok = [c for c in candidates if c.meets and c.stages]
    if not ok:
        return None
    best = min(c.vibration for c in ok)
    close = [c for c in ok if c.vibration <= best + 0.05]
    return min(close, key=lambda c: (c.length, c.vibration))


def firmware_lines(c: Candidate, axis: str) -> list[str] | None:
    """[input_shaper] lines for a single shaper 3-D printer firmware knows, else None."""
    if len(c.stages) != 1:
        return None
    s = c.stages[0]
    name = FIRMWARE_NAMES.get(s.kind)
    if s.kind in ("ei", "ei2", "ei3") and abs(s.tolerance - 0.05) > 1e-12:
        return None
    if s.kind == "gmzv":
        name = f"mzv(n={s.order}, t={s.duration:.6g})"
    if name is None:
        return None
    lines = [f"shaper_type_{axis}: {name}", f"shaper_freq_{axis}: {s.wn / (2 * math.pi):.6g}",
             f"damping_ratio_{axis}: {s.zeta:.6g}"]
    if s.kind == "gmzv":
        lines.insert(0, "# generalised MZV: understood by firmware with D. Butyugin's "
                        "shaper_defs.py (e.g. Kalico); others take shaper_type mzv only")
    return lines
