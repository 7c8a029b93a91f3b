# SPDX-License-Identifier: Apache-2.0
"""The common finish of the generator figures that stack q, v, a (and j) over time: labels,
grid, legend, title, x label, and the PNG written at the size the docs show."""
from __future__ import annotations

from .. import _optional

__all__ = ["finish"]


def finish(fig, axes, names, *, title: str, legend_loc: str, path: str) -> None:
    """Label ``axes`` (top to bottom) with ``names``, put the legend on the top one at
    ``legend_loc``, title it, write ``fig`` to ``path`` (PNG, 110 dpi) and close it."""
    plt = _optional.require("matplotlib.pyplot", "the generator figures")
    for ax, name in zip(axes, names):
        ax.set_ylabel(name)
        ax.grid(alpha=0.3)
    axes[0].legend(loc=legend_loc, fontsize=8)
    axes[0].set_title(title, fontsize=9)
    axes[-1].set_xlabel("t [s]")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
