# SPDX-License-Identifier: Apache-2.0
"""The scheduled ZV^n shaper by its definition (the oracle of :class:`ScheduledShaper`).

At every update sample ``n`` (every ``update_every`` samples from the first) the schedule value
``s[n]`` is mapped to a pole by linear interpolation of ``-zeta wn + j wn sqrt(1 - zeta^2)``
between the table's rows (the end rows' outside), and the taps are the reference's exact-timing
shaper (:func:`smoothshaper.reference.shapers.shaper_taps`) of that mode; in between the taps
hold. ``y[n] = x[n] + sum_{i>0} h[i] (x[n-i] - x[n])`` with the input at ``rest`` before its
first sample. It never calls the C code (which designs the taps in closed form).
"""
from __future__ import annotations

import math

import numpy as np

from ..stages import Stage
from ._checks import check_Ts
from .shapers import shaper_taps
from .._checks import finite as _finite, finite_signal as _finite_signal, integer as _integer
from .._checks import real_array as _real_array
from ..errors import ParameterError

__all__ = ["schedule_mode", "scheduled"]


def schedule_mode(table, s: float) -> tuple[float, float]:
    """The mode (wn, zeta) a schedule table maps ``s`` to.

    Parameters
    ----------
    table : array_like, shape (n, 3)
        Rows (value, wn, zeta), values strictly increasing.
    s : float
        The scheduling value.

    Returns
    -------
    tuple of float
        ``(wn, zeta)`` of the pole interpolated linearly between the rows around ``s``.

    Raises
    ------
    ParameterError
        Naming ``table`` (shape) or ``s`` (not finite).
    """
    t = np.asarray(_real_array("table", table), dtype=np.float64)
    if t.ndim != 2 or t.shape[1] != 3 or t.shape[0] < 1:
        raise ParameterError("table", f"table must have rows (value, wn, zeta), got {t.shape}")
    s = _finite("s", s)
    sigma = -t[:, 2] * t[:, 1]
    wd = t[:, 1] * np.sqrt(1.0 - t[:, 2] ** 2)
    sig = float(np.interp(s, t[:, 0], sigma))
    w = float(np.interp(s, t[:, 0], wd))
    wn = math.hypot(sig, w)
    return wn, -sig / wn


def scheduled(kind: str, table, x, schedule, *, Ts: float, order: int = 1,
              update_every: int = 1, rest: float = 0.0, s0: float | None = None) -> np.ndarray:
    """Filter ``x`` through a ZV^n shaper scheduled by ``schedule`` through ``table``.

    Parameters
    ----------
    kind : {"zv", "zvd", "zvdd", "zvn"}
        The shaper.
    table : array_like, shape (n, 3)
        Rows (value, wn [rad/s], zeta).
    x : array_like of float, shape (N,)
        Input samples.
    schedule : array_like of float, shape (N,)
        The scheduling value at every sample.
    Ts : float, keyword-only
        Sample period [s].
    order : int, keyword-only
        n of ZV^n for ``"zvn"``.
    update_every : int, keyword-only
        Update period of the taps [samples] (first update on sample 0).
    rest : float, keyword-only
        The input before ``x[0]``.
    s0 : float or None, keyword-only
        Unused for the output (the first sample updates the taps); accepted for symmetry with
        ``ScheduledShaper.reset``.

    Returns
    -------
    ndarray of float64, shape (N,)
        The output.

    Raises
    ------
    ParameterError
        Naming ``kind``, ``x``, ``schedule``, ``Ts``, ``order``, ``update_every`` or ``rest``.
    """
    if kind not in ("zv", "zvd", "zvdd", "zvn"):
        raise ParameterError("kind", f"kind must be zv, zvd, zvdd or zvn, got {kind!r}")
    Ts = check_Ts(Ts)
    x = _finite_signal("x", x)
    s = np.asarray(_real_array("schedule", schedule), dtype=np.float64)
    if s.shape != x.shape:
        raise ParameterError("schedule", f"schedule must have the shape of x, got {s.shape}")
    every = _integer("update_every", update_every, 1)
    rest = _finite("rest", rest)
    y = np.empty_like(x)
    h = np.ones(1)
    for n in range(x.size):
        if n % every == 0 and math.isfinite(s[n]):
            wn, zeta = schedule_mode(table, s[n])
            stage = Stage(kind, wn=wn, zeta=zeta, order=order if kind == "zvn" else None)
            h = shaper_taps(stage, Ts=Ts)
        i = np.arange(1, h.size)
        past = np.where(n - i >= 0, x[np.maximum(n - i, 0)], rest)
        y[n] = x[n] + float(np.dot(h[1:], past - x[n]))
    return y
