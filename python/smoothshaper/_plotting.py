# SPDX-License-Identifier: Apache-2.0
"""Scales for percentages of residual vibration, shared by the CLI, the calibration figures
and the report: the levels users compare against (1 %, 5 %, 20 %, 100 %) must stay apart on
every plot, which a linear scale up to the hundreds of percent far off a mode cannot do."""
from __future__ import annotations

import math

import numpy as np

from . import _optional

__all__ = ["PRV_LEVELS", "PRV_CONTOURS", "percent_axis", "prv_map", "difference_map"]

#: Colour band edges of a PRV map [%]: roughly logarithmic, clipped at 200 %.
PRV_LEVELS = (0, 1, 2, 5, 10, 20, 50, 100, 200)
#: Labelled contour lines of a PRV map [%].
PRV_CONTOURS = (1, 5, 20, 100)


def percent_axis(ax, *, top: float = 110.0) -> None:
    """Make the y axis of ``ax`` a residual-vibration axis [%]: linear from 0 to 1 %,
    logarithmic above (symlog), ticks at 0, 1, 2, 5, 10, 20, 50, 100 %..., range 0 to
    ``top``."""
    ticker = _optional.require("matplotlib.ticker", "a residual-vibration axis")
    FixedLocator, FormatStrFormatter, NullLocator = (ticker.FixedLocator, ticker.FormatStrFormatter,
                                                     ticker.NullLocator)
    ax.set_yscale("symlog", linthresh=1.0, linscale=0.6)
    ax.set_ylim(0, top)
    if top <= 2000:
        ticks = [t for t in (0, 1, 2, 5, 10, 20, 50, 100, 200, 500, 1000) if t <= top]
    else:       # far beyond 100 %: decades only, at most about eight labels
        top_decade = int(math.floor(math.log10(top)))
        every = max(1, math.ceil((top_decade - 2) / 6))
        ticks = [0] + [10.0 ** k for k in range(2, top_decade + 1, every)]
    ax.yaxis.set_major_locator(FixedLocator(ticks))
    ax.yaxis.set_minor_locator(NullLocator())
    ax.yaxis.set_major_formatter(FormatStrFormatter("%g"))


def prv_map(ax, x, y, prv, *, label: str = "PRV [%] (clipped at 200 %)"):
    """Filled PRV map on :data:`PRV_LEVELS` bands with labelled :data:`PRV_CONTOURS` lines and
    a colour bar; ``prv[i, j]`` is at ``(x[j], y[i])``. Returns the filled contour set."""
    BoundaryNorm = _optional.require("matplotlib.colors", "PRV contours").BoundaryNorm
    prv = np.asarray(prv, dtype=float)
    levels = list(PRV_LEVELS)
    cs = ax.contourf(x, y, np.minimum(prv, levels[-1]), levels=levels, cmap="viridis",
                     norm=BoundaryNorm(levels, 256))
    ax.figure.colorbar(cs, ax=ax, label=label, ticks=levels)
    if np.nanmin(prv) < PRV_CONTOURS[-1] and np.nanmax(prv) > PRV_CONTOURS[0]:
        lines = ax.contour(x, y, prv, levels=list(PRV_CONTOURS), colors="white",
                           linewidths=0.9)
        ax.clabel(lines, fmt="%g %%", fontsize=8)
    return cs


def difference_map(ax, x, y, d, *, label: str):
    """Filled map of a signed difference of percentages with a diverging colour scale whose
    bands are roughly logarithmic in size (+-1, 2, 5, 10, 20, 50 %), so small and large
    differences are both visible. Returns the filled contour set."""
    BoundaryNorm = _optional.require("matplotlib.colors", "PRV contours").BoundaryNorm
    edges = [1, 2, 5, 10, 20, 50]
    levels = [-e for e in edges[::-1]] + [0] + edges
    d = np.clip(np.asarray(d, dtype=float), -edges[-1], edges[-1])
    cs = ax.contourf(x, y, d, levels=levels, cmap="RdBu", norm=BoundaryNorm(levels, 256))
    ax.figure.colorbar(cs, ax=ax, label=label, ticks=levels)
    return cs
