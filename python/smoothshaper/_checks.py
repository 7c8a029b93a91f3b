"""Argument checks shared by every public function: each raises ValueError naming the
parameter, so callers get the same message for the same mistake everywhere."""
from __future__ import annotations

import math

import numpy as np


def finite(name: str, value) -> float:
    """``value`` as a float; ValueError naming ``name`` unless it is a finite real number."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number, got {value!r}") from None
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite, got {v!r}")
    return v


def positive(name: str, value) -> float:
    """A finite real number > 0."""
    v = finite(name, value)
    if v <= 0:
        raise ValueError(f"{name} must be > 0, got {v!r}")
    return v


def nonnegative(name: str, value) -> float:
    """A finite real number >= 0."""
    v = finite(name, value)
    if v < 0:
        raise ValueError(f"{name} must be >= 0, got {v!r}")
    return v


def finite_signal(name: str, values) -> np.ndarray:
    """A one-dimensional float64 array of finite values."""
    try:
        x = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be an array of real numbers") from None
    if x.ndim != 1:
        raise ValueError(f"{name} must be one-dimensional, got shape {x.shape}")
    bad = np.flatnonzero(~np.isfinite(x))
    if bad.size:
        raise ValueError(f"{name} must be finite: {name}[{bad[0]}] = {x[bad[0]]!r}")
    return x
