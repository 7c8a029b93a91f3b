# SPDX-License-Identifier: Apache-2.0
"""What every ``smoothshaper`` subcommand module shares: exit codes, the one-line error, the
argument parser, tables, the progress bar and the matplotlib import. Kept apart from the
package's entry point (:mod:`smoothshaper.cli`, which imports every subcommand module) so that
they import it without a cycle."""
from __future__ import annotations

import argparse
import math
import sys

import numpy as np

from .. import _optional

__all__ = ["EXIT_ERROR", "EXIT_USAGE", "EXIT_UNAVAILABLE", "CliError", "Parser", "format_table",
           "run_samples", "Progress", "pyplot", "numbers", "parse_via_list", "parse_via_points", "write_csv", "write_outputs",
           "save_figure", "decimate"]

EXIT_ERROR = 1
EXIT_USAGE = 2
EXIT_UNAVAILABLE = 3


class CliError(Exception):
    """A user error: printed as one line, exit code ``code``."""

    def __init__(self, message: str, code: int = EXIT_ERROR):
        super().__init__(message)
        self.code = code


class Parser(argparse.ArgumentParser):
    """argparse that reports usage errors as one line (no usage dump)."""

    def error(self, message):
        raise CliError(f"{self.prog}: {message} (see --help)", EXIT_USAGE)


def _fmt(value) -> str:
    if value is None:
        return "-"
    if isinstance(value, float):
        return f"{value:.6g}"
    return str(value)


def format_table(header: list[str], rows: list[list]) -> str:
    cells = [header] + [[_fmt(v) for v in row] for row in rows]
    widths = [max(len(r[i]) for r in cells) for i in range(len(header))]
    lines = ["  ".join(c.rjust(w) for c, w in zip(row, widths)) for row in cells]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join(lines)


class Progress:
    """A one-line progress bar on stderr (drawn only when ``enabled``).

    Plain use: ``Progress(total, label, enabled)`` and ``advance(n)`` units at a time.
    Phased use (:meth:`phased`): one bar over every phase of a request, each phase weighted by
    its modelled seconds (:class:`smoothshaper.cli.cost.Cost`), so the bar covers the whole
    work and moves at a steady pace; :meth:`phase` starts the next phase with its own unit
    count and :meth:`finish` draws 100 %.
    """

    def __init__(self, total: float, label: str, enabled: bool, stream=None):
        self.total, self.label, self.enabled, self.done = max(1, total), label, enabled, 0
        self.stream = sys.stderr if stream is None else stream
        self._weights: dict = {}
        self._base = 0.0            # fraction of the bar covered by finished phases
        self._span = 1.0            # fraction the current phase covers
        self._shown = None

    @classmethod
    def phased(cls, cost, enabled: bool, stream=None) -> "Progress":
        """One bar over the phases of ``cost`` (a :class:`smoothshaper.cli.cost.Cost`)."""
        bar = cls(1, cost.what, enabled, stream)
        total = cost.seconds or 1.0
        bar._weights = {name: sec / total for name, sec in cost.phases.items()}
        bar._span = 0.0
        return bar

    def phase(self, name: str, units: float = 1) -> None:
        """Start phase ``name`` (a key of the cost's phases) made of ``units`` units."""
        self._base = min(1.0, self._base + self._span)
        self._span = self._weights.get(name, 0.0)
        self.label, self.total, self.done = name, max(1, units), 0
        self._draw()

    def advance(self, n: float = 1) -> None:
        """Mark ``n`` more units of the current phase done."""
        self.done = min(self.total, self.done + n)
        self._draw()

    def finish(self) -> None:
        """Draw 100 % and end the line."""
        self._base, self._span, self.done, self._shown = 1.0, 0.0, self.total, None
        self._draw()

    @property
    def fraction(self) -> float:
        """Fraction of the whole request done (0 to 1)."""
        if not self._weights:
            return self.done / self.total
        return min(1.0, self._base + self._span * self.done / self.total)

    def _draw(self) -> None:
        if not self.enabled:
            return
        frac = self.fraction
        permille = int(1000 * frac)
        if (self.label, permille) == self._shown:
            return
        self._shown = (self.label, permille)
        bar = "#" * int(30 * frac)
        self.stream.write(f"\r{self.label:<14} [{bar:<30}] {100 * frac:5.1f}%")
        if permille >= 1000 and (not self._weights or self._base >= 1.0):
            self.stream.write("\n")
        self.stream.flush()


def pyplot(command: str = "analyze"):
    """matplotlib.pyplot (Agg); CliError with exit 3 naming the extra when it is missing."""
    try:
        return _optional.pyplot(f"smoothshaper {command} (its figures)")
    except _optional.MissingDependency as exc:
        raise CliError(str(exc), EXIT_UNAVAILABLE) from None


def numbers(option: str, text: str) -> list[float]:
    """'1,2,-3' -> [1.0, 2.0, -3.0]; CliError naming ``option`` otherwise."""
    items = [s.strip() for s in text.split(",")]
    try:
        values = [float(s) for s in items]
    except ValueError:
        raise CliError(f"{option} must be comma-separated numbers, got {text!r}") from None
    bad = [v for v in values if not math.isfinite(v)]
    if bad:
        raise CliError(f"{option} must be finite, got {bad[0]!r}")
    return values


def run_samples(terms, Ts: float, limit: int, extra: int = 0) -> int:
    """Samples a run needs (an upper bound), or CliError naming the option that makes it long.

    ``terms`` are (option, seconds, advice) triples whose sum bounds the run's duration: a
    via-point's move (``"--via point 2 (1e+300)"``), the holds, the limits' rise times. When
    the whole run would fit ``limit`` samples at Ts = 1 ms, the sample period is what is
    extreme and ``--Ts`` is named; else the largest term. O(len(terms)), numbers as %.3g.
    """
    total = math.fsum(t[1] for t in terms)
    samples = total / Ts + extra
    if samples <= limit:
        return int(math.ceil(samples))
    if total / 1e-3 <= limit:
        option, advice = f"--Ts={Ts:.3g}", "use a larger --Ts"
    else:
        option, _, advice = max(terms, key=lambda t: t[1])
    raise CliError(f"{option}: the run would take about {total:.3g} s = {samples:.3g} samples "
                   f"of Ts = {Ts:.3g} s, more than the {limit:.3g} a run may hold; {advice}")


def parse_via_list(text: str) -> np.ndarray:
    """``--via`` of the generator: '0,20,40' -> array of at least two positions."""
    via = np.array(numbers("--via", text))
    if via.size < 2:
        raise CliError("--via needs at least two points: the start and one target")
    return via


def parse_via_points(text: str, max_axes: int = 3) -> np.ndarray:
    """``--via`` of the B-spline (and of multi-axis via-points): 'x,y;x,y;...' -> (M, axes)
    with M >= 2, 1 <= axes <= max_axes."""
    rows = [r for r in (part.strip() for part in text.split(";")) if r]
    points = [numbers("--via", r) for r in rows]
    if len(points) < 2:
        raise CliError("--via needs at least two points separated by ';'")
    axes = len(points[0])
    if any(len(p) != axes for p in points):
        raise CliError("--via: every point must have the same number of coordinates, got "
                       + ", ".join(str(len(p)) for p in points))
    if not 1 <= axes <= max_axes:
        raise CliError(f"--via: points must have 1 to {max_axes} coordinates (axes), got {axes}")
    return np.array(points)


def write_csv(path: str, header: list[str], columns: list[np.ndarray], progress=None) -> None:
    """Columns as a CSV with a header row, full precision; CliError naming --csv.
    ``progress``: None or callable(rows) after every block of rows written."""
    data = np.column_stack(columns)
    block = 100_000
    try:
        with open(path, "w", encoding="ascii") as fh:
            fh.write(",".join(header) + "\n")
            for start in range(0, data.shape[0], block):
                np.savetxt(fh, data[start:start + block], delimiter=",", fmt="%.17g")
                if progress is not None:
                    progress(min(block, data.shape[0] - start))
    except OSError as exc:
        raise CliError(f"--csv: cannot write {path}: {exc.strerror}") from None


def write_outputs(args, bar, columns, draw) -> None:
    """The common end of a trajectory run: the CSV of ``columns()`` (header, list of arrays)
    with ``--csv``, the figure ``draw(path)`` with ``--plot``, each a phase of ``bar``; then
    the bar finished and the files written named on stdout."""
    if args.csv:
        header, cols = columns()
        bar.phase("csv", cols[0].size)
        write_csv(args.csv, header, cols, progress=bar.advance)
    if args.plot:
        bar.phase("plot")
        draw(args.plot)
    bar.finish()
    if args.csv:
        print(f"csv: {args.csv}")
    if args.plot:
        print(f"plot: {args.plot}")


def decimate(t: np.ndarray, y: np.ndarray, points: int) -> tuple[np.ndarray, np.ndarray]:
    """At most about ``points`` samples of ``(t, y)`` for a line plot: the minimum and the
    maximum of each bin in time order, so peaks and steps stay visible (matplotlib would take
    minutes and gigabytes for a 1e7-sample line)."""
    y = np.asarray(y)
    if y.size <= points:
        return t, y
    edges = np.linspace(0, y.size, points // 2 + 1).astype(np.int64)
    i_lo = np.array([a + np.argmin(y[a:b]) for a, b in zip(edges[:-1], edges[1:])])
    i_hi = np.array([a + np.argmax(y[a:b]) for a, b in zip(edges[:-1], edges[1:])])
    idx = np.unique(np.r_[0, i_lo, i_hi, y.size - 1])
    return t[idx], y[idx]


def save_figure(fig, plt, path: str) -> None:
    """Write a matplotlib figure as PNG (120 dpi) and close it; CliError naming --plot."""
    try:
        fig.savefig(path, dpi=120)
    except OSError as exc:
        raise CliError(f"--plot: cannot write {path}: {exc.strerror}") from None
    finally:
        plt.close(fig)


# -- generator -----------------------------------------------------------------------------
