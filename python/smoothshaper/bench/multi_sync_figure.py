# SPDX-License-Identifier: Apache-2.0
"""The figure of docs/multi-axis.md, "Time, TimeIfNecessary, None": one move of three axes
from a moving start state, once per synchronisation mode, the path of x and y in the plane
and each axis's velocity over time, the arrival of each axis marked.

``python -m smoothshaper.bench.multi_sync_figure PATH`` writes it.
"""
from __future__ import annotations

import sys

import numpy as np

from .. import _optional

__all__ = ["run", "plot"]

# x starts moving away from its target at rest; y's target moves (0.3 unit/s); z, at rest,
# is the slowest axis. time: x and y stretched to z; time_if_necessary: y alone stretched
# (the only moving target); none: each on its own; axis_sync=["time", "none", "time"]: x
# stretched to z, y on its own
LIMITS = dict(vmax=[1.0, 0.6, 0.3], amax=[2.0, 1.5, 1.0], jmax=[10.0, 6.0, 5.0])
START = ([0.0, 0.0, 0.0], [-0.6, 0.0, 0.0], [1.0, 0.0, 0.0])
TARGET = dict(positions=[0.6, 0.5, 1.0], velocities=[0.0, 0.3, 0.0],
              accelerations=[0.0, 0.0, 0.0])
RUNS = (("time", None), ("time_if_necessary", None), ("none", None),
        ("time", ["time", "none", "time"]))
Ts = 1e-3


def run(sync, axis_sync):
    """Samples from the start state to a while after the last arrival: (t, out, arrivals)."""
    from ..multi_axis import MultiAxisGenerator
    g = MultiAxisGenerator(Ts=Ts, sync=sync, **LIMITS)
    g.start(*START, axis_sync=axis_sync, **TARGET)
    arrivals = list(g.axis_arrival)
    n = max(arrivals) + 100
    rows = {k: np.tile(v, (n, 1)) for k, v in TARGET.items()}
    out = g.process_targets(rows["positions"], velocities=rows["velocities"],
                            accelerations=rows["accelerations"], axis_sync=axis_sync)
    first = np.array([[START[0][i], START[1][i], START[2][i], 0.0] for i in range(3)])
    return np.arange(n + 1) * Ts, np.r_[first[None], out], arrivals


def plot(path: str) -> None:
    plt = _optional.pyplot("the multi-axis synchronisation figure")
    fig, axes = plt.subplots(1, 4, figsize=(17, 4.2))
    # wide to narrow, so that runs sharing a curve show as nested lines
    styles = (("C0", 5.0), ("C1", 3.5), ("C2", 2.0), ("C3", 1.0))
    for (sync, axis_sync), (colour, lw) in zip(RUNS, styles):
        t, out, arrivals = run(sync, axis_sync)
        label = sync if axis_sync is None else f"{sync}, axis_sync={axis_sync}"
        end = max(arrivals) + 1   # the path until the last axis has arrived
        axes[0].plot(out[:end, 0, 0], out[:end, 1, 0], colour, lw=lw, label=label)
        for i in range(3):
            axes[1 + i].plot(t, out[:, i, 1], colour, lw=lw, label=label)
            k = arrivals[i]
            axes[1 + i].plot(t[k], out[k, i, 1], "o", color=colour, ms=5)
            if i < 2:
                axes[0].plot(out[k, 0, 0], out[k, 1, 0], "o", color=colour, ms=4)
    axes[0].plot(*START[0][:2], "ks", ms=5, label="start (x moving away)")
    axes[0].plot(*TARGET["positions"][:2], "k*", ms=9, label="target positions (y to arrive "
                 "at 0.3 unit/s and move on)")
    axes[0].set(xlabel="x", ylabel="y", title="path until the last arrival (o: x's or y's)")
    fig.legend(*axes[0].get_legend_handles_labels(), loc="lower center", ncol=6, fontsize=8)
    for i, name in enumerate("xyz"):
        axes[1 + i].set(xlabel="t [s]", ylabel=f"v_{name}", title=f"velocity of {name} "
                        f"(vmax {LIMITS['vmax'][i]}; o: arrival)")
        axes[1 + i].axhline(0, color="0.7", lw=0.5)
    fig.tight_layout(rect=(0, 0.08, 1, 1))
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    plot(sys.argv[1] if len(sys.argv) > 1 else "multi_axis_sync.png")
