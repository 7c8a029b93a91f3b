# SPDX-License-Identifier: Apache-2.0
"""The figure of docs/design.md, "Asymmetric limits": a vertical axis that may rise fast but
must come down slowly (vmax = 1, vmin = -0.25 unit/s; amax = 10, amin = -2.5 unit/s^2), up
to 1 and back down to 0.2, against the symmetric limits that would hold the same promise
(+-0.25 unit/s, +-2.5 unit/s^2): q, v, a, j over time with the bounds, each arrival marked.

``python -m smoothshaper.bench.asymmetric_figure PATH`` writes it.
"""
from __future__ import annotations

import sys

import numpy as np

from .. import _optional
from .profile_axes import finish

__all__ = ["LIMITS", "SYMMETRIC", "run", "plot"]

LIMITS = dict(vmax=1.0, amax=10.0, jmax=100.0, vmin=-0.25, amin=-2.5)
# the symmetric limits within which the descent's bounds also hold
SYMMETRIC = dict(vmax=0.25, amax=2.5, jmax=100.0)
TARGETS = (1.0, 0.2)
Ts = 1e-3


def run(limits):
    """(t, out, arrivals): the two moves one after the other, each target held until 0.3 s
    after the output rests on it; arrivals: the first sample resting on each target."""
    from ..trajectory import Generator
    g = Generator(Ts=Ts, **limits)
    blocks, arrivals, n = [], [], 0
    for x in TARGETS:
        first = g.process(np.full(1, x))          # the sample that plans the move
        rest = g.process(np.full(g.arrival + 300, x))
        block = np.vstack([first, rest])
        still = (block[:, 0] == x) & np.all(block[:, 1:] == 0, axis=1)
        arrivals.append(n + int(np.flatnonzero(still)[0]))
        blocks.append(block)
        n += block.shape[0]
    out = np.vstack(blocks)
    return np.arange(out.shape[0]) * Ts, out, arrivals


def plot(path: str) -> None:
    """Write the figure to ``path`` (PNG)."""
    plt = _optional.require("matplotlib.pyplot", "the asymmetric-limits figure")
    fig, axes = plt.subplots(4, 1, sharex=True, figsize=(8, 8))
    names = ("q [unit]", "v [unit/s]", "a [unit/s^2]", "j [unit/s^3]")
    for limits, style, label in ((LIMITS, "-", "asymmetric: v in [-0.25, 1], a in [-2.5, 10]"),
                                 (SYMMETRIC, "--", "symmetric: |v| <= 0.25, |a| <= 2.5")):
        t, out, arrivals = run(limits)
        for i, ax in enumerate(axes):
            line, = ax.plot(t, out[:, i], style, lw=1.2, label=label if i == 0 else None)
            for a in arrivals:
                if i == 0:
                    ax.plot(t[a], out[a, 0], "o", ms=5, mfc="none", color=line.get_color())
    for ax, lo, hi in ((axes[1], LIMITS["vmin"], LIMITS["vmax"]),
                       (axes[2], LIMITS["amin"], LIMITS["amax"]),
                       (axes[3], -LIMITS["jmax"], LIMITS["jmax"])):
        for b in (lo, hi):
            ax.axhline(b, color="gray", lw=0.8, ls=":")
    finish(fig, axes, names, legend_loc="upper right", path=path,
           title="A vertical axis: up fast, down slowly (Ts = 1 ms; circles: at rest on the "
                 "target)")


if __name__ == "__main__":
    plot(sys.argv[1] if len(sys.argv) > 1 else "generator_asymmetric.png")
