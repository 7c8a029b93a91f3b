"""What every ``smoothshaper`` subcommand module shares: exit codes, the one-line error, the
argument parser, tables, the progress bar and the matplotlib import. Kept apart from
:mod:`smoothshaper.cli` so subcommand modules import it without importing the CLI (no cycle)."""
from __future__ import annotations

import argparse
import sys

__all__ = ["EXIT_ERROR", "EXIT_USAGE", "EXIT_UNAVAILABLE", "CliError", "Parser", "format_table",
           "Progress", "pyplot"]

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
