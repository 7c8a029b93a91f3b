# SPDX-License-Identifier: Apache-2.0
"""TrajectoryGenerator.fmu's target inputs through fmpy: position targets with a velocity and
an acceleration at arrival, the velocity interface and the stop, bit for bit the Python
Generator fed the same targets per sample (fmpy's timing: inputs at t_k, doStep, outputs at
t_(k+1)); fmpy's simulate_fmu with its defaults; a target beyond the limits fails fmi2DoStep
naming it and changes nothing."""
from __future__ import annotations

import numpy as np
import pytest

fmpy = pytest.importorskip("fmpy", reason="fmpy is needed to import the FMUs")
from fmpy.fmi1 import FMICallException  # noqa: E402

from smoothshaper.trajectory import Generator  # noqa: E402
from test_fmu_smoothshaper import Logged, fmus, slave  # noqa: E402,F401
from test_fmu_trajectory import LIMITS, TS, start, trajectory_dir  # noqa: E402,F401


def targets(seed, blocks=12, hold=60):
    """A random sequence of held targets: positions reached moving, velocities, stops."""
    rng = np.random.default_rng(seed)
    pos, vel, acc, code = [], [], [], []
    for _ in range(blocks):
        kind = rng.choice(3, p=[0.6, 0.3, 0.1])
        v = rng.uniform(-0.8, 0.8) if rng.random() < 0.7 else 0.0
        a = rng.uniform(-2.0, 2.0) if kind == 0 and rng.random() < 0.5 else 0.0
        n = int(rng.integers(5, hold))
        pos += [rng.uniform(-1.0, 1.0)] * n
        vel += [v] * n
        acc += [a] * n
        code += [int(kind)] * n
    return np.array(pos), np.array(vel), np.array(acc), np.array(code)


def run_targets(fmu, t0, pos, vel, acc, code, tmin=None):
    out = np.empty((pos.size, 4))
    qvaj = [fmu.vr[n] for n in "qvaj"]
    real = [fmu.vr["target"], fmu.vr["target_velocity"], fmu.vr["target_acceleration"]]
    for i in range(pos.size):
        fmu.setReal(real, [pos[i], vel[i], acc[i]])
        if tmin is not None:
            fmu.setReal([fmu.vr["minimum_duration"]], [tmin[i]])
        fmu.setInteger([fmu.vr["interface"]], [int(code[i])])
        fmu.doStep(t0 + i * TS, TS)
        out[i] = fmu.getReal(qvaj)
    return out


def python_run(pos, vel, acc, code, tmin=None, **extra):
    if "profile" in extra:   # the FMU's code, the class's name
        extra = dict(extra, profile=("polynomial", "trigonometric", "damped")[extra["profile"]])
    g = Generator(Ts=TS, **LIMITS, **extra)
    names = np.array(["position", "velocity", "velocity"])[code]
    return g.process(pos, velocity=vel, acceleration=acc, interface=names, stop=code == 2,
                     minimum_duration=tmin)


def test_minimum_duration_through_fmpy_equals_the_python_generator(trajectory_dir):  # noqa: F811
    """The input minimum_duration (half the targets stretched to up to 0.2 s)."""
    pos, vel, acc, code = targets(5, blocks=16, hold=200)
    rng = np.random.default_rng(6)
    # one minimum per held target: constant over each block of equal targets
    block = np.r_[0, np.cumsum((np.diff(pos) != 0) | (np.diff(vel) != 0) | (np.diff(code) != 0))]
    tmin = np.where(rng.random(block.max() + 1) < 0.5, rng.uniform(0, 0.2, block.max() + 1),
                    0.0)[block]
    fmu = slave(trajectory_dir, "tg")
    start(fmu)
    y = run_targets(fmu, 0.0, pos, vel, acc, code, tmin)
    fmu.freeInstance()
    assert np.array_equal(y, python_run(pos, vel, acc, code, tmin))


@pytest.mark.parametrize("seed,extra", [(1, {}), (2, {"profile": 2, "wn": 60.0, "zeta": 0.1})],
                         ids=["polynomial", "damped"])
def test_targets_through_fmpy_equal_the_python_generator(trajectory_dir, seed, extra):  # noqa: F811
    pos, vel, acc, code = targets(seed)
    fmu = slave(trajectory_dir, "tg")
    start(fmu, **extra)
    y = run_targets(fmu, 0.0, pos, vel, acc, code)
    fmu.freeInstance()
    assert np.array_equal(y, python_run(pos, vel, acc, code, **extra))


def test_simulate_fmu_with_its_defaults_equals_the_python_generator(fmus):  # noqa: F811
    """fmpy.simulate_fmu with its default step (the DefaultExperiment's 1 ms = Ts) and
    piecewise-constant inputs (each change given twice, at the same time: a step)."""
    n, hold = 900, 150
    t = np.arange(n) * TS
    k = np.arange(n) // hold
    pos = np.where(k % 2 == 0, 0.4, -0.3) * (1 + k / 10)
    vel = np.where(k % 3 == 0, 0.3, -0.2)
    acc = np.where(k % 4 == 1, 1.0, 0.0)
    code = np.where(k == 4, 1, 0)
    change = np.flatnonzero(np.diff(k)) + 1
    rows = []
    for i in range(n):
        if i in change:   # the value before the step, at the step's instant
            rows.append((t[i], pos[i - 1], vel[i - 1], acc[i - 1], code[i - 1]))
        rows.append((t[i], pos[i], vel[i], acc[i], code[i]))
    signals = np.array(rows, dtype=[("time", float), ("target", float),
                                    ("target_velocity", float),
                                    ("target_acceleration", float), ("interface", np.int32)])
    res = fmpy.simulate_fmu(str(fmus["TrajectoryGenerator"]), start_time=0.0,
                            stop_time=(n - 1) * TS, input=signals, output=["q", "v", "a", "j"],
                            output_interval=TS, start_values=LIMITS)
    y = np.column_stack([res[name] for name in "qvaj"])
    ref = python_run(pos, vel, acc, code)
    # the output at t_(k+1) is the generator's sample k (the first row is the initial rest)
    assert np.array_equal(y[1:], ref[:len(y) - 1])


@pytest.mark.parametrize("field,value,words", [
    ("target_velocity", 1.5, "target_velocity = 1.5 is beyond vmax"),
    ("target_acceleration", 12.0, "target_acceleration = 12"),
    ("target_acceleration", 3.0, "v + a|a|/(2 jmax)"),
    ("minimum_duration", -1.0, "minimum_duration = -1 must be finite, >= 0"),
])
def test_a_target_beyond_the_limits_fails_the_step_naming_it(trajectory_dir, field, value,  # noqa: F811
                                                             words):
    """v = 0.9 with a = 3 would pass vmax after arrival (0.9 + 9/200 = 0.945 is inside, but
    a = 3 from v = 0.98: 1.025): the step fails, the log names the input, and the instance
    runs on as its twin once the input is valid again."""
    log = Logged()
    fmu, twin = slave(trajectory_dir, "tg", logged=log), slave(trajectory_dir, "twin")
    pos, vel, acc, code = targets(3, blocks=3)
    for f in (fmu, twin):
        start(f)
        run_targets(f, 0.0, pos, vel, acc, code)
    t0 = pos.size * TS
    fmu.setReal([fmu.vr["target_velocity"]], [0.98 if field == "target_acceleration" else 0.0])
    fmu.setReal([fmu.vr[field]], [value])
    before = fmu.serializeFMUstate(fmu.getFMUstate())
    with pytest.raises(FMICallException):
        fmu.doStep(t0, TS)
    assert words in log.messages[-1], log.messages[-1]
    assert fmu.serializeFMUstate(fmu.getFMUstate()) == before
    fmu.setReal([fmu.vr["minimum_duration"]], [0.0])   # (run_targets sets the other three)
    more = targets(4, blocks=3)
    assert np.array_equal(run_targets(fmu, t0, *more), run_targets(twin, t0, *more))
    for f in (fmu, twin):
        f.freeInstance()
