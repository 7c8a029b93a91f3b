"""TrajectoryGenerator.fmu through fmpy: agreement with the NumPy generator reference, bounds,
FMU state, a foreign state refused, bad parameters named."""
from __future__ import annotations

import math

import numpy as np
import pytest

fmpy = pytest.importorskip("fmpy", reason="fmpy is needed to import the FMUs")
from fmpy import extract  # noqa: E402
from fmpy.fmi1 import FMICallException  # noqa: E402

from smoothshaper import validation  # noqa: E402
from test_fmu_smoothshaper import Logged, fmus, slave, smoothshaper_dir  # noqa: E402,F401

TS = 1e-3
LIMITS = validation.TRAJECTORY_LIMITS


@pytest.fixture(scope="session")
def trajectory_dir(fmus, tmp_path_factory):  # noqa: F811
    if "TrajectoryGenerator" not in fmus:
        pytest.skip("TrajectoryGenerator.fmu was not built")
    return extract(str(fmus["TrajectoryGenerator"]), str(tmp_path_factory.mktemp("tg")))


@pytest.mark.parametrize("step", [TS, 7 * TS, 2.5 * TS], ids=["Ts", "7Ts", "2.5Ts"])
def test_q_v_a_j_equal_reference_and_bounds_hold(fmus, trajectory_dir, step):  # noqa: F811
    # the limits put every jerk jump on a tick: FMU and reference both give the right limit
    t, target, y, ref, rel = validation.compare_trajectory(
        fmus["TrajectoryGenerator"], Ts=TS, step=step, stop_time=1.5)
    assert np.all(rel <= validation.REL_TOL), rel
    # docs/design.md: within the limits (a few ulps) and exactly on the last target once it holds.
    bounds = np.array([LIMITS["vmax"], LIMITS["amax"], LIMITS["jmax"]])
    assert np.all(np.max(np.abs(y[:, 1:]), axis=0) <= bounds * (1 + 1e-12))
    assert y[-1, 0] == target[-1] and np.all(y[-1, 1:] == 0.0)


def start(fmu, *, target=0.0, **params):
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    for name, value in {"Ts": TS, **LIMITS, **params}.items():
        if name == "profile":
            fmu.setInteger([fmu.vr[name]], [value])
        else:
            fmu.setReal([fmu.vr[name]], [value])
    fmu.setReal([fmu.vr["target"]], [target])
    fmu.exitInitializationMode()


def run(fmu, t0, targets):
    out = np.empty((len(targets), 4))
    vr = [fmu.vr[n] for n in "qvaj"]
    for i, x in enumerate(targets):
        fmu.setReal([fmu.vr["target"]], [x])
        fmu.doStep(t0 + i * TS, TS)
        out[i] = fmu.getReal(vr)
    return out


TARGETS = np.repeat(np.random.default_rng(7).uniform(-0.5, 0.5, 20), 40)


@pytest.mark.parametrize("profile", [0, 1, 2])
def test_state_and_serialisation_round_trip(trajectory_dir, profile):
    extra = {"profile": profile, "wn": 60.0, "zeta": 0.1} if profile == 2 else {"profile": profile}
    a = slave(trajectory_dir, "a")
    start(a, target=0.2, **extra)
    run(a, 0.0, TARGETS[:300])
    state = a.getFMUstate()
    blob = a.serializeFMUstate(state)
    first = run(a, 0.3, TARGETS[300:])
    a.setFMUstate(state)
    assert np.array_equal(run(a, 0.3, TARGETS[300:]), first)
    b = slave(trajectory_dir, "b")
    b.setFMUstate(b.deSerializeFMUstate(blob))
    assert np.array_equal(run(b, 0.3, TARGETS[300:]), first)
    for f in (a, b):
        f.freeInstance()


def test_state_of_the_other_model_is_refused(trajectory_dir, smoothshaper_dir):  # noqa: F811
    ss = slave(smoothshaper_dir, "ss")
    ss.setupExperiment(startTime=0.0)
    ss.enterInitializationMode()
    ss.exitInitializationMode()
    blob = ss.serializeFMUstate(ss.getFMUstate())
    log = Logged()
    tg = slave(trajectory_dir, "tg", logged=log)
    with pytest.raises(FMICallException):
        tg.deSerializeFMUstate(blob)
    assert "another model" in log.messages[-1]
    for f in (ss, tg):
        f.freeInstance()


@pytest.mark.parametrize("name,value,expected", [
    ("vmax", 0.0, "vmax"), ("jmax", -3.0, "jmax"), ("zeta", 1.2, "zeta"), ("wn", 1e5, "wn"),
    ("profile", 7, "profile"), ("Ts", -1.0, "Ts")])
def test_bad_parameters_fail_at_exit_initialization_naming_them(trajectory_dir, name, value, expected):
    log = Logged()
    fmu = slave(trajectory_dir, logged=log)
    params = {"wn": 50.0} if name == "zeta" else {}
    params[name] = value
    with pytest.raises(FMICallException):
        start(fmu, **params)
    assert expected in log.messages[-1], log.messages[-1]
    fmu.freeInstance()


@pytest.mark.parametrize("name,params", validation.TRAJECTORY_PROFILES,
                         ids=[p[0] for p in validation.TRAJECTORY_PROFILES])
def test_libcosim_sets_every_profile_and_equals_fmpy_bit_for_bit(fmus, trajectory_dir, name,  # noqa: F811
                                                                 params):
    pytest.importorskip("libcosimpy", reason="libcosimpy is the second importer")
    assert validation.compare_importers_trajectory(fmus["TrajectoryGenerator"], **params) == 0.0


def test_profiles_differ_so_the_profile_code_took_effect(fmus, trajectory_dir):  # noqa: F811
    pytest.importorskip("libcosimpy", reason="libcosimpy is the second importer")
    t = validation.communication_points(step=TS, stop_time=0.3)
    target = validation.target_staircase(t)
    runs = [validation.simulate_libcosim(str(fmus["TrajectoryGenerator"]), t, target,
                                         {"Ts": TS, **LIMITS, **params}, input_name="target",
                                         outputs="qvaj")[1:] for _, params in validation.TRAJECTORY_PROFILES]
    assert not np.array_equal(runs[0], runs[1]) and not np.array_equal(runs[1], runs[2])


def test_an_fmu_state_of_the_other_model_is_refused_in_process(trajectory_dir, smoothshaper_dir):  # noqa: F811
    ss, tg = slave(smoothshaper_dir, "ss"), slave(trajectory_dir, "tg")
    state = ss.getFMUstate()
    with pytest.raises(FMICallException):
        tg.setFMUstate(state)          # same process, other binary: refused, no copy
    ss.freeFMUstate(state)
    for f in (ss, tg):
        f.freeInstance()


def test_starts_at_q0_and_a_target_stepped_at_t0_moves_time_optimally(trajectory_dir):
    """q0 is where the FMU rests after initialization; a target already there at t = 0 is a
    move, reaching it on the first tick at or after ruckig's time-optimal duration."""
    ruckig = pytest.importorskip("ruckig")
    h = 0.0819                       # default limits v = 1, a = 10, j = 100: 0.297 s
    otg, inp, traj = ruckig.Ruckig(1), ruckig.InputParameter(1), ruckig.Trajectory(1)
    inp.current_position, inp.target_position = [0.25], [0.25 + h]
    inp.max_velocity, inp.max_acceleration, inp.max_jerk = [1.0], [10.0], [100.0]
    otg.calculate(inp, traj)
    fmu = slave(trajectory_dir, "q0")
    start(fmu, target=0.25 + h, q0=0.25, vmax=1.0, amax=10.0, jmax=100.0)
    assert fmu.getReal([fmu.vr["q"]])[0] == 0.25
    out = run(fmu, 0.0, [0.25 + h] * 400)
    arrive = np.flatnonzero((out[:, 0] == 0.25 + h) & (out[:, 1] == 0.0))[0]
    assert arrive == math.ceil(traj.duration / TS)
    assert abs(traj.duration - 0.297) < 5e-4
    fmu.freeInstance()
