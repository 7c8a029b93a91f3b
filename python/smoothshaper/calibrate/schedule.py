# SPDX-License-Identifier: Apache-2.0
"""A schedule table for :class:`smoothshaper.ScheduledShaper` from several records, one per
point (a position along the travel, a payload): each record is calibrated through
:func:`smoothshaper.calibrate.run`, and its dominant mode (the largest share of the measured
vibration energy) becomes the row (value, wn, zeta) of that point (docs/scheduled.md)."""
from __future__ import annotations

import math

import numpy as np

from .._checks import real_array as _real_array
from ..errors import ParameterError

__all__ = ["schedule_table", "format_table"]


def schedule_table(paths, values, *, axis: str = "x", kind: str = "auto",
                   band=None) -> np.ndarray:
    """The schedule table of a mode measured at several points.

    Parameters
    ----------
    paths : sequence of str
        One CSV record per point (any record :func:`smoothshaper.calibrate.run` reads).
    values : sequence of float
        The scheduling value of each record (its position, load, ...), finite and distinct.
    axis : str, keyword-only
        The column the mode is measured on (``"x"``, ``"y"``, ``"z"``, default ``"x"``).
    kind : {"auto", "raw", "decay", "psd", "frf"}, keyword-only
        Record kind, as for :func:`smoothshaper.calibrate.run`.
    band : (float, float) or None, keyword-only
        Frequency band to search [Hz] (default: as :func:`smoothshaper.calibrate.run`).

    Returns
    -------
    ndarray of float64, shape (n, 3)
        Rows (value, wn [rad/s], zeta), sorted by value, for ``ScheduledShaper(kind, table)``.

    Raises
    ------
    ParameterError
        Naming ``values`` (not one per record, not finite, repeated) or ``paths`` (empty, or
        a record in which the axis has no mode, naming the file).
    RecordError
        From reading a record (naming the file, row or column).
    """
    from . import run
    paths = list(paths)
    v = np.asarray(_real_array("values", values), dtype=np.float64).ravel()
    if not paths:
        raise ParameterError("paths", "paths must name at least one record")
    if v.size != len(paths):
        raise ParameterError("values", f"values must give one scheduling value per record "
                             f"({len(paths)}), got {v.size}")
    if not np.all(np.isfinite(v)) or np.unique(v).size != v.size:
        raise ParameterError("values", f"values must be finite and distinct, got {v.tolist()}")
    rows = []
    for path, value in zip(paths, v):
        cal = run([path], kind=kind, axis=axis, band=band)
        modes = [m for a in cal.axes for m in a.modes]
        if not modes:
            raise ParameterError("paths", f"paths: {path} has no mode on axis {axis!r} "
                                 "(nothing to schedule from)")
        dominant = max(modes, key=lambda m: m.weight)
        rows.append((float(value), float(dominant.wn), float(dominant.zeta)))
    rows.sort()
    table = np.array(rows)
    if not np.all(np.isfinite(table)) or not all(0 <= z < 1 for z in table[:, 2]):
        raise ParameterError("paths", "paths: a record gave a mode outside 0 <= zeta < 1")
    return table


def format_table(table: np.ndarray) -> str:
    """The table as aligned text.

    Parameters
    ----------
    table : ndarray of float64, shape (n, 3)
        Rows (value, wn [rad/s], zeta).

    Returns
    -------
    str
        A heading and one line per row: value, wn [rad/s], f [Hz], zeta.
    """
    lines = ["schedule table (value, wn [rad/s], f [Hz], zeta):"]
    for value, wn, zeta in table:
        lines.append(f"  {value:12.6g} {wn:12.6g} {wn / (2 * math.pi):10.4g} {zeta:8.4g}")
    return "\n".join(lines) + "\n"
