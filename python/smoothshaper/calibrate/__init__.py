# SPDX-License-Identifier: Apache-2.0
"""From a measured record to a recommended, verified filter (``smoothshaper calibrate``).

>>> from smoothshaper import calibrate
>>> result = calibrate.run(["examples/resonance_x.csv"], max_delay=0.03)   # doctest: +SKIP
>>> result.axes[0].recommended.stages                                      # doctest: +SKIP

Steps (docs/calibrate.md): read and recognise the record (:mod:`.records`), estimate the
spectrum (Welch) or fit the decay and identify every significant mode with its uncertainty
(:mod:`.modes`), tune every candidate family to the modes and rank them (:mod:`.candidates`),
then plots (:mod:`.plots`) and ready-to-use outputs (:mod:`.outputs`).
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass, field, replace

import numpy as np

from .._checks import finite as _finite, positive as _positive, real_array as _real_array
from ..errors import ParameterError
from .candidates import (Candidate, Objective, Reference, evaluate, families,
                         recommend, tune)
from .modes import Mode, Spectrum, decay_modes, spectral_modes, welch
from .records import KINDS, Record, RecordError, load

__all__ = ["run", "Calibration", "AxisResult", "Mode", "Candidate", "Reference", "RecordError",
           "KINDS", "load"]


@dataclass
class AxisResult:
    """Everything found for one axis (one signal column) of one record.

    Attributes
    ----------
    name : str
        The column (``"x"``, ``"accel_y"``, ...; ``"file:column"`` with several files).
    record : Record
        The parsed record it came from.
    modes : list of Mode
        The identified modes, lowest first, each with its frequency, damping and standard
        deviations.
    band : (float, float)
        Frequency band searched [Hz].
    resolution : float
        Frequency resolution of the spectrum [Hz].
    spectrum : Spectrum or None
        What the modes were fitted on (None for free decays).
    candidates : list of Candidate
        Every tuned filter, least remaining vibration first.
    recommended : Candidate or None
        The best candidate within the limits (None if none meets them).
    fit_r2 : float or None
        Free decays: the fraction of the signal's variance the fit explains.
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


@dataclass
class Calibration:
    """The result of :func:`run`: one :class:`AxisResult` per axis and the limits applied.

    Attributes
    ----------
    axes : list of AxisResult
        The axes with a resonance.
    reference : Reference
        Sample period of the filters and the reference move.
    max_delay : float or None
        Longest impulse response allowed [s].
    max_smoothing : float or None
        Largest corner rounding allowed (length units of the reference move).
    skipped : list of str
        Axes without a resonance, and why.
    """
    axes: list[AxisResult]
    reference: Reference
    max_delay: float | None
    max_smoothing: float | None
    skipped: list[str] = field(default_factory=list)   # axes without a resonance, and why


def _band(record: Record, band, spec: Spectrum | None) -> tuple[float, float]:
    if record.kind in ("psd", "frf"):
        lo_default, hi_default = float(record.f[1] if record.f[0] == 0 else record.f[0]), \
            float(record.f[-1])
        if record.kind == "psd":        # a resonance test's PSD: its excited part
            lo_default, hi_default = excited_band(spec, lo_default, hi_default)
    else:
        df = float(spec.f[1] - spec.f[0])
        lo_default, hi_default = excited_band(spec, 5 * df, 0.4 / record.Ts)
    if band is None:
        return lo_default, hi_default
    lo, hi = band
    return max(lo, lo_default), min(hi, hi_default)


def excited_band(spec: Spectrum, lo: float, hi: float) -> tuple[float, float]:
    """The part of [lo, hi] a resonance test excited: where the smoothed PSD stands 10 dB above
    the noise floor (the median of the top fifth of the spectrum), shrunk by 15 % at each end,
    so that the steep edges of a sweep's band are not taken for resonances."""
    f, P = spec.f, spec.P
    logP = np.log10(np.maximum(P, 1e-300))
    kern = np.hanning(29)[1:-1]
    smooth = np.convolve(logP, kern / kern.sum(), mode="same")
    floor = float(np.median(logP[int(0.8 * f.size):]))
    excited = np.flatnonzero((smooth > floor + 1.0) & (f >= lo) & (f <= hi))
    if excited.size < 16:
        return lo, hi
    return max(lo, f[excited[0]] * 1.15), min(hi, f[excited[-1]] / 1.15)


def _columns(record: Record, axis: str) -> list[int]:
    if axis == "all" or record.kind in ("decay", "frf"):
        return list(range(record.signals.shape[1]))
    if axis in record.names:
        return [record.names.index(axis)]
    raise RecordError(record.path, f"no axis {axis!r} (columns: {', '.join(record.names)})")


def identify(record: Record, column: int, band=None) -> AxisResult:
    """Modes of one column of a record."""
    name = record.names[column]
    if record.kind == "decay":
        x = record.signals[:, column]
        modes, r2 = decay_modes(x, record.Ts, path=record.path, column=name, band=band)
        return AxisResult(name, record, modes, _band_decay(record, band),
                          1.0 / (x.size * record.Ts), None, fit_r2=r2)
    if record.kind == "raw":
        spec = welch(record.signals[:, column], record.Ts)
    else:
        P = record.signals[:, column]
        if record.kind == "frf":
            P = P ** 2
        spec = Spectrum(record.f, P)
    b = _band(record, band, spec)
    modes = spectral_modes(spec, b, path=record.path, column=name)
    return AxisResult(name, record, modes, b, float(np.median(np.diff(spec.f))), spec)


def _band_decay(record, band):
    hi = 0.4 / record.Ts
    return (0.0, hi) if band is None else (max(0.0, band[0]), min(hi, band[1]))


#: Most samples of Ts one period of the slowest mode may span (the filters' length, whose
#: square the tuning costs: a 47 Hz mode at Ts = 3e-6 s, 7100 samples, tunes in about 20 s).
MAX_PERIOD_SAMPLES = 1 << 14


def run(paths, *, kind: str = "auto", axis: str = "all", band=None,
        reference: Reference | None = None, max_delay: float | None = None,
        max_smoothing: float | None = None, spread: float = 0.0,
        progress=None) -> Calibration:
    """Identify the modes in every record and rank every candidate filter.

    Modes come from Welch PSD estimates with least-squares modal fits (raw accelerometer
    records, PSD tables, frequency responses) or from a least-squares fit of the whole free
    decay; every filter family is then tuned to the modes and scored by its remaining
    vibration over the modes' uncertainty (docs/calibrate.md).

    Parameters
    ----------
    paths : sequence of str
        CSV records.
    kind : {"auto", "raw", "decay", "psd", "frf"}, keyword-only
        Record kind (default ``"auto"``: from the header and the signal).
    axis : str, keyword-only
        ``"x"``, ``"y"``, ``"z"`` (a column name) or ``"all"`` (default).
    band : (float, float) or None, keyword-only
        Frequency band to search [Hz] (default: the part of the spectrum a resonance test
        excited, the table's range for a frequency response).
    reference : Reference or None, keyword-only
        Sample period of the filters and the reference move (default ``Reference()``).
    max_delay : float or None, keyword-only
        Longest impulse response allowed [s], > 0.
    max_smoothing : float or None, keyword-only
        Largest corner rounding allowed (length units of ``reference``), > 0.
    spread : float, keyword-only
        Expected variation of the natural frequencies over the workspace as a fraction in
        [0, 0.5), added in quadrature to each fit's standard deviation (default 0).
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
        Naming ``max_delay``, ``max_smoothing``, ``spread``, ``Ts`` or ``accel`` when out of
        range, or ``Ts`` when a mode lies at or above the filters' Nyquist frequency.
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
    if not (math.isfinite(reference.Ts) and reference.Ts > 0):
        raise ParameterError("Ts", f"Ts must be finite and > 0, got {reference.Ts!r}")
    if not (math.isfinite(reference.accel) and reference.accel > 0):
        raise ParameterError("accel", f"accel must be finite and > 0, got {reference.accel!r}")
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
        raise ParameterError("axis", f"axis must be a column name or 'all', got "
                             f"{type(axis).__name__}")
    if band is not None:
        b = _real_array("band", band, ndim=1)
        if b.size != 2 or not (np.all(np.isfinite(b)) and b[0] < b[1] and b[1] > 0):
            raise ParameterError("band", "band must be two finite frequencies FMIN < FMAX [Hz] "
                                 f"with FMAX > 0, got {b.tolist()}")
        band = (float(b[0]), float(b[1]))
    records = [load(p, kind) for p in paths]
    axes, skipped = [], []
    for rec in records:
        columns = _columns(rec, axis)
        for j in columns:
            try:
                res = identify(rec, j, band)
            except RecordError as exc:
                # --axis all: an axis without a resonance (e.g. z of a horizontal test) is
                # reported and skipped; a record with none at all is an error
                if len(columns) == 1:
                    raise
                skipped.append(str(exc))
                continue
            if spread:
                res.modes = [replace(m, wn_std=math.hypot(m.wn_std, spread * m.wn))
                             for m in res.modes]
            if len(records) > 1:
                res.name = f"{rec.path}:{res.name}"
            axes.append(res)
    if not axes:
        raise RecordError(paths[0], "no axis shows a resonance: " + "; ".join(skipped))
    work = sum(len(families(len(a.modes))) for a in axes)
    done = 0
    for res in axes:
        fast = [m for m in res.modes if m.wn < 0.95 * math.pi / reference.Ts]
        if len(fast) < len(res.modes):
            raise ParameterError("Ts", f"Ts = {reference.Ts:g} s: a mode at {res.modes[0].wn:.4g} rad/s "
                             "is at or above the filters' Nyquist frequency; use a smaller --Ts")
        # the filters span a few periods of the slowest mode, and scoring a filter costs the
        # square of its length: refused here, before hours of tuning (a record read as the
        # wrong kind puts a "mode" at a fraction of a hertz)
        slowest = min(m.wn for m in res.modes)
        period = 2 * math.pi / (slowest * reference.Ts)
        if not period <= MAX_PERIOD_SAMPLES:
            raise ParameterError(
                "Ts", f"Ts = {reference.Ts:g} s: the mode at {slowest:.4g} rad/s "
                f"({slowest / (2 * math.pi):.4g} Hz, axis {res.name}) lasts {period:.4g} samples "
                f"a period, more than {MAX_PERIOD_SAMPLES}: tuning its filters would take hours; "
                "use a larger --Ts, or check the record's kind and --band")
        objective = Objective(res.modes, reference.Ts)
        h0 = np.ones(1)
        res.candidates.append(evaluate("none", [], h0, objective, reference, max_delay,
                                       max_smoothing))
        for fam in families(len(res.modes)):
            c = tune(fam, res.modes, objective, reference, max_delay, max_smoothing)
            if c is not None:
                res.candidates.append(c)
            done += 1
            if progress:
                progress(done, work)
        res.candidates.sort(key=lambda c: c.vibration)
        res.recommended = recommend(res.candidates)
    return Calibration(axes, reference, max_delay, max_smoothing, skipped)
