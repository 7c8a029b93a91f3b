# SPDX-License-Identifier: Apache-2.0
"""From a measured record to a recommended, verified filter (``smoothshaper calibrate``).

>>> from smoothshaper import calibrate
>>> result = calibrate.run(["examples/resonance_x.csv"], max_delay=0.03)   # doctest: +SKIP
>>> result.axes[0].recommended.stages                                      # doctest: +SKIP

Steps (docs/calibrate.md): read and recognise the record (:mod:`.records`), estimate the
spectrum (Welch) or fit the decay and identify every significant mode with its uncertainty
(:mod:`.modes`), tune every candidate family to the modes and rank them (:mod:`.candidates`),
then plots (:mod:`.plots`) and ready-to-use outputs (:mod:`.outputs`). A scheduled shaper's
table from one record per point: :func:`.schedule.schedule_table`.
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass, field, replace

import numpy as np

from .._checks import finite as _finite, positive as _positive, real_array as _real_array
from ..errors import ParameterError
from ..stages import impulse_shaper
from . import spectra
from .candidates import (TIE_PP, Candidate, Reference, candidate_taps, evaluate, families,
                         recommend, tune)
from . import default_limit as _budget
from . import firmware as _fw
from .default_limit import DefaultLimit
from .modes import Mode, decay_modes
from .objectives import ModalObjective, SpectralObjective, WorstOf, impulses_R2, taps_R2
from .records import AXIS_NAMES, KINDS, Record, RecordError, load
from .spectra import Spectrum
from .spectral_fit import fit_modes

__all__ = ["run", "Calibration", "AxisResult", "Mode", "Candidate", "Reference", "RecordError",
           "KINDS", "RANKINGS", "load"]

#: Which figure ranks the candidates: "auto" (the modal fit where it explains the spectrum,
#: else the measured spectrum), "spectrum" or "modal" (the modal fit even where it does not).
RANKINGS = ("auto", "spectrum", "modal")


@dataclass
class AxisResult:
    """Everything found for one analysed axis of one record.

    Attributes
    ----------
    name : str
        What was analysed: the test's axis (``"x"``, ``"y"``, ``"a"``/``"b"`` for CoreXY
        belts) or ``"xyz"`` for the summed analysis of a record of unknown direction, a column
        (``"x"``, ...), or a projection; ``"file:name"`` with several files.
    record : Record
        The parsed record it came from.
    signal : str
        How the analysed spectrum was formed (``"x+y+z"``, ``"x"``, ``"projection (0.71,
        -0.71, 0)"``, ...).
    modes : list of Mode
        The identified modes, largest first, with standard deviations.
    band : (float, float)
        Frequency band analysed [Hz] (the user's ``band`` when given).
    resolution : float
        Frequency resolution of the spectrum [Hz].
    spectrum : Spectrum or None
        The analysed spectrum (None for free decays).
    model : ndarray or None
        The modal fit's PSD on the spectrum's bins (NaN outside the band).
    misfit : float or None
        The modal fit's goodness-of-fit statistic (the fraction of the measured vibration
        energy it misplaces); the fit explains the spectrum when ``explains``.
    explains : bool
    ranked_by : str
        ``"measured spectrum"`` or ``"modal fit"``: the figure the ranking used.
    candidates : list of Candidate
        Every tuned filter, least remaining vibration first.
    recommended : Candidate or None
        The best candidate within the limits (None if none meets them).
    fit_r2 : float or None
        Free decays: the fraction of the signal's variance the fit explains.
    notes : list of str
        What the analysis excluded, repaired or suspects (gaps, clipping, a sensor whose axes
        do not match the printer's, modes at the end of the band).
    firmware_axis : str
        The firmware axis the recommendation is for (``"x"``, ``"y"``, ``"xy"`` for a
        diagonal or unknown direction).
    objectives : dict
        The figures of merit the candidates were scored by (``"spectrum"``, and ``"modal"``
        where the fit explains the spectrum or the modal ranking was asked for).
    user_band : bool
        Whether ``band`` is the user's (it then replaces the automatic band).
    figure_spectrum : Spectrum or None
        Raw records: the spectrum the spectral figure scores, at the established tool's
        resolution (0.5 s windows); None when it is ``spectrum`` itself.
    hull_hi : float or None
        Top of the excited band [Hz] (the spectral figure's bins reach 1.5 times it).
    default_limit : DefaultLimit or None
        Without ``max_delay`` and ``max_smoothing``: the delay budget the candidates were
        tuned within and the trade-off pick that set it (:mod:`.default_limit`).
    datasets : tuple of int
        A PSD table of several data sets of one axis (``freq,name1,name2,...``: a test at
        several points): their columns. The modes are fitted on their sum; every spectral
        figure is the worst over the data sets (:class:`.objectives.WorstOf`).
    """
    name: str
    record: Record
    modes: list[Mode]
    band: tuple[float, float]
    resolution: float                    # [Hz]
    spectrum: Spectrum | None            # what the modes were fitted on (None for decays)
    candidates: list[Candidate] = field(default_factory=list)
    recommended: Candidate | None = None
    fit_r2: float | None = None          # decays: variance explained
    signal: str = ""
    model: np.ndarray | None = None
    misfit: float | None = None
    explains: bool = False
    ranked_by: str = ""
    notes: list = field(default_factory=list)
    firmware_axis: str = "x"
    objectives: dict = field(default_factory=dict, repr=False)
    user_band: bool = False
    figure_spectrum: Spectrum | None = field(default=None, repr=False)
    hull_hi: float | None = None
    default_limit: DefaultLimit | None = None
    datasets: tuple = ()


@dataclass
class Calibration:
    """The result of :func:`run`: one :class:`AxisResult` per analysed axis and the limits.

    Attributes
    ----------
    axes : list of AxisResult
        The analysed axes.
    reference : Reference
        Sample period of the filters and the reference move.
    max_delay : float or None
        Longest impulse response allowed [s].
    max_smoothing : float or None
        Largest corner rounding allowed (length units of the reference move).
    skipped : list of str
        Axes without a resonance, and why.
    firmware : str
        The firmware whose shapers were the candidates (``"none"``: every family and chain of
        the library).
    """
    axes: list[AxisResult]
    reference: Reference
    max_delay: float | None
    max_smoothing: float | None
    skipped: list[str] = field(default_factory=list)   # axes without a resonance, and why
    firmware: str = "none"


#: Lowest frequency an accelerometer test's band starts at [Hz] (below it a printer's test
#: moves the toolhead slowly back and forth, which is no resonance).
MIN_TEST_FREQ = 5.0


def _running_median(x, w):
    w = max(1, min(int(w), x.size) | 1)
    if w == 1:
        return x
    pad = np.pad(x, w // 2, mode="edge")
    return np.median(np.lib.stride_tricks.sliding_window_view(pad, w), axis=1)


def excited_band(spec: Spectrum, lo: float, hi: float) -> tuple[float, float]:
    """The part of [lo, hi] a resonance test excited: the hull of the bins whose smoothed PSD
    stands 10 dB above the quietest part of the spectrum (its 5th percentile), ending at the
    sweep's end where the spectrum falls off a cliff (:func:`_sweep_end`); all of [lo, hi] when
    nothing is quiet or too few bins stand out."""
    f, P = spec.f, spec.P
    inr = (f >= lo) & (f <= hi) & (f > 0)
    if np.count_nonzero(inr) < 8:
        return lo, hi
    logP = np.log10(np.maximum(P, 1e-300))
    smooth = _running_median(logP, 5)
    floor = float(np.percentile(smooth[f > 0], 5))
    excited = np.flatnonzero((smooth > floor + 1.0) & inr)
    if excited.size < 8:
        return lo, hi
    a, b = max(lo, float(f[excited[0]])), min(hi, float(f[excited[-1]]))
    return a, _sweep_end(f, smooth, a, b, hi)


def _sweep_end(f, smooth, a, b, hi):
    """The top of a sweep's excited band: the last bin of the highest cliff in [a, b] (the
    smoothed PSD over 5 % above it stands 10 dB over everything from 10 % above it up to
    ``hi``, and what follows lies under the band's start, where the test's acceleration is the
    weakest); ``b`` when there is none.

    The quiet floor of :func:`excited_band` is a percentile of the whole spectrum, so a record
    sampled faster holds more quiet bins and a lower floor, and the sweep's harmonics and noise
    above its end (a test's square-wave acceleration has odd harmonics) then stand above it: at
    1.6 kHz the band reached 200 to 500 Hz where at 800 Hz it stopped at the sweep's end, and
    the fit took the cliff for a broad mode. The cliff is where the sweep ends whatever the
    rate."""
    inb = np.flatnonzero((f >= a) & (f <= b))
    if inb.size < 8:
        return b
    start = float(np.median(smooth[inb[: max(3, inb.size // 50)]]))
    # the running maximum from the top down: the largest smoothed PSD at or above each bin
    top = np.maximum.accumulate(np.where(f <= hi, smooth, -np.inf)[::-1])[::-1]
    best = None
    for i in inb:
        fc = float(f[i])
        j_post = int(np.searchsorted(f, 1.1 * fc))
        if j_post >= f.size or f[j_post] > hi:
            break
        j_pre = int(np.searchsorted(f, 1.05 * fc, side="right"))
        pre = float(np.median(smooth[i: max(j_pre, i + 1)]))
        post = float(top[j_post])
        if pre - post >= 1.0 and post < start:
            best = (i, j_post, pre)
    if best is None:
        return b
    # the cliff's top: its last bin within 5 dB of the level before it (what lies under the
    # cliff, harmonics and noise, depends on the rate)
    i, j_post, pre = best
    last = i + int(np.flatnonzero(smooth[i: j_post] > pre - 0.5)[-1])
    return min(b, float(f[last]))


def _parse_direction(axis: str):
    parts = axis.split(",")
    if len(parts) not in (2, 3):
        return None
    try:
        v = np.array([float(p) for p in parts])
    except ValueError:
        return None
    n = float(np.linalg.norm(v))
    if not (np.all(np.isfinite(v)) and n > 0):
        raise ParameterError("axis", f"axis: the direction {axis!r} must be finite and not 0")
    return v / n


def _analyses(rec: Record, axis: str) -> list[tuple[str, str, object]]:
    """(name, description of the signal, columns or direction) of each analysis of ``rec``."""
    names = rec.names
    if rec.kind in ("decay", "frf"):
        return [(names[j], names[j], [j]) for j in range(len(names))]
    label = rec.test_axis if rec.test_axis in ("x", "y", "z", "a", "b") else None
    per_axis = [j for j, n in enumerate(names) if n in AXIS_NAMES]
    d = _parse_direction(axis) if "," in axis else None
    if d is not None:
        if rec.kind != "raw":
            raise RecordError(rec.path, f"--axis {axis}: a projection onto a direction needs a "
                              "raw record (a PSD table holds no cross-spectra)")
        return [(f"({', '.join(f'{v:.3g}' for v in d)})",
                 "projection (" + ", ".join(f"{v:.3g}" for v in d) + ")", d)]
    if axis in ("auto", "xyz"):
        if rec.kind == "psd" and "xyz" in names:
            return [(label or "xyz", "x+y+z (the table's psd_xyz)", [names.index("xyz")])]
        cols = per_axis if len(per_axis) >= 2 else list(range(len(names)))
        cols = [j for j in cols if names[j] != "xyz"] or cols
        if len(cols) == 1:
            return [(label or names[cols[0]], names[cols[0]], cols)]
        return [(label or "xyz", "+".join(names[j] for j in cols), cols)]
    if axis == "all":
        cols = [j for j in range(len(names)) if names[j] != "xyz"]
        return [(names[j], names[j], [j]) for j in cols]
    if axis in names:
        j = names.index(axis)
        return [(axis, axis, [j])]
    raise RecordError(rec.path, f"no axis {axis!r} (columns: {', '.join(names)}; or auto, "
                      "xyz, all, or a direction such as 1,-1)")


#: Shortest overlap of the frequency grids of files combined into one axis, as a fraction of
#: the first file's span (a shorter one leaves most of a test unscored).
MIN_GRID_OVERLAP = 0.5


def _datasets(rec: Record, axis: str) -> list[tuple[str, np.ndarray, np.ndarray]]:
    """(name, f [Hz], PSD) of each data set one record brings to a combined axis."""
    if rec.kind not in ("raw", "psd"):
        raise RecordError(rec.path, f"combining files into one axis takes resonance tests (raw "
                          f"accelerometer records or PSD tables), not a {rec.kind} record")
    plan = _analyses(rec, axis)
    if len(plan) != 1:
        raise RecordError(rec.path, f"--axis {axis} gives {len(plan)} analyses of this file; "
                          "combining files into one axis takes one per file (--axis auto, a "
                          "column or a direction)")
    label, _signal, cols = plan[0]
    base = os.path.basename(str(rec.path)) or str(rec.path)
    if rec.kind == "raw":
        direction = cols if isinstance(cols, np.ndarray) else None
        n = 1 << max(0, int(0.5 / rec.Ts - 1)).bit_length()
        # the established tool's resolution (0.5 s segments), as a raw record's figure has
        spec = spectra.record_spectrum(rec, None if direction is not None else cols, direction,
                                       nperseg=n if n >= 64 else None)
        return [(base, spec.f, spec.P)]
    if (len(cols) >= 2 and not any(rec.names[j] in AXIS_NAMES + ("xyz",) for j in cols)):
        # a table that already holds several data sets: each stays one
        return [(f"{base}:{rec.names[j]}", rec.f, rec.signals[:, j]) for j in cols]
    return [(base, rec.f, rec.signals[:, cols].sum(axis=1))]


def _combine(records: list[Record], axis: str) -> Record:
    """One PSD table of several data sets from several resonance tests of one axis: each file
    (its summed x+y+z, or the ``axis`` asked for) a data set, on the first file's frequency
    grid (the others linearly interpolated onto it, over the frequencies every file covers)."""
    marked = {bool(r.marked) for r in records}
    if len(marked) > 1:
        odd = next(r for r in records if r.marked != records[0].marked)
        raise RecordError(odd.path, "a calibration table (header with 'shapers:', already "
                          "divided by the frequency) cannot be combined with an unprocessed "
                          "resonance test: give files of one kind")
    sets, owner = [], []
    for rec in records:
        for name, f, P in _datasets(rec, axis):
            sets.append((name, np.asarray(f, float), np.asarray(P, float)))
            owner.append(rec)
    f0 = sets[0][1]
    lo = max(float(f[0]) for _n, f, _P in sets)
    hi = min(float(f[-1]) for _n, f, _P in sets)
    # the span that counts: the first file's, up to the established tool's last scored bin (a
    # raw record's spectrum reaches its Nyquist frequency, a table stops at 200 Hz)
    top = min(float(f0[-1]), ESTIMATE_MAX_FREQ)
    span = top - float(f0[0])
    if not min(hi, top) - lo >= MIN_GRID_OVERLAP * span:
        # the file that cuts the overlap most
        k = max(range(len(sets)), key=lambda i: max(float(sets[i][1][0]) - f0[0],
                                                    top - float(sets[i][1][-1])))
        f = sets[k][1]
        raise RecordError(owner[k].path, f"its frequencies ({f[0]:.4g} to {f[-1]:.4g} Hz) "
                          f"overlap those of {owner[0].path} ({f0[0]:.4g} to {top:.4g} Hz) "
                          f"over less than {MIN_GRID_OVERLAP:.0%} of them: the files cannot be "
                          "scored as one axis; analyse them on their own (--separate)")
    keep = (f0 >= lo - 1e-9) & (f0 <= hi + 1e-9)
    grid = f0[keep]
    cols, notes, names = [], [], []
    for (name, f, P), rec in zip(sets, owner):
        same = f.size == f0.size and np.allclose(f, f0, rtol=0, atol=1e-6 * max(1.0, f0[-1]))
        cols.append(P[keep] if same else np.interp(grid, f, P))
        if not same:
            notes.append(f"{rec.path}: its frequency grid ({f.size} bins, {f[0]:.4g} to "
                         f"{f[-1]:.4g} Hz) differs from {owner[0].path}'s: linearly "
                         "interpolated onto it")
        names.append(name)
    if len(set(names)) < len(names):       # the same file name in two folders
        names = [f"{i + 1}:{n}" for i, n in enumerate(names)]
    if keep.sum() < f0.size:
        notes.append(f"scored over {grid[0]:.4g} to {grid[-1]:.4g} Hz, the frequencies every "
                     "file covers")
    for rec in records:
        notes.extend(f"{rec.path}: {n}" for n in rec.notes)
    axes_named = {r.test_axis for r in records}
    first = records[0]
    return Record(path=" + ".join(str(r.path) for r in records), kind="psd", names=names,
                  f=grid, signals=np.column_stack(cols),
                  normalized=all(r.kind == "psd" and r.normalized for r in records),
                  marked=bool(first.marked),
                  direction=first.direction if len(axes_named) == 1 else None,
                  test_axis=first.test_axis if len(axes_named) == 1 else None, notes=notes)


def _combines(records: list[Record], combine) -> bool:
    """Whether several records are one axis: asked (True/False), or by default (None) when
    every file is a resonance test named for the same axis (Klipper's resonances_x_*.csv)."""
    if len(records) < 2 or combine is False:
        return False
    if combine:
        return True
    axes_named = {r.test_axis for r in records}
    return (all(r.kind in ("raw", "psd") for r in records) and len(axes_named) == 1
            and None not in axes_named and len({r.marked for r in records}) == 1)


def _spectrum(rec: Record, cols) -> Spectrum:
    if rec.kind == "raw":
        if isinstance(cols, np.ndarray):
            return spectra.record_spectrum(rec, None, direction=cols)
        return spectra.record_spectrum(rec, cols)
    P = rec.signals[:, cols].sum(axis=1)
    if rec.kind == "frf":
        P = P ** 2
    df = np.diff(rec.f)
    uniform = df.size > 0 and np.allclose(df, df[0], rtol=1e-3, atol=0.06)
    # Klipper's tables are Welch estimates with a Kaiser window (beta 6): their kernel
    kernel = spectra.kaiser_kernel() if (rec.kind == "psd" and uniform) else None
    return Spectrum(rec.f, P, kernel, 4, None, 1.5 if kernel is not None else 1.0)


def _firmware_axis(name: str, rec: Record) -> str:
    if name in ("x", "y", "z"):
        return name
    return "xy"


#: The established tool's test damping ratios: every spectral figure covers them.
TEST_DAMPINGS = (0.075, 0.1, 0.15)
#: Highest bin of the established tool's estimate [Hz] (its ``MAX_FREQ``).
ESTIMATE_MAX_FREQ = 200.0


def _zeta_nodes(f, modes, explains):
    """(damping ratios of the spectral figure, relative half-width of each bin's mode): the
    established tool's test dampings, and where the fit explains the spectrum the two main
    modes' fitted damping +-3 sd."""
    nodes = list(TEST_DAMPINGS)
    if not modes:
        return np.array(nodes), np.full(f.size, 0.08)
    total = sum(m.weight for m in modes)
    for m in sorted(modes, key=lambda m: -m.weight)[:2]:
        if explains and m.weight >= 0.1 * total:
            nodes += [m.zeta - 3 * m.zeta_std, m.zeta, m.zeta + 3 * m.zeta_std]
    fm = np.array([m.f_hz for m in modes])
    near = np.argmin(np.abs(np.log(np.maximum(f, 1e-9))[:, None] - np.log(fm)[None, :]), axis=1)
    z = np.array([m.zeta for m in modes])[near]
    return np.clip(np.array(nodes), 0.005, 0.6), np.clip(np.maximum(z, 0.02), 0.02, 0.5)


def _energy_note(rec: Record, band) -> str | None:
    """A note when the energy sits mostly on a column other than the test's direction."""
    if rec.direction is None or rec.kind not in ("raw", "psd"):
        return None
    cols = [j for j, n in enumerate(rec.names) if n in AXIS_NAMES]
    if len(cols) < 2:
        return None
    share = spectra.energy_shares(rec, band, cols)
    d = np.array([abs(rec.direction[AXIS_NAMES.index(rec.names[j])]) for j in cols])
    expected = float(share[d > 0.3].sum())
    top = int(np.argmax(share))
    if expected < 0.4 and d[top] < 0.3 and share[top] > 0.5:
        return (f"{100 * share[top]:.0f} % of the vibration energy is on the "
                f"{rec.names[cols[top]]} column during a {rec.test_axis} test: the sensor's "
                "axes do not seem to match the printer's (check its axes_map); the summed "
                "x+y+z analysis is unaffected")
    return None


#: Relative standard deviation of the test's excitation at one frequency against another (added
#: in quadrature to each mode's weight): the modes' weights are read through the excitation's
#: assumed growth with the frequency, and a real test's square wave (its odd harmonics excite a
#: mode from a third of its frequency) and slow back-and-forth depart from it; on the
#: campaign's 35/56/94 Hz plant the normalised spectrum holds the first two modes' energies as
#: 1 : 0.47 where the plant's are 1 : 0.53.
EXCITATION_RSD = 0.05

#: Standard deviation of a fitted mode's bias per unit of the fit's misfit (the fraction of the
#: vibration energy it misplaces, :mod:`.spectral_fit`): in bins of the spectrum for the natural
#: frequency, relative for the damping ratio. The model's bias (the window's kernel, the local
#: power law, a mode seen through another's roll-off) shows in what the fit misplaces: on the
#: synthetic campaign (800 Hz) clean single modes, misfit 0.009 to 0.018, came out within 0.023
#: bin and 0.8 % of their damping, where a mode in series behind a 20 Hz one (misfit 0.024 to
#: 0.042) came out up to 0.32 bin and 3.8 % off, and a mode at the sweep's start (0.065 to
#: 0.079) 0.33 bin off. A fixed tenth of a bin had stated the clean modes 5 to 30 times their
#: error and the mode behind the 20 Hz one's damping 3.1 sd off.
FREQ_BIAS_PER_MISFIT = 4.0
ZETA_BIAS_PER_MISFIT = 0.5


def identify(rec: Record, name: str, signal: str, cols, band=None,
             spread: float = 0.0) -> AxisResult:
    """Spectrum, band, modal fit and notes of one analysis of a record."""
    if rec.kind == "decay":
        j = cols[0]
        x = rec.signals[:, j]
        modes, r2 = decay_modes(x, rec.Ts, path=rec.path, column=name, band=band)
        res = AxisResult(name, rec, modes, _band_decay(rec, band), 1.0 / (x.size * rec.Ts), None,
                         fit_r2=r2, signal=signal, explains=True)
        res.firmware_axis = "x"
        return res
    spec = _spectrum(rec, cols)
    f = spec.f
    pos = f[f > 0]
    if pos.size == 0 or not np.any(spec.P[f > 0] > 0):
        raise RecordError(rec.path, f"the spectrum of {signal} is zero everywhere: no motion "
                          "recorded", column=name)
    full = (float(pos[0]), float(f[-1]))
    hull_hi = None
    if band is not None:
        b = (max(band[0], full[0]), min(band[1], full[1]))
        if not b[0] < b[1]:
            raise RecordError(rec.path, f"--band {band[0]:g} {band[1]:g} Hz lies outside the "
                              f"record's spectrum ({full[0]:.4g} to {full[1]:.4g} Hz)",
                              column=name)
    else:
        lo = full[0]
        if rec.kind in ("raw", "psd") and full[1] > 4 * MIN_TEST_FREQ:
            lo = max(lo, MIN_TEST_FREQ)
        hi = full[1] if rec.kind != "raw" else min(full[1], 0.45 / rec.Ts)
        b = excited_band(spec, lo, hi)
        hull_hi = b[1]
        if rec.kind in ("raw", "psd") and b[1] / 1.15 > b[0] * 1.5:
            # the steep end of a sweep is no resonance: the fit stops 15 % short of it (a mode
            # there is marked); the spectral figure still reaches past it
            b = (b[0], b[1] / 1.15)
    inb = (f >= b[0]) & (f <= b[1]) & (f > 0)
    if np.count_nonzero(inb) < 3:                # a band of one or two bins: widen to three
        i = int(np.argmin(np.abs(f - 0.5 * (b[0] + b[1]))))
        lo_i, hi_i = max(0, i - 1), min(f.size - 1, i + 1)
        b = (float(f[max(lo_i, int(np.argmax(f > 0)))]), float(f[hi_i]))
    res = AxisResult(name, rec, [], b, float(np.median(np.diff(f))) if f.size > 1 else 0.0, spec,
                     signal=signal)
    res.hull_hi = hull_hi if band is None else b[1]
    res.notes = list(rec.notes)
    res.user_band = band is not None
    n = 1 << max(0, int(0.5 / rec.Ts - 1)).bit_length() if rec.kind == "raw" else 0
    if n >= 64:
        # the spectral figure at the established tool's resolution (segments of 0.5 s): a
        # spectrum resolved finer than the modes move over a print rewards shapers too narrow
        # (a record sampled too slowly for that keeps its own spectrum)
        direction = cols if isinstance(cols, np.ndarray) else None
        res.figure_spectrum = spectra.record_spectrum(rec, None if direction is not None else cols,
                                                      direction, nperseg=n)
    fit = fit_modes(spec, b)
    modes = []
    if fit is not None:
        res.model, res.misfit, res.explains = fit.model, fit.misfit, fit.explains
        # the modes' weights on the spectrum the figures score: a resonance test's PSD divided
        # by its excitation's growth with the frequency (spectra.normalize_to_excitation)
        scale = rec.kind in ("raw", "psd") and not rec.marked
        for d in fit.modes:
            if scale:
                d["weight"] = d["weight"] / (d["fn"] + 0.1)
            # the fit's own sd, and the model's bias growing with what the fit misplaces
            misfit = min(fit.misfit, 1.0)
            sd = math.hypot(d["fn_sd"], FREQ_BIAS_PER_MISFIT * misfit * res.resolution)
            if spread:
                sd = math.hypot(sd, spread * d["fn"])
            zeta_sd = math.hypot(d["zeta_sd"], ZETA_BIAS_PER_MISFIT * misfit * d["zeta"])
            modes.append(Mode(wn=2 * math.pi * d["fn"], zeta=d["zeta"], wn_std=2 * math.pi * sd,
                              zeta_std=zeta_sd, weight=d["weight"],
                              weight_rsd=math.hypot(d["weight_rsd"], EXCITATION_RSD),
                              at_edge=d["at_edge"]))
            if d["at_edge"]:
                res.notes.append(f"the mode at {d['fn']:.4g} Hz lies within 3 half-power widths "
                                 f"of the band's end ({b[0]:.4g} to {b[1]:.4g} Hz): its estimate "
                                 "may be biased; a test over a wider range of frequencies "
                                 "measures it better")
    res.modes = modes
    if (rec.kind == "psd" and not isinstance(cols, np.ndarray) and len(cols) >= 2
            and not any(rec.names[j] in AXIS_NAMES + ("xyz",) for j in cols)):
        # a table of several data sets of one axis: scored as the established tool scores
        # them, each on its own and the worst counts
        res.datasets = tuple(int(j) for j in cols)
        res.notes.append(f"{len(cols)} data sets ({', '.join(rec.names[j] for j in cols)}): "
                         "modes fitted on their sum, each filter scored by the worst of them")
    note = _energy_note(rec, b)
    if note:
        res.notes.append(note)
    res.firmware_axis = _firmware_axis(name, rec)
    return res


def _band_decay(record, band):
    hi = 0.4 / record.Ts
    return (0.0, hi) if band is None else (max(0.0, band[0]), min(hi, band[1]))


def _objectives(res: AxisResult, ranking: str):
    """The spectral and (where the fit explains the spectrum, or ranking='modal') modal
    objectives, and which ranks."""
    if res.spectrum is None:                      # a free decay: modes only
        modal = ModalObjective(res.modes)
        spec = modal
        spec_obj = _ModalAsSpectral(modal)
        return {"spectrum": spec_obj, "modal": modal}, "modal"
    fig = res.figure_spectrum if res.figure_spectrum is not None else res.spectrum
    f = fig.f
    # the figure's bins: the user's band, else everything up to 1.5 x the excited band's top
    # (a twentieth of the peak is the figure's floor; the test's slow back-and-forth below
    # 10 Hz is attenuated by the normalisation)
    if res.user_band:
        inb = (f >= res.band[0]) & (f <= res.band[1]) & (f > 0)
    else:
        inb = (f > 0) & (f <= 1.5 * (res.hull_hi or res.band[1]))
        if res.record.kind not in ("raw", "psd"):
            inb &= f >= res.band[0]
    nodes, width = _zeta_nodes(f[inb], res.modes, res.explains)
    scale = res.record.kind in ("raw", "psd") and not res.record.marked
    # one PSD per data set (several for a table of several data sets of one axis)
    sets = ([res.record.signals[:, j] for j in res.datasets] if res.datasets else [fig.P])

    def scored(keep):
        out = []
        for Q in sets:
            Q = Q[keep]
            out.append(spectra.normalize_to_excitation(f[keep], Q) if scale else Q)
        return out

    Ps = scored(inb)
    P = np.sum(Ps, axis=0)
    if P.size < 3 or not float(np.max(P)) > 0.0:
        raise RecordError(res.record.path, f"no vibration in the band {res.band[0]:.4g} to "
                          f"{res.band[1]:.4g} Hz ({P.size} frequencies, none with power): "
                          "nothing to score a filter against")

    def objective(fs, parts, zetas, **kw):
        loud = [Q for Q in parts if Q.size and float(np.max(Q)) > 0.0]
        if len(loud) <= 1:               # one data set (or none with power: as before)
            return SpectralObjective(fs, (loud or parts)[0], zetas, **kw)
        parts = loud
        return WorstOf([SpectralObjective(fs, Q, zetas, **kw) for Q in parts])

    spec_obj = objective(f[inb], Ps, nodes, width=width, group_hz=0.5)
    # the established tool's estimate itself (its three test dampings, every bin): what the
    # default delay budget is traded against (default_limit) and what the pick must not lose
    # on. A printer's test is scored, as that tool does, on every bin up to ESTIMATE_MAX_FREQ:
    # a real table's floor stood above a twentieth of its peak up to 200 Hz, and cut at 1.5
    # times the excited band's top the estimate had moved its trade-off pick from 63.4 to
    # 63.8 Hz and put 0.9 points on what it leaves
    fk, Pk = f[inb], Ps
    if res.record.kind in ("raw", "psd") and not res.user_band:
        kb = (f > 0) & (f <= ESTIMATE_MAX_FREQ)
        fk, Pk = f[kb], scored(kb)
    trade = objective(fk, Pk, TEST_DAMPINGS)
    modal = None
    if res.modes and (res.explains or ranking == "modal"):
        modal = ModalObjective(res.modes)
    rank = "modal" if modal is not None and ranking in ("auto", "modal") else "spectrum"
    unsure = ModalObjective(res.modes) if res.modes and modal is None else None
    return {"spectrum": spec_obj, "modal": modal, "unsure": unsure, "trade-off": trade}, rank


def _default_limit(res: AxisResult, objs, anchors, firmware) -> DefaultLimit | None:
    """The default delay budget of one analysis (:mod:`.default_limit`): the established
    tool's trade-off on its own estimate where there is a measured spectrum, else on the modal
    figure of a free decay."""
    obj = objs.get("trade-off") or objs["spectrum"]
    printer = res.record.kind in ("raw", "psd")
    # the top of the scored spectrum (the ranking's bins, up to 1.5 x the excited band's top)
    spec = objs["spectrum"]
    top = float(spec.f.max()) if getattr(spec, "f", None) is not None and spec.f.size else 0.0
    hz = [a / (2 * math.pi) for a in anchors]
    if firmware in ("none", "klipper") or objs.get("trade-off") is None:
        return _budget.default_limit(obj, firmware, hz, printer=printer, top_hz=top)
    # another firmware: the established tool's own pick on this spectrum too. The firmware's
    # trade-off over its own shapers can pick a shorter one that leaves more (a ZV where the
    # established tool picks an MZV); its shapers get at least the established pick's length,
    # and the pick is held to that pick's estimate where a candidate reaches it
    # (_hold_to_trade_off)
    ref = _budget.default_limit(obj, "klipper", hz, printer=printer, top_hz=top)
    if ref is None:
        return own
    # and where none of its designs within both lengths leaves as little as the established
    # pick (a firmware's time grid, or a definition that differs from the established one),
    # the budget reaches the shortest that does
    return _budget.default_limit(obj, firmware, hz, printer=printer, top_hz=top,
                                 established=ref)


def _established(c: Candidate, trade, Ts: float) -> float:
    """What ``c`` leaves by the established tool's own estimate [%] (``trade``: its three test
    dampings over every bin of the scored spectrum)."""
    if c.firmware is not None:
        shaper, freq, damping = c.firmware
        R2 = impulses_R2(*shaper.impulses(freq, damping), trade.poles)
    else:
        R2 = taps_R2(candidate_taps(c, Ts), Ts, trade.poles)
    return trade.value(R2, c.length)


def _hold_to_trade_off(res: AxisResult, objs, rank, reference, delay, firmware) -> None:
    """The default budget's promise: the pick leaves, by the established tool's own estimate,
    at most what its trade-off pick leaves (within ``TIE_PP``). The trade-off pick itself joins
    the candidates (so one always meets it), and a candidate leaving more is outside the
    limits. Where the modal fit ranks, it explains the band, but the estimate also counts the
    vibration outside it: on a real table whose floor stood above a twentieth of the peak at
    every frequency, the modal ranking's ZV notch left 26.2 % of the measured PSD where the
    trade-off's MZV left 25.0 %."""
    trade = objs.get("trade-off")
    if trade is None:                 # a free decay: no established estimate
        return
    limit = res.default_limit
    shaper = next(s for s in _budget.trade_off_shapers(firmware)
                  if f"{s.firmware} {s.name}" == limit.shaper)
    lo_z, hi_z = shaper.damping_range()
    z = min(max(_budget.DESIGN_DAMPING, lo_z), hi_z)
    A, t = shaper.impulses(limit.freq, z)
    A, t = np.asarray(A, float), np.asarray(t, float)
    name = f"{limit.shaper} (trade-off pick)"
    if firmware == "none":           # the library's user-defined impulses, for the C library
        pick = evaluate(name, [impulse_shaper(amplitudes=A, times=t)], objs, rank, reference,
                        delay, None)
    else:
        pick = evaluate(name, [], objs, rank, reference, delay, None, impulses=(A, t),
                        firmware=(shaper, limit.freq, z))
    pick.design = ((limit.freq, z),)
    res.candidates.append(pick)
    for c in res.candidates:
        c.vibration_established = _established(c, trade, reference.Ts)
    if limit.match is not None:
        # the firmware's design that leaves no more than the established pick: a candidate,
        # so one always reaches it where any design of this firmware does
        ms, mf, mz, _, _ = limit.match
        mA, mt = ms.impulses(mf, mz)
        near = evaluate(f"{ms.firmware} {ms.name} (as the established pick)", [], objs, rank,
                        reference, delay, None, impulses=(np.asarray(mA, float),
                                                          np.asarray(mt, float)),
                        firmware=(ms, mf, mz))
        near.design = ((mf, mz),)
        near.vibration_established = _established(near, trade, reference.Ts)
        res.candidates.append(near)
    cap = pick.vibration_established
    whose = "its trade-off pick's"
    ref = limit.established
    if ref is not None:
        # the established tool's own pick (which this firmware may not run): where a candidate
        # leaves no more than it, the pick must not either
        kA, kt = _fw.by_name("klipper", ref.shaper.split(maxsplit=1)[1]).impulses(
            ref.freq, _budget.DESIGN_DAMPING)
        theirs = trade.value(impulses_R2(kA, kt, trade.poles), float(kt[-1]))
        reach = min((c.vibration_established for c in res.candidates if c.meets),
                    default=math.inf)
        held = max(theirs, reach)
        if held < cap:
            cap, whose = held, (f"the established tool's pick's ({ref.shaper} at "
                                f"{ref.freq:.1f} Hz: {theirs:.3g} %)" if held == theirs else
                                "the least any candidate leaves")
    for c in res.candidates:
        if c.meets and c.vibration_established > cap + TIE_PP:
            c.reasons.append(f"leaves {c.vibration_established:.3g} % by the established "
                             f"estimate > {cap:.3g} % (+{TIE_PP:g}), {whose}")
            c.meets = False


class _ModalAsSpectral:
    """A free decay has no spectrum: its 'measured spectrum' figure is the modal one."""

    def __init__(self, modal):
        self.m = modal
        self.kind = "modal fit"
        self.poles, self.box, self.nominal = modal.poles, modal.box, modal.nominal

    def value(self, R2, L=0.0):
        return self.m.value(R2, L)

    def range(self, R2, L=0.0):
        return self.m.range(R2, L)

    def nominal_value(self, R2, L=0.0):
        return self.m.nominal_value(R2, L)


def _anchors(res: AxisResult, objs) -> list[float]:
    """Natural frequencies [rad/s] to tune around: the modes by weight, else the largest bins
    of the vibration content."""
    if res.modes:
        return [m.wn for m in res.modes]
    spec = objs["spectrum"]
    return [2 * math.pi * float(spec.f[int(np.argmax(spec.P))])]


#: Most samples of Ts one period of the slowest mode may span (the filters' length, whose
#: square the tuning costs: a 47 Hz mode at Ts = 3e-6 s, 7100 samples, tunes in about 20 s).
MAX_PERIOD_SAMPLES = 1 << 14


def run(paths, *, kind: str = "auto", axis: str = "auto", band=None,
        reference: Reference | None = None, max_delay: float | None = None,
        max_smoothing: float | None = None, spread: float = 0.0, firmware: str = "none",
        ranking: str = "auto", combine: bool | None = None, progress=None) -> Calibration:
    """Identify the resonances in every record and rank every candidate filter.

    Each analysed spectrum (a Welch estimate over the contiguous segments of a raw record, or a
    PSD table's column) is fitted with every significant mode; every candidate (every family
    and chain of the library, or a firmware's own shapers) is tuned and scored by what it
    leaves of the measured vibration, over the spectrum itself and over the modal fit where
    that fit explains the spectrum (docs/calibrate.md).

    Parameters
    ----------
    paths : sequence of str
        CSV records.
    kind : {"auto", "raw", "decay", "psd", "frf"}, keyword-only
        Record kind (default ``"auto"``: from the header and the signal).
    axis : str, keyword-only
        ``"auto"`` (default: the summed x+y+z analysis of an accelerometer record, named by
        the test's axis when the file name tells it), ``"xyz"`` (the same), ``"all"`` (each
        column on its own), a column name (``"x"``, ...), or a direction ``"1,-1"`` /
        ``"1,1,0"`` (the projection of a raw record's acceleration onto it).
    band : (float, float) or None, keyword-only
        Frequency band to analyse [Hz], replacing the automatic one (the part of the spectrum
        the test excited).
    reference : Reference or None, keyword-only
        Sample period of the filters and the reference move (default ``Reference()``).
    max_delay : float or None, keyword-only
        Longest impulse response allowed [s], > 0. Without it and ``max_smoothing``, each
        analysis gets a default budget: the length of the shaper the established tool's
        trade-off of vibration against smoothing picks on its spectrum
        (:mod:`.default_limit`, ``AxisResult.default_limit``).
    max_smoothing : float or None, keyword-only
        Largest corner rounding allowed (length units of ``reference``), > 0.
    spread : float, keyword-only
        Expected variation of the natural frequencies over the workspace as a fraction in
        [0, 0.5), added in quadrature to each fit's standard deviation (default 0).
    firmware : {"none", "klipper", "marlin", "rrf", "prusa"}, keyword-only
        Restrict the candidates to what that firmware runs, with its own definitions (default
        ``"none"``: every family and chain of the library).
    ranking : {"auto", "spectrum", "modal"}, keyword-only
        The figure that ranks (default ``"auto"``: the modal fit where it explains the
        spectrum, else the measured spectrum).
    combine : bool or None, keyword-only
        Several files analysed as one axis with one data set each, as Klipper's
        ``calibrate_shaper.py FILE1 FILE2 ...`` does: the modes fitted on their sum, every
        filter scored by the worst data set (:class:`.objectives.WorstOf`); files on other
        frequency grids are linearly interpolated onto the first file's. ``None`` (default):
        when every file is a resonance test named for the same axis (``resonances_x_*.csv``);
        ``True``: always (the files must be raw records or PSD tables); ``False``: each file
        on its own.
    progress : callable or None, keyword-only
        Called as ``progress(done, total)`` after each filter family is tuned.

    Returns
    -------
    Calibration
        The axes, their modes, candidates and recommendations.

    Raises
    ------
    RecordError
        (a ValueError) naming the file, row or column and the reason the record cannot be
        used.
    ParameterError
        Naming ``max_delay``, ``max_smoothing``, ``spread``, ``Ts``, ``accel``, ``axis``,
        ``firmware``, ``ranking`` or ``combine`` when out of range, or ``Ts`` when a mode lies at or above
        the filters' Nyquist frequency.
    """
    if reference is None:
        reference = Reference()
    elif not isinstance(reference, Reference):
        raise ParameterError("reference", "reference must be a calibrate.Reference, got "
                             f"{type(reference).__name__}")
    # the shared checks: bool, text, 10**400 and NumPy scalars named, not a TypeError
    max_delay = None if max_delay is None else _positive("max_delay", max_delay)
    max_smoothing = None if max_smoothing is None else _positive("max_smoothing", max_smoothing)
    spread = _finite("spread", spread)
    if not 0 <= spread < 0.5:
        raise ParameterError("spread", f"spread must be in [0, 0.5), got {spread!r}")
    if isinstance(paths, (str, os.PathLike)):
        paths = [paths]            # one file (a str is not a sequence of file names)
    try:
        paths = list(paths)
    except TypeError:
        raise ParameterError("paths", "paths must be a sequence of file names, got "
                             f"{type(paths).__name__}") from None
    if not paths:
        raise ParameterError("paths", "paths must name at least one record")
    if not isinstance(axis, str):
        raise ParameterError("axis", f"axis must be a column name, auto, xyz, all or a "
                             f"direction, got {type(axis).__name__}")
    from .._checks import choice as _choice
    firmware = _choice("firmware", firmware, ("none", "klipper", "marlin", "rrf", "prusa"))
    ranking = _choice("ranking", ranking, RANKINGS)
    if band is not None:
        b = _real_array("band", band, ndim=1)
        if b.size != 2 or not (np.all(np.isfinite(b)) and b[0] < b[1] and b[1] > 0):
            raise ParameterError("band", "band must be two finite frequencies FMIN < FMAX [Hz] "
                                 f"with FMAX > 0, got {b.tolist()}")
        band = (float(b[0]), float(b[1]))
    if combine is not None and not isinstance(combine, bool):
        raise ParameterError("combine", "combine must be True, False or None, got "
                             f"{type(combine).__name__}")
    records = [load(p, kind) for p in paths]
    if _combines(records, combine):
        records, axis = [_combine(records, axis)], "auto"
    axes, skipped = [], []
    for rec in records:
        plan = _analyses(rec, axis)
        for name, signal, cols in plan:
            try:
                res = identify(rec, name, signal, cols, band, spread)
            except RecordError as exc:
                if len(plan) == 1:
                    raise
                skipped.append(str(exc))
                continue
            if len(records) > 1:
                res.name = f"{rec.path}:{res.name}"
            axes.append(res)
    if not axes:
        raise RecordError(paths[0], "no axis can be analysed: " + "; ".join(skipped))
    plans = []
    for res in axes:
        objs, rank = _objectives(res, ranking)
        res.objectives, res.ranked_by = objs, objs[rank].kind
        anchors = _anchors(res, objs)
        fams = families(len(res.modes) if res.modes else 1, firmware)
        plans.append((res, objs, rank, anchors, fams))
    work = sum(len(p[4]) for p in plans)
    done = 0
    for res, objs, rank, anchors, fams in plans:
        fast = max(anchors)
        if not fast < 0.95 * math.pi / reference.Ts:
            raise ParameterError("Ts", f"Ts = {reference.Ts:g} s: a resonance at {fast:.4g} "
                                 "rad/s is at or above the filters' Nyquist frequency; use a "
                                 "smaller --Ts")
        # the filters span a few periods of the slowest resonance, and scoring a filter costs
        # the square of its length: refused here, before hours of tuning (a record read as the
        # wrong kind puts a "mode" at a fraction of a hertz)
        slowest = min(anchors)
        period = 2 * math.pi / (slowest * reference.Ts)
        if not period <= MAX_PERIOD_SAMPLES:
            raise ParameterError(
                "Ts", f"Ts = {reference.Ts:g} s: the resonance at {slowest:.4g} rad/s "
                f"({slowest / (2 * math.pi):.4g} Hz, axis {res.name}) lasts {period:.4g} samples "
                f"a period, more than {MAX_PERIOD_SAMPLES}: tuning its filters would take hours; "
                "use a larger --Ts, or check the record's kind and --band")
        delay = max_delay
        if max_delay is None and max_smoothing is None:
            res.default_limit = _default_limit(res, objs, anchors, firmware)
            if res.default_limit is not None:
                # the exact discrete filters span whole samples of Ts: the budget is the
                # shaper's duration rounded up to one
                delay = res.default_limit.max_delay
                delay = math.ceil(delay / reference.Ts - 1e-9) * reference.Ts
                res.default_limit = replace(res.default_limit, max_delay=delay)
                res.notes.append(res.default_limit.note())
        res.candidates.append(evaluate("none", [], objs, rank, reference, delay,
                                       max_smoothing))
        for fam in fams:
            c = tune(fam, anchors, objs, rank, reference, delay, max_smoothing)
            if c is not None:
                res.candidates.append(c)
            done += 1
            if progress:
                progress(done, work)
        if res.default_limit is not None:
            _hold_to_trade_off(res, objs, rank, reference, delay, firmware)
        res.candidates.sort(key=lambda c: c.vibration)
        res.recommended = recommend(res.candidates, res.modes, sample=reference.Ts)
    return Calibration(axes, reference, max_delay, max_smoothing, skipped, firmware)
