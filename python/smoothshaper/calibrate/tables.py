# SPDX-License-Identifier: Apache-2.0
"""Reading numeric CSV tables fast, and naming the row of anything wrong in them.

The fast path is ``numpy.loadtxt`` (a C parser: a 600 s, 3.2 kHz three-axis record of 1.9 M
rows reads in about half a second); only when it refuses a file does a line-by-line reader run,
to name the row and column of the problem, or to read what loadtxt cannot (empty cells, as in
the empty ``shapers:`` column of a Klipper calibration table). Comma, semicolon, tab or space
separated; ``#`` lines are comments, except that a ``#`` line directly above the data may name
the columns (Klipper's ``#time,accel_x,accel_y,accel_z``, Shake&Tune's ``#freq,psd_x,...``).
"""
from __future__ import annotations

import csv
import math
import os
import stat

import numpy as np

from ..errors import ParameterError

__all__ = ["MAX_VALUE", "RecordError", "Lines", "read_table"]

#: Largest magnitude a data value may have: squares and sums of squares (spectra, fits) of
#: larger values overflow a double.
MAX_VALUE = 1e150
_QUOTE = 60
_HEAD_BYTES = 1 << 16


class RecordError(ValueError):
    """A record that cannot support an estimate. ``path``, ``row`` (1-based line) and
    ``column`` (0-based) locate the problem where it has a location."""

    def __init__(self, path: str, reason: str, *, row: int | None = None,
                 column: int | str | None = None):
        where = str(path)
        if row is not None:
            where += f", row {row}"
        if column is not None:
            where += f", column {column}"
        super().__init__(f"{where}: {reason}")
        self.path, self.row, self.column, self.reason = str(path), row, column, reason


class Lines:
    """Line number in the file (1-based) of each data row, worked out only when asked (an
    error message): the data rows are contiguous unless comments or blank lines sit among
    them, which a scan of the file then finds."""

    def __init__(self, path: str, first: int, n: int, delimiter: str | None):
        self.path, self.first, self.n, self._map = path, first, n, None
        self.delimiter = delimiter

    def __len__(self):
        return self.n

    def __getitem__(self, i):
        i = int(i)
        if self._map is None:
            self._map = self._scan()
        return int(self._map[i]) if i < len(self._map) else self.first + i

    def _scan(self):
        out = []
        with open(self.path, encoding="utf-8", errors="replace") as fh:
            for no, line in enumerate(fh, start=1):
                if no < self.first:
                    continue
                s = line.strip()
                if s and not s.startswith("#"):
                    out.append(no)
        return np.asarray(out, dtype=np.int64)


def _split(line: str, delimiter: str | None) -> list[str]:
    if delimiter is None:
        return line.split()
    return [v.strip() for v in next(csv.reader([line], delimiter=delimiter))]


def _sniff(line: str) -> str | None:
    for d in (",", ";", "\t"):
        if d in line:
            return d
    return None


def _is_number(v: str) -> bool:
    try:
        float(v)
        return True
    except ValueError:
        return False


def _quote(text: str) -> str:
    return repr(text if len(text) <= _QUOTE else text[:_QUOTE] + "...")


def _open_check(path) -> None:
    if not isinstance(path, (str, os.PathLike)):
        # open() takes an int as a file descriptor: load(1) read and closed stdout
        raise ParameterError("path", f"path must be a file name (str or os.PathLike), got "
                             f"{type(path).__name__}")
    try:
        mode = os.stat(path).st_mode
    except OSError as exc:
        raise RecordError(path, f"cannot read the file ({exc.strerror})") from None
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        # /dev/zero or /dev/urandom would be read until memory runs out
        raise RecordError(path, "not a file of records but a device")
    if stat.S_ISDIR(mode):
        raise RecordError(path, "cannot read the file (Is a directory)")


def _head(path):
    """(header or None, line number of the first data row, delimiter, first data row's values)
    from the first 64 KiB."""
    try:
        with open(path, "rb") as fh:
            raw = fh.read(_HEAD_BYTES)
    except OSError as exc:
        raise RecordError(path, f"cannot read the file ({exc.strerror})") from None
    text = raw.decode("utf-8", errors="replace")
    lines = text.splitlines()
    if len(raw) == _HEAD_BYTES and lines:
        lines = lines[:-1]                 # the last line may be cut
    header = None
    for no, s, comment in _data_lines(lines):
        d = _sniff(s)
        try:
            values = _split(s, d)
        except csv.Error:
            return None, None, None, None
        if header is None and _names_row(values):
            header = values
            continue
        if header is None:
            header = _comment_header(comment, values, d)
        return header, no, d, values
    return header, None, None, None


def _data_lines(lines):
    """(line number, the line stripped, the last comment line's text before it or None) of every
    line that is neither blank nor a ``#`` comment."""
    last_comment = None
    for no, raw in enumerate(lines, start=1):
        line = raw.strip()
        if not line:
            continue
        if line.startswith("#"):
            last_comment = line.lstrip("#").strip()
            continue
        yield no, line, last_comment


def _names_row(values) -> bool:
    """A row that is not all numbers (its empty cells aside): the header."""
    return not all(_is_number(v) for v in values if v)


def _comment_header(comment, values, delimiter):
    """The column names a comment line just above the first data row gives (as many names as
    the row has values, none a number), or None."""
    if not comment:
        return None
    try:
        names = _split(comment, delimiter)
    except csv.Error:
        return None
    if len(names) == len(values) and not any(_is_number(v) for v in names):
        return names
    return None


def read_table(path) -> tuple[list[str] | None, np.ndarray, Lines]:
    """(header or None, data (n, m), line number of each row) of a numeric table.

    Raises
    ------
    RecordError
        Naming the file, the row (its line number) and column of the first problem: no data,
        rows of different lengths, a non-numeric or non-finite value, a value beyond
        :data:`MAX_VALUE`.
    """
    _open_check(path)
    header, first, delimiter, values = _head(path)
    data = None
    if first is not None and values is not None:
        width = len(values)
        try:
            data = np.loadtxt(path, delimiter=delimiter, comments="#", skiprows=first - 1,
                              ndmin=2, dtype=np.float64, encoding="utf-8")
        except (ValueError, UnicodeDecodeError):
            data = None
        if data is not None and data.shape[1] != width:
            data = None
    if data is None:
        header, data, lines = _read_slow(path)
        _check_values(path, data, lines)
    else:
        lines = Lines(str(path), first, data.shape[0], delimiter)
        try:
            _check_values(path, data, lines)
        except RecordError:
            # the line-by-line reader names what the fast one only saw as a bad number (a
            # cell past csv's limit, a number beyond the double range)
            header, data, lines = _read_slow(path)
            _check_values(path, data, lines)
    if header is not None and len(header) != data.shape[1]:
        header = None
    return header, data, lines


def _read_slow(path):
    """Line by line: names the row of a problem; empty cells of a column that is empty on
    every row (Klipper's ``shapers:`` separator) are dropped with that column."""
    try:
        with open(path, encoding="utf-8", errors="replace") as fh:
            lines = fh.read().splitlines()
    except OSError as exc:
        raise RecordError(path, f"cannot read the file ({exc.strerror})") from None
    header, rows, numbers, delimiter = None, [], [], None
    for no, line, comment in _data_lines(lines):
        if delimiter is None and not rows:
            delimiter = _sniff(line)
        try:
            values = _split(line, delimiter)
        except csv.Error as exc:     # e.g. a field beyond csv's limit of 131072 characters
            raise RecordError(path, f"cannot split the line into values ({exc})", row=no) from None
        if not rows and header is None and _names_row(values):
            header = values
            continue
        if not rows and header is None:
            header = _comment_header(comment, values, delimiter)
        rows.append(values)
        numbers.append(no)
    if not rows:
        raise RecordError(path, "no data rows (empty file, or only comments and a header)")
    width = len(rows[0])
    empty = [j for j in range(width) if all(len(r) == width and r[j] == "" for r in rows)]
    data = np.empty((len(rows), width))
    for i, (values, no) in enumerate(zip(rows, numbers)):
        if len(values) != width:
            raise RecordError(path, f"{len(values)} values where the first data row has {width}",
                             row=no)
        for j, v in enumerate(values):
            if j in empty:
                data[i, j] = 0.0
                continue
            try:
                data[i, j] = float(v)
            except ValueError:
                raise RecordError(path, f"non-numeric value {_quote(v)}", row=no,
                                 column=j) from None
    if empty:
        keep = [j for j in range(width) if j not in empty]
        data = data[:, keep]
        if header is not None and len(header) == width:
            header = [header[j] for j in keep]
    out = Lines(str(path), numbers[0], len(numbers), delimiter)
    out._map = np.asarray(numbers, dtype=np.int64)
    return header, data, out


def _check_values(path, data, lines) -> None:
    if data.size == 0 or data.shape[0] == 0:
        raise RecordError(path, "no data rows (empty file, or only comments and a header)")
    # the extremes decide both checks without a copy of the table (a 600 s record at 3.2 kHz
    # is 61 MB of float64): any NaN or infinity reaches min or max, and |x| <= MAX_VALUE for
    # every x exactly when both extremes lie within it; the arrays are built only to name a cell
    lo, hi = float(data.min()), float(data.max())
    if not (math.isfinite(lo) and math.isfinite(hi)):
        finite = np.isfinite(data)
        i, j = np.argwhere(~finite)[0]
        raise RecordError(path, f"non-finite value ({float(data[i, j])!r}); remove or repair the row",
                         row=lines[i], column=int(j))
    if max(-lo, hi) > MAX_VALUE:
        big = np.abs(data) > MAX_VALUE
        i, j = np.argwhere(big)[0]
        raise RecordError(path, f"value {float(data[i, j]):.6g} is beyond {MAX_VALUE:g} in "
                         "magnitude (its square would overflow in a spectrum); rescale the "
                         "column", row=lines[i], column=int(j))
