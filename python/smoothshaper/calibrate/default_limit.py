# SPDX-License-Identifier: Apache-2.0
"""The delay ``calibrate`` allows when no limit is given (neither ``max_delay`` nor
``max_smoothing``).

Without a limit the least remaining vibration is always a longer filter: a shaper tuned for a
damping of 0.99, a smoother spanning several periods of the slowest mode (on a real Voron 2
table, 124 to 289 ms where the established tool's pick lasts 18 ms). Printing speed is lost
to that length, so a default must trade vibration against it. The established 3-D printer
tool's trade-off (Klipper ``klippy/extras/shaper_calibrate.py``, ``fit_shaper`` and
``find_best_shaper``, K. O'Connor and D. Butyugin) was chosen on real users' data; it is
applied here, on this calibration's own measured-spectrum figure, to fix the delay budget:

* Candidates: the target firmware's shapers (Klipper's five it calibrates, zv, mzv, ei,
  2hump_ei and 3hump_ei, for ``firmware="none"`` and ``"klipper"``), each designed for a
  damping ratio of 0.1 and scanned every 0.2 Hz from its lowest frequency up to 150 Hz (or
  the top of the scored spectrum, if higher). The lowest frequency of a resonance test's
  shaper is Klipper's own minimum (``shaper_defs.py``, "chosen to have projected max_accel ~=
  1500"), for another firmware's shaper the lowest frequency whose suggested maximum
  acceleration (:func:`.firmware.max_accel`) reaches 1500 mm/s^2 (the rule gives Klipper's
  minima within 1.6 Hz). A mode below every shaper's lowest frequency moves the scans' start
  to half its frequency. For a free decay or a frequency response (no printer's test) the
  scan runs from half the slowest to twice the fastest identified mode. Outside the printer's
  grid the step is a hundredth of the lowest frequency, or coarser to keep to
  :data:`MAX_SCAN` frequencies.
* Each design's vibration ``v`` (a fraction) is the measured-spectrum figure at the test
  dampings 0.075, 0.1, 0.15 (the established tool's estimate), its smoothing ``s`` Klipper's
  ``_get_shaper_smoothing`` at 5000 mm/s^2 and a square-corner velocity of 5 mm/s, its score
  ``s (v^1.5 + 0.2 v + 0.01)``.
* Per shaper the least-vibration frequency is found; the pick is the least score among the
  frequencies leaving at most ``1.1 v_best + 0.0005``. Across shapers, in the order above, a
  later one replaces the pick when its score is 20 % lower, or 5 % lower with 10 % less
  smoothing; then any of its frequencies with both less vibration and less smoothing than the
  pick replaces it; a ZV pick gives way to the first other shaper leaving 10 % less (every
  two-impulse shaper counts as a ZV: Marlin's classic ``M593 ZV`` too).

With a firmware other than Klipper, the established tool's own trade-off (over Klipper's
shapers) is also taken on the same spectrum, and the budget is the longer of the two picks'
durations (:attr:`DefaultLimit.established`): a trade-off over the firmware's shapers can pick
a shorter one that leaves more than the established pick.

The budget is the picked shaper's duration (its last impulse). Every candidate family then
competes within it for the least remaining vibration, so the recommendation is never longer
than the established trade-off's pick and, since that pick itself is among the candidates
(with ``firmware="none"``, Klipper's shapers join as user-defined impulses), it leaves no
more by the ranking figure. The budget is at most the duration of the longest shaper at its
lowest frequency (3hump_ei at 48 Hz: 42 ms).
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from . import firmware as fw
from .candidates import TIE_PP
from .objectives import impulses_R2

__all__ = ["TRADE_OFF_SHAPERS", "MAX_SHAPER_FREQ", "FREQ_STEP", "DESIGN_DAMPING", "ACCEL",
           "SCV", "MIN_ACCEL", "DefaultLimit", "trade_off_shapers", "default_limit"]

#: The shapers the established tool calibrates, in its order (``AUTOTUNE_SHAPERS``).
TRADE_OFF_SHAPERS = ("zv", "mzv", "ei", "2hump_ei", "3hump_ei")
#: Top of the established tool's frequency scan [Hz] (``MAX_SHAPER_FREQ``).
MAX_SHAPER_FREQ = 150.0
#: Its frequency step [Hz].
FREQ_STEP = 0.2
#: The damping ratio the shapers are designed for (``DEFAULT_DAMPING_RATIO``).
DESIGN_DAMPING = 0.1
#: Acceleration [mm/s^2] and square-corner velocity [mm/s] of the score's smoothing.
ACCEL, SCV = 5000.0, 5.0
#: Most frequencies a shaper is scanned at outside the printer's range.
MAX_SCAN = 4000
#: A shaper's lowest frequency for another firmware: its suggested max_accel reaches this.
MIN_ACCEL = 1500.0


@dataclass(frozen=True)
class DefaultLimit:
    """The default delay budget of one analysis and the design that set it.

    Attributes
    ----------
    max_delay : float
        The budget [s]: the picked shaper's duration (:func:`.run` rounds it up to a whole
        sample of the filters' period, since the exact discrete filters span whole samples).
    duration : float
        The picked shaper's own duration [s] (its last impulse).
    shaper : str
        The picked shaper, ``"<firmware> <name>"``.
    freq : float
        Its frequency [Hz] (designed for damping :data:`DESIGN_DAMPING`).
    vibration : float
        Its measured-spectrum figure at the test dampings [%].
    smoothing : float
        Its smoothing at :data:`ACCEL`, :data:`SCV` [mm].
    established : DefaultLimit or None
        A firmware other than Klipper: the established tool's own trade-off pick over
        Klipper's shapers on the same spectrum (the budget covers its length).
    match : tuple or None
        With ``established``: ``(FirmwareShaper, freq [Hz], damping, duration [s], vibration
        fraction)`` of the firmware's design leaving at most the established pick's estimate +
        ``TIE_PP`` (the least within both picks' lengths, else the shortest, which the budget
        then reaches); None when no design of the firmware does.
    """
    max_delay: float
    duration: float
    shaper: str
    freq: float
    vibration: float
    smoothing: float
    established: "DefaultLimit | None" = None
    match: tuple | None = None

    def note(self) -> str:
        e = self.established
        if e is None:
            return (f"no --max-delay or --max-smoothing: the delay is limited to "
                    f"{1e3 * self.max_delay:.4g} ms, the length of {self.shaper} at "
                    f"{self.freq:.1f} Hz, the established tool's trade-off of vibration "
                    f"({self.vibration:.2g} %) against smoothing on this spectrum "
                    "(docs/calibrate.md)")
        return (f"no --max-delay or --max-smoothing: the delay is limited to "
                f"{1e3 * self.max_delay:.4g} ms, the longer of {self.shaper} at "
                f"{self.freq:.1f} Hz ({1e3 * self.duration:.4g} ms, {self.vibration:.2g} %), "
                "the established tool's trade-off of vibration against smoothing over this "
                f"firmware's shapers, and the established tool's own pick {e.shaper} at "
                f"{e.freq:.1f} Hz ({1e3 * e.duration:.4g} ms, {e.vibration:.2g} %), whose "
                "estimate the pick is held to where a shaper of this firmware reaches it"
                + ("" if self.match is None or self.match[3] <= max(self.duration, e.duration)
                   else f", here first at {1e3 * self.match[3]:.4g} ms "
                   f"({self.match[0].firmware} {self.match[0].name} at {self.match[1]:.1f} Hz, "
                   f"damping {self.match[2]:.3g})")
                + " (docs/calibrate.md)")

    def as_dict(self) -> dict:
        out = {"max_delay": self.max_delay, "duration": self.duration, "shaper": self.shaper,
               "freq_hz": self.freq, "vibration": self.vibration, "smoothing": self.smoothing}
        if self.established is not None:
            out["established"] = self.established.as_dict()
        if self.match is not None:
            s, f, z, d, v = self.match
            out["match"] = {"shaper": f"{s.firmware} {s.name}", "freq_hz": f, "damping": z,
                            "duration": d, "vibration": 100.0 * v}
        return out


#: The frequency [Hz] at which a shaper's form is read (:func:`_is_zv`).
FORM_FREQ = 50.0


def _is_zv(shaper) -> bool:
    """A shaper of the ZV form (two impulses), whatever the firmware calls it (Marlin has two:
    FT Motion's ``ZV`` and classic ``M593 ZV``)."""
    lo_z, hi_z = shaper.damping_range()
    f = min(max(FORM_FREQ, shaper.min_freq), shaper.max_freq)
    A, _ = shaper.impulses(f, min(max(DESIGN_DAMPING, lo_z), hi_z))
    return A.size == 2


def trade_off_shapers(firmware: str) -> tuple:
    """The firmware shapers the trade-off is taken over, in the order it visits them: Klipper's
    five it calibrates, in its order, for ``"none"`` and ``"klipper"``; another firmware's
    shapers in that firmware's own order (its list of shapers)."""
    if firmware in ("none", "klipper"):
        return tuple(fw.by_name("klipper", n) for n in TRADE_OFF_SHAPERS)
    return fw.shapers(firmware)


def _smoothing(A, T):
    """Klipper's _get_shaper_smoothing at ACCEL, SCV [mm] of each row of impulses (A, T) (A
    summing to 1; padding impulses of amplitude 0 add nothing): with the shift ts = sum A t,
    the larger of the 90-degree corner's sqrt2 sum_{t >= ts} A (SCV + ACCEL (t - ts)/2)(t - ts)
    and the 180-degree turn's ACCEL sum A (t - ts)^2 / 2 (as :func:`.firmware.max_accel`)."""
    ts = np.sum(A * T, axis=1, keepdims=True)
    dt = T - ts
    # impulses at one time: ts carries rounding, not spread
    dt[np.abs(dt) <= 8 * np.finfo(float).eps * np.abs(T).max(axis=1, keepdims=True)] = 0.0
    late = T >= ts
    off90 = math.sqrt(2.0) * np.sum(np.where(late, A * (SCV + 0.5 * ACCEL * dt) * dt, 0.0), axis=1)
    off180 = 0.5 * ACCEL * np.sum(A * dt * dt, axis=1)
    return np.maximum(off90, off180)


def _designs(shaper, freqs, z):
    """(freqs it accepts, amplitudes, times), padded to one width. A design without a time
    grid (its impulse times scale as 1/f, its amplitudes do not change) is built once and
    scaled; one on a firmware's grid is built at each frequency."""
    ok = []
    for f in (freqs[0], freqs[-1]) if freqs.size else ():
        try:
            ok.append(shaper.impulses(float(f), z))
        except ValueError:
            ok.append(None)
    if len(ok) == 2 and ok[0] is not None and ok[1] is not None:
        (A0, t0), (A1, t1) = ok
        if (A0.size == A1.size and np.allclose(A0, A1, rtol=1e-12, atol=1e-15)
                and np.allclose(t0 * freqs[0], t1 * freqs[-1], rtol=1e-12, atol=1e-15)):
            return freqs, np.broadcast_to(A0, (freqs.size, A0.size)), \
                np.outer(freqs[0] / freqs, t0)
    keep, imps = [], []
    for f in freqs:
        try:
            imps.append(shaper.impulses(float(f), z))
        except ValueError:
            continue
        keep.append(f)
    if not imps:
        return np.zeros(0), np.zeros((0, 1)), np.zeros((0, 1))
    m = max(a.size for a, _ in imps)
    A, T = np.zeros((len(imps), m)), np.zeros((len(imps), m))
    for i, (a, t) in enumerate(imps):
        A[i, : a.size], T[i, : a.size], T[i, a.size:] = a, t, t[-1]
    return np.asarray(keep, float), A, T


def _vibrations(objective, R2, L):
    """The objective's value / 100 of each design (columns of R2 at its poles, lengths L):
    the established tool's estimate all at once for a spectral objective, else one by one."""
    if all(hasattr(objective, k) for k in ("n", "nz", "P", "tau", "den")):
        if not objective.den > 0:
            return np.zeros(L.size)
        decay = np.exp(2.0 * np.real(objective.poles)[:, None] * L[None, :])
        R = np.sqrt(np.maximum(R2 * decay, 0.0)).reshape(objective.n, objective.nz, L.size)
        left = np.maximum(R * objective.P[:, None, None] - objective.tau, 0.0).sum(axis=0)
        return left.max(axis=0) / objective.den
    return np.array([objective.value(R2[:, i], float(L[i])) / 100.0 for i in range(L.size)])


#: Designs scored at once (the poles x designs x impulses array stays a few MiB).
_BLOCK = 256


def _scan(shaper, freqs, objective, damping=DESIGN_DAMPING):
    """Rows (freq, vibration fraction, smoothing, score, duration) of ``shaper`` at each of
    ``freqs`` it accepts, designed at ``damping`` (default DESIGN_DAMPING)."""
    lo_z, hi_z = shaper.damping_range()
    z = min(max(damping, lo_z), hi_z)
    f, A, T = _designs(shaper, np.asarray(freqs, float), z)
    if f.size == 0:
        return np.zeros((0, 5))
    out = np.zeros((f.size, 5))
    out[:, 0], out[:, 2], out[:, 4] = f, _smoothing(A, T), T[:, -1]
    # |sum A e^{-p t}|^2 of the designs, a block at a time (A sums to 1)
    for k in range(0, f.size, _BLOCK):
        sl = slice(k, k + _BLOCK)
        E = np.exp(-objective.poles[:, None, None] * T[None, sl, :])
        H = np.einsum("pnm,nm->pn", E, A[sl])
        out[sl, 1] = _vibrations(objective, np.abs(H) ** 2, out[sl, 4])
    v = out[:, 1]
    out[:, 3] = out[:, 2] * (v ** 1.5 + 0.2 * v + 0.01)
    return out


def _fit(rows):
    """fit_shaper's selection: index of the chosen row (rows scanned from the top down)."""
    order = np.argsort(-rows[:, 0], kind="stable")      # downwards, as the tool scans
    best = order[0]
    for i in order:
        if rows[i, 1] < rows[best, 1]:
            best = i
    selected = best
    for i in order[::-1]:
        if rows[i, 1] < rows[best, 1] * 1.1 + 0.0005 and rows[i, 3] < rows[selected, 3]:
            selected = i
    return selected


def _printer_min(shaper) -> float:
    lo = shaper.suggested_min_freq
    return max(_min_accel_freq(shaper) if lo is None else lo, shaper.min_freq)


def _range(shaper, printer: bool, anchors_hz, top_hz, below: bool):
    """(lowest, highest frequency, step) of the shaper's scan [Hz]."""
    if printer and not below:
        return _printer_min(shaper), min(max(MAX_SHAPER_FREQ, top_hz), shaper.max_freq), \
            FREQ_STEP
    lo = max(0.5 * min(anchors_hz), shaper.min_freq)
    hi = min(max(MAX_SHAPER_FREQ, top_hz) if printer else 2.0 * max(anchors_hz),
             shaper.max_freq)
    # a hundredth of the lowest frequency, at most MAX_SCAN frequencies
    return lo, hi, max(min(FREQ_STEP, lo / 100.0), (hi - lo) / MAX_SCAN)


@functools.lru_cache(maxsize=None)
def _min_accel_freq(shaper) -> float:
    """The lowest frequency (0.2 Hz grid from 1 Hz) whose suggested max_accel reaches
    MIN_ACCEL (max_accel grows with the frequency)."""
    lo_z, hi_z = shaper.damping_range()
    z = min(max(DESIGN_DAMPING, lo_z), hi_z)
    for f in np.arange(max(shaper.min_freq, 1.0), 500.0, FREQ_STEP):
        try:
            A, t = shaper.impulses(float(f), z)
        except ValueError:
            continue
        if fw.max_accel(A, t) >= MIN_ACCEL:
            return float(f)
    return max(shaper.min_freq, 1.0)


#: Damping ratios a firmware's shapers are also designed at when none designed at
#: DESIGN_DAMPING leaves as little as the established pick (their damping is tuned later).
MATCH_DAMPINGS = (0.05, 0.15, 0.2)


def _match(scans, objective, target, within, below, printer, anchors_hz, top_hz):
    """(shaper, freq, damping, duration, vibration) of the firmware design leaving at most
    ``target`` (a fraction): the least-vibration one no longer than ``within`` [s], else the
    shortest one, designed at DESIGN_DAMPING or at :data:`MATCH_DAMPINGS`; None if none."""
    def pick(found):
        short = [r for r in found if r[3] <= within * (1 + 1e-12)]
        if short:
            return min(short, key=lambda r: (r[4], r[3]))
        return min(found, key=lambda r: (r[3], r[4])) if found else None

    def rows_ok(s, z, rows):
        ok = rows[:, 1] <= target
        return [(s, float(r[0]), z, float(r[4]), float(r[1])) for r in rows[ok]]

    found = [m for s, rows in scans for m in rows_ok(s, DESIGN_DAMPING, rows)]
    best = pick(found)
    if best is not None and best[3] <= within * (1 + 1e-12):
        return best
    for z in MATCH_DAMPINGS:
        for s, _ in scans:
            lo_z, hi_z = s.damping_range()
            if not lo_z <= z <= hi_z:
                continue
            lo, hi, step = _range(s, printer, anchors_hz, top_hz, below)
            if lo < hi:
                found += rows_ok(s, z, _scan(s, np.arange(lo, hi, step), objective, z))
    return pick(found)


def default_limit(objective, firmware: str, anchors_hz, *, printer: bool,
                  top_hz: float = 0.0, established: DefaultLimit | None = None
                  ) -> DefaultLimit | None:
    """The default delay budget of one analysis (module docstring).

    Parameters
    ----------
    objective : SpectralObjective (or the modal figure of a free decay)
        The figure the shapers' vibration is read from: ``value(R2, L)`` [%] of
        ``|H(poles)|^2``; for the established tool's estimate a :class:`.SpectralObjective`
        at the test dampings 0.075, 0.1 and 0.15.
    firmware : str
        The target firmware (:func:`trade_off_shapers`).
    anchors_hz : sequence of float
        The identified modes' frequencies [Hz] (the scan's range without a printer's test).
    printer : bool, keyword-only
        Whether the record is a printer's resonance test (raw accelerometer record or PSD
        table): the scan then runs over the established tool's frequencies.
    top_hz : float, keyword-only
        Highest frequency of the scored spectrum [Hz] (the scan reaches it if above 150 Hz).
    established : DefaultLimit or None, keyword-only
        Another firmware: the established tool's own pick on the same objective. The budget
        is then the longest of this firmware's pick, the established pick and, where no
        design of this firmware within those leaves as little as the established pick (+
        ``TIE_PP``), the shortest design that does (``DefaultLimit.match``).

    Returns
    -------
    DefaultLimit or None
        None when no shaper could be designed in the range.
    """
    best = None
    best_name = None
    tuned, scans = [], []
    shapers = trade_off_shapers(firmware)
    # a mode below every shaper's printer minimum: the scans start at half its frequency
    below = printer and bool(anchors_hz) and min(anchors_hz) < min(_printer_min(s)
                                                                    for s in shapers)
    for s in shapers:
        lo, hi, step = _range(s, printer, anchors_hz, top_hz, below)
        if not lo < hi:
            continue
        rows = _scan(s, np.arange(lo, hi, step), objective)
        if rows.shape[0] == 0:
            continue
        scans.append((s, rows))
        i = _fit(rows)
        pick = rows[i]
        if (best is None or pick[3] * 1.2 < best[3]
                or (pick[3] * 1.05 < best[3] and pick[2] * 1.1 < best[2])):
            best, best_name = pick, s
        for j in np.argsort(rows[:, 0], kind="stable"):    # upwards, as the tool revisits
            r = rows[j]
            if r[1] < best[1] and r[2] < best[2]:
                best, best_name = r, s
                pick = r
        tuned.append((s, pick))
    if best is None:
        return None
    if _is_zv(best_name):
        for s, r in tuned:
            if not _is_zv(s) and r[1] * 1.1 < best[1]:
                best, best_name = r, s
                break
    own = DefaultLimit(float(best[4]), float(best[4]), f"{best_name.firmware} {best_name.name}",
                       float(best[0]), 100.0 * float(best[1]), float(best[2]))
    if established is None:
        return own
    within = max(own.duration, established.duration)
    match = _match(scans, objective, (established.vibration + TIE_PP) / 100.0, within, below,
                   printer, anchors_hz, top_hz)
    budget = within if match is None else max(within, match[3])
    return DefaultLimit(budget, own.duration, own.shaper, own.freq, own.vibration,
                        own.smoothing, established, match)
