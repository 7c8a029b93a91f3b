# SPDX-License-Identifier: Apache-2.0
"""smoothshaper: exact, drift-free trajectory smoothers and vibration input shapers.

``stages`` describes filters (pure Python); ``Chain`` and the functions from ``filters`` run
the compiled C core (built by ``pip install``); ``reference`` and ``analysis`` are the
independent NumPy implementation and the analysis tools. Submodules load on first use, so
``import smoothshaper as sms; sms.design.kinematic(...)`` works without importing SciPy or
matplotlib up front.

Every invalid argument raises :class:`ParameterError` (a ``ValueError``) whose ``parameter``
attribute names the offending parameter, and whose message starts with that name.
"""
import importlib as _importlib

from .errors import ParameterError
from .stages import (KINDS, Stage, damped_harmonic, exponential, for_mode, harmonic,
                     impulse_shaper, input_smoother, notch, rectangular, shaper)
from .filters import (Chain, Mode, design_for_mode, identify_from_peaks, identify_from_record,
                      notch_pole_zeta_from_bandwidth, si_design, si_insensitivity, si_shaper)
from .tunable import TunableChain
from .scheduled import ScheduledShaper

__all__ = ["KINDS", "Stage", "rectangular", "harmonic", "damped_harmonic", "exponential",
           "shaper", "notch", "input_smoother", "impulse_shaper", "for_mode", "Chain",
           "TunableChain", "ScheduledShaper", "Mode", "ParameterError", "design_for_mode",
           "identify_from_peaks", "identify_from_record", "notch_pole_zeta_from_bandwidth",
           "si_design", "si_insensitivity", "si_shaper"]
__version__ = "0.1.0"

#: Public submodules, imported lazily on attribute access (as SciPy does).
SUBMODULES = ("align", "analysis", "cli", "design", "errors", "filters", "fmi", "multi_axis",
              "plants", "reference", "report", "scheduled", "stages", "trajectory", "tunable",
              "validation")


def __getattr__(name):
    if name in SUBMODULES:
        return _importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(SUBMODULES))
