# SPDX-License-Identifier: Apache-2.0
"""Shared plotting for the report: one style, labelled axes with units, a legend, PNG out.

Matplotlib is imported lazily with the non-interactive Agg backend so that computing a
section's numbers (what the tests do) never needs a display or matplotlib at all.
"""
from __future__ import annotations

from contextlib import contextmanager
from pathlib import Path

from .. import _optional
from .claims import Figure

__all__ = ["COLORS", "figure", "surface"]

#: Colours by filter family, so one family looks the same in every figure.
COLORS = {
    "harmonic": "k", "rectangular": "tab:red", "rect_chain": "tab:blue",
    "damped_harmonic": "tab:purple", "exponential": "tab:orange", "zv": "tab:green",
    "zvd": "tab:olive", "zvdd": "tab:cyan", "zvddd": "tab:brown", "ei": "tab:pink",
    "ei2": "tab:gray", "mzv": "tab:blue", "plant": "0.5",
}


def _pyplot():
    return _optional.pyplot("smoothshaper report (its figures)")


@contextmanager
def figure(path: Path, caption: str, out: list, *, nrows: int = 1, ncols: int = 1,
           size: tuple[float, float] = (7.0, 4.0), **kw):
    """Yield (fig, axes); on exit save ``path`` (PNG, 120 dpi) and append a Figure to ``out``.

    Every axes drawn inside must have labelled axes; a legend is added to each axes that has
    labelled artists and no legend yet.
    """
    plt = _pyplot()
    fig, axes = plt.subplots(nrows, ncols, figsize=size, squeeze=False, **kw)
    try:
        yield fig, (axes[0, 0] if nrows * ncols == 1 else axes.ravel())
        for ax in axes.ravel():
            if not ax.has_data():
                continue
            if not ax.get_xlabel() or not ax.get_ylabel():
                raise ValueError(f"{path.name}: every plot needs x and y labels with units")
            handles, labels = ax.get_legend_handles_labels()
            if ax.get_legend() is None and any(not lb.startswith("_") for lb in labels):
                ax.legend(fontsize=8)
            ax.grid(True, alpha=0.3)
        fig.tight_layout()
        path.parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(path, dpi=120)
        out.append(Figure(path=path, caption=caption))
    finally:
        plt.close(fig)


def surface(ax, x, y, z, *, levels, cmap="viridis", label: str = ""):
    """Filled contour map with a colour bar (readable in a PNG, unlike a 3-D mesh)."""
    cs = ax.contourf(x, y, z, levels=levels, cmap=cmap, extend="max")
    cb = ax.figure.colorbar(cs, ax=ax)
    if label:
        cb.set_label(label)
    return cs
