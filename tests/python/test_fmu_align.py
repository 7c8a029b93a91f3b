# SPDX-License-Identifier: Apache-2.0
"""MultiAxisGenerator.fmu with align = 1, in fmpy (default settings, explicit output_interval)
and libcosim: every axis equals the NumPy multi-axis reference delayed by its pad to the
common lag (reference.delay), the lag output equals smoothshaper.align's common lag, and a
straight constant-speed move stays on the line to rounding where align = 0 leaves it."""
from __future__ import annotations

import numpy as np
import pytest

fmpy = pytest.importorskip("fmpy", reason="fmpy is needed to import the FMUs")

from smoothshaper import align, reference as ref, validation  # noqa: E402
from smoothshaper.reference.multi_axis import multi_axis_reference  # noqa: E402
from test_fmu_multi_axis import (LIMITS, Q0, STAGES, TS, multi_fmu, outputs,  # noqa: E402,F401
                                 run_libcosim, stage_list, staircase, start_values)
from test_fmu_smoothshaper import fmus  # noqa: E402,F401


def expected_aligned(t, target, axes=3, stages="mixed") -> np.ndarray:
    """The reference profile through the stages, each axis delayed by its pad, sampled at
    the communication points as fmpy records them."""
    x, n_at = validation.tick_inputs(t, np.arange(t.size), Ts=TS)
    chains = [stage_list(tr) for tr in STAGES[stages][axes]]
    rows = multi_axis_reference(target[x.astype(int)], Ts=TS, sync="phase", q0=Q0[axes],
                                stages=chains, **LIMITS[axes])
    _, pads = align.align(chains, Ts=TS)
    for i in range(axes):
        for m in range(4):
            rows[:, i, m] = ref.delay(rows[:, i, m], samples=pads[i] / TS,
                                      rest=Q0[axes][i] if m == 0 else 0.0)
    rest = np.zeros((axes, 4))
    rest[:, 0] = Q0[axes]
    return validation.at_communication_points(rows, n_at, rest)


def simulate(fmu, t, target, axes=3, stages="mixed", aligned=1, **more):
    names = [f"target[{i}]" for i in range(axes)]
    signal = np.zeros(t.size, dtype=[("time", float)] + [(n, float) for n in names])
    signal["time"] = t
    for i, n in enumerate(names):
        signal[n] = target[:, i]
    r = fmpy.simulate_fmu(str(fmu), start_values={**start_values(axes, 0, stages),
                                                  "align": aligned, **more},
                          input=signal, stop_time=float(t[-1]),
                          output_interval=float(t[1] - t[0]), output=outputs(axes) + ["lag"])
    y = np.stack([np.asarray(r[n], dtype=float) for n in outputs(axes)], axis=1)
    return y.reshape(t.size, axes, 4), np.asarray(r["lag"], dtype=float)


def assert_close(y, want, axes=3):
    scale = np.array([np.abs(want[:, :, 0]).max()] + [np.max(LIMITS[axes][k])
                                                      for k in ("vmax", "amax", "jmax")])
    err = np.abs(y - want).max(axis=(0, 1)) / scale
    assert np.all(err <= 1e-12), err


def test_fmpy_aligned_equals_the_delayed_reference(multi_fmu):
    t = validation.communication_points(step=2.5 * TS, stop_time=1.5)
    target = staircase(t, 3)
    y, lag = simulate(multi_fmu, t, target)
    assert_close(y, expected_aligned(t, target))
    chains = [stage_list(tr) for tr in STAGES["mixed"][3]]
    assert np.all(lag == pytest.approx(align.align(chains, Ts=TS)[0], rel=1e-13))
    assert lag[0] > 0.0


def test_fmpy_straight_move_on_the_line_only_aligned(multi_fmu):
    """Constant speed (the profile cruises from 0.236 s to 1.187 s on this move; y carries a
    0.2 s rectangular stage, so from 0.5 s): off the line with align = 0, on it to rounding
    with align = 1. x: a ZVD, y: the rectangular stage, z: none (FIR only, so the cruise is
    exactly constant)."""
    t = validation.communication_points(step=TS, stop_time=1.5)
    goal = np.array([1.0, -0.6, 0.8])
    target = np.tile(goal, (t.size, 1))
    d = goal - Q0[3]
    u = d / np.linalg.norm(d)
    cruise = slice(500, 1180)
    bare_z = {"stage[0].kind[2]": -1, "stage[1].kind[2]": -1}
    off = {}
    for a in (0, 1):
        q = simulate(multi_fmu, t, target, aligned=a, **bare_z)[0][:, :, 0] - Q0[3]
        off[a] = np.linalg.norm(q - np.outer(q @ u, u), axis=1)[cruise]
    assert off[0].max() > 1e-4
    assert off[1].max() <= 64 * 2.0 ** -53 * np.abs(goal).max()


def test_libcosim_aligned_equals_the_delayed_reference(multi_fmu):
    pytest.importorskip("libcosimpy", reason="libcosimpy is the second importer")
    import test_fmu_multi_axis as base
    t = validation.communication_points(step=TS, stop_time=1.0)
    target = staircase(t, 3)
    values = base.start_values
    try:
        base.start_values = lambda axes, sync, stages=None: {**values(axes, sync, stages),
                                                             "align": 1}
        y = run_libcosim(str(multi_fmu), t, target, 3, "mixed")
    finally:
        base.start_values = values
    assert_close(y[1:], expected_aligned(t, target)[1:])
