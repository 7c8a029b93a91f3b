# SPDX-License-Identifier: Apache-2.0
"""Shaper impulses remembered per stage, for the tuning loop.

The tuning loop asks a design's impulses twice (its length, then its residuals), and the
length of a ZV^n asked for its ZV's through a new Stage, validated again. A Stage is
frozen and validated where it is built, and its impulses depend on its fields alone, so equal
stages share one computation (the same arrays: read-only here).
"""
from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from ..reference.input_smoothers import _transfer, smoother_kernel
from ..reference.shapers import _pole, impulses_unchecked

__all__ = ["impulses", "kernel", "smoother_R", "zv_span"]

#: The second ask follows the first within one design: a short memory is enough (a few
#: thousand designs' arrays would be held for nothing).
_SIZE = 64


@lru_cache(maxsize=_SIZE)
def impulses(stage):
    """(amplitudes, times [s]) of a shaper Stage, as ``reference.shaper_impulses`` gives them
    (read-only arrays)."""
    A, t = impulses_unchecked(stage)
    A.setflags(write=False)
    t.setflags(write=False)
    return A, t


@lru_cache(maxsize=_SIZE)
def kernel(stage):
    """``smoother_kernel`` of an input smoother Stage, remembered as :func:`impulses` is (the
    tuning loop asks it for the length, then for the transfer)."""
    q, T = smoother_kernel(stage)
    q.setflags(write=False)
    return q, T


def smoother_R(stage, poles):
    """``smoother_transfer(stage, poles)`` from the remembered kernel (the same floats)."""
    q, T = kernel(stage)
    return _transfer(q, np.asarray(poles, dtype=complex) * T)


def zv_span(stage) -> float:
    """Time [s] of the last impulse of the ZV at a shaper Stage's mode: half a damped period,
    computed as the ZV's design computes it (the same float), without building that Stage."""
    return 0.5 * (2.0 * math.pi / _pole(stage.wn, stage.zeta).imag)
