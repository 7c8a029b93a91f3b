# SPDX-License-Identifier: Apache-2.0
"""Candidate filters for a measured record: the registry of families, tuning, figures of merit,
recommendation.

Every family of the library (shapers, smoothers, their chains; one stage per mode for the
multi-mode chains) and, with ``--firmware``, each firmware's own shapers (:mod:`.firmware`)
comes from one registry (:func:`families`), so a new kind joins the ranking by registering
itself. Each candidate's design frequency and damping (and the generalised MZV's duration) is
tuned to minimise the ranking figure (:mod:`.objectives`) under the delay and smoothing limits:
a grid around the largest resonances (a shaper's frequencies at each damping, a chain's stage
pairs, each in one matrix evaluation), then Nelder-Mead from its best point, on the
continuous designs; the reported figures are those of the exact discrete filter at Ts (the
firmware's shapers: their own impulses, as the firmware applies them).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..reference import impulse_response, shaper_impulses
from ..stages import INPUT_SMOOTHERS, SHAPERS
from ..reference.continuous import transfer_unchecked
from ..stages import Stage, _with_mode, for_mode, impulse_shaper, shaper
from .._checks import positive as _positive
from .design_memo import impulses, kernel, zv_span
from ..errors import ParameterError
from ..reference.shapers import _pole as _pole_of, _undamped_design
from .objectives import BOX, impulses_R2, stages_R2, taps_R2

__all__ = ["BOX", "Reference", "Candidate", "chain_taps", "candidate_taps", "impulse_taps",
           "duration", "Family", "register", "families", "continuity", "smoothing", "move_peaks",
           "class_name", "tune", "evaluate", "on_a_mode", "recommend"]

#: Stage families whose impulse response integrates a step once (+1) or twice (+2).
_SMOOTHING_ORDER = {"rectangular": 1, "exponential": 1, "harmonic": 2, "damped_harmonic": 2,
                    # the input smoothers' kernels are continuous and zero at both ends
                    **{k: 2 for k in INPUT_SMOOTHERS}}

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
    vibration_range: tuple[float, float] = (math.nan, math.nan)   # [%] +-3 sd, of the estimate
    vibration_nominal: float = math.nan    # [%] at the identified modes
    vibration_estimate: float = math.nan   # [%] on the plant: the value the range is about
    length: float = 0.0                    # impulse-response length [s]
    lag: float = 0.0                       # centroid [s]
    smoothing: float = 0.0                 # corner rounding, length units
    peak_accel: float = 0.0
    peak_jerk: float = 0.0
    continuity: str = ""
    meets: bool = True
    reasons: list[str] = field(default_factory=list)
    vibration_spectrum: float = math.nan   # [%] over the measured spectrum
    vibration_modal: float | None = None   # [%] over the modal fit (when it explains it)
    ranked_by: str = ""
    range_from: str = ""
    firmware: object = None                # a firmware's shaper: (FirmwareShaper, freq, damping)
    design: tuple = ()                     # ((f [Hz], zeta), ...) it was tuned to, per slot
    # [%] the established tool's own estimate (its three test dampings, every bin), where a
    # default delay budget was traded against it
    vibration_established: float = math.nan
    # what the range joins: ((figure, low, high), ...), the measured spectrum's bounds and,
    # where a fit does not explain the spectrum, the modal fit's +-3 sd
    range_parts: tuple = ()

    def as_dict(self) -> dict:
        from dataclasses import asdict
        return {"name": self.name, "stages": [asdict(s) for s in self.stages],
                "vibration": self.vibration, "vibration_range": list(self.vibration_range),
                "vibration_estimate": self.vibration_estimate,
                "vibration_nominal": self.vibration_nominal, "delay": {
                    "length": self.length, "centroid": self.lag},
                "smoothing": self.smoothing, "peak_accel": self.peak_accel,
                "peak_jerk": None if math.isinf(self.peak_jerk) else self.peak_jerk,
                "jerk_bounded": not math.isinf(self.peak_jerk),
                "continuity": self.continuity, "meets_limits": self.meets,
                "limit_violations": self.reasons,
                "vibration_spectrum": self.vibration_spectrum,
                "vibration_modal": self.vibration_modal, "ranked_by": self.ranked_by,
                "range_from": self.range_from,
                "range_parts": [{"from": k, "low": lo, "high": hi}
                                for k, lo, hi in self.range_parts],
                "vibration_established": None if math.isnan(self.vibration_established)
                else self.vibration_established,
                "design": [{"freq_hz": f, "damping": z} for f, z in self.design],
                "firmware_shaper": None if self.firmware is None else {
                    "firmware": self.firmware[0].firmware, "name": self.firmware[0].name,
                    "freq_hz": self.firmware[1], "damping": self.firmware[2]}}


def chain_taps(stages: list[Stage], Ts: float) -> np.ndarray:
    h = np.ones(1)
    for s in stages:
        h = np.convolve(h, impulse_response(s, Ts=Ts))
    return h


def candidate_taps(c, Ts: float) -> np.ndarray:
    """Taps at Ts of a candidate: its chain, or its firmware shaper's impulses."""
    if c.firmware is not None:
        shaper, freq, damping = c.firmware
        return impulse_taps(*shaper.impulses(freq, damping), Ts)
    return chain_taps(c.stages, Ts) if c.stages else np.ones(1)


def impulse_taps(A, t, Ts: float) -> np.ndarray:
    """Taps at Ts of impulses (A, t [s]): each impulse split linearly between its two nearest
    samples (for the figures of merit of a firmware's shaper, which the firmware applies in
    continuous time)."""
    A = np.asarray(A, dtype=float) / float(np.sum(A))
    x = np.asarray(t, dtype=float) / Ts
    k = np.floor(x).astype(int)
    frac = x - k
    h = np.zeros(int(k.max()) + 2)
    np.add.at(h, k, A * (1 - frac))
    np.add.at(h, k + 1, A * frac)
    return np.trim_zeros(h, "b")


_ZVN_ORDER = {"zv": lambda s: 1, "zvd": lambda s: 2, "zvdd": lambda s: 3,
              "zvn": lambda s: s.order}


def duration(stages, Ts: float) -> float:
    """Impulse-response length (L - 1) Ts of the discrete chain [s], without building it: a
    smoother of duration T spans floor(T/Ts) samples, a shaper whose last impulse is at t
    spans ceil(t/Ts) (exact timing splits it onto the next sample)."""
    n = 0
    for s in stages:
        if s.kind in INPUT_SMOOTHERS:   # every sample of the kernel's span a tap
            n += math.ceil(kernel(s)[1] / Ts - 1e-9)
        elif s.kind in _SMOOTHING_ORDER:
            n += math.floor(s.T / Ts + 1e-9)
        elif s.kind in _ZVN_ORDER:      # exact ZV^n: n convolved exact ZVs
            n += _ZVN_ORDER[s.kind](s) * math.ceil(zv_span(s) / Ts - 1e-9)
        else:
            n += math.ceil(float(impulses(s)[1][-1]) / Ts - 1e-9)
    return n * Ts


def _pole(wn, zeta):
    return complex(-zeta * wn, wn * math.sqrt(1 - zeta * zeta))


# ---------------------------------------------------------------- families

@dataclass
class Family:
    """A candidate family: ``build(params)`` -> stages, params = per slot (wn, zeta) [+ extra].
    A firmware's shaper has ``shaper`` (a :class:`.firmware.FirmwareShaper`) instead: its
    impulses at (freq, damping) are the candidate."""
    name: str
    slots: int
    build: object = None
    extra: tuple = ()          # (start, low, high) of extra parameters
    shaper: object = None


class _ModeStage:
    """Builds the family's stage at a mode (wn, zeta[, duration]): the first design through
    the public constructor ``make`` (every field checked), every later one as a copy of it
    with only those fields changed and checked (``stages._with_mode``: the same Stage, the
    same errors). The tuning builds thousands of designs per family, and re-checking the
    kind, order, tolerance and timing of each was about a fourteenth of its time."""
    __slots__ = ("make", "first")

    def __init__(self, make):
        self.make = make
        self.first = None

    def __call__(self, wn, zeta, duration=None):
        if self.first is not None:
            return _with_mode(self.first, wn, zeta, duration)
        stage = self.make(wn, zeta) if duration is None else self.make(wn, zeta, duration)
        self.first = stage
        return stage


def _shaper(kind, **kw):
    st = _ModeStage(lambda wn, zeta: shaper(kind, wn=wn, zeta=zeta, **kw))
    return lambda p: [st(p[0], p[1])]


def _gmzv(n):
    st = _ModeStage(lambda wn, zeta, d: shaper("gmzv", wn=wn, zeta=zeta, order=n, duration=d))
    return lambda p: [st(p[0], p[1], p[2])]


def _smoother(kind):
    if kind not in INPUT_SMOOTHERS:     # the trajectory smoothers: for_mode builds them unchecked
        return lambda p: [for_mode(kind, wn=p[0], zeta=p[1])]
    st = _ModeStage(lambda wn, zeta: for_mode(kind, wn=wn, zeta=zeta))
    return lambda p: [st(p[0], p[1])]


def _library_single() -> list[Family]:
    out = [Family(k, 1, _shaper(k)) for k in ("zv", "mzv", "zvd", "zvdd", "ei", "ei2", "ei3")]
    out.append(Family("zvn (n=4)", 1, _shaper("zvn", order=4)))
    out.append(Family("gmzv (n=4)", 1, _gmzv(4), extra=((1.0, 0.55, 1.45),)))
    out.append(Family("gmzv (n=5)", 1, _gmzv(5), extra=((1.3, 0.6, 1.95),)))
    out += [Family(k, 1, _smoother(k)) for k in ("harmonic", "damped_harmonic", "exponential")]
    zv = _ModeStage(lambda wn, zeta: shaper("zv", wn=wn, zeta=zeta))
    out.append(Family("rectangular*zv", 1, lambda p: [for_mode("rectangular", wn=p[0], zeta=p[1]),
                                                      zv(p[0], p[1])]))
    return out


def _si(n):
    st = _ModeStage(lambda wn, zeta, d: shaper("si", wn=wn, zeta=zeta, order=n, duration=d))
    return lambda p: [st(p[0], p[1], p[2])]


#: The specified-insensitivity shapers' impulse counts and the span of each [damped periods]
#: (``Stage``'s range for si: (n - 1)/4 to (n - 1)/2).
SI_ORDERS = (3, 5, 7)


def _input_smoothers() -> list[Family]:
    """The input smoothers of Klipper-derived firmware (polynomial kernels zero at both ends,
    D. Butyugin): unlike a shaper they attenuate every frequency above their band, what a
    spectrum with resonances above the first needs, so they join records of two or more
    modes (each costs about 0.3 s of tuning: its kernel's transfer is a series)."""
    return [Family(k, 1, _smoother(k)) for k in INPUT_SMOOTHERS]


def _library_insensitive() -> list[Family]:
    """The specified-insensitivity shapers (Singhose, Seering and Singer 1996) of 3, 5 and 7
    impulses, their span tuned."""
    out = []
    for n in SI_ORDERS:
        lo, hi = 0.25 * (n - 1), 0.5 * (n - 1)
        out.append(Family(f"si (n={n})", 1, _si(n), extra=((0.5 * (lo + hi), lo, hi),)))
    return out


def _chain(a, b):
    sa = _ModeStage(lambda wn, zeta: shaper(a, wn=wn, zeta=zeta))
    sb = _ModeStage(lambda wn, zeta: shaper(b, wn=wn, zeta=zeta))
    return lambda p: [sa(p[0], p[1]), sb(p[2], p[3])]


def _library_chains() -> list[Family]:
    return [Family(f"{a}+{b}", 2, _chain(a, b))
            for a, b in (("zv", "zv"), ("mzv", "mzv"), ("zvd", "zvd"), ("mzv", "zv"), ("ei", "ei"))]


def _as_impulses(fw_shaper):
    def build(p):
        A, t = fw_shaper.impulses(p[0] / (2 * math.pi), p[1])
        return [impulse_shaper(amplitudes=A, times=t)]
    return build


#: The established tool's own shapers that differ from the library's: Klipper's EI family is
#: fitted polynomials in the damping ratio, not the papers' closed forms (the library's EI
#: leaves up to 1.7 percentage points more at zeta 0.1); its ZV, MZV and ZVD are the library's.
KLIPPER_OWN = ("ei", "2hump_ei", "3hump_ei")


def _firmware_defined() -> list[Family]:
    """Klipper's EI family as user-defined impulses of the library (exact discrete filters for
    the C library and the FMUs): every ranking holds what the established tool would pick."""
    from . import firmware as fw
    return [Family(f"klipper {n} impulses", 1, _as_impulses(fw.by_name("klipper", n)))
            for n in KLIPPER_OWN]


#: What a firmware runs beyond its named shapers: RepRapFirmware's user-defined shaper (up to
#: 5 impulses) holds the specified-insensitivity shapers of 3 and 5 impulses, each over the
#: middle of its span. Klipper, Marlin and Prusa run neither the SI shapers nor the input
#: smoothers (those are for the C library, the FMUs and Klipper-derived firmware).
RRF_SI = ((3, 0.75), (5, 1.5))


def _firmware_extra(firmware: str):
    if firmware != "rrf":
        return []
    from . import firmware as fw
    return [(f"rrf custom si (n={n}, {d:g} Td)", fw.rrf_si(n, d)) for n, d in RRF_SI]


#: The registry: (minimum number of resonances, factory of families). A new kind of filter
#: joins every ranking by appending here (:func:`register`).
_REGISTRY: list = [(1, _library_single), (2, _library_chains), (1, _firmware_defined),
                   (1, _library_insensitive), (2, _input_smoothers)]


def register(factory, min_modes: int = 1) -> None:
    """Add ``factory`` (a callable returning a list of :class:`Family`) to the candidates of
    every record with at least ``min_modes`` resonances."""
    _REGISTRY.append((min_modes, factory))


def families(n_modes: int, firmware: str = "none") -> list[Family]:
    """The candidate families for a record with ``n_modes`` resonances: every registered
    family (``firmware="none"``), or the given firmware's own shapers."""
    if firmware != "none":
        from . import firmware as fw
        out = [Family(f"{s.firmware} {s.name}", 1, shaper=s) for s in fw.shapers(firmware)]
        return out + [Family(name, 1, shaper=s) for name, s in _firmware_extra(firmware)]
    out = []
    for need, factory in _REGISTRY:
        if n_modes >= need:
            out += factory()
    return out


# ---------------------------------------------------------------- figures of merit

def _convolve(a: np.ndarray, h: np.ndarray) -> np.ndarray:
    """np.convolve(a, h), by FFT when both are long (the figures of merit convolve moves of
    thousands of samples with filters of hundreds: a direct sum costs seconds)."""
    if min(a.size, h.size) < 64:
        return np.convolve(a, h)
    n = a.size + h.size - 1
    m = 1 << (n - 1).bit_length()
    return np.fft.irfft(np.fft.rfft(a, m) * np.fft.rfft(h, m), m)[:n]


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
    xf = _convolve(x, h)[: t.size]
    yf = _convolve(y, h)[: t.size]
    sl = slice(L, None)                     # past the start-up transient of the window
    d1 = np.hypot(np.maximum(xf[sl], 0.0), yf[sl])
    d2 = np.hypot(xf[sl], np.minimum(yf[sl], 0.0))
    dev90 = float(np.max(np.minimum(d1, d2)))
    r = -0.5 * A * t * t
    rf = _convolve(r, h)[: t.size]
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
    qf = _convolve(q, h)[: t.size]
    acc = np.diff(qf, 2) / Ts ** 2
    peak_a = float(np.max(np.abs(acc)))
    if continuity(stages) + 2 < 2:
        return peak_a, math.inf
    return peak_a, float(np.max(np.abs(np.diff(acc)))) / Ts


def class_name(k: int) -> str:
    return "discontinuous" if k < 0 else f"C{k}"


# ---------------------------------------------------------------- tuning

def _R2(objective_poles, stages=None, impulses=None, h=None, Ts=None):
    if impulses is not None:
        return impulses_R2(impulses[0], impulses[1], objective_poles)
    if h is not None:
        return taps_R2(h, Ts, objective_poles)
    return stages_R2(stages, objective_poles)


def tune(family: Family, anchors, objectives, rank: str, ref: Reference,
         max_delay: float | None, max_smoothing: float | None) -> Candidate | None:
    """The family's design minimising the ranking figure within the limits.

    ``anchors``: natural frequencies [rad/s] of the largest resonances, largest first;
    ``objectives``: {"spectrum": SpectralObjective, "modal": ModalObjective or None};
    ``rank``: which of them ranks."""
    from ..errors import ParameterError
    obj = objectives[rank]
    slots = family.slots
    anchors = [anchors[min(i, len(anchors) - 1)] for i in range(slots)]
    nyq = math.pi / ref.Ts
    fw = family.shaper
    if fw is not None:
        zlo, zhi = fw.damping_range()
        z_grid = sorted({min(max(z, zlo), zhi) for z in (zlo, 0.05, 0.1, 0.15, zhi)})
        f_lo, f_hi = 2 * math.pi * fw.min_freq, 2 * math.pi * fw.max_freq
    else:
        zlo, zhi = 0.0, 0.6
        z_grid = (0.02, 0.07, 0.12, 0.2)
        f_lo, f_hi = 0.0, 0.95 * nyq

    def params(u):
        p = []
        for i, wn in enumerate(anchors):
            p += [wn * math.exp(u[2 * i]), u[2 * i + 1]]
        return p + list(u[2 * slots:])

    def penalty(u):
        pen = 0.0
        for i in range(slots):
            wn = anchors[i] * math.exp(u[2 * i])
            pen += max(0.0, abs(u[2 * i]) - 1.2) + max(0.0, zlo - u[2 * i + 1]) \
                + max(0.0, u[2 * i + 1] - zhi) + max(0.0, f_lo / wn - 1) + max(0.0, wn / f_hi - 1)
        for j, (_, lo, hi) in enumerate(family.extra):
            v = u[2 * slots + j]
            pen += max(0.0, lo - v) + max(0.0, v - hi)
        return pen

    cache = {}

    def design(u):
        key = tuple(np.round(u, 10))
        if key not in cache:
            try:
                p = params(u)
                if fw is not None:
                    A, t = fw.impulses(p[0] / (2 * math.pi), p[1])
                    cache[key] = (None, (np.asarray(A, float), np.asarray(t, float)),
                                  float(t[-1]))
                else:
                    stages = family.build(p)
                    cache[key] = (stages, None, duration(stages, ref.Ts))
            except (ValueError, ParameterError, ZeroDivisionError, OverflowError):
                cache[key] = None
        return cache[key]

    def cost(u):
        pen = penalty(u)
        if pen > 0:
            return 1e3 * (1 + pen)
        d = design(u)
        if d is None:
            return 1e3
        stages, imp, length = d
        v = obj.tuning_value(_R2(obj.poles, stages, imp), length)
        if not math.isfinite(v):
            return 1e3
        if max_delay is not None:
            excess = length / max_delay - 1
            if excess > 1e-9:               # any violation costs more than any V [%]
                v += 1e3 * (1 + excess)
        if max_smoothing is not None:
            h = chain_taps(stages, ref.Ts) if stages is not None else impulse_taps(*imp, ref.Ts)
            excess = smoothing(h, ref) / max_smoothing - 1
            if excess > 0:
                v += 1e3 * (1 + excess)
        return v

    extra0 = [e[0] for e in family.extra]
    scored = []
    if slots == 1:
        ratios = np.geomspace(0.5, 2.0, 61)
        extras = [extra0]
        if family.extra:            # the generalised MZV's duration: its start and two others
            lo_e, hi_e = family.extra[0][1], family.extra[0][2]
            extras += [[lo_e + 0.25 * (hi_e - lo_e)], [lo_e + 0.75 * (hi_e - lo_e)]]
        step_r, step_z = 0.03, 0.04
        single = fw is not None or _is_single_shaper(design, z_grid[0], extra0)
        if single:
            # one shaper: every frequency at a damping ratio in one matrix evaluation, so the
            # grid is fine in both (the refinement then starts next to the optimum). The scan
            # is built at the mode, or for a firmware at the nearest frequency it accepts (a
            # belt's 122 Hz mode is above Prusa's 100 Hz: no design at the mode, an empty scan)
            r0 = 0.0 if fw is None else math.log(min(max(anchors[0], f_lo * (1 + 1e-9)),
                                                     f_hi * (1 - 1e-9)) / anchors[0])
            zs = sorted(set(z_grid) | {min(max(z, zlo), zhi) for z in _SINGLE_ZETAS})
            for z in zs:
                for ex in extras:
                    scored += _scan_single(design, obj, np.array([r0, z] + ex), ratios[::2],
                                           max_delay, ref.Ts, fw is not None)
        else:
            base = design(np.array([0.0, z_grid[min(1, len(z_grid) - 1)]] + extra0))
            if max_delay is not None and base is not None and base[2] > 0:
                fit = base[2] / max_delay
                ratios = np.r_[ratios, fit * np.array([1.002, 1.02, 1.08, 1.2])]
            step_r, step_z = 0.1, 0.06     # the coarser grid's steps
            for z in z_grid:
                for ex in extras:
                    for r in ratios[::4]:
                        u = np.array([math.log(r), z] + ex)
                        scored.append((cost(u), tuple(u)))
    else:
        step_r, step_z, single = 0.06, 0.04, False
        scored = _scan_chain(family, anchors, obj, max_delay, ref.Ts, extra0)
        if scored is None:
            grid = [np.array([math.log(r1), z, math.log(r2), z] + extra0)
                    for r1 in (0.92, 1.0, 1.1) for r2 in (0.92, 1.0, 1.1) for z in z_grid[1:3]]
            if max_delay is not None:
                grid += [np.array([math.log(q), z, math.log(q), z] + extra0)
                         for q in (1.2, 1.45, 1.75) for z in z_grid[1:3]]
            scored = [(cost(u), tuple(u)) for u in grid]
    if not scored:                      # no design of the family near the modes
        return None
    scored.sort(key=lambda x: x[0])
    # a short bounded refinement of each parameter in turn from the grid's best point, within
    # about a grid step of it (scipy's bounded scalar minimiser: a dozen costs each)
    steps = [step_r, step_z] * slots + [0.25 * (e[2] - e[1]) for e in family.extra]
    clamp = None
    if single and max_delay is not None:
        def clamp(u):
            """A one-shaper design below the least frequency that meets the delay limit, moved
            onto it (the refinement then follows that limit as the damping moves: the best
            design within a delay limit often lies on it)."""
            u0 = np.concatenate(([0.0], u[1:]))
            taps = (_shaper_taps(design, u0, True) if fw is not None
                    else _shaper_span(family, params(u0)))
            if taps is not None:
                lo = math.log(_min_ratio(taps, max_delay, ref.Ts))
                if math.isfinite(lo) and u[0] < lo:
                    u = u.copy()
                    u[0] = lo
            return u
    u, fu = _refine(cost if clamp is None else (lambda v: cost(clamp(v))),
                    np.array(scored[0][1]), steps,
                    # a chain's four parameters to 0.1 % of a frequency (a tenth of a bin of
                    # a 60 s record at 60 Hz): half its costs of 1e-4
                    xatol=1e-4 if slots == 1 else 1e-3)
    if clamp is not None:
        u = clamp(u)
    if fu >= 1e3:
        return None
    d = design(u)
    if d is None:
        return None
    stages, imp, _ = d
    p = params(u)
    if fw is not None:
        c = evaluate(family.name, [], objectives, rank, ref, max_delay, max_smoothing,
                     impulses=imp, firmware=(fw, p[0] / (2 * math.pi), p[1]))
    else:
        c = evaluate(family.name, stages, objectives, rank, ref, max_delay, max_smoothing)
    c.design = tuple((p[2 * i] / (2 * math.pi), p[2 * i + 1]) for i in range(slots))
    return c


def _refine(cost, u0, steps, xatol: float = 1e-4):
    """``u0`` refined from a simplex of ``steps`` about it by scipy's Nelder-Mead (a narrow
    valley of damping against frequency is followed, where a search along each parameter in
    turn stopped at its first point); returns (u, cost)."""
    from scipy.optimize import minimize
    u0 = np.array(u0, dtype=float)
    simplex = [u0] + [u0 + np.eye(u0.size)[j] * steps[j] for j in range(u0.size)]
    res = minimize(cost, u0, method="Nelder-Mead",
                   options={"initial_simplex": np.array(simplex), "xatol": xatol,
                            "fatol": 1e-4, "maxiter": 30 * u0.size})
    return np.asarray(res.x, dtype=float), float(res.fun)


def _is_single_shaper(design, z, extra0):
    d = design(np.array([0.0, z] + extra0))
    return d is not None and d[0] is not None and len(d[0]) == 1 and d[0][0].kind in SHAPERS


def _shaper_taps(design, u0, fw):
    """(A normalised, t [s], zvn order or 0) of a one-shaper design, at ratio 1."""
    d = design(u0)
    if d is None:
        return None
    stages, imp, _ = d
    if imp is None:
        A, t = impulses(stages[0])
        order = _ZVN_ORDER[stages[0].kind](stages[0]) if stages[0].kind in _ZVN_ORDER else 0
        span = zv_span(stages[0]) if order else 0.0
    else:
        A, t = imp
        order, span = 0, 0.0
    A = np.asarray(A, float) / float(np.sum(A))
    return A, np.asarray(t, float), order, span, fw


def _shaper_span(family, p):
    """What :func:`_min_ratio` reads of :func:`_shaper_taps` for a one-shaper library design
    at parameters ``p`` (its last impulse time, ZV^n order and ZV span), without computing its
    impulses: the last time is the undamped design's last time in damped periods times the
    damped period, the float its impulses hold. None where the design fails, as there."""
    try:
        stage = family.build(p)[0]
        if stage.kind in _ZVN_ORDER:
            return None, None, _ZVN_ORDER[stage.kind](stage), zv_span(stage), False
        if stage.kind == "impulses":        # a shaper given by its impulses: their last time
            return None, impulses(stage)[1], 0, 0.0, False
        units = _undamped_design(stage)[1]
    except (ValueError, ParameterError, ZeroDivisionError, OverflowError):
        return None
    last = units[-1] * (2.0 * math.pi / _pole_of(stage.wn, stage.zeta).imag)
    return None, (last,), 0, 0.0, False


def _scaled_lengths(taps, ratios, Ts):
    """Lengths [s] of the design at each frequency ratio: a firmware's impulses as applied
    (their last time), a library shaper as :func:`duration` counts its discrete filter."""
    A, t, order, span, fw = taps
    if fw:
        return t[-1] / ratios
    if order:
        return order * np.ceil(span / ratios / Ts - 1e-9) * Ts
    return np.ceil(t[-1] / ratios / Ts - 1e-9) * Ts


def _min_ratio(taps, max_delay, Ts):
    """The least frequency ratio at which the design's length meets ``max_delay``: a firmware's
    impulses as applied, a library shaper's discrete filter as :func:`duration` counts it."""
    A, t, order, span, fw = taps
    if fw:
        return float(t[-1]) / max_delay * (1 + 1e-9)
    n = math.floor(max_delay / Ts + 1e-9)
    if order:
        per = n // order
        return math.inf if per < 1 else span / (per * Ts) * (1 + 1e-9)
    return math.inf if n < 1 else float(t[-1]) / (n * Ts) * (1 + 1e-9)


def _boundary_ratios(taps, max_delay, Ts):
    """Frequency ratios at which the design's length just meets ``max_delay`` (and a few
    above): the best design within a delay limit often lies on it."""
    rb = _min_ratio(taps, max_delay, Ts)
    if not math.isfinite(rb):
        return np.zeros(0)
    return rb * np.array([1.0, 1.02, 1.08, 1.2])


def _delay_penalty(L, max_delay):
    if max_delay is None:
        return 0.0
    excess = L / max_delay - 1
    return np.where(excess > 1e-9, 1e3 * (1 + excess), 0.0)


#: Largest real part of an exponent the scans evaluate: |e^x|^2 stays within the float range
#: (e^709.78 is the largest double).
_EXP_LIMIT = 350.0

#: Damping ratios of the one-shaper grid (with the family's own grid and its limits).
_SINGLE_ZETAS = (0.01, 0.035, 0.06, 0.09, 0.12, 0.15, 0.2, 0.25)


def _scan_single(design, obj, u0, ratios, max_delay, Ts, fw):
    """The least cost of the one-shaper design ``u0`` moved to each frequency ratio (its
    impulses scale as 1/f at a fixed damping, amplitudes unchanged), all in one matrix
    evaluation, with the ratios where its length meets ``max_delay``. Returns [(cost, u)]."""
    taps = _shaper_taps(design, u0, fw)
    if taps is None:
        return []
    if max_delay is not None:
        ratios = np.r_[ratios, _boundary_ratios(taps, max_delay, Ts)]
    A, t = taps[0], taps[1]
    E = -obj.poles[:, None, None] * (t[None, :] / ratios[:, None])[None, :, :]
    # a firmware's damping ratio near 1 stretches its shaper to seconds: e^{zeta wn t} at the
    # plant's poles, squared, then lies beyond the float range. Such a scale is infeasible
    # (the cost of 1e3), not computed (an overflow warning on real records with Marlin or
    # Prusa's damping up to 1)
    unbounded = np.any(E.real > _EXP_LIMIT, axis=(0, 2))
    E[:, unbounded, :] = 0.0
    H = np.exp(E) @ A
    L = _scaled_lengths(taps, ratios, Ts)
    v = obj.tuning_values(H.real ** 2 + H.imag ** 2, L) + _delay_penalty(L, max_delay)
    v = np.where(np.isfinite(v) & ~unbounded, v, 1e3)
    j = int(np.argmin(v))               # the best of the scan (the refinement starts there)
    u = u0.copy()
    u[0] = u0[0] + math.log(ratios[j])
    return [(float(v[j]), tuple(u))]


#: The chains' grid: frequency ratios of each stage to its mode, and damping ratios.
_CHAIN_RATIOS = np.geomspace(0.8, 1.25, 9)
_CHAIN_ZETAS = (0.04, 0.07, 0.1, 0.14)


def _scan_chain(family, anchors, obj, max_delay, Ts, extra0):
    """Costs over a grid of a two-shaper chain, each stage at every frequency and damping ratio
    of the grid independently (the chain's |H|^2 is the product of its stages': one matrix
    evaluation of each stage, then every pair at once). None when the family is not two
    library shapers."""
    from ..errors import ParameterError
    ratios = _CHAIN_RATIOS
    if max_delay is not None:
        ratios = np.r_[ratios, 1.2, 1.45, 1.75]
    per_slot = []
    for slot in range(2):
        R2s, Ls, us = [], [], []
        for z in _CHAIN_ZETAS:
            try:
                stages = family.build([anchors[0], z, anchors[1], z] + list(extra0))
            except (ValueError, ParameterError, ZeroDivisionError, OverflowError):
                return None
            if len(stages) != 2 or any(s.kind not in SHAPERS for s in stages):
                return None
            st = stages[slot]
            A, t = impulses(st)
            A = np.asarray(A, float) / float(np.sum(A))
            order = _ZVN_ORDER[st.kind](st) if st.kind in _ZVN_ORDER else 0
            taps = (A, np.asarray(t, float), order, zv_span(st) if order else 0.0, False)
            H = np.exp(-obj.poles[:, None, None] * (taps[1][None, :] / ratios[:, None])
                       [None, :, :]) @ A
            R2s.append(np.abs(H) ** 2)
            Ls.append(_scaled_lengths(taps, ratios, Ts))
            us += [(math.log(r), z) for r in ratios]
        per_slot.append((np.hstack(R2s), np.concatenate(Ls), us))
    (R1, L1, u1), (R2, L2, u2) = per_slot
    R = (R1[:, :, None] * R2[:, None, :]).reshape(R1.shape[0], -1)
    L = (L1[:, None] + L2[None, :]).ravel()
    v = obj.tuning_values(R, L) + _delay_penalty(L, max_delay)
    n2 = len(u2)
    return [(float(v[k]) if math.isfinite(v[k]) else 1e3,
             tuple(u1[k // n2]) + tuple(u2[k % n2]) + tuple(extra0)) for k in range(v.size)]


def evaluate(name: str, stages: list[Stage], objectives, rank: str, ref: Reference,
             max_delay: float | None, max_smoothing: float | None, *, impulses=None,
             firmware=None) -> Candidate:
    """Every figure of one candidate: the library's ``stages`` as the exact discrete filter at
    Ts, or a firmware's ``impulses`` (A, t) as the firmware applies them."""
    c = Candidate(name, list(stages), firmware=firmware)
    if impulses is not None:
        h = impulse_taps(*impulses, ref.Ts)
        c.length = float(impulses[1][-1])

        def R2(p):
            return _R2(p, impulses=impulses)
    else:
        h = chain_taps(stages, ref.Ts) if stages else np.ones(1)
        c.length = (h.size - 1) * ref.Ts

        def R2(p):
            return _R2(p, h=h, Ts=ref.Ts)
    spec, modal = objectives["spectrum"], objectives.get("modal")
    L = c.length
    c.vibration_spectrum = spec.value(R2(spec.poles), L)
    if modal is not None:
        c.vibration_modal = modal.value(R2(modal.poles), L)
        c.vibration_range = modal.range(R2(modal.box), L)
        c.vibration_nominal = modal.nominal_value(R2(modal.nominal), L)
        c.vibration_estimate = c.vibration_modal
        c.range_from = modal.kind
    else:
        c.vibration_range = spec.range(R2(spec.box.ravel()), L)
        c.range_parts = ((spec.kind, *c.vibration_range),)
        c.vibration_nominal = spec.nominal_value(R2(spec.nominal), L)
        # the spectral figure is not the plant's remaining vibration (it counts nothing under a
        # twentieth of the peak): the range is about the spectrum's estimate of the plant's
        c.vibration_estimate = c.vibration_nominal
        c.range_from = spec.kind
        unsure = objectives.get("unsure")
        if unsure is not None:       # a fit that does not explain the spectrum: either may hold
            lo, hi = unsure.range(R2(unsure.box), L)
            c.range_parts += ((unsure.kind, lo, hi),)
            c.vibration_range = (min(lo, c.vibration_range[0]), max(hi, c.vibration_range[1]))
            c.range_from = "measured spectrum and modal fit"
    c.vibration = c.vibration_modal if rank == "modal" else c.vibration_spectrum
    c.ranked_by = objectives[rank].kind
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


#: Candidates whose ranking figure lies within this many percentage points of the least tie.
TIE_PP = 0.05
#: Tied candidates whose lengths lie within this fraction of the shortest: the least smoothing
#: of them (at the default budget most lie on it: a firmware's impulses just under it, the
#: library's discrete filters rounded up to a sample).
LENGTH_TIE = 0.01
#: Least relative gain in smoothing that a tie is given to (less is no gain worth the
#: tie's extra vibration).
SMOOTHING_GAIN = 0.01
#: A design "on" an identified mode: within this fraction of its frequency (or its +-3 sd).
ON_MODE = 0.15


def on_a_mode(c: Candidate, modes) -> bool:
    """Whether every slot of ``c`` was designed near an identified mode's frequency."""
    if not c.design or not modes:
        return False
    return all(any(abs(f - m.f_hz) <= max(ON_MODE * m.f_hz, BOX * m.wn_std / (2 * math.pi))
                   for m in modes) for f, _ in c.design)


def recommend(candidates: list[Candidate], modes=(), *, sample: float = 0.0) -> Candidate | None:
    """Least remaining vibration among those within the limits; within 0.05 percentage points
    of it, the shorter one, and of those within 1 % (and ``sample`` [s], the filters' sample
    period: the budget is rounded up to it) of the shortest length, the one that rounds
    corners least (the least smoothing, if 1 % less than the least-vibration one's). Where the measured PSD ranks, ties are first
    told apart by the plant estimate, among the candidates designed on an identified mode
    (``modes``): of those within 5 % (and 0.05 points) of their least estimate, the shorter
    one, then the least smoothing.

    At the default delay budget most tied candidates last as long as the budget: the shortest
    of them was whichever came first, with up to 9 % more corner rounding than the established
    tool's pick of the same length on real records; and the trade-off's own pick lasts up to a
    sample less than the budget it set, so "shorter" alone gave it every tie.

    The measured-PSD figure counts nothing under a twentieth of the peak, so on a clean
    spectrum many candidates tie at 0 %; the shortest of them was often the narrowest (a ZV
    where an MZV leaves half as much of the plant: a mode whose frequency moves with the
    amplitude). The plant estimate tells those ties apart; a design far from every mode is
    left out of that (on a record clipped for two thirds of its samples, the least estimate
    was a filter tuned at 6.3 Hz where the oscillation is at 8 Hz). Where the modal fit ranks,
    the estimate is the ranking figure."""
    ok = [c for c in candidates if c.meets and (c.stages or c.firmware is not None)]
    if not ok:
        return None
    best = min(c.vibration for c in ok)
    close = [c for c in ok if c.vibration <= best + TIE_PP]
    tied = [c for c in close if c.ranked_by == "measured spectrum" and on_a_mode(c, modes)
            and math.isfinite(c.vibration_estimate)]
    if tied:
        least = min(c.vibration_estimate for c in tied)
        close = [c for c in tied if c.vibration_estimate <= 1.05 * least + TIE_PP]
    shortest = min(c.length for c in close)
    close = [c for c in close if c.length <= shortest * (1 + LENGTH_TIE) + sample]
    least = min(close, key=lambda c: (c.vibration, c.length))
    sharper = [c for c in close if c.smoothing < (1 - SMOOTHING_GAIN) * least.smoothing]
    if not sharper:
        return least
    return min(sharper, key=lambda c: (c.smoothing, c.length, c.vibration))
