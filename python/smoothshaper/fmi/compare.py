# SPDX-License-Identifier: Apache-2.0
"""One FMU run against the NumPy reference, and the two importers against each other."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .cases import TRAJECTORY_LIMITS, target_staircase, test_input
from .parameters import start_values
from .simulate import simulate, simulate_libcosim, simulate_trajectory
from .timing import communication_points, expected_output, expected_trajectory

__all__ = ["REL_TOL", "compare", "compare_trajectory", "compare_importers",
           "compare_importers_trajectory"]


#: Relative error accepted between FMU and reference (docs/numerics.md: 1e-12 in double).
REL_TOL = 1e-12


def compare(fmu: Path, stages, *, Ts: float, step: float, stop_time: float):
    """One SmoothShaper run by fmpy against the NumPy reference.

    Parameters
    ----------
    fmu : str or Path
        Path of the FMU file.
    stages : sequence of Stage or ModeStage
        The chain.
    Ts : float, keyword-only
        The FMU's sample period [s].
    step : float, keyword-only
        Communication step [s] (any multiple or fraction of Ts).
    stop_time : float, keyword-only
        Length of the run [s].

    Returns
    -------
    tuple
        ``(t, u, y, y_ref, err, rel)``: points, inputs, FMU and reference outputs, the
        maximum absolute error and the error relative to ``max |y_ref|``.

    Raises
    ------
    RuntimeError
        fmpy returned other points than ``t``.
    """
    t = communication_points(step=step, stop_time=stop_time)
    u = test_input(t)
    y = simulate(str(fmu), stages, t, u, Ts=Ts)
    y_ref = expected_output(stages, t, u, Ts=Ts)
    err = float(np.max(np.abs(y - y_ref)))
    rel = err / max(float(np.max(np.abs(y_ref))), 1e-300)
    return t, u, y, y_ref, err, rel


def compare_trajectory(fmu: Path, *, Ts: float, step: float, stop_time: float, **limits):
    """One TrajectoryGenerator run by fmpy against the NumPy reference.

    Parameters
    ----------
    fmu : str or Path
        Path of the FMU file.
    Ts : float, keyword-only
        The FMU's sample period [s].
    step : float, keyword-only
        Communication step [s].
    stop_time : float, keyword-only
        Length of the run [s].
    **limits
        The FMU's parameters.

    Returns
    -------
    tuple
        ``(t, target, y, ref, rel)``: points, targets, FMU and reference outputs (K, 4) and
        the relative maximum errors of q, v, a, j.

    Raises
    ------
    RuntimeError
        fmpy returned other points than ``t``.
    """
    limits = limits or TRAJECTORY_LIMITS
    t = communication_points(step=step, stop_time=stop_time)
    target = target_staircase(t)
    y = simulate_trajectory(str(fmu), t, target, Ts=Ts, **limits)
    ref = expected_trajectory(t, target, Ts=Ts, **limits)
    rel = np.max(np.abs(y - ref), axis=0) / np.max(np.abs(ref), axis=0)
    return t, target, y, ref, rel


def compare_importers(fmu: Path, stages, *, Ts: float = 1e-3,
                      stop_time: float = 0.3) -> tuple[float, float]:
    """The SmoothShaper FMU with the chain ``stages`` in libcosim and in fmpy, and fmpy against
    the NumPy reference.

    Parameters
    ----------
    fmu : str or Path
        Path of the FMU file.
    stages : sequence of Stage or ModeStage
        The chain.
    Ts : float, keyword-only
        Sample period and communication step [s] (default 1e-3).
    stop_time : float, keyword-only
        Length of the run [s] (default 0.3).

    Returns
    -------
    tuple of float
        ``(max |y_libcosim - y_fmpy|, max |y_fmpy - reference|)``.

    Raises
    ------
    RuntimeError
        An importer failed.
    """
    t = communication_points(step=Ts, stop_time=stop_time)
    u = test_input(t)
    y_cosim = simulate_libcosim(str(fmu), t, u, start_values(stages, Ts=Ts))[1:, 0]
    y_fmpy = simulate(str(fmu), stages, t, u, Ts=Ts)
    ref = expected_output(stages, t, u, Ts=Ts)
    return float(np.max(np.abs(y_cosim - y_fmpy[1:]))), float(np.max(np.abs(y_fmpy - ref)))


def compare_importers_trajectory(fmu: Path, *, Ts: float = 1e-3, stop_time: float = 1.0,
                                 profile: int = 0, wn: float = 0.0, zeta: float = 0.0) -> float:
    """The TrajectoryGenerator FMU in libcosim and in fmpy for one profile.

    Parameters
    ----------
    fmu : str or Path
        Path of the FMU file.
    Ts : float, keyword-only
        Sample period and communication step [s] (default 1e-3).
    stop_time : float, keyword-only
        Length of the run [s] (default 1).
    profile : int, keyword-only
        Integer code: 0 polynomial, 1 trigonometric, 2 damped (with the mode wn, zeta).
    wn : float, keyword-only
        Mode of the damped profile [rad/s].
    zeta : float, keyword-only
        Its damping ratio.

    Returns
    -------
    float
        ``max |(q, v, a, j)_libcosim - (q, v, a, j)_fmpy|``.

    Raises
    ------
    RuntimeError
        An importer failed.
    """
    t = communication_points(step=Ts, stop_time=stop_time)
    target = target_staircase(t)
    params = {"Ts": Ts, **TRAJECTORY_LIMITS, "profile": int(profile), "wn": wn, "zeta": zeta}
    y_cosim = simulate_libcosim(str(fmu), t, target, params, input_name="target", outputs="qvaj")
    y_fmpy = simulate_trajectory(str(fmu), t, target, Ts=Ts, **TRAJECTORY_LIMITS,
                                 profile=int(profile), wn=wn, zeta=zeta)
    return float(np.max(np.abs(y_cosim[1:] - y_fmpy[1:])))
