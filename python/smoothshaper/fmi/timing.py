# SPDX-License-Identifier: Apache-2.0
"""What an FMU reports at the communication points, from the NumPy reference.

Co-simulation output timing (what the comparison accounts for). fmpy sets the inputs at the
communication point t_k, calls ``doStep(t_k, h)`` and records the outputs at t_{k+1}. The FMU
runs internal ticks at n*Ts (n = 1, 2, ...); a doStep from t to t+h computes the ticks in
(t, t+h] with the input held at its value at t, and its outputs are those of the last tick.
So tick n filters x[n-1] = u(t_c), t_c the last communication point before n*Ts, and the value
recorded at a communication point t is y[n_t - 1], n_t = floor(t/Ts) (the chain at rest at u(0)
before the first tick, so y = u(0) while n_t = 0). :func:`expected_output` builds exactly this
from the reference.
"""
from __future__ import annotations

import numpy as np

from .. import reference
from .._checks import (finite as _finite, finite_signal as _finite_signal,
                       nonnegative as _nonnegative, positive as _positive)
from ..errors import ParameterError
from ..reference._checks import check_samples
from .parameters import reference_stages

__all__ = ["TICK_SLACK", "communication_points", "tick_inputs", "at_communication_points",
           "expected_output", "expected_trajectory"]


#: Fraction of Ts by which a tick may follow the end of a step and still belong to it (fmu/).
TICK_SLACK = 1e-6


def communication_points(*, step: float, stop_time: float) -> np.ndarray:
    """``t_k = k step``, ``k = 0 .. round(stop_time/step)``, as fmpy computes them.

    Parameters
    ----------
    step : float, keyword-only
        Communication step [s], > 0.
    stop_time : float, keyword-only
        Last point [s].

    Returns
    -------
    ndarray of float64, shape (K,)
        The points [s].

    Raises
    ------
    ZeroDivisionError
        ``step`` is 0.
    """
    step, stop_time = _positive("step", step), _nonnegative("stop_time", stop_time)
    check_samples("step", stop_time / step + 1, "the communication points")
    n = int(round(stop_time / step))
    return np.arange(n + 1) * step


def tick_inputs(t: np.ndarray, u: np.ndarray, *, Ts: float) -> tuple[np.ndarray, np.ndarray]:
    """The input of every tick of the FMU's internal sample period and the ticks done by each
    communication point (the timing of the module docstring).

    Tick n is computed in the step from ``t_k`` with ``n_at[k] < n <= n_at[k+1]`` and filters
    ``u[k]`` (set at ``t_k``).

    Parameters
    ----------
    t : ndarray of float64, shape (K,)
        Communication points [s].
    u : ndarray of float64, shape (K,) or (K, m)
        Inputs set at them.
    Ts : float, keyword-only
        The FMU's sample period [s].

    Returns
    -------
    x : ndarray of float64, shape (N,) or (N, m)
        The input of ticks 1..N.
    n_at : ndarray of int64, shape (K,)
        Ticks done by each ``t_k``.

    Raises
    ------
    IndexError
        ``u`` is shorter than ``t``.
    """
    t, u, Ts = _finite_signal("t", t), _finite_signal("u", u), _positive("Ts", Ts)
    if t.size == 0 or np.any(t < 0) or np.any(np.diff(t) < 0):
        raise ParameterError("t", "t must be communication points: non-empty, >= 0 and "
                             "non-decreasing")
    if u.size < t.size:
        raise ParameterError("u", f"u must hold a value for each of the {t.size} points of t, "
                             f"got {u.size}")
    check_samples("Ts", t[-1] / Ts + 1, "the ticks up to the last communication point")
    n_at = np.floor(t / Ts + TICK_SLACK).astype(np.int64)
    ticks = np.arange(1, int(n_at[-1]) + 1)
    step_of_tick = np.searchsorted(n_at, ticks, side="left") - 1
    return u[step_of_tick], n_at


def at_communication_points(y_ticks: np.ndarray, n_at: np.ndarray, rest) -> np.ndarray:
    """Outputs read at the communication points: the last tick's, the rest value before any.

    Parameters
    ----------
    y_ticks : ndarray of float64, shape (N,) or (N, m)
        Output of every tick.
    n_at : ndarray of int64, shape (K,)
        Ticks done by each communication point (:func:`tick_inputs`).
    rest : float or ndarray
        The output before the first tick.

    Returns
    -------
    ndarray of float64, shape (K,) or (K, m)
        The outputs fmpy records.

    Raises
    ------
    IndexError
        ``n_at`` counts more ticks than ``y_ticks`` holds.
    """
    out = np.empty((n_at.size,) + y_ticks.shape[1:])
    out[...] = rest
    done = n_at > 0
    out[done] = y_ticks[n_at[done] - 1]
    return out


def expected_output(stages, t: np.ndarray, u: np.ndarray, *, Ts: float,
                    rest: float | None = None) -> np.ndarray:
    """What the SmoothShaper FMU reports at the communication points, computed with the NumPy
    reference (the chain starts at rest at ``rest``; the timing of the module docstring).

    Parameters
    ----------
    stages : sequence of Stage or ModeStage
        The chain.
    t : ndarray of float64, shape (K,)
        Communication points [s] (:func:`communication_points`).
    u : ndarray of float64, shape (K,)
        Inputs set at ``t``.
    Ts : float, keyword-only
        The FMU's sample period [s].
    rest : float or None, keyword-only
        Rest value (default ``u[0]``, the input at initialization).

    Returns
    -------
    ndarray of float64, shape (K,)
        The expected output ``y`` at ``t``.

    Raises
    ------
    ParameterError
        An invalid stage at ``Ts``.
    """
    x, n_at = tick_inputs(t, u, Ts=Ts)
    rest = float(np.asarray(u, dtype=float)[0]) if rest is None else _finite("rest", rest)
    y_ticks = reference.filter(reference_stages(stages), x - rest, Ts=Ts) + rest  # unit DC gain
    return at_communication_points(y_ticks, n_at, rest)


def expected_trajectory(t: np.ndarray, target: np.ndarray, *, Ts: float, **limits) -> np.ndarray:
    """What the TrajectoryGenerator FMU reports (columns q, v, a, j) at the communication points,
    from the NumPy reference of the generator
    (:func:`smoothshaper.trajectory.generator_reference`).

    Parameters
    ----------
    t : ndarray of float64, shape (K,)
        Communication points [s] (:func:`communication_points`).
    target : ndarray of float64, shape (K,)
        Targets set at ``t``.
    Ts : float, keyword-only
        The FMU's sample period [s].
    **limits
        ``vmax``, ``amax``, ``jmax``, ``profile``, ``wn``, ``zeta`` and ``q0`` (the rest
        position, default 0) as the FMU's parameters.

    Returns
    -------
    ndarray of float64, shape (K, 4)
        q, v, a, j at ``t``.

    Raises
    ------
    ParameterError
        Invalid limits.
    """
    from ..trajectory import generator_reference
    x, n_at = tick_inputs(t, target, Ts=Ts)
    limits = dict(limits)
    rest = _finite("q0", limits.pop("q0", 0.0))
    rows = generator_reference(x, Ts=Ts, position=rest, **limits) if x.size else np.zeros((0, 4))
    return at_communication_points(rows, n_at, np.array([rest, 0.0, 0.0, 0.0]))
