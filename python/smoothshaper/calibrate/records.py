# SPDX-License-Identifier: Apache-2.0
"""Reading measured records and telling their kind apart.

Four kinds of file are understood (CSV as :mod:`.tables` reads them):

* ``raw``: a resonance-test record: a time column [s] and 1 to 3 acceleration columns
  (Klipper's and Shake&Tune's ``#time,accel_x,accel_y,accel_z``). Real accelerometer logs have
  gaps where the sensor's FIFO overflowed and samples where it clipped: the record is cut into
  contiguous segments at every gap (a step longer than 1.5 median sample periods), each placed
  on the uniform time grid where its first stamp falls, the spectra are estimated from the
  samples the segments hold (:func:`.spectra.welch`), and the fraction excluded is stated.
  Clipped samples' values are excluded and reconstructed from the oscillation around them
  (:mod:`.clipping`). Time stamps that jitter by more than 5 % of the period are interpolated onto a
  uniform grid per segment; below that they are taken as uniform (the phase error, 2 pi f x
  jitter, is under 1e-3 at a tenth of the sample rate). A constant offset (gravity) is allowed.
* ``decay``: a free decay: a time column [s] and one signal column; any constant offset.
* ``psd``: a power spectral density table: a frequency column [Hz] and PSD columns. Klipper's
  tables of every vintage: ``freq,psd_x,psd_y,psd_z,psd_xyz``; calibration tables with shaper
  columns (``zv(39.2)``, with or without the ``shapers:`` marker; their PSD is already divided
  by the frequency); tables of several data sets (``freq,name1,name2,shapers:,...``);
  Shake&Tune's ``#freq,psd_x,...``.
* ``frf``: a measured frequency response: frequency [Hz], magnitude (linear, or dB when the
  header says so) and an optional phase column.

``--kind auto`` decides from the header (``freq`` + ``psd`` or shaper columns -> psd; ``freq`` +
``mag``/``gain``/``phase`` -> frf; ``accel`` -> raw) and, for two time-domain columns, from the
envelope: a record whose amplitude dies away is a decay, anything else a resonance test.

The direction of a resonance test is read from Klipper's and Shake&Tune's file names
(``resonances_x_...``, ``raw_data_y_...``, ``calibration_data_x_...``, ``..._X.csv``,
``belt_..._A.csv``, ``raw_data_axis=1.000,-1.000_...``); it names the analysed axis and lets
:func:`energy_shares` tell when the sensor's axes do not match the printer's.

Every problem raises :class:`RecordError` naming the file, the row (1-based line number in the
file) or column, and the reason.
"""
from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass, field

import numpy as np

from .._checks import choice as _choice
from .clipping import clipped_samples, reconstruct
from .tables import MAX_VALUE, RecordError, read_table

__all__ = ["KINDS", "AXIS_NAMES", "RecordError", "Record", "read_table", "detect_kind", "load",
           "MAX_VALUE", "test_direction"]

KINDS = ("auto", "raw", "decay", "psd", "frf")
AXIS_NAMES = ("x", "y", "z")
#: Interpolate time stamps onto a uniform grid when they jitter by more than this fraction
#: of the sample period.
RESAMPLE_JITTER = 0.05
#: A step in the time stamps longer than this many median periods is a gap.
GAP_PERIODS = 1.5
_SHAPER_COLUMN = re.compile(r"^[a-z0-9_]+\(.*\)$")


@dataclass
class Record:
    """A parsed record.

    Time-domain kinds: ``t`` [s] (the stamps, from 0), ``signals`` (n, k), ``Ts`` (median
    sample period), ``segments`` ([(start, stop)] index ranges of contiguous samples),
    ``grid_starts`` (the index on the uniform time grid of each segment's first sample),
    ``excluded`` (fraction of the record's span not in a segment: the gaps), ``clipped``
    (samples whose values were reconstructed). Frequency-domain kinds: ``f`` [Hz] and
    ``signals`` (PSD columns, or the magnitude) with ``phase`` [rad] for a frequency response; ``normalized`` when a PSD table was already
    divided by the frequency (Klipper's calibration tables), ``marked`` when its header says so
    with the ``shapers:`` marker: the established tool divides every other table by the
    frequency, the older calibration tables a second time, and the spectral figure reads a
    table the way it does, so that both score the same spectrum. ``direction``: the test direction
    (unit 3-vector) read from the file name, ``test_axis`` its name (``x``, ``y``, ``z``,
    ``a``/``b`` for CoreXY belts, ``diagonal``), ``notes``: what was excluded or repaired."""
    path: str
    kind: str
    names: list[str]
    t: np.ndarray | None = None
    Ts: float | None = None
    f: np.ndarray | None = None
    signals: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    phase: np.ndarray | None = None
    jitter: float = 0.0            # largest |dt - Ts| / Ts inside the segments
    resampled: bool = False
    segments: list = field(default_factory=list)
    excluded: float = 0.0
    gaps: int = 0
    clipped: int = 0               # samples reconstructed as clipped
    grid_starts: list = field(default_factory=list)
    normalized: bool = False
    marked: bool = False           # the table's header has Klipper's ",shapers:" marker
    direction: np.ndarray | None = None
    test_axis: str | None = None
    notes: list = field(default_factory=list)
    #: Raw records: Welch PSD of each column per segment length (:func:`.spectra.column_spectrum`).
    column_psd: dict = field(default_factory=dict, repr=False, compare=False)


def _lower(names):
    return [n.lower().strip() for n in names] if names else []


def _is_shaper_column(name: str) -> bool:
    return bool(_SHAPER_COLUMN.match(name.lower().strip()))


def detect_kind(path: str, header, data) -> str:
    names = _lower(header)
    first = names[0] if names else ""
    rest = " ".join(names[1:])
    if names and re.search(r"freq|hz|omega|rad/s", first):
        if "psd" in rest or "power" in rest or "shapers:" in names \
                or any(_is_shaper_column(n) for n in names[1:]):
            return "psd"
        if re.search(r"mag|gain|amp|phase|db|\|h\|", rest):
            return "frf"
        if first.startswith("freq") and len(names) >= 2:
            return "psd"            # Klipper's tables of several data sets name them freely
        raise RecordError(path, f"a frequency column ({header[0]!r}) but columns "
                          f"{header[1:]} name neither a PSD (psd_x, ...) nor a frequency response "
                          "(magnitude, phase): name them or pass --kind psd|frf", row=None)
    if "accel" in rest:
        return "raw"
    if data.shape[1] == 2:
        x = data[:, 1] - np.mean(data[-max(2, data.shape[0] // 10):, 1])
        n = x.size
        if n >= 20:
            head = np.sqrt(np.mean(x[: n // 5] ** 2))
            tail = np.sqrt(np.mean(x[-(n // 5):] ** 2))
            if head > 5.0 * tail:
                return "decay"
    return "raw"


def test_direction(path: str) -> tuple[np.ndarray | None, str | None]:
    """(unit direction, name) of the test a file name announces, else (None, None)."""
    base = os.path.basename(str(path)).lower()
    m = re.search(r"axis=(-?[\d.]+),(-?[\d.]+)(?:,(-?[\d.]+))?", base)
    if m:
        v = np.array([float(m.group(1)), float(m.group(2)), float(m.group(3) or 0.0)])
        n = float(np.linalg.norm(v))
        if n > 0 and np.all(np.isfinite(v)):
            v = v / n
            hit = np.flatnonzero(np.abs(v) > 1 - 1e-9)
            return v, (AXIS_NAMES[int(hit[0])] if hit.size else "diagonal")
    m = re.search(r"(?:resonances|raw_data|calibration_data)_([xyz])(?:_|\.|$)", base) \
        or re.search(r"_([xyz])\.(?:csv|stdata)$", base)
    if m:
        v = np.zeros(3)
        v[AXIS_NAMES.index(m.group(1))] = 1.0
        return v, m.group(1)
    m = re.search(r"belt_.*_([ab])\.csv$", base)
    if m:                           # CoreXY belts: A moves along (1, -1), B along (1, 1)
        s = math.sqrt(0.5)
        return (np.array([s, -s, 0.0]) if m.group(1) == "a" else np.array([s, s, 0.0])), \
            m.group(1)
    return None, None


def _segments(path, t, lines):
    """(segment bounds, median period, jitter inside the segments, number of gaps)."""
    dt = np.diff(t)
    if dt.size == 0:
        raise RecordError(path, "a single time stamp: a record needs many samples")
    bad = np.flatnonzero(~(dt > 0))
    if bad.size:
        i = int(bad[0]) + 1
        raise RecordError(path, f"time {float(t[i]):g} s does not increase (previous "
                          f"{float(t[i - 1]):g} s): "
                          "time stamps must be strictly increasing", row=lines[i], column=0)
    Ts = float(np.median(dt))
    if not (math.isfinite(Ts) and Ts > 0):
        raise RecordError(path, f"sample period {Ts!r} s from the time stamps is not a "
                          "positive number", column=0)
    gap = np.flatnonzero(dt > GAP_PERIODS * Ts)
    cuts = np.r_[0, gap + 1, t.size]
    segs = [(int(a), int(b)) for a, b in zip(cuts[:-1], cuts[1:]) if b > a]
    inside = np.delete(dt, gap)
    jitter = float(np.max(np.abs(inside - Ts)) / Ts) if inside.size else 0.0
    return segs, Ts, jitter, int(gap.size)


def _grid_starts(t, segs, Ts) -> list[int]:
    """Index on the uniform grid k Ts of each segment's first sample (a segment never lands on
    samples of the one before it)."""
    out, end = [], 0
    for a, b in segs:
        g = max(int(round(float(t[a]) / Ts)), end)
        out.append(g)
        end = g + (b - a)
    return out


def _axis_name(name: str, j: int) -> str:
    low = name.lower().strip()
    if low in ("xyz", "psd_xyz", "accel_xyz"):
        return "xyz"
    for a in AXIS_NAMES:
        if low == a or low.endswith("_" + a):
            return a
    return name


def _raw(path, header, data, lines, kind, names) -> Record:
    if kind == "decay" and data.shape[1] != 2:
        raise RecordError(path, f"a free decay has one signal column, this file has "
                          f"{data.shape[1] - 1}", column=2)
    if data.shape[1] > 4:
        raise RecordError(path, f"{data.shape[1] - 1} signal columns: a resonance-test record "
                          "has 1 to 3 acceleration columns", column=4)
    t = data[:, 0]
    x = data[:, 1:]
    if x.shape[0] < 64:
        raise RecordError(path, f"only {x.shape[0]} samples: too short to estimate a mode "
                          "(need at least 64)")
    segs, Ts, jitter, gaps = _segments(path, t, lines)
    if kind == "raw" and header is not None:
        names = [_axis_name(n, j) for j, n in enumerate(names)]
    elif kind == "raw":
        names = list(AXIS_NAMES[: x.shape[1]])
    rec = Record(path, kind, names, Ts=Ts, jitter=jitter, gaps=gaps)
    span = (t[-1] - t[0]) / Ts + 1
    notes = []
    if kind == "raw":
        constant = [j for j in range(x.shape[1]) if x[:, j].max() == x[:, j].min()]
        if len(constant) == x.shape[1]:
            raise RecordError(path, f"column {names[0]!r} is constant: no motion recorded",
                              column=1)
        clip, cols = clipped_samples(x)
        rec.clipped = int(np.count_nonzero(clip.any(axis=1)))
        if rec.clipped:
            x = x.copy()
            for j in cols:
                x[:, j] = reconstruct(x[:, j], clip[:, j])
            notes.append(f"{rec.clipped} clipped samples ({100 * rec.clipped / x.shape[0]:.2g} %"
                         f", column {', '.join(names[j] for j in cols)}) sit on the sensor's "
                         "range: their values are excluded and reconstructed from the "
                         "oscillation around them; lower the test's "
                         "accel_per_hz or raise the sensor's range for a cleaner record")
    segs = [(a, b) for a, b in segs if b - a >= 16]
    valid = sum(b - a for a, b in segs)
    if valid < 64:
        raise RecordError(path, f"only {valid} contiguous samples between gaps: too short to "
                          "estimate a mode (need at least 64)")
    rec.excluded = max(0.0, 1.0 - valid / span)
    if gaps:
        notes.insert(0, f"{gaps} gaps in the time stamps (the sensor's FIFO overflowed): "
                     f"{100 * rec.excluded:.2g} % of the record's span is excluded and the "
                     f"spectrum is estimated from {len(segs)} contiguous segments")
    elif rec.excluded > 0.001:
        notes.append(f"{100 * rec.excluded:.2g} % of the record excluded")
    if jitter > RESAMPLE_JITTER:
        x = x.copy()
        for a, b in segs:
            grid = t[a] + np.arange(b - a) * Ts
            grid = np.minimum(grid, t[b - 1])
            for j in range(x.shape[1]):
                x[a:b, j] = np.interp(grid, t[a:b], x[a:b, j])
        rec.resampled = True
    rec.t = t - t[0]
    rec.signals = x
    rec.segments = segs
    rec.grid_starts = _grid_starts(rec.t, segs, Ts)
    rec.notes = notes
    rec.direction, rec.test_axis = test_direction(path)
    return rec


def _has_marker(path) -> bool:
    """Whether the header line has Klipper's ``,shapers:`` marker (its empty column is dropped
    with the column it heads, so it is looked for in the file itself)."""
    try:
        with open(path, encoding="utf-8", errors="replace") as fh:
            for line in fh:
                if line.strip() and not line.startswith("#"):
                    return ",shapers:" in line
    except OSError:
        pass
    return False


def _psd_columns(names):
    """Indices (into the value columns) of the PSD columns and their names: Klipper's shaper
    columns and everything after ``shapers:`` are dropped."""
    keep, out = [], []
    for j, n in enumerate(names):
        low = n.lower().strip()
        if low == "shapers:":
            break
        if _is_shaper_column(low) or low == "":
            continue
        keep.append(j)
        out.append(_axis_name(n, j))
    return keep, out


def load(path: str, kind: str = "auto") -> Record:
    """Read and check ``path`` as a record of ``kind`` (see the module docstring)."""
    if kind not in KINDS:
        kind = _choice("kind", kind, KINDS)
    header, data, lines = read_table(path)
    if data.shape[1] < 2:
        raise RecordError(path, "one column only: a record needs a time (or frequency) column "
                          "and at least one signal column", column=0)
    if kind == "auto":
        kind = detect_kind(path, header, data)
    names = list(header[1:]) if header else [f"column {j}" for j in range(1, data.shape[1])]
    if kind in ("raw", "decay"):
        return _raw(path, header, data, lines, kind, names)
    f = data[:, 0]
    if header and re.search(r"rad|omega", header[0].lower()):
        f = f / (2 * math.pi)
    df = np.diff(f)
    bad = np.flatnonzero(~(df > 0))
    if bad.size:
        i = int(bad[0]) + 1
        raise RecordError(path, f"frequency {float(f[i]):g} does not increase: frequencies must be "
                          "strictly increasing", row=lines[i], column=0)
    if f[0] < 0:
        raise RecordError(path, "negative frequency", row=lines[0], column=0)
    if f.size < 16:
        raise RecordError(path, f"only {f.size} frequencies: too few to fit a mode (need 16)")
    if kind == "psd":
        P = data[:, 1:]
        cols = list(range(P.shape[1]))
        normalized = False
        if header is not None:
            low = _lower(names)
            normalized = _has_marker(path) or any(_is_shaper_column(n) for n in low)
            cols, names = _psd_columns(names)
            if not cols:
                raise RecordError(path, "no PSD column (only shaper columns)", column=1)
            P = P[:, cols]
        neg = np.argwhere(P < 0)
        if neg.size:
            i, j = neg[0]
            raise RecordError(path, f"PSD value {float(P[i, j]):g} is negative: a power spectral "
                              "density is >= 0", row=lines[i], column=int(cols[j]) + 1)
        rec = Record(path, kind, names, f=f, signals=P, normalized=normalized,
                     marked=_has_marker(path))
        rec.direction, rec.test_axis = test_direction(path)
        return rec
    # frequency response: magnitude, optional phase
    lower = _lower(header)
    mag = data[:, 1]
    if lower and "db" in lower[1]:
        mag = 10.0 ** (np.minimum(mag, 3000.0) / 20.0)
    elif np.any(mag < 0):
        i = int(np.flatnonzero(mag < 0)[0])
        raise RecordError(path, f"magnitude {float(mag[i]):g} is negative (if it is in dB, say so in "
                          "the header, e.g. 'mag_db')", row=lines[i], column=1)
    phase = None
    if data.shape[1] >= 3:
        phase = data[:, 2]
        if not (lower and "rad" in lower[2]):
            phase = np.deg2rad(phase)
    return Record(path, "frf", names[:1], f=f, signals=mag[:, None], phase=phase)
