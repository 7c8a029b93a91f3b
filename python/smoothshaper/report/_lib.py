"""The few library calls the report makes, in one place (the report computes nothing itself
beyond the closed forms its claims are checked against)."""
from __future__ import annotations

import math

import numpy as np

from ..reference.continuous import continuous_transfer


def mode_pole(wn, zeta):
    """``p = -zeta wn + j wn sqrt(1 - zeta^2)`` (arrays broadcast)."""
    wn = np.asarray(wn, dtype=float)
    zeta = np.asarray(zeta, dtype=float)
    return -zeta * wn + 1j * wn * np.sqrt(1.0 - zeta * zeta)


def transfer(stages, s) -> np.ndarray:
    """Continuous transfer of a chain of stages at complex ``s``."""
    s = np.asarray(s, dtype=complex)
    out = np.ones(s.shape, dtype=complex)
    for st in stages:
        out = out * continuous_transfer(st, s)
    return out


def prv(stages, wn, zeta=0.0) -> np.ndarray:
    """Percent residual vibration of a chain for a step into the mode (wn, zeta):
    ``100 |H(p)|``, the residual oscillation's amplitude over the unfiltered step's at the
    same instant once the filter has finished (seed 003 footnote 2, SPEC 6)."""
    return 100.0 * np.abs(transfer(stages, mode_pole(wn, zeta)))


def band_around(x: np.ndarray, y: np.ndarray, level: float, x0: float = 1.0):
    """Edges ``(lo, hi)`` of the contiguous run of ``y <= level`` containing the grid point
    nearest ``x0``, refined by linear interpolation (``hi = inf`` if the run reaches the end)."""
    ok = y <= level
    i0 = int(np.argmin(np.abs(x - x0)))
    if not ok[i0]:
        raise ValueError(f"level {level} is not met at x0 = {x0}")
    lo = i0
    while lo > 0 and ok[lo - 1]:
        lo -= 1
    hi = i0
    while hi < len(x) - 1 and ok[hi + 1]:
        hi += 1

    def cross(i, j):  # y[i] <= level < y[j]
        return x[i] + (level - y[i]) * (x[j] - x[i]) / (y[j] - y[i])

    left = x[0] if lo == 0 else cross(lo, lo - 1)
    right = math.inf if hi == len(x) - 1 else cross(hi, hi + 1)
    return left, right
