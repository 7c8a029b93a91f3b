# SPDX-License-Identifier: Apache-2.0
"""The figure of docs/multi-axis.md, "Position limits": left, the path of a phase-synchronised
staircase of two axes in the plane, retargeted every 300 ms, without limits (each change
blended in mid-motion: the corners are cut) and with qmin, qmax (a change waits for the
arrival and starts from rest: straight segments between points inside the box, the targets
that came and went during a move skipped); right, a Time-synchronised move whose axis y starts moving up
towards a target near qmax and is stretched to x's longer move: without limits its stretched
motion rises past qmax, with them it brakes to rest, rests a sample and moves, still arriving
with x. q over time.

``python -m smoothshaper.bench.multi_position_figure PATH`` writes it.
"""
from __future__ import annotations

import sys

import numpy as np

from .. import _optional
from .profile_axes import finish

__all__ = ["BOX", "STAIRCASE", "phase_run", "time_run", "plot"]

Ts = 1e-3
LIMITS = dict(vmax=[1.0, 2.0], amax=[10.0, 4.0], jmax=[100.0, 50.0])
BOX = ([-0.1, -0.1], [1.0, 0.8])                    # qmin, qmax of x and y
STAIRCASE = ([0.9, 0.1], [0.9, 0.7], [0.1, 0.7], [0.6, 0.3])   # 300 ms each, then held
START = ([0.0, 0.5], [0.0, 1.5], [0.0, 0.0])         # q, v, a of x and y
TARGET = [3.0, 0.9]
TIME_QMAX = 0.95


def phase_run(bounded: bool) -> np.ndarray:
    """(n, 2, 4) of the staircase in phase mode, with or without the box."""
    from ..multi_axis import MultiAxisGenerator
    g = MultiAxisGenerator(Ts=Ts, sync="phase", **LIMITS,
                           **(dict(qmin=BOX[0], qmax=BOX[1]) if bounded else {}))
    rows = np.vstack([np.tile(p, (300, 1)) for p in STAIRCASE] + [np.tile(STAIRCASE[-1],
                                                                          (1500, 1))])
    return g.process(rows)


def time_run(bounded: bool):
    """(t, out) of the Time-synchronised move from START to TARGET."""
    from ..multi_axis import MultiAxisGenerator
    g = MultiAxisGenerator(Ts=Ts, sync="time", **LIMITS,
                           **(dict(qmin=[None, -1.0], qmax=[None, TIME_QMAX]) if bounded
                              else {}))
    g.start(*START, positions=TARGET)
    n = g.arrival + 200
    return np.arange(1, n + 1) * Ts, g.process_targets(np.tile(TARGET, (n, 1)))


def plot(path: str) -> None:
    """Write the figure to ``path`` (PNG)."""
    plt = _optional.require("matplotlib.pyplot", "the multi-axis position-limits figure")
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4.4))
    for bounded, style, label in ((False, "--", "without limits: blended mid-motion"),
                                  (True, "-", "qmin, qmax (box): from rest at each arrival")):
        out = phase_run(bounded)
        left.plot(out[:, 0, 0], out[:, 1, 0], style, lw=1.2, label=label)
    (x0, y0), (x1, y1) = BOX[0], BOX[1]
    left.plot([x0, x1, x1, x0, x0], [y0, y0, y1, y1, y0], color="gray", lw=0.8, ls=":")
    left.plot(*np.array(STAIRCASE).T, "k.", ms=6, label="targets (300 ms each)")
    left.set_xlabel("x [unit]")
    left.set_aspect("equal", adjustable="datalim")
    for bounded, style, label in ((False, "--", "y without limits: stretched, past qmax"),
                                  (True, "-", f"y, qmax = {TIME_QMAX}: brake, rest, move")):
        t, out = time_run(bounded)
        right.plot(t, out[:, 1, 0], style, lw=1.2, label=label)
    right.plot(t, out[:, 0, 0] / 4, ":", lw=1.0, label="x / 4 (the longer move)")
    right.axhline(TIME_QMAX, color="gray", lw=0.8, ls=":")
    right.annotate("qmax of y", (0.05, TIME_QMAX), xytext=(0, 3), textcoords="offset points",
                   fontsize=8, color="gray")
    right.legend(loc="lower right", fontsize=8)
    right.set_title("sync = time from a moving start: y stretched to x's 3.2 s", fontsize=9)
    finish(fig, [left, right], ["y [unit]", "q [unit]"], legend_loc="upper left", path=path,
           title="sync = phase, retargeted every 300 ms (Ts = 1 ms)")


if __name__ == "__main__":
    plot(sys.argv[1] if len(sys.argv) > 1 else "multi_position.png")
