# SPDX-License-Identifier: Apache-2.0
"""``smoothshaper identify``: one mode (wn, zeta) from a CSV record of a free decay."""
from __future__ import annotations

import math
import os

import numpy as np

from .common import CliError, format_table
from .cost import add_options as add_cost_options

__all__ = ["read_record", "first_two_peaks", "cmd_identify", "add_parser"]


def read_record(path: str, column: str | None, time_column: str | None,
                Ts: float | None) -> tuple[np.ndarray, float]:
    """(x, Ts) from a CSV: optional header row (also a '#time,accel_x,...' comment line right
    above the data), comma/semicolon/tab/space separated; errors name the file and row."""
    from ..calibrate.records import read_table
    header, data, rows = read_table(path)

    def index(name, default):
        if name is None:
            return default
        if header is not None and name in header:
            return header.index(name)
        try:
            i = int(name)
        except ValueError:
            raise CliError(f"{path}: no column {name!r}"
                           + (f" (columns: {', '.join(header)})" if header else "")) from None
        if not -data.shape[1] <= i < data.shape[1]:
            raise CliError(f"{path}: column index {i} out of range ({data.shape[1]} columns)")
        return i

    xi = index(column, data.shape[1] - 1)
    x = data[:, xi]
    if Ts is None:
        if data.shape[1] < 2 and time_column is None:
            raise CliError(f"{path}: one column only: give --Ts (the sample period)")
        ti = index(time_column, 0) % data.shape[1]
        t = data[:, ti]
        dt = np.diff(t)
        if dt.size == 0:
            raise CliError(f"{path}: a single data row: a record needs at least two samples")
        bad = np.flatnonzero(~(dt > 0))
        if bad.size:
            i = int(bad[0]) + 1
            raise CliError(f"{path}, row {int(rows[i])}, column {ti}: time {t[i]:.6g} s does "
                           f"not increase (previous {t[i - 1]:.6g} s): time stamps must be "
                           "strictly increasing")
        Ts = float(np.mean(dt))
        if np.max(np.abs(dt - Ts)) > 1e-6 * Ts + 1e-12:
            # jittered time stamps (real accelerometer logs): resample onto a uniform grid
            from scipy.interpolate import CubicSpline
            if np.max(dt) > 5 * Ts:
                i = int(np.argmax(dt)) + 1
                raise CliError(f"{path}, row {int(rows[i])}: a gap of {dt[i - 1]:.6g} s before "
                               f"time {t[i]:.6g} s: the record is not contiguous")
            x = _spline_onto_grid(CubicSpline, t - t[0], x, Ts)
    return x, Ts


#: Samples per piece of the chunked spline, and the knots each piece reaches beyond its ends.
_SPLINE_CHUNK, _SPLINE_PAD = 1 << 16, 64


def _spline_onto_grid(CubicSpline, t, x, Ts):
    """The record's cubic spline through (t, x) at k Ts, in pieces of bounded memory (the whole
    record's spline holds a dozen arrays of its length). A cubic spline's value depends on a
    knot k places away by a factor (2 - sqrt 3)^k (C. de Boor, "A Practical Guide to Splines",
    1978, ch. IV): fitting each piece with 64 knots beyond its ends changes it by 0.27^64, far
    below rounding; the record's own ends keep the spline's end conditions."""
    grid_n = t.size
    out = np.empty(grid_n)
    for a in range(0, grid_n, _SPLINE_CHUNK):
        b = min(grid_n, a + _SPLINE_CHUNK)
        g = np.arange(a, b) * Ts
        lo = max(0, int(np.searchsorted(t, g[0], side="right")) - 1 - _SPLINE_PAD)
        hi = min(t.size, int(np.searchsorted(t, g[-1], side="left")) + 1 + _SPLINE_PAD)
        out[a:b] = CubicSpline(t[lo:hi], x[lo:hi])(g)
    return out


def first_two_peaks(x: np.ndarray, Ts: float) -> tuple[float, float, float, float]:
    """(t1, p1, t2, p2): the first two successive positive maxima of x about its final value
    (the mean of the record's last tenth, so a settled decay with an offset works), each
    refined by a parabola through the sample and its neighbours (peaks of a damped sinusoid
    are exactly one damped period apart, so their spacing and ratio give wd and sigma)."""
    x = x - np.mean(x[-max(1, x.size // 10):])
    i = np.flatnonzero((x[1:-1] > x[:-2]) & (x[1:-1] >= x[2:]) & (x[1:-1] > 0)) + 1
    if i.size < 2:
        raise CliError("the record has fewer than two positive peaks: cannot use --method peaks")
    out = []
    for j in i[:2]:
        a, b, c = x[j - 1], x[j], x[j + 1]
        denom = a - 2 * b + c
        shift = 0.5 * (a - c) / denom if denom != 0 else 0.0
        out += [(j + shift) * Ts, b - 0.25 * (a - c) * shift]
    return tuple(out)


def cmd_identify(args) -> int:
    from .cost import record_cost, start
    from ..filters import identify_from_peaks, identify_from_record
    nbytes = os.path.getsize(args.csv) if os.path.isfile(args.csv) else 0
    bar = start(record_cost("identify", nbytes=nbytes), args, f"a record of {nbytes} bytes")
    if bar is None:
        return 0
    bar.phase("read and fit")
    if args.Ts is not None and not (math.isfinite(args.Ts) and args.Ts > 0):
        raise CliError(f"--Ts must be finite and > 0, got {args.Ts:.3g}")
    x, Ts = read_record(args.csv, args.column, args.time_column, args.Ts)
    if args.start is not None:
        duration = x.size * Ts
        if not (math.isfinite(args.start) and 0 <= args.start < duration):
            raise CliError(f"--start must be a time within the record [0, {duration:.3g}) s, "
                           f"got {args.start:.3g}")
        x = x[int(round(args.start / Ts)):]
    # a sweep or noise must not yield a confident mode: the whole record has to be explained
    # by damped oscillations (calibrate.modes.decay_modes); it also gives the uncertainties
    from ..calibrate.modes import decay_modes
    try:
        fitted, r2 = decay_modes(x, Ts, path=args.csv, column=args.column or "signal")
        if args.method == "peaks":
            t1, p1, t2, p2 = first_two_peaks(x, Ts)
            mode = identify_from_peaks(t1=t1, p1=p1, t2=t2, p2=p2)
        else:
            # a long record at the rate its content needs, as the decay fit above reads it
            from ..calibrate.decay_decimation import fit_rate
            _, xq, q = fit_rate(x, Ts)
            mode = identify_from_record(xq, Ts=q * Ts)
    except (CliError, ValueError) as exc:
        if args.Ts is None:
            raise
        # the record's own time scale was overridden: name the option with the failure
        raise CliError(f"{exc} (with --Ts={args.Ts:.3g})") from None
    if args.method == "peaks":
        print(f"peaks about the final value: ({t1:.6g} s, {p1:.6g}) and ({t2:.6g} s, {p2:.6g})")
    bar.finish()
    print(f"record: {x.size} samples at Ts = {Ts:.6g} s")
    print(format_table(["wn [rad/s]", "zeta", "wd [rad/s]", "sigma [1/s]", "Td [s]"],
                       [[mode.wn, mode.zeta, mode.wd, mode.sigma, 2 * math.pi / mode.wd]]))
    m = fitted[0]
    print(f"whole-record fit (explains {100 * r2:.1f} % of the signal): wn = {m.wn:.6g} +- "
          f"{m.wn_std:.2g} rad/s (f = {m.f_hz:.5g} Hz), zeta = {m.zeta:.4g} +- "
          f"{m.zeta_std:.2g} (1 sd)"
          + (f"; {len(fitted) - 1} further mode(s): see 'smoothshaper calibrate'"
             if len(fitted) > 1 else ""))
    print("suggested stages: "
          f"damped_harmonic:wn={mode.wn:.6g},zeta={mode.zeta:.6g}  "
          f"zv:wn={mode.wn:.6g},zeta={mode.zeta:.6g}")
    return 0


def add_parser(sub) -> None:
    """The ``identify`` subcommand."""
    p = sub.add_parser("identify", help="mode (wn, zeta) from a CSV record of a free decay",
                       description="Estimate the natural frequency wn [rad/s] and damping ratio "
                       "zeta of one mode from a sampled free decay (a CSV with a time column and "
                       "a signal column, or one column with --Ts), and suggest stages that "
                       "cancel it. Example data: examples/decay.csv. For accelerometer sweeps, "
                       "PSD tables and several modes use 'smoothshaper calibrate'.")
    p.add_argument("csv", help="CSV file: a time column and a signal column (header optional)")
    p.add_argument("--column", help="signal column: header name or index (default: last)")
    p.add_argument("--time-column", help="time column: header name or index (default: first)")
    p.add_argument("--Ts", type=float, help="sample period [s] when the file has no time column")
    p.add_argument("--start", type=float, help="ignore samples before this time [s]")
    p.add_argument("--method", choices=("record", "peaks"), default="record",
                   help="record: least-squares fit of the whole decay, any constant offset "
                   "included (default); peaks: two successive peaks, measured about the "
                   "final value (the mean of the record's last tenth)")
    add_cost_options(p)
    p.set_defaults(func=cmd_identify)
