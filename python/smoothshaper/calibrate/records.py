# SPDX-License-Identifier: Apache-2.0
"""Reading measured records and telling their kind apart.

Four kinds of file are understood (CSV: comma, semicolon, tab or space separated; ``#`` lines
are comments, except that a ``#`` line directly followed by data may name the columns, as
Klipper's ``#time,accel_x,accel_y,accel_z`` does):

* ``raw``: a resonance-test record: a time column [s] and 1 to 3 acceleration columns. Time
  stamps may jitter or be non-uniform (the record is resampled onto a uniform grid); a constant
  offset (gravity on one axis) is allowed.
* ``decay``: a free decay: a time column [s] and one signal column; any constant offset.
* ``psd``: a power spectral density table: a frequency column [Hz] and one or more PSD columns.
* ``frf``: a measured frequency response: frequency [Hz], magnitude (linear, or dB when the
  header says so) and an optional phase column.

``--kind auto`` decides from the header (``freq`` + ``psd`` -> psd; ``freq`` + ``mag``/``gain``/
``phase`` -> frf; ``accel`` -> raw) and, for two time-domain columns, from the envelope: a record
whose amplitude dies away is a decay, anything else a resonance test.

Every problem raises :class:`RecordError` naming the file, the row (1-based line number in the
file) or column, and the reason.
"""
from __future__ import annotations

import csv
import math
import os
import stat
import re
from dataclasses import dataclass, field

import numpy as np

from .._checks import choice as _choice
from ..errors import ParameterError

__all__ = ["KINDS", "AXIS_NAMES", "RecordError", "Record", "read_table", "detect_kind", "load"]

KINDS = ("auto", "raw", "decay", "psd", "frf")
AXIS_NAMES = ("x", "y", "z")


class RecordError(ValueError):
    """A record that cannot support an estimate. ``path``, ``row`` (1-based line) and
    ``column`` (0-based) locate the problem where it has a location."""

    def __init__(self, path: str, reason: str, *, row: int | None = None,
                 column: int | str | None = None):
        where = path
        if row is not None:
            where += f", row {row}"
        if column is not None:
            where += f", column {column}"
        super().__init__(f"{where}: {reason}")
        self.path, self.row, self.column, self.reason = path, row, column, reason


@dataclass
class Record:
    """A parsed record. Time-domain kinds: ``t`` [s] (uniform after resampling), ``signals``
    (n, k) and ``Ts``; frequency-domain kinds: ``f`` [Hz] and ``signals`` (PSD columns, or the
    magnitude) with ``phase`` [rad] for a frequency response."""
    path: str
    kind: str
    names: list[str]
    t: np.ndarray | None = None
    Ts: float | None = None
    f: np.ndarray | None = None
    signals: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    phase: np.ndarray | None = None
    jitter: float = 0.0            # largest |dt - Ts| / Ts of the original time stamps
    resampled: bool = False


def _split(line: str, delimiter: str | None) -> list[str]:
    if delimiter is None:
        return line.split()
    return [v.strip() for v in next(csv.reader([line], delimiter=delimiter))]


def _sniff_delimiter(line: str) -> str | None:
    for d in (",", ";", "\t"):
        if d in line:
            return d
    return None


#: Largest magnitude a data value may have: squares and sums of squares (spectra, fits) of
#: larger values overflow a double. Measured data never come near it; beyond it a file is
#: refused naming the row, instead of a NaN spectrum or a misleading "no resonance".
MAX_VALUE = 1e150
#: Longest text of a cell or a line quoted in an error message.
_QUOTE = 60


def _quote(text: str) -> str:
    """``text`` for an error message, shortened to about :data:`_QUOTE` characters."""
    return repr(text if len(text) <= _QUOTE else text[:_QUOTE] + "...")


def _is_number(v: str) -> bool:
    try:
        float(v)
        return True
    except ValueError:
        return False


def read_table(path: str) -> tuple[list[str] | None, np.ndarray, np.ndarray]:
    """(header or None, data (n, m), line numbers (n,)) of a numeric CSV table."""
    if not isinstance(path, (str, os.PathLike)):
        # open() takes an int as a file descriptor: load(1) read and closed stdout
        raise ParameterError("path", f"path must be a file name (str or os.PathLike), got "
                             f"{type(path).__name__}")
    try:
        if stat.S_ISCHR(os.stat(path).st_mode) or stat.S_ISBLK(os.stat(path).st_mode):
            # /dev/zero or /dev/urandom would be read until memory runs out
            raise RecordError(path, "not a file of records but a device")
        with open(path, encoding="utf-8", errors="replace") as fh:
            lines = fh.read().splitlines()
    except OSError as exc:
        raise RecordError(path, f"cannot read the file ({exc.strerror})") from None
    header, rows, numbers, delimiter = None, [], [], None
    last_comment = None
    for no, raw in enumerate(lines, start=1):
        line = raw.strip()
        if not line:
            continue
        if line.startswith("#"):
            last_comment = line.lstrip("#").strip()
            continue
        if delimiter is None and not rows:
            delimiter = _sniff_delimiter(line)
        try:
            values = _split(line, delimiter)
        except csv.Error as exc:     # e.g. a field beyond csv's limit of 131072 characters
            raise RecordError(path, f"cannot split the line into values ({exc})", row=no) from None
        if not rows and header is None and not all(_is_number(v) for v in values if v):
            header = values
            continue
        if not rows and header is None and last_comment:
            try:
                names = _split(last_comment, delimiter)
            except csv.Error:
                names = []
            if len(names) == len(values) and not any(_is_number(v) for v in names):
                header = names
        rows.append(values)
        numbers.append(no)
    if not rows:
        raise RecordError(path, "no data rows (empty file, or only comments and a header)")
    width = len(rows[0])
    data = np.empty((len(rows), width))
    for i, (values, no) in enumerate(zip(rows, numbers)):
        if len(values) != width:
            raise RecordError(path, f"{len(values)} values where the first data row has {width}",
                              row=no)
        for j, v in enumerate(values):
            try:
                data[i, j] = float(v)
            except ValueError:
                raise RecordError(path, f"non-numeric value {_quote(v)}", row=no,
                                  column=j) from None
    bad = ~np.isfinite(data)
    if bad.any():
        i, j = np.argwhere(bad)[0]
        raise RecordError(path, f"non-finite value ({_quote(lines[numbers[i] - 1].strip())}); "
                          "remove or repair the row", row=int(numbers[i]), column=int(j))
    big = np.abs(data) > MAX_VALUE
    if big.any():
        i, j = np.argwhere(big)[0]
        raise RecordError(path, f"value {float(data[i, j]):.6g} is beyond {MAX_VALUE:g} in "
                          "magnitude (its square would overflow in a spectrum); rescale the "
                          "column", row=int(numbers[i]), column=int(j))
    if header is not None and len(header) != width:
        header = None
    return header, data, np.asarray(numbers)


def _lower(names):
    return [n.lower() for n in names] if names else []


def detect_kind(path: str, header, data) -> str:
    names = _lower(header)
    first = names[0] if names else ""
    rest = " ".join(names[1:])
    if names and re.search(r"freq|hz|omega|rad/s", first):
        if "psd" in rest or "power" in rest:
            return "psd"
        if re.search(r"mag|gain|amp|phase|db|\|h\|", rest):
            return "frf"
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


def _resample(path, t, x, numbers):
    """Uniform grid at the mean sample period; cubic spline through the measured samples."""
    from scipy.interpolate import CubicSpline
    dt = np.diff(t)
    if dt.size == 0:
        raise RecordError(path, "a single time stamp: a record needs many samples")
    bad = np.flatnonzero(dt <= 0)
    if bad.size:
        i = int(bad[0]) + 1
        raise RecordError(path, f"time {float(t[i]):g} s does not increase (previous "
                          f"{float(t[i - 1]):g} s): "
                          "time stamps must be strictly increasing", row=int(numbers[i]), column=0)
    Ts = (t[-1] - t[0]) / (t.size - 1)
    jitter = float(np.max(np.abs(dt - Ts)) / Ts)
    gap = np.flatnonzero(dt > 5.0 * Ts)
    if gap.size:
        i = int(gap[0]) + 1
        raise RecordError(path, f"a gap of {dt[i - 1]:.6g} s ({dt[i - 1] / Ts:.1f} sample "
                          "periods) in the time stamps: the record is not contiguous",
                          row=int(numbers[i]), column=0)
    if jitter <= 1e-9:
        return t - t[0], x, Ts, jitter, False
    grid = np.arange(t.size) * Ts
    return grid, CubicSpline(t - t[0], x, axis=0)(grid), Ts, jitter, True


def _check_clipping(path, x, numbers, names):
    for j in range(x.shape[1]):
        col = x[:, j]
        span = col.max() - col.min()
        if span == 0:
            raise RecordError(path, f"column {names[j]!r} is constant: no motion recorded",
                              column=j + 1)
        for value in (col.max(), col.min()):
            at = np.flatnonzero(col == value)
            # a clipped sensor sits on its rail for several consecutive samples, repeatedly;
            # a quantised but unclipped peak holds its value for at most 2-3 samples
            starts = np.flatnonzero(np.diff(np.r_[-2, at]) != 1)
            lengths = np.diff(np.r_[starts, at.size])
            if np.count_nonzero(lengths >= 5) >= 3:
                raise RecordError(path, f"column {names[j]!r} is clipped: {at.size} samples sit "
                                  f"at {value:g} (the sensor's range); reduce the excitation",
                                  row=int(numbers[at[0]]), column=j + 1)


def load(path: str, kind: str = "auto") -> Record:
    """Read and check ``path`` as a record of ``kind`` (see the module docstring)."""
    if kind not in KINDS:
        kind = _choice("kind", kind, KINDS)
    header, data, numbers = read_table(path)
    if data.shape[1] < 2:
        raise RecordError(path, "one column only: a record needs a time (or frequency) column "
                          "and at least one signal column", column=0)
    if kind == "auto":
        kind = detect_kind(path, header, data)
    names = list(header[1:]) if header else [f"column {j}" for j in range(1, data.shape[1])]
    if kind in ("raw", "decay"):
        if kind == "decay" and data.shape[1] != 2:
            raise RecordError(path, f"a free decay has one signal column, this file has "
                              f"{data.shape[1] - 1}", column=2)
        if data.shape[1] > 4:
            raise RecordError(path, f"{data.shape[1] - 1} signal columns: a resonance-test record "
                              "has 1 to 3 acceleration columns", column=4)
        t, x, Ts, jitter, resampled = _resample(path, data[:, 0], data[:, 1:], numbers)
        if x.shape[0] < 64:
            raise RecordError(path, f"only {x.shape[0]} samples: too short to estimate a mode "
                              "(need at least 64)")
        _check_clipping(path, data[:, 1:], numbers, names)
        if kind == "raw" and header is not None:
            names = [_axis_name(n, j) for j, n in enumerate(names)]
        elif kind == "raw":
            names = list(AXIS_NAMES[: x.shape[1]])
        return Record(path, kind, names, t=t, Ts=Ts, signals=x, jitter=jitter,
                      resampled=resampled)
    f = data[:, 0]
    if names and header and re.search(r"rad|omega", header[0].lower()):
        f = f / (2 * math.pi)
    df = np.diff(f)
    bad = np.flatnonzero(df <= 0)
    if bad.size:
        i = int(bad[0]) + 1
        raise RecordError(path, f"frequency {float(f[i]):g} does not increase: frequencies must be "
                          "strictly increasing", row=int(numbers[i]), column=0)
    if f[0] < 0:
        raise RecordError(path, "negative frequency", row=int(numbers[0]), column=0)
    if f.size < 16:
        raise RecordError(path, f"only {f.size} frequencies: too few to fit a mode (need 16)")
    if kind == "psd":
        P = data[:, 1:]
        neg = np.argwhere(P < 0)
        if neg.size:
            i, j = neg[0]
            raise RecordError(path, f"PSD value {float(P[i, j]):g} is negative: a power spectral "
                              "density is >= 0", row=int(numbers[i]), column=int(j) + 1)
        if header is not None:
            # Klipper's calibration CSV also carries shaper-response columns ("zv(39.2)") and
            # the sum psd_xyz: keep the per-axis PSD columns
            cols = [j for j, n in enumerate(names) if "psd" in n.lower()] or list(range(len(names)))
            per_axis = [j for j in cols if _axis_name(names[j], j) in AXIS_NAMES]
            cols = per_axis or cols
            P = P[:, cols]
            names = [_axis_name(names[j], j) for j in cols]
        return Record(path, kind, names, f=f, signals=P)
    # frequency response: magnitude, optional phase
    lower = _lower(header)
    mag = data[:, 1]
    if lower and "db" in lower[1]:
        mag = 10.0 ** (mag / 20.0)
    elif np.any(mag < 0):
        i = int(np.flatnonzero(mag < 0)[0])
        raise RecordError(path, f"magnitude {float(mag[i]):g} is negative (if it is in dB, say so in "
                          "the header, e.g. 'mag_db')", row=int(numbers[i]), column=1)
    phase = None
    if data.shape[1] >= 3:
        phase = data[:, 2]
        if not (lower and "rad" in lower[2]):
            phase = np.deg2rad(phase)
    return Record(path, "frf", names[:1], f=f, signals=mag[:, None], phase=phase)


def _axis_name(name: str, j: int) -> str:
    low = name.lower().strip()
    for a in AXIS_NAMES:
        if low == a or low.endswith("_" + a):
            return a
    return name
