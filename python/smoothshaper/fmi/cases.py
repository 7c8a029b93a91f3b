# SPDX-License-Identifier: Apache-2.0
"""The validation cases: the chains, inputs, targets and limits the FMUs are compared on."""
from __future__ import annotations

import math

import numpy as np

from ..stages import (damped_harmonic, exponential, harmonic, impulse_shaper, input_smoother,
                      notch, rectangular, shaper)
from .._checks import finite_array as _finite_array, integer as _integer
from ..errors import ParameterError
from .parameters import ModeStage

__all__ = ["test_input", "validation_cases", "TRAJECTORY_LIMITS", "TRAJECTORY_PROFILES",
           "target_staircase", "multi_axis_case"]


def test_input(t: np.ndarray, *, seed: int = 1) -> np.ndarray:
    """A staircase with steps of several sizes and both signs, then holding still.

    Parameters
    ----------
    t : ndarray of float64, shape (K,)
        Communication points [s], ascending (the steps fall between 5 % and 60 % of
        ``t[-1]``).
    seed : int, keyword-only
        Seed of the step heights (default 1).

    Returns
    -------
    ndarray of float64, shape (K,)
        The input at ``t``, starting at the rest value 0.5.

    Raises
    ------
    IndexError
        ``t`` is empty.
    """
    rng = np.random.default_rng(seed)
    u = np.zeros_like(t)
    edges = np.linspace(0.05, 0.6, 6) * t[-1]
    for e in edges:
        u[t >= e] += rng.uniform(-2.0, 3.0)
    return u + 0.5   # a non-zero rest point exercises "initial u is the rest point"


def validation_cases(Ts: float) -> list[tuple[str, list]]:
    """The validation cases: every family (raw and designed for a mode, every timing)
    and a few chains, with durations and a mode off the sample grid.

    Parameters
    ----------
    Ts : float
        Sample period [s] the durations are scaled to.

    Returns
    -------
    list of (str, list)
        ``(name, stages)`` pairs.

    Raises
    ------
    ParameterError
        ``Ts`` so large that a stage is invalid.
    """
    wn, zeta = 2 * math.pi * 7.3, 0.08            # Td ~ 137 Ts at Ts = 1 ms: off the grid
    T = 21.37 * Ts
    cases = [
        ("rectangular", [rectangular(T=T)]),
        ("rectangular (paper)", [rectangular(T=T, timing="paper")]),
        ("rectangular (bounded)", [rectangular(T=T, timing="bounded")]),
        ("exponential (bounded)", [exponential(T=T, sigma=-9.0, timing="bounded")]),
        ("harmonic", [harmonic(T=T)]),
        ("damped_harmonic", [damped_harmonic(T=T, sigma=-12.0)]),
        ("exponential", [exponential(T=T, sigma=-9.0)]),
        ("zv", [shaper("zv", wn=wn, zeta=zeta)]),
        ("zvd", [shaper("zvd", wn=wn, zeta=zeta)]),
        ("zvdd", [shaper("zvdd", wn=wn, zeta=zeta)]),
        ("zvn (n=4)", [shaper("zvn", wn=wn, zeta=zeta, order=4)]),
        ("ei", [shaper("ei", wn=wn, zeta=zeta, tolerance=0.05)]),
        ("ei2", [shaper("ei2", wn=wn, zeta=zeta, tolerance=0.05)]),
        ("mzv", [shaper("mzv", wn=wn, zeta=zeta)]),
        ("ei3", [shaper("ei3", wn=wn, zeta=zeta, tolerance=0.05)]),
        ("gmzv (n=5, 1.2 Td)", [shaper("gmzv", wn=wn, zeta=zeta, order=5, duration=1.2)]),
        ("zv (paper)", [shaper("zv", wn=wn, zeta=zeta, timing="paper")]),
        ("si (n=7, 2.3 Td)", [shaper("si", wn=wn, zeta=zeta, order=7, duration=2.3)]),
        ("smooth_mzv", [input_smoother("smooth_mzv", wn=wn, zeta=zeta)]),
        ("smooth_si", [input_smoother("smooth_si", wn=wn)]),
        ("chain smooth_zv*smooth_ei*smooth_ei2*smooth_zvd_ei (3 wn)",
         [input_smoother(kind, wn=3 * wn, zeta=zeta)
          for kind in ("smooth_zv", "smooth_ei", "smooth_ei2", "smooth_zvd_ei")]),
        ("impulses (pasted ZVD, a delay)",
         [impulse_shaper(amplitudes=[0.25, 0.5, 0.25], times=[3.3 * Ts, 71.8 * Ts, 140.3 * Ts])]),
        ("notch_tustin", [notch(wn=wn, zeta=0.02, notch_pole_zeta=0.5, discretization="tustin")]),
        ("notch_matched", [notch(wn=wn, zeta=0.02, notch_pole_zeta=0.5, discretization="matched")]),
        ("zvd for mode", [ModeStage("zvd", wn, zeta)]),
        ("damped_harmonic for mode", [ModeStage("damped_harmonic", wn, zeta)]),
        ("exponential for mode (k=2)", [ModeStage("exponential", wn, zeta, 2)]),
        ("chain M*M*S (double-S, harmonic end)",
         [rectangular(T=40 * Ts), rectangular(T=12.5 * Ts), harmonic(T=6.3 * Ts)]),
        ("chain M*ZV", [rectangular(T=30 * Ts), shaper("zv", wn=wn, zeta=zeta)]),
        ("chain M*M*S_sigma*notch", [rectangular(T=25 * Ts), rectangular(T=9 * Ts),
                                     damped_harmonic(T=T, sigma=-5.0),
                                     notch(wn=3 * wn, zeta=0.0, notch_pole_zeta=0.7)]),
    ]
    return cases


#: The TrajectoryGenerator profiles the importer comparison runs (the damped one with a mode).
TRAJECTORY_PROFILES = (("polynomial", dict(profile=0)), ("trigonometric", dict(profile=1)),
                       ("damped", dict(profile=2, wn=60.0, zeta=0.1)))


TRAJECTORY_LIMITS = dict(vmax=1.0, amax=10.0, jmax=200.0)


def target_staircase(t: np.ndarray) -> np.ndarray:
    """Targets for the TrajectoryGenerator runs: via-points with a reversal mid-motion, a target
    arriving mid-motion and a tiny step.

    Parameters
    ----------
    t : ndarray of float64, shape (K,)
        Communication points [s].

    Returns
    -------
    ndarray of float64, shape (K,)
        The target at each point [m].

    Raises
    ------
    IndexError
        ``t`` is empty.
    """
    t = _finite_array("t", t)
    x = np.full(t.shape, 0.1)
    for at, value in ((0.05, 0.4), (0.4, 0.0), (0.45, 0.35), (1.0, 0.3501)):
        x[t >= at] = value
    return x


def multi_axis_case(axes: int, t: np.ndarray) -> tuple[dict, np.ndarray, dict]:
    """A MultiAxisGenerator case for ``axes`` axes (1 to 8): limits and rest positions that
    differ by axis, phase-synchronised for an even count and independent for an odd one, a ZV
    stage (50 rad/s, zeta 0.05) on every axis from 4 axes on; targets that step at t = 0 and
    change mid-motion.

    Parameters
    ----------
    axes : int
        Axes in use, 1 to 8.
    t : ndarray of float64, shape (K,)
        Communication points [s].

    Returns
    -------
    tuple
        ``(values, targets, reference)``: the FMU's start values as the FMI 2.0 FMU names
        them (with ``Ts`` = 1 ms), the targets (K, axes) and the arguments of
        ``reference.multi_axis.multi_axis_reference`` (limits, ``q0``, ``sync``, ``stages``).

    Raises
    ------
    ParameterError
        ``axes`` is not an integer from 1 to 8.
    """
    axes = _integer("axes", axes, 1)
    if axes > 8:
        raise ParameterError("axes", f"axes must be at most 8, got {axes}")
    t = _finite_array("t", t)
    i = np.arange(axes)
    limits = dict(vmax=list(0.5 + 0.1 * i), amax=list(5.0 + i), jmax=list(80.0 + 10.0 * i))
    q0 = list(0.02 * i - 0.05)
    values = {"Ts": 1e-3, "axes": axes, "sync": axes % 2}
    for name, v in limits.items():
        values.update({f"{name}[{k}]": x for k, x in enumerate(v)})
    values.update({f"q0[{k}]": x for k, x in enumerate(q0)})
    stages = None
    if axes >= 4:
        values.update({f"stage[0].kind[{k}]": 4 for k in range(axes)})
        values.update({f"stage[0].wn[{k}]": 50.0 for k in range(axes)})
        values.update({f"stage[0].zeta[{k}]": 0.05 for k in range(axes)})
        stages = [[shaper("zv", wn=50.0, zeta=0.05)]] * axes
    targets = np.zeros((t.size, axes))
    for at, shift in ((0.0, 0.25), (0.3, -0.15)):
        targets[t >= at - 1e-12] = [shift * (1 + 0.1 * k) for k in range(axes)]
    reference = dict(limits, q0=q0, sync="phase" if axes % 2 == 0 else "independent",
                     stages=stages)
    return values, targets, reference
