# SPDX-License-Identifier: Apache-2.0
"""Argument checks and the sample-grid rule shared by every reference stage.

The integer test and the rounding are those of ``docs/exact-mode.md``: a ratio ``nu`` is the
integer ``N = round(nu)`` when ``|nu - N| <= 1e-9 * max(1, nu)``; ``round`` is half away from
zero (C ``round``), not Python's half-to-even, so both implementations pick the same sample.
"""
from __future__ import annotations

import math

from ..stages import Stage
from .._checks import positive as _positive
from ..errors import ParameterError

GRID_TOLERANCE = 1e-9

#: Most taps or samples one reference array holds (2**28 float64: 2 GiB), the same limit as the
#: C-backed Chain's delay line; beyond it a ParameterError names the parameter instead of numpy
#: failing in the allocator (or the machine swapping).
MAX_SAMPLES = 1 << 28


def check_samples(parameter: str, n, what: str) -> int:
    """``n`` as an int; ParameterError naming ``parameter`` when it exceeds :data:`MAX_SAMPLES`."""
    if not n <= MAX_SAMPLES:
        try:
            count = f"{float(n):.4g}"
        except OverflowError:     # an int beyond the largest float
            count = f"more than 2^{int(n).bit_length() - 1}"
        raise ParameterError(
            parameter, f"{parameter} out of range: {what} would hold {count} samples, "
            f"more than the limit of {MAX_SAMPLES} (2 GiB of float64)")
    return int(n)


def round_half_up(x: float) -> int:
    """C ``round`` for x >= 0 (ties away from zero)."""
    return int(math.floor(x + 0.5))


def on_grid(nu: float) -> int | None:
    """``round(nu)`` if ``nu`` passes the integer test, else None (also for inf or NaN: the
    caller's sample-count check names the parameter)."""
    if not math.isfinite(nu):
        return None
    n = round_half_up(nu)
    return n if abs(nu - n) <= GRID_TOLERANCE * max(1.0, nu) else None


def check_Ts(Ts) -> float:
    """``Ts`` as a float; ParameterError naming ``Ts`` unless a finite real number > 0."""
    return _positive("Ts", Ts)


def check_stage(stage) -> Stage:
    if not isinstance(stage, Stage):
        raise ParameterError(
            "stage", f"stage must be a smoothshaper.Stage, got {type(stage).__name__}")
    return stage


def as_stage_list(stages) -> list[Stage]:
    """One Stage or a sequence of them, as a non-empty list."""
    if isinstance(stages, Stage):
        return [stages]
    try:
        items = list(stages)
    except TypeError:
        raise ParameterError(
            "stages", f"stages must be a Stage or a sequence of Stage, got {stages!r}") from None
    if not items:
        raise ParameterError("stages", "stages must hold at least one Stage")
    for i, s in enumerate(items):
        if not isinstance(s, Stage):
            raise ParameterError(
                f"stages[{i}]", f"stages[{i}] must be a smoothshaper.Stage, got {type(s).__name__}")
    return items
