"""What every ``smoothshaper`` subcommand module shares: exit codes, the one-line error, the
argument parser, tables, the progress bar and the matplotlib import. Kept apart from
:mod:`smoothshaper.cli` so subcommand modules import it without importing the CLI (no cycle)."""
from __future__ import annotations

import argparse
import math
import sys

import numpy as np

__all__ = ["EXIT_ERROR", "EXIT_USAGE", "EXIT_UNAVAILABLE", "CliError", "Parser", "format_table",
           "Progress", "pyplot", "numbers", "parse_via_list", "parse_via_points", "write_csv",
           "save_figure"]

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
    """A one-line progress bar on stderr for long sweeps (only when enabled)."""

    def __init__(self, total: int, label: str, enabled: bool):
        self.total, self.label, self.enabled, self.done = max(1, total), label, enabled, 0

    def advance(self, n: int = 1) -> None:
        self.done = min(self.total, self.done + n)
        if self.enabled:
            frac = self.done / self.total
            bar = "#" * int(30 * frac)
            sys.stderr.write(f"\r{self.label} [{bar:<30}] {100 * frac:5.1f}%")
            if self.done == self.total:
                sys.stderr.write("\n")
            sys.stderr.flush()


def pyplot(command: str = "analyze"):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise CliError(f"{command} needs matplotlib: pip install 'smoothshaper[plot]'",
                       EXIT_UNAVAILABLE) from None
    return plt


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


def write_csv(path: str, header: list[str], columns: list[np.ndarray]) -> None:
    """Columns as a CSV with a header row, full precision; CliError naming --csv."""
    data = np.column_stack(columns)
    try:
        np.savetxt(path, data, delimiter=",", header=",".join(header), comments="", fmt="%.17g")
    except OSError as exc:
        raise CliError(f"--csv: cannot write {path}: {exc.strerror}") from None


def save_figure(fig, plt, path: str) -> None:
    """Write a matplotlib figure as PNG (120 dpi) and close it; CliError naming --plot."""
    try:
        fig.savefig(path, dpi=120)
    except OSError as exc:
        raise CliError(f"--plot: cannot write {path}: {exc.strerror}") from None
    finally:
        plt.close(fig)


# -- generator -----------------------------------------------------------------------------
