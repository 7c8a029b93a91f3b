"""smoothshaper: exact, drift-free trajectory smoothers and vibration input shapers.

``stages`` describes filters (pure Python); ``Chain`` and the functions from ``filters`` run
the compiled C core (built by ``pip install``); ``reference`` and ``analysis`` are the
independent NumPy implementation and the analysis tools.
"""
from .stages import (KINDS, Stage, damped_harmonic, exponential, for_mode, harmonic, notch,
                     rectangular, shaper)
from .filters import (Chain, Mode, ParameterError, design_for_mode, identify_from_peaks,
                      identify_from_record, notch_pole_zeta_from_bandwidth)

__all__ = ["KINDS", "Stage", "rectangular", "harmonic", "damped_harmonic", "exponential",
           "shaper", "notch", "for_mode", "Chain", "Mode", "ParameterError", "design_for_mode",
           "identify_from_peaks", "identify_from_record", "notch_pole_zeta_from_bandwidth"]
__version__ = "0.1.0"
