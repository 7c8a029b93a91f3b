# SPDX-License-Identifier: Apache-2.0
"""The optional dependencies and the extra that installs each.

``pip install smoothshaper`` brings NumPy, SciPy and cffi: the filters, designs, generators,
analysis, plants, servo loop and calibration. Figures, the FMU tooling and the benchmark's
comparison need more; every place that imports such a package goes through :func:`require`,
so a missing one fails with a message naming the extra to install
(``pip install 'smoothshaper[plot]'``), and the command line exits with 3 ("not available in
this installation") instead of showing a traceback.
"""
from __future__ import annotations

import importlib

__all__ = ["EXTRAS", "MissingDependency", "missing", "explain", "require", "require_all", "pyplot"]

#: Importable top-level module -> (distribution name on PyPI, the extra that installs it).
EXTRAS = {
    "matplotlib": ("matplotlib", "plot"),
    "fmpy": ("fmpy", "validate"),
    "libcosimpy": ("libcosimpy", "validate"),
    "fmu_manipulation_toolbox": ("fmu-manipulation-toolbox", "validate"),
    "ruckig": ("ruckig", "bench"),
}


class MissingDependency(ModuleNotFoundError):
    """An optional package is not installed; the message names the extra that installs it.
    ``name`` is the missing top-level module (as for every ModuleNotFoundError)."""


def missing(module: str, purpose: str) -> MissingDependency:
    """The error for ``module`` (a key of :data:`EXTRAS`) missing when ``purpose`` needs it."""
    top = module.split(".")[0]
    dist, extra = EXTRAS[top]
    return MissingDependency(f"{purpose} needs the Python package {dist!r}, which is not "
                             f"installed: pip install 'smoothshaper[{extra}]'", name=top)


def explain(exc: ModuleNotFoundError, purpose: str) -> MissingDependency | None:
    """``exc`` as a :class:`MissingDependency` naming the extra, if the module it did not find
    is an optional dependency (a key of :data:`EXTRAS`); else None (a broken installation)."""
    if isinstance(exc, MissingDependency):
        return exc
    top = (exc.name or "").split(".")[0]
    return missing(top, purpose) if top in EXTRAS else None


def require(module: str, purpose: str):
    """Import ``module`` (``"fmpy"``, ``"libcosimpy.CosimExecution"``) and return it.

    Parameters
    ----------
    module : str
        Dotted module name whose top level is a key of :data:`EXTRAS`.
    purpose : str
        What needs it, for the message (``"smoothshaper validate"``).

    Returns
    -------
    module
        The imported module.

    Raises
    ------
    MissingDependency
        (a ModuleNotFoundError) when the package is not installed, naming the extra.
    """
    top = module.split(".")[0]
    if top not in EXTRAS:
        raise KeyError(f"{top!r} is not an optional dependency of smoothshaper")
    try:
        return importlib.import_module(module)
    except ModuleNotFoundError as exc:
        if (exc.name or "").split(".")[0] != top:
            raise                   # the package is there but broken: show the real error
        raise missing(module, purpose) from None


def require_all(modules, purpose: str) -> None:
    """:func:`require` each of ``modules``: a campaign checks everything it will need before
    it starts, so a missing package is named at once, not after minutes of work."""
    for module in modules:
        require(module, purpose)


def pyplot(purpose: str):
    """``matplotlib.pyplot`` on the non-interactive Agg backend (figures go to files).

    Raises
    ------
    MissingDependency
        matplotlib is not installed (extra ``plot``).
    """
    matplotlib = require("matplotlib", purpose)
    matplotlib.use("Agg")
    return importlib.import_module("matplotlib.pyplot")
