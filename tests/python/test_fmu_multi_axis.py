"""MultiAxisGenerator.fmu in fmpy (default settings, explicit output_interval) and libcosim:
equal to the NumPy multi-axis reference for 1 and 3 axes, phase-synchronised and independent;
FMU state round trip; bad parameters refused with fmi2Error naming the variable."""
from __future__ import annotations

import numpy as np
import pytest

fmpy = pytest.importorskip("fmpy", reason="fmpy is needed to import the FMUs")
from fmpy import extract  # noqa: E402
from fmpy.fmi1 import FMICallException  # noqa: E402

from smoothshaper import validation  # noqa: E402
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


def start_values(axes: int, sync: int) -> dict:
    values = {"Ts": TS, "axes": axes, "sync": sync}
    for name, v in LIMITS[axes].items():
        values.update({f"{name}[{i}]": x for i, x in enumerate(v)})
    values.update({f"q0[{i}]": x for i, x in enumerate(Q0[axes])})
    return values


def expected(t, target, axes, sync) -> np.ndarray:
    """(n, axes, 4) at the communication points from the reference (fmpy timing: the input
    at t_k drives the ticks in (t_k, t_k+1], the outputs are the last tick's)."""
    x, n_at = validation.tick_inputs(t, np.arange(t.size), Ts=TS)
    ticks = target[x.astype(int)]
    rows = multi_axis_reference(ticks, Ts=TS, sync="phase" if sync == 0 else "independent",
                                q0=Q0[axes], **LIMITS[axes])
    rest = np.zeros((axes, 4))
    rest[:, 0] = Q0[axes]
    return validation.at_communication_points(rows, n_at, rest)


def outputs(axes):
    return [f"{n}[{i}]" for i in range(axes) for n in "qvaj"]


def simulate_fmpy(fmu, t, target, axes, sync) -> np.ndarray:
    names = [f"target[{i}]" for i in range(axes)]
    signal = np.zeros(t.size, dtype=[("time", float)] + [(n, float) for n in names])
    signal["time"] = t
    for i, n in enumerate(names):
        signal[n] = target[:, i]
    r = fmpy.simulate_fmu(str(fmu), start_values=start_values(axes, sync), input=signal,
                          stop_time=float(t[-1]), output_interval=float(t[1] - t[0]),
                          output=outputs(axes))
    return np.stack([np.asarray(r[n], dtype=float) for n in outputs(axes)],
                    axis=1).reshape(t.size, axes, 4)


def assert_matches(y, ref, axes):
    scale = np.array([np.abs(ref[:, :, 0]).max()] + [np.max(LIMITS[axes][k])
                                                     for k in ("vmax", "amax", "jmax")])
    err = np.abs(y - ref).max(axis=(0, 1)) / scale
    assert np.all(err <= 1e-12), err


@pytest.mark.parametrize("axes", [1, 3])
@pytest.mark.parametrize("sync", [0, 1], ids=["phase", "independent"])
@pytest.mark.parametrize("step", [TS, 2.5 * TS], ids=["Ts", "2.5Ts"])
def test_fmpy_equals_reference(multi_fmu, axes, sync, step):
    t = validation.communication_points(step=step, stop_time=2.0)
    target = staircase(t, axes)
    y = simulate_fmpy(multi_fmu, t, target, axes, sync)
    ref = expected(t, target, axes, sync)
    assert_matches(y, ref, axes)
    lim = np.array([LIMITS[axes][k] for k in ("vmax", "amax", "jmax")]).T
    assert np.all(np.abs(y[:, :, 1:]) <= lim[None] * (1 + 1e-12))
    np.testing.assert_array_equal(y[-1, :, 0], target[-1])  # exact arrival on the held target


@pytest.mark.parametrize("axes", [1, 3])
def test_libcosim_equals_reference(multi_fmu, axes):
    pytest.importorskip("libcosimpy", reason="libcosimpy is the second importer")
    t = validation.communication_points(step=TS, stop_time=1.0)
    target = staircase(t, axes)
    y = run_libcosim(str(multi_fmu), t, target, axes)
    ref = expected(t, target, axes, 0)
    assert_matches(y[1:], ref[1:], axes)


def run_libcosim(fmu, t, target, axes):
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
    for name, value in start_values(axes, 0).items():
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
        if name in ("axes", "sync"):
            fmu.setInteger([fmu.vr[name]], [value])
        else:
            fmu.setReal([fmu.vr[name]], [value])
    fmu.exitInitializationMode()


@pytest.mark.parametrize("name,value,expected", [
    ("axes", 0, "axes = 0"), ("axes", 9, "axes = 9"), ("sync", 2, "sync = 2"),
    ("amax[1]", -2.0, "amax[1]"), ("vmax[2]", 0.0, "vmax[2]"), ("Ts", -1.0, "Ts")])
def test_bad_parameters_fail_naming_the_variable(multi_dir, name, value, expected):
    log = Logged()
    fmu = slave(multi_dir, "bad", logged=log)
    values = start_values(3, 0)
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


def test_state_and_serialisation_round_trip(multi_dir):
    a = slave(multi_dir, "a")
    start(a, **start_values(3, 0))
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
