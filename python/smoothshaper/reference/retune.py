# SPDX-License-Identifier: Apache-2.0
"""A stage retuned while it runs, by its definition (the oracle of :class:`TunableChain`).

Every input increment ``dx[k] = x[k] - x[k-1]`` is filtered by the stage that was active when
it arrived (docs/retune.md): with ``s_j`` the step response of stage ``j`` and ``a(k)`` the
stage active at sample ``k``,

    y[n] = rest + sum_k s_{a(k)}[n - k] dx[k].

Computed here in the equivalent form ``y[n] = x[n] - sum_k r_{a(k)}[n - k] dx[k]`` with
``r = 1 - s`` (zero after a FIR stage's length), one convolution per stage. It never calls the
C code and knows nothing of how the C core realises a switch (two slots, a fading old filter):
the tests compare the two.
"""
from __future__ import annotations

import numpy as np

from ..stages import NOTCHES, Stage
from ._checks import as_stage_list, check_Ts
from .filtering import impulse_response
from .._checks import finite as _finite, finite_signal as _finite_signal, integer as _integer
from ..errors import ParameterError


def _remaining_step(stage: Stage, n: int, Ts: float) -> np.ndarray:
    """``r[m] = 1 - s[m]``: what of a unit step has not yet come out, ``m = 0 ..``; for a FIR
    stage of length L only ``m < L - 1`` (it is 0 after: unit DC gain), for a notch ``m < n``."""
    if stage.kind in NOTCHES:
        return 1.0 - np.cumsum(impulse_response(stage, Ts=Ts, length=n))
    h = impulse_response(stage, Ts=Ts)
    return 1.0 - np.cumsum(h[:-1])


def switched(stages, x, *, Ts: float, switch_at=(), rest: float = 0.0) -> np.ndarray:
    """Filter ``x`` through one stage whose configuration changes at the given samples.

    Parameters
    ----------
    stages : Stage or sequence of Stage
        The configurations in the order they become active: ``stages[0]`` from the start,
        ``stages[j]`` for the increments from sample ``switch_at[j-1]`` on.
    x : array_like of float, shape (n,)
        Input samples, finite.
    Ts : float, keyword-only
        Sample period [s], > 0.
    switch_at : sequence of int, keyword-only
        ``len(stages) - 1`` strictly increasing sample indices in ``[0, n]``: the first sample
        filtered by the next configuration.
    rest : float, keyword-only
        The value the input rested at before ``x[0]`` (default 0): ``dx[0] = x[0] - rest``.

    Returns
    -------
    ndarray of float64, shape (n,)
        ``y[n] = rest + sum_k s_{a(k)}[n-k] dx[k]``.

    Raises
    ------
    ParameterError
        Naming ``x``, ``Ts``, ``rest``, ``switch_at`` (wrong count, not increasing, outside
        ``[0, n]``) or a stage parameter invalid at ``Ts``.
    """
    stages = as_stage_list(stages)
    Ts = check_Ts(Ts)
    x = _finite_signal("x", x)
    rest = _finite("rest", rest)
    try:
        at = [_integer("switch_at", s, 0) for s in switch_at]
    except TypeError:
        raise ParameterError("switch_at", "switch_at must be a sequence of sample indices") \
            from None
    if len(at) != len(stages) - 1:
        raise ParameterError("switch_at", f"switch_at must hold len(stages) - 1 = "
                                          f"{len(stages) - 1} indices, got {len(at)}")
    if any(b <= a for a, b in zip(at, at[1:])) or any(s > x.size for s in at):
        raise ParameterError("switch_at", f"switch_at must increase strictly within [0, "
                                          f"{x.size}], got {at}")
    n = x.size
    dx = np.diff(x, prepend=rest)
    bounds = [0, *at, n]
    y = x.copy()
    for j, stage in enumerate(stages):
        lo, hi = bounds[j], bounds[j + 1]
        r = _remaining_step(stage, n, Ts)
        if hi > lo:
            part = np.zeros(n)
            part[lo:hi] = dx[lo:hi]
            if r.size:
                y -= np.convolve(part, r)[:n]
    return y


__all__ = ["switched"]
