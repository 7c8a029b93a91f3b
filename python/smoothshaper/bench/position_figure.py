# SPDX-License-Identifier: Apache-2.0
"""The figure of docs/design.md, "Position limits": a move upwards retargeted 0.11 below
with a minimum duration of 1 s, whose stretched motion first rises past qmax = 0.22; with the
limits the generator brakes to rest, waits for the sample and moves, arriving on the same
sample. q, v, a over time, without and with the limits.

``python -m smoothshaper.bench.position_figure PATH`` writes it.
"""
from __future__ import annotations

import sys

import numpy as np

from .. import _optional
from .profile_axes import finish

__all__ = ["LIMITS", "QMAX", "run", "plot"]

LIMITS = dict(vmax=1.0, amax=10.0, jmax=100.0)
QMAX = 0.22
Ts = 1e-3
# the start (q, v, a), its first target and the samples until the retarget
START = (0.18, -0.09, 8.9, -0.28, 44)
RETARGET = (0.09, 1.0)            # position, minimum duration [s]


def run(bounded: bool):
    """(t, out): the run from START, retargeted after its samples, 1.3 s in all."""
    from ..trajectory import Generator
    q, v, a, first, k = START
    g = Generator(Ts=Ts, **LIMITS, **(dict(qmin=-1.0, qmax=QMAX) if bounded else {}))
    g.start_from(q, v, a, target=first)
    n = 1300
    x = np.r_[np.full(k, first), np.full(n - k, RETARGET[0])]
    m = np.r_[np.zeros(k), np.full(n - k, RETARGET[1])]
    return np.arange(n) * Ts, g.process(x, minimum_duration=m)


def plot(path: str) -> None:
    """Write the figure to ``path`` (PNG)."""
    plt = _optional.require("matplotlib.pyplot", "the position-limits figure")
    fig, axes = plt.subplots(3, 1, sharex=True, figsize=(8, 6.5))
    names = ("q [unit]", "v [unit/s]", "a [unit/s^2]")
    for bounded, style, label in ((False, "--", "without limits: the stretched motion"),
                                  (True, "-", f"qmax = {QMAX}: brake to rest, then move")):
        t, out = run(bounded)
        for i, ax in enumerate(axes):
            ax.plot(t, out[:, i], style, lw=1.2, label=label if i == 0 else None)
    axes[0].axhline(QMAX, color="gray", lw=0.8, ls=":")
    axes[0].annotate("qmax", (1.25, QMAX), xytext=(0, 3), textcoords="offset points",
                     fontsize=8, color="gray")
    for ax in axes:
        ax.axvline(START[4] * Ts, color="gray", lw=0.6, ls="-.")
    finish(fig, axes, names, legend_loc="lower left", path=path,
           title="Retarget at 44 ms to 0.09 with a minimum duration of 1 s (Ts = 1 ms; both "
                 "arrive at 1.044 s)")


if __name__ == "__main__":
    plot(sys.argv[1] if len(sys.argv) > 1 else "generator_position.png")
