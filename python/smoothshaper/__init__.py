"""smoothshaper: exact, drift-free trajectory smoothers and vibration input shapers."""
from .stages import (KINDS, Stage, damped_harmonic, exponential, for_mode, harmonic, notch,
                     rectangular, shaper)

__all__ = ["KINDS", "Stage", "rectangular", "harmonic", "damped_harmonic", "exponential",
           "shaper", "notch", "for_mode"]
__version__ = "0.1.0"
