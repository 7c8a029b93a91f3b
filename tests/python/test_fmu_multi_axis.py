# SPDX-License-Identifier: Apache-2.0
"""MultiAxisGenerator.fmu in fmpy (default settings, explicit output_interval) and libcosim:
equal to the NumPy multi-axis reference for 1 and 3 axes, phase-synchronised and independent,
without and with vibration stages per axis; FMU state round trip; bad parameters refused with
fmi2Error naming the variable; different stages per axis warned about through the logger."""
from __future__ import annotations

import numpy as np
import pytest

fmpy = pytest.importorskip("fmpy", reason="fmpy is needed to import the FMUs")
from fmpy import extract  # noqa: E402
from fmpy.fmi1 import FMICallException  # noqa: E402

from smoothshaper import fmi  # noqa: E402
from smoothshaper.reference.multi_axis import multi_axis_reference  # noqa: E402
from test_fmu_smoothshaper import Logged, fmus, slave  # noqa: E402,F401

TS = 1e-3
LIMITS = {1: dict(vmax=[0.8], amax=[6.0], jmax=[90.0]),
          3: dict(vmax=[0.8, 0.5, 1.2], amax=[6.0, 9.0, 4.0], jmax=[90.0, 200.0, 60.0])}
Q0 = {1: [0.05], 3: [0.05, -0.1, 0.0]}


@pytest.fixture(scope="session")
def multi_fmu(fmus):  # noqa: F811
    if "MultiAxisGenerator" not in fmus:
        pytest.skip("MultiAxisGenerator.fmu was not built")
    return fmus["MultiAxisGenerator"]


@pytest.fixture(scope="session")
def multi_dir(multi_fmu, tmp_path_factory):
    return extract(str(multi_fmu), str(tmp_path_factory.mktemp("ma")))


def staircase(t: np.ndarray, axes: int) -> np.ndarray:
    """Target vectors: a step at t = 0 (from q0), a change mid-motion, a reversal, a hold."""
    x = np.zeros((t.size, axes))
    plan = ((0.0, [0.3, 0.2, -0.25]), (0.18, [0.1, 0.35, 0.1]), (0.3, [-0.2, -0.1, 0.3]),
            (0.75, [-0.15, -0.1, 0.3]))
    for at, value in plan:
        x[t >= at - 1e-12] = value[:axes]
    return x


# Vibration stages per axis (kind code, wn, zeta) as the FMU's stage[k].kind/wn/zeta[i] take
# them: two stages on every axis (a ZV shaper and a notch), or one stage that differs by axis.
KIND = {"zv": 4, "zvd": 5, "notch_matched": 12, "rectangular": 0}
SAME_STAGES = [("zv", 40.0, 0.05), ("notch_matched", 70.0, 0.02)]
STAGES = {None: None, "same": {1: [SAME_STAGES], 3: [SAME_STAGES] * 3},
          "mixed": {1: [[("zvd", 25.0, 0.1)]],
                    3: [[("zvd", 25.0, 0.1)], [("rectangular", 31.0, 0.0)], SAME_STAGES]}}


def stage_list(triples):
    from smoothshaper import stages
    return [stages.for_mode(kind, wn=wn, zeta=zeta) for kind, wn, zeta in triples]


def start_values(axes: int, sync: int, stages=None) -> dict:
    values = {"Ts": TS, "axes": axes, "sync": sync}
    for name, v in LIMITS[axes].items():
        values.update({f"{name}[{i}]": x for i, x in enumerate(v)})
    values.update({f"q0[{i}]": x for i, x in enumerate(Q0[axes])})
    for i, triples in enumerate(STAGES[stages][axes] if stages else []):
        for k, (kind, wn, zeta) in enumerate(triples):
            values.update({f"stage[{k}].kind[{i}]": KIND[kind], f"stage[{k}].wn[{i}]": wn,
                           f"stage[{k}].zeta[{i}]": zeta})
    return values


def expected(t, target, axes, sync, stages=None) -> np.ndarray:
    """(n, axes, 4) at the communication points from the reference (fmpy timing: the input
    at t_k drives the ticks in (t_k, t_k+1], the outputs are the last tick's)."""
    x, n_at = fmi.tick_inputs(t, np.arange(t.size), Ts=TS)
    ticks = target[x.astype(int)]
    chains = [stage_list(tr) for tr in STAGES[stages][axes]] if stages else None
    rows = multi_axis_reference(ticks, Ts=TS, sync="phase" if sync == 0 else "independent",
                                q0=Q0[axes], stages=chains, **LIMITS[axes])
    rest = np.zeros((axes, 4))
    rest[:, 0] = Q0[axes]
    return fmi.at_communication_points(rows, n_at, rest)


def outputs(axes):
    return [f"{n}[{i}]" for i in range(axes) for n in "qvaj"]


def simulate_fmpy(fmu, t, target, axes, sync, stages=None) -> np.ndarray:
    # every axis's target given (the unused ones at rest): fmpy warns of no missing input
    from smoothshaper.fmi.simulate import simulate_multi_axis
    return simulate_multi_axis(fmu, t, target, start_values(axes, sync, stages))


def assert_matches(y, ref, axes):
    scale = np.array([np.abs(ref[:, :, 0]).max()] + [np.max(LIMITS[axes][k])
                                                     for k in ("vmax", "amax", "jmax")])
    err = np.abs(y - ref).max(axis=(0, 1)) / scale
    assert np.all(err <= 1e-12), err


@pytest.mark.parametrize("axes", [1, 3])
@pytest.mark.parametrize("sync", [0, 1], ids=["phase", "independent"])
@pytest.mark.parametrize("step", [TS, 2.5 * TS], ids=["Ts", "2.5Ts"])
def test_fmpy_equals_reference(multi_fmu, axes, sync, step):
    t = fmi.communication_points(step=step, stop_time=2.0)
    target = staircase(t, axes)
    y = simulate_fmpy(multi_fmu, t, target, axes, sync)
    ref = expected(t, target, axes, sync)
    assert_matches(y, ref, axes)
    lim = np.array([LIMITS[axes][k] for k in ("vmax", "amax", "jmax")]).T
    assert np.all(np.abs(y[:, :, 1:]) <= lim[None] * (1 + 1e-12))
    np.testing.assert_array_equal(y[-1, :, 0], target[-1])  # exact arrival on the held target


@pytest.mark.parametrize("axes", [1, 3])
@pytest.mark.parametrize("stages", ["same", "mixed"])
def test_fmpy_with_stages_equals_reference(multi_fmu, axes, stages):
    t = fmi.communication_points(step=2.5 * TS, stop_time=1.5)
    target = staircase(t, axes)
    y = simulate_fmpy(multi_fmu, t, target, axes, 0, stages)
    assert_matches(y, expected(t, target, axes, 0, stages), axes)


def test_same_stages_keep_a_straight_move_straight(multi_fmu):
    """Same stages on every axis, one rest-to-rest move from q0: q stays on the segment to
    1e-12 of the move, while moving and while the stages settle."""
    t = fmi.communication_points(step=TS, stop_time=1.0)
    goal = np.array([0.3, 0.2, -0.25])
    target = np.tile(goal, (t.size, 1))
    q = simulate_fmpy(multi_fmu, t, target, 3, 0, "same")[:, :, 0]
    d = goal - Q0[3]
    s = (q[:, 0] - Q0[3][0]) / d[0]
    assert np.abs(q - Q0[3] - np.outer(s, d)).max() <= 1e-12 * np.abs(d).max()
    assert s.max() > 1.0  # the notch overshoots a little: the test sees the whole filtered move


@pytest.mark.parametrize("axes", [1, 3])
@pytest.mark.parametrize("stages", [None, "same", "mixed"])  # mixed: fmi2Warning, accepted
def test_libcosim_equals_reference(multi_fmu, axes, stages):
    pytest.importorskip("libcosimpy", reason="libcosimpy is the second importer")
    t = fmi.communication_points(step=TS, stop_time=1.0)
    target = staircase(t, axes)
    y = run_libcosim(str(multi_fmu), t, target, axes, stages)
    ref = expected(t, target, axes, 0, stages)
    assert_matches(y[1:], ref[1:], axes)


def run_libcosim(fmu, t, target, axes, stages=None):
    """libcosim (libcosimpy) with every target component overridden before each step."""
    from fmpy import read_model_description
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimManipulator import CosimManipulator
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave
    log_output_level(CosimLogLevel.ERROR)
    vr = {v.name: v.valueReference for v in read_model_description(fmu).modelVariables}
    execution = CosimExecution.from_step_size(step_size=int(round((t[1] - t[0]) * 1e9)))
    index = execution.add_local_slave(local_slave=CosimLocalSlave(fmu_path=fmu, instance_name="m"))
    override = CosimManipulator.create_override()
    execution.add_manipulator(manipulator=override)
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer=observer)
    for name, value in start_values(axes, 0, stages).items():
        ok = (execution.integer_initial_value(index, vr[name], value) if isinstance(value, int)
              else execution.real_initial_value(index, vr[name], float(value)))
        assert ok, name
    ins = [vr[f"target[{i}]"] for i in range(axes)]
    outs = [vr[n] for n in outputs(axes)]
    y = np.full((t.size, axes * 4), np.nan)
    for k in range(t.size - 1):
        override.slave_real_values(index, ins, [float(x) for x in target[k]])
        assert execution.step()
        y[k + 1] = observer.last_real_values(index, outs)
    return y.reshape(t.size, axes, 4)


def start(fmu, **values):
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    for name, value in values.items():
        if isinstance(value, int):
            fmu.setInteger([fmu.vr[name]], [value])
        else:
            fmu.setReal([fmu.vr[name]], [value])
    fmu.exitInitializationMode()


@pytest.mark.parametrize("name,value,expected", [
    ("axes", 0, "axes = 0"), ("axes", 9, "axes = 9"), ("sync", 2, "sync = 2"),
    ("amax[1]", -2.0, "amax[1]"), ("vmax[2]", 0.0, "vmax[2]"), ("Ts", -1.0, "Ts"),
    ("stage[1].kind[2]", 23, "stage[1].kind[2] = 23"),
    ("stage[1].kind[2]", 22, "stage[1].kind[2] = 22"),   # impulses: no mode to design for
    ("stage[1].kind[2]", -2, "stage[1].kind[2] = -2"),
    ("stage[0].wn[1]", 5000.0, "stage[0].wn[1]"), ("stage[0].wn[1]", 0.0, "stage[0].wn[1]"),
    ("stage[1].zeta[0]", 1.0, "stage[1].zeta[0]"),
    ("stage[0].wn[0]", 1e-9, "stage[0].wn[0]"),
    # 2^53 Ts (the longest duration a state holds) must stay finite: Ts <= SMS_TS_MAX = 2^967
    ("Ts", 1.7976931348623157e308, "Ts = 1.7976931348623157e+308 is above"),
    ("Ts", 2.0 ** 967 * (1 + 2.0 ** -52), "(SMS_TS_MAX)")])
def test_bad_parameters_fail_naming_the_variable(multi_dir, name, value, expected):
    log = Logged()
    fmu = slave(multi_dir, "bad", logged=log)
    values = start_values(3, 0, "same")
    values[name] = value
    with pytest.raises(FMICallException):
        start(fmu, **values)
    assert expected in log.messages[-1], log.messages[-1]
    fmu.freeInstance()


def test_unused_axis_limits_are_ignored(multi_dir):
    fmu = slave(multi_dir, "two")
    values = start_values(3, 0)
    values.update({"axes": 2, "vmax[2]": 0.0})  # axis 2 is not in use
    start(fmu, **values)
    fmu.freeInstance()


@pytest.mark.parametrize("stages", [None, "mixed"])
def test_state_and_serialisation_round_trip(multi_dir, stages):
    a = slave(multi_dir, "a")
    start(a, **start_values(3, 0, stages))
    target = staircase(np.arange(900) * TS, 3)
    ins = [a.vr[f"target[{i}]"] for i in range(3)]
    outs = [a.vr[n] for n in outputs(3)]

    def run(f, t0, rows):
        y = []
        for k, row in enumerate(rows):
            f.setReal(ins, list(row))
            f.doStep(t0 + k * TS, TS)
            y.append(f.getReal(outs))
        return np.array(y)

    run(a, 0.0, target[:250])  # mid-motion, a change pending
    state = a.getFMUstate()
    blob = a.serializeFMUstate(state)
    first = run(a, 0.25, target[250:])
    a.setFMUstate(state)
    assert np.array_equal(run(a, 0.25, target[250:]), first)
    b = slave(multi_dir, "b")
    b.setFMUstate(b.deSerializeFMUstate(blob))
    assert np.array_equal(run(b, 0.25, target[250:]), first)
    for f in (a, b):
        f.freeInstance()


@pytest.mark.parametrize("stages, warned", [(None, False), ("same", False), ("mixed", True)])
def test_different_stages_per_axis_warn_through_the_logger(multi_dir, stages, warned):
    log = Logged()
    fmu = slave(multi_dir, "warn", logged=log)
    start(fmu, **start_values(3, 0, stages))  # fmi2Warning is no failure
    hits = [m for m in log.messages if "different vibration stages" in m]
    assert bool(hits) == warned, log.messages
    if warned:
        assert "axes 0 and 1" in hits[0] and "bend" in hits[0]
    fmu.doStep(0.0, TS)
    fmu.freeInstance()


def test_unused_axis_stages_are_ignored(multi_dir):
    values = start_values(3, 0, "same")
    values.update({"axes": 2, "stage[0].kind[2]": 99, "stage[0].wn[2]": 0.0})
    log = Logged()
    fmu = slave(multi_dir, "two", logged=log)
    start(fmu, **values)
    assert not [m for m in log.messages if "stage" in m], log.messages
    fmu.freeInstance()



@pytest.mark.parametrize("limits,quantity", [
    ({"vmax[1]": 1.0, "amax[1]": 1e-30, "jmax[1]": 1e-300}, "sqrt(vmax/jmax) (of vmax, jmax)"),
    ({"vmax[1]": 1.0, "amax[1]": 2.0 ** 57, "jmax[1]": 1.0}, "amax/vmax (of vmax, amax)")])
def test_limits_with_which_no_move_reaches_vmax_fail_naming_axis_and_quantity(
        multi_dir, limits, quantity):
    """Limits with which no move of axis 1 can reach its vmax (sms_multi_generator_reach)
    fail exitInitializationMode; the logger names the axis, its limits and the quantity."""
    log = Logged()
    fmu = slave(multi_dir, "reach", logged=log)
    values = start_values(3, 0, "same")
    values.update(limits)
    with pytest.raises(FMICallException):
        start(fmu, **values)
    message = log.messages[-1]
    assert "axis 1: vmax[1] = 1, amax[1] = " in message and quantity in message, message
    assert "no move of axis 1 that reaches vmax[1] can be planned" in message, message
    fmu.freeInstance()


@pytest.mark.parametrize("sync", [0, 1], ids=["phase", "independent"])
def test_a_dropped_target_vector_is_logged_once_and_the_step_warns(multi_dir, sync):
    """As the TrajectoryGenerator: a target 1e300 away on axis 1 (more than 2^52 ticks at
    vmax) is dropped; that doStep returns fmi2Warning and the logger names the target, once;
    the next steps under the same target are OK and quiet."""
    from fmpy.fmi2 import fmi2True
    log = Logged()
    fmu = slave(multi_dir, "ma", logged=log)
    start(fmu, **start_values(3, sync))
    statuses = []
    for i in range(4):
        fmu.setReal([fmu.vr[f"target[{k}]"] for k in range(3)], [0.1, 1e300, 0.0])
        statuses.append(fmu.fmi2DoStep(fmu.component, i * TS, TS, fmi2True))
    assert statuses == [1, 0, 0, 0]
    steps = [m for m in log.messages if m.startswith("fmi2DoStep")]
    assert len(steps) == 1 and "target[1] = 1.0000000000000001e+300" in steps[0], steps
    assert ("target[0] = 0.10000000000000001" in steps[0]) == (sync == 0)
    # the farthest axis's limits and Ts, as the user set them
    assert "Ts = 0.001 (farthest, axis 1:" in steps[0], steps
    assert "vmax[1] = 0.5, amax[1] = 9, jmax[1] = 200;" in steps[0], steps
    assert np.all(np.isfinite(fmu.getReal([fmu.vr[n] for n in outputs(3)])))
    fmu.freeInstance()


@pytest.mark.parametrize("sync", [0, 1], ids=["phase", "independent"])
def test_two_axes_dropping_in_one_step_are_both_named(multi_dir, sync):
    """Axes 0 and 1 at rest both get a target 1e300 away: one warning names both targets (two
    moves when independent, one when phase-synchronised), and the farthest axis's limits."""
    from fmpy.fmi2 import fmi2True
    log = Logged()
    fmu = slave(multi_dir, "ma", logged=log)
    start(fmu, **start_values(3, sync))
    fmu.setReal([fmu.vr[f"target[{k}]"] for k in range(3)], [-1e300, 1e300, 0.0])
    assert fmu.fmi2DoStep(fmu.component, 0.0, TS, fmi2True) == 1
    steps = [m for m in log.messages if m.startswith("fmi2DoStep")]
    assert len(steps) == 1, steps
    assert "target[0] = -1.0000000000000001e+300, target[1] = 1.0000000000000001e+300" \
        in steps[0], steps
    # vmax[1] = 0.5 < vmax[0] = 0.8: axis 1's cruise is the longer
    assert "(farthest, axis 1: " in steps[0] and "vmax[1] = 0.5, amax[1] = 9, jmax[1] = 200;" \
        in steps[0], steps
    fmu.freeInstance()


@pytest.mark.parametrize("sync", [0, 1], ids=["phase", "independent"])
def test_position_limits_equal_the_reference_and_fail_outside(multi_fmu, multi_dir, sync):
    """Parameters qmin[i], qmax[i] (both 0: none): the staircase, which retargets mid-motion,
    equals the reference under the same limits (no blend for a limited group), every q inside;
    a target outside fails the step naming it; limits out of order or a q0 outside fail
    initialisation naming them."""
    lo, hi = [-0.3, -0.2, -0.3], [0.35, 0.4, 0.35]
    values = start_values(3, sync)
    values.update({f"qmin[{i}]": x for i, x in enumerate(lo)})
    values.update({f"qmax[{i}]": x for i, x in enumerate(hi)})
    t = fmi.communication_points(step=TS, stop_time=2.0)
    target = staircase(t, 3)
    from smoothshaper.fmi.simulate import simulate_multi_axis
    y = simulate_multi_axis(multi_fmu, t, target, values)
    x, n_at = fmi.tick_inputs(t, np.arange(t.size), Ts=TS)
    rows = multi_axis_reference(target[x.astype(int)], Ts=TS,
                                sync="phase" if sync == 0 else "independent", q0=Q0[3],
                                qmin=lo, qmax=hi, **LIMITS[3])
    rest = np.zeros((3, 4))
    rest[:, 0] = Q0[3]
    assert_matches(y, fmi.at_communication_points(rows, n_at, rest), 3)
    assert np.all(y[:, :, 0] >= lo) and np.all(y[:, :, 0] <= hi)
    log = Logged()
    fmu = slave(multi_dir, "outside", logged=log)
    start(fmu, **values)
    fmu.setReal([fmu.vr["target[1]"]], [0.5])
    with pytest.raises(FMICallException):
        fmu.doStep(currentCommunicationPoint=0.0, communicationStepSize=TS)
    assert "target[1] = 0.5 is outside [qmin[1], qmax[1]]" in log.messages[-1], log.messages[-1]
    fmu.freeInstance()
    for changes, words in [({"qmin[2]": 0.5}, "qmin[2] = 0.5, qmax[2] = 0.34999999999999998"),
                           ({"q0[0]": 0.4}, "q0[0] = 0.40000000000000002 is outside")]:
        log = Logged()
        fmu = slave(multi_dir, "bad-limits", logged=log)
        with pytest.raises(FMICallException):
            start(fmu, **{**values, **changes})
        assert words in log.messages[-1], log.messages[-1]
        fmu.freeInstance()
