# SPDX-License-Identifier: Apache-2.0
"""TrajectoryGenerator.fmu through fmpy: agreement with the NumPy generator reference, bounds,
the sampled limits and equality with the Python Generator on random staircases, FMU state, a
foreign state refused, bad parameters named."""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings, strategies as st

fmpy = pytest.importorskip("fmpy", reason="fmpy is needed to import the FMUs")
from fmpy import extract  # noqa: E402
from fmpy.fmi1 import FMICallException  # noqa: E402
from fmpy.fmi2 import fmi2True  # noqa: E402

from smoothshaper import fmi  # noqa: E402
from smoothshaper.filters import ParameterError  # noqa: E402
from smoothshaper.trajectory import Generator  # noqa: E402
from test_fmu_smoothshaper import Logged, fmus, slave, smoothshaper_dir  # noqa: E402,F401
from test_trajectory import BOUND_RTOL, assert_sampled_limits  # noqa: E402

TS = 1e-3
LIMITS = fmi.TRAJECTORY_LIMITS


@pytest.fixture(scope="session")
def trajectory_dir(fmus, tmp_path_factory):  # noqa: F811
    if "TrajectoryGenerator" not in fmus:
        pytest.skip("TrajectoryGenerator.fmu was not built")
    return extract(str(fmus["TrajectoryGenerator"]), str(tmp_path_factory.mktemp("tg")))


@pytest.mark.parametrize("step", [TS, 7 * TS, 2.5 * TS], ids=["Ts", "7Ts", "2.5Ts"])
def test_q_v_a_j_equal_reference_and_bounds_hold(fmus, trajectory_dir, step):  # noqa: F811
    # the limits put every jerk jump on a tick: FMU and reference both give the right limit
    t, target, y, ref, rel = fmi.compare_trajectory(
        fmus["TrajectoryGenerator"], Ts=TS, step=step, stop_time=1.5)
    assert np.all(rel <= fmi.REL_TOL), rel
    # within the limits to 32 u (docs/sampled-limits.md) and exactly on the last target once
    # it holds
    bounds = np.array([LIMITS["vmax"], LIMITS["amax"], LIMITS["jmax"]])
    assert np.all(np.max(np.abs(y[:, 1:]), axis=0) <= bounds * (1 + 32 * 2.0 ** -53))
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


def run_equal_to_the_generator(trajectory_dir, lim, x):
    """The FMU started with the extra parameters ``lim`` and fed ``x``: its outputs, asserted
    equal bit for bit to the Python Generator's with the same parameters."""
    fmu = slave(trajectory_dir)
    start(fmu, **lim)
    y = run(fmu, 0.0, x)
    fmu.freeInstance()
    assert np.array_equal(y, Generator(Ts=TS, **LIMITS, **lim).process(x))
    return y


def assert_start_refused(trajectory_dir, params, words):
    """Initialising with ``params`` is refused, and the logger's last message has ``words``."""
    log = Logged()
    fmu = slave(trajectory_dir, logged=log)
    with pytest.raises(FMICallException):
        start(fmu, **params)
    assert words in log.messages[-1], log.messages[-1]
    fmu.freeInstance()


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


@pytest.mark.parametrize("name,params", fmi.TRAJECTORY_PROFILES,
                         ids=[p[0] for p in fmi.TRAJECTORY_PROFILES])
def test_libcosim_sets_every_profile_and_equals_fmpy_bit_for_bit(fmus, trajectory_dir, name,  # noqa: F811
                                                                 params):
    pytest.importorskip("libcosimpy", reason="libcosimpy is the second importer")
    assert fmi.compare_importers_trajectory(fmus["TrajectoryGenerator"], **params) == 0.0


def test_profiles_differ_so_the_profile_code_took_effect(fmus, trajectory_dir):  # noqa: F811
    pytest.importorskip("libcosimpy", reason="libcosimpy is the second importer")
    t = fmi.communication_points(step=TS, stop_time=0.3)
    target = fmi.target_staircase(t)
    runs = [fmi.simulate_libcosim(str(fmus["TrajectoryGenerator"]), t, target,
                                         {"Ts": TS, **LIMITS, **params}, input_name="target",
                                         outputs="qvaj")[1:] for _, params in fmi.TRAJECTORY_PROFILES]
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


@pytest.mark.parametrize("limits, words", [
    (dict(vmax=1.0, amax=1e-30, jmax=1e-300),
     ["vmax = 1, jmax = 1e-300, Ts = 0.001", "sqrt(vmax/jmax) = 1e+150 s", "2^50"]),
    (dict(vmax=1e300, amax=1e100, jmax=1e5), ["vmax = 1.0000000000000001e+300, amax = 1e+100", "vmax/amax = 1e+200 s"]),
    (dict(vmax=4.0, amax=1.0, jmax=1e307), ["vmax = 4, jmax = 9.9999999999999999e+306", "vmax*jmax = 4e+307 exceeds"]),
])
def test_infeasible_limits_fail_at_exit_initialization_naming_the_quantity(trajectory_dir, limits,
                                                                           words):
    """Limits with which no plan can reach vmax: fmi2ExitInitializationMode fails and the
    logger names the variables, their values and the derived quantity."""
    log = Logged()
    fmu = slave(trajectory_dir, logged=log)
    with pytest.raises(FMICallException):
        start(fmu, **limits)
    for w in words:
        assert w in log.messages[-1], log.messages[-1]
    fmu.freeInstance()


def test_a_dropped_target_is_logged_once_and_the_step_warns(trajectory_dir):
    """A target 1e300 away (a cruise of 1e297 s at vmax 1e3: more than 2^52 ticks) is dropped:
    the doStep that drops it returns fmi2Warning and logs the target once; later steps under
    the same target are OK and quiet; a reachable target then moves; a new dropped target is
    logged again, and a restored state does not repeat the message."""
    log = Logged()
    fmu = slave(trajectory_dir, logged=log)
    start(fmu, vmax=1e3, amax=1e5, jmax=1e7)
    vr = [fmu.vr[n] for n in "qvaj"]
    statuses = []
    for i, x in enumerate([1e300] * 5 + [2.0] * 200 + [-1e300] * 3):
        fmu.setReal([fmu.vr["target"]], [x])
        statuses.append(fmu.fmi2DoStep(fmu.component, i * TS, TS, fmi2True))
        assert np.all(np.isfinite(fmu.getReal(vr)))
        if i == 4:
            assert fmu.getReal(vr) == [0.0, 0.0, 0.0, 0.0]
    assert statuses[0] == 1 and statuses[205] == 1          # fmi2Warning
    assert statuses.count(1) == 2 and statuses.count(0) == len(statuses) - 2
    assert fmu.getReal([fmu.vr["q"]]) == [2.0]
    dropped = [m for m in log.messages if m.startswith("fmi2DoStep")]
    assert len(dropped) == 2
    assert "t = 0.001: target = 1.0000000000000001e+300 dropped" in dropped[0]
    assert "goal 0 " in dropped[0]
    # the limits and Ts the user set, with which the move cannot be represented
    assert "vmax = 1000, amax = 100000, jmax = 10000000, Ts = 0.001" in dropped[0]
    assert "target = -1.0000000000000001e+300 dropped" in dropped[1] and "goal 2 " in dropped[1]
    state = fmu.getFMUstate()
    fmu.setFMUstate(state)
    assert fmu.fmi2DoStep(fmu.component, 208 * TS, TS, fmi2True) == 0
    assert len([m for m in log.messages if m.startswith("fmi2DoStep")]) == 2
    fmu.freeInstance()


def test_fmpy_default_settings_with_a_dropped_target(fmus):  # noqa: F811
    """fmpy.simulate_fmu with its default settings: a target step to 1e300 (dropped) and back
    to 0.5 runs to the end, every output finite, within the limits, at rest on 0.5."""
    sig = np.array([(0.0, 0.0), (0.01, 0.0), (0.01, 1e300), (0.05, 1e300), (0.05, 0.5),
                    (2.0, 0.5)], dtype=[("time", float), ("target", float)])
    r = fmpy.simulate_fmu(str(fmus["TrajectoryGenerator"]), start_values=LIMITS, input=sig,
                          stop_time=2.0, output_interval=TS)
    y = np.column_stack([r[n] for n in "qvaj"])
    assert np.all(np.isfinite(y))
    assert np.all(np.max(np.abs(y[:, 1:]), axis=0)
                  <= np.array(list(LIMITS.values())) * (1 + 32 * 2.0 ** -53))
    assert np.all(y[(r["time"] > 0.01) & (r["time"] <= 0.05), 0] == 0.0)
    assert y[-1, 0] == 0.5 and np.all(y[-1, 1:] == 0.0)


PROFILE_CODES = {"polynomial": 0, "trigonometric": 1, "damped": 2}


@st.composite
def fmu_staircases(draw, with_mode):
    """Limits over several decades, a sample period from three times the time to reach vmax
    (every phase shorter than a sample) to 1/300 of it, q0 and a staircase of targets on the
    scale of that move, held from 2 % to 3 times its time (most change mid-motion); with a
    mode from a third to three times that time (at least four samples) and a damping ratio."""
    vmax = 10.0 ** draw(st.floats(-2, 2))
    amax = vmax * 10.0 ** draw(st.floats(-1, 2))
    jmax = amax * 10.0 ** draw(st.floats(0, 3))
    ap = min(amax, math.sqrt(vmax * jmax))
    rise = vmax / ap + ap / jmax                  # from rest to vmax
    Ts = rise / 10.0 ** draw(st.floats(-0.5, 2.5))
    scale = vmax * rise
    q0 = scale * draw(st.floats(-3, 3))
    steps = draw(st.lists(st.tuples(st.floats(-3, 3), st.floats(0.02, 3)), min_size=1,
                          max_size=6))
    targets = [(q0 + scale * value, max(1, round(hold * rise / Ts))) for value, hold in steps]
    params = dict(vmax=vmax, amax=amax, jmax=jmax, q0=q0)
    if with_mode:
        params["wn"] = 2 * math.pi / max(rise * 10.0 ** draw(st.floats(-0.5, 0.5)), 4 * Ts)
        params["zeta"] = draw(st.floats(0.0, 0.2))
    return Ts, params, targets


@pytest.mark.parametrize("profile, with_mode", [
    ("polynomial", False), ("polynomial", True), ("trigonometric", False),
    ("trigonometric", True), ("damped", True)])       # the damped profile needs a mode
@settings(max_examples=30, deadline=None)
@given(data=st.data())
def test_random_staircases_keep_the_sampled_limits_and_equal_the_python_generator(
        trajectory_dir, profile, with_mode, data):
    """fmpy (default settings, output_interval = Ts) on random staircases, every profile,
    with and without a mode: (a) the backward differences of q over Ts^i within vmax, amax,
    jmax to 1e-9 plus the rounding of the positions (16 u S per sample, 2^i of them in a
    difference of order i; docs/sampled-limits.md), (b) the reported v, a, j within the limits
    to 32 u, (c) q, v, a, j equal to the Python Generator on the inputs the FMU's ticks see
    (the target set at t_k drives the tick recorded at t_(k+1)), (d) exactly on the last
    target, at rest, once it has held long enough."""
    Ts, params, targets = data.draw(fmu_staircases(with_mode))
    limits = (params["vmax"], params["amax"], params["jmax"])
    try:
        gen = Generator(Ts=Ts, profile=profile, **params)
    except ParameterError as exc:
        assume(exc.parameter != "wn")             # a mode the grid cannot place
        raise
    values = [v for v, _ in targets] + [params["q0"]]
    # the last target held for the worst case: the stop, the way back across the staircase,
    # the velocity rise and fall ((pi/2) amax/jmax for half cosines) and the tuned stage
    ap = min(params["amax"], math.sqrt(params["vmax"] * params["jmax"]))
    move = 2 * np.ptp(values) / params["vmax"] + 4 * (params["vmax"] / ap + 2 * ap / params["jmax"])
    hold = int(move / Ts) + gen.tail_samples + 10
    target = np.concatenate([np.full(n, v) for v, n in targets] + [np.full(hold, targets[-1][0])])
    t = fmi.communication_points(step=Ts, stop_time=(target.size - 1) * Ts)
    assert t.size == target.size
    y = fmi.simulate_trajectory(str(trajectory_dir), t, target, Ts=Ts,
                                       profile=PROFILE_CODES[profile], **params)
    # (c) the Python Generator (the same C core, another build) on the ticks' inputs
    x, n_at = fmi.tick_inputs(t, target, Ts=Ts)
    expected = fmi.at_communication_points(
        gen.process(x), n_at, np.array([params["q0"], 0.0, 0.0, 0.0]))
    assert np.array_equal(y, expected), np.max(np.abs(y - expected), axis=0)
    # (a) fmpy's first row is the rest at q0 after initialization, where it rested before
    rest = np.tile(y[:1], (2, 1))
    assert_sampled_limits(np.vstack([rest, y]), target, limits, Ts, "double",
                          at_rest_before=False)
    # (b)
    assert np.all(np.max(np.abs(y[:, 1:]), axis=0) <= np.array(limits) * (1 + BOUND_RTOL["double"]))
    # (d)
    assert y[-1, 0] == target[-1] and np.all(y[-1, 1:] == 0.0)


def test_asymmetric_limits_equal_the_python_generator_bit_for_bit(trajectory_dir):
    """Parameters vmin, amin (0: symmetric): the FMU's q, v, a, j equal the Python Generator
    with the same lower bounds bit for bit, each side within its own bound; a positive vmin,
    a trigonometric profile with amin and a target velocity below vmin fail naming them."""
    lim = dict(vmin=-0.25, amin=-2.5)
    y = run_equal_to_the_generator(trajectory_dir, lim, np.r_[np.full(1500, 0.6), np.full(3000, -0.2)])
    assert y[:, 1].min() == -0.25 and y[:, 2].min() == -2.5
    for params, words in [(dict(vmin=0.5), "vmin"),
                          (dict(amin=-5.0, profile=1), "trigonometric profile takes symmetric")]:
        assert_start_refused(trajectory_dir, params, words)
    log = Logged()
    fmu = slave(trajectory_dir, logged=log)
    start(fmu, **lim)
    fmu.setReal([fmu.vr["target_velocity"]], [-0.3])
    with pytest.raises(FMICallException):
        fmu.doStep(0.0, TS)
    assert "[vmin, vmax]" in log.messages[-1], log.messages[-1]
    fmu.freeInstance()


def test_position_limits_equal_the_python_generator_bit_for_bit(trajectory_dir):
    """Parameters qmin, qmax (both 0: none): the FMU's outputs equal the Python Generator with
    the same limits bit for bit, q within them; limits in the wrong order, q0 outside and a
    target outside fail naming them."""
    lim = dict(qmin=-0.3, qmax=0.5)
    y = run_equal_to_the_generator(trajectory_dir, lim, np.r_[np.full(1500, 0.5), np.full(3000, -0.3)])
    assert y[:, 0].min() == -0.3 and y[:, 0].max() == 0.5
    for params, words in [(dict(qmin=1.0, qmax=-1.0), "qmin < qmax"),
                          (dict(qmin=0.1, qmax=1.0), "q0 = 0 is outside"),
                          (dict(qmin=-1.0, qmax=1.0, profile=1), "not the trigonometric")]:
        assert_start_refused(trajectory_dir, params, words)
    log = Logged()
    fmu = slave(trajectory_dir, logged=log)
    start(fmu, **lim)
    fmu.setReal([fmu.vr["target"]], [0.7])
    with pytest.raises(FMICallException):
        fmu.doStep(0.0, TS)
    assert "outside [qmin, qmax]" in log.messages[-1], log.messages[-1]
    fmu.freeInstance()
