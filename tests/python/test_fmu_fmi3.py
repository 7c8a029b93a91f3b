# SPDX-License-Identifier: Apache-2.0
"""The FMI 3.0 FMUs, built from the same model files as the FMI 2.0 ones, in fmpy: both
versions pass fmpy's validation and carry the licence; FMI 3.0 runs bit for bit as FMI 2.0 and
within the reference's tolerance of the NumPy reference for every model (MultiAxisGenerator's
arrays for 1 to 8 axes; ServoDrive for every controller), without fmpy's "missing input" warnings; the independent variable
time; serialised states move between the two versions; FMI 3.0's refusals."""
from __future__ import annotations

import zipfile
from pathlib import Path

import numpy as np
import pytest

fmpy = pytest.importorskip("fmpy", reason="fmpy is needed to import the FMUs")
from fmpy import extract, read_model_description  # noqa: E402
from fmpy.fmi3 import FMU3Slave, fmi3LogMessageCallback  # noqa: E402

from smoothshaper import fmi  # noqa: E402
from smoothshaper.fmi.cases import multi_axis_case, validation_cases  # noqa: E402
from smoothshaper.fmi.simulate import simulate_multi_axis  # noqa: E402
from smoothshaper.reference.multi_axis import multi_axis_reference  # noqa: E402
from test_fmu_smoothshaper import fmus  # noqa: E402,F401
from fmu_builds import fmu_build_dir  # noqa: E402

TS = 1e-3


@pytest.fixture(scope="session")
def fmus3(fmus):  # noqa: F811   (the FMI 2.0 build first: the same build folder)
    return fmi.build_fmus(fmu_build_dir(), fmi_version="3.0")


def test_both_versions_pass_fmpy_validate_and_state_the_licence(fmus, fmus3):  # noqa: F811
    assert set(fmus3) == set(fmus)
    for version, built in (("2.0", fmus), ("3.0", fmus3)):
        for model, path in built.items():
            assert fmi.fmpy_problems(path) == [], (version, model)
            md = read_model_description(str(path))
            assert md.fmiVersion == version
            with zipfile.ZipFile(path) as z:
                names = set(z.namelist())
                root = z.read("modelDescription.xml").decode()
                page = z.read("documentation/index.html").decode()
            assert 'license="Apache License 2.0' in root and "copyright=" in root
            assert "documentation/licenses/LICENSE.txt" in names
            assert "Apache License, Version 2.0" in page
            platform = "x86_64-linux" if version == "3.0" else "linux64"
            assert f"binaries/{platform}/{model}.so" in names
            if version == "3.0":   # the FMI 3.0 page names FMI 3.0's functions
                assert "fmi2" not in page and "sources/buildDescription.xml" in names


def _fmpy_run(path, t, signal_name, x, start, outputs):
    sig = np.zeros(t.size, dtype=[("time", float), (signal_name, float)])
    sig["time"], sig[signal_name] = t, x
    r = fmpy.simulate_fmu(str(path), start_values=start, input=sig, stop_time=float(t[-1]),
                          output_interval=float(t[1] - t[0]), output=outputs)
    return np.column_stack([np.asarray(r[n], dtype=float) for n in outputs])


def test_smoothshaper_fmi3_equals_fmi2_bit_for_bit(fmus, fmus3):  # noqa: F811
    t = fmi.communication_points(step=TS, stop_time=0.3)
    u = fmi.test_input(t)
    for name, stages in validation_cases(TS):
        start = fmi.start_values(stages, Ts=TS)
        y2 = _fmpy_run(fmus["SmoothShaper"], t, "u", u, start, ["y"])
        y3 = _fmpy_run(fmus3["SmoothShaper"], t, "u", u, start, ["y"])
        assert np.array_equal(y2, y3), name
        ref = fmi.expected_output(stages, t, u, Ts=TS)
        assert np.max(np.abs(y3[:, 0] - ref)) <= fmi.REL_TOL * np.max(np.abs(ref)), name


@pytest.mark.parametrize("params", [dict(profile=0), dict(profile=1, wn=60.0, zeta=0.05),
                                    dict(profile=2, wn=40.0, zeta=0.1)],
                         ids=["polynomial", "trigonometric+mode", "damped"])
def test_trajectory_generator_fmi3_equals_fmi2_and_the_reference(fmus, fmus3, params):  # noqa: F811
    t = fmi.communication_points(step=TS, stop_time=1.2)
    target = fmi.target_staircase(t)
    start = dict(Ts=TS, **fmi.TRAJECTORY_LIMITS, **params)
    y2 = _fmpy_run(fmus["TrajectoryGenerator"], t, "target", target, start, list("qvaj"))
    y3 = _fmpy_run(fmus3["TrajectoryGenerator"], t, "target", target, start, list("qvaj"))
    assert np.array_equal(y2, y3)
    names = dict(params, profile=("polynomial", "trigonometric", "damped")[params["profile"]])
    ref = fmi.expected_trajectory(t, target, Ts=TS, **fmi.TRAJECTORY_LIMITS, **names)
    scale = np.max(np.abs(ref), axis=0)
    assert np.all(np.max(np.abs(y3 - ref), axis=0) <= fmi.REL_TOL * scale)


def test_elastic_plant_fmi3_equals_fmi2(fmus, fmus3):  # noqa: F811
    t = fmi.communication_points(step=2.5 * TS, stop_time=0.3)
    u = fmi.test_input(t)
    y2 = _fmpy_run(fmus["ElasticPlant"], t, "u", u, {"Ts": TS}, ["y"])
    y3 = _fmpy_run(fmus3["ElasticPlant"], t, "u", u, {"Ts": TS}, ["y"])
    assert np.array_equal(y2, y3)


@pytest.mark.parametrize("controller", range(4))   # pid, pid_tdo, pole_placement, lqg
def test_servo_drive_fmi3_equals_fmi2_for_every_controller(fmus, fmus3, controller):  # noqa: F811
    from smoothshaper.fmi import servo
    t = fmi.communication_points(step=servo.TS, stop_time=0.6)
    q_ref, tau_load = servo.reference_input(t, Ts=servo.TS)
    y2, y3 = (servo.simulate_servo(f["ServoDrive"], t, q_ref, tau_load, {"controller": controller})
              for f in (fmus, fmus3))
    for name in servo.OUTPUTS:
        assert np.array_equal(y2[name], y3[name]), name
    assert servo.default_parameters(fmus3["ServoDrive"]) == servo.default_parameters(
        fmus["ServoDrive"])


def test_multi_axis_arrays_for_1_to_8_axes_equal_fmi2_and_the_reference(  # noqa: F811
        fmus, fmus3, capfd):
    t = fmi.communication_points(step=TS, stop_time=0.8)
    for axes in range(1, 9):
        values, target, ref_args = multi_axis_case(axes, t)
        y2 = simulate_multi_axis(fmus["MultiAxisGenerator"], t, target, values)
        y3 = simulate_multi_axis(fmus3["MultiAxisGenerator"], t, target, values)
        assert np.array_equal(y2, y3), axes
        x, n_at = fmi.tick_inputs(t, np.arange(t.size), Ts=TS)
        rows = multi_axis_reference(target[x.astype(int)], Ts=TS, **ref_args)
        rest = np.zeros((axes, 4))
        rest[:, 0] = ref_args["q0"]
        ref = fmi.at_communication_points(rows, n_at, rest)
        scale = np.max(np.abs(ref), axis=(0, 1))
        assert np.all(np.max(np.abs(y3 - ref), axis=(0, 1)) <= fmi.REL_TOL * scale), axes
    # every input given (the unused axes at their rest): fmpy warns of no missing input
    assert "missing input" not in capfd.readouterr().out


def test_multi_axis_with_two_axes_prints_no_missing_input_warning(fmus, fmus3, capfd):  # noqa: F811
    t = fmi.communication_points(step=TS, stop_time=0.05)
    values, _, _ = multi_axis_case(2, t)
    for path in (fmus["MultiAxisGenerator"], fmus3["MultiAxisGenerator"]):
        simulate_multi_axis(path, t, np.full((t.size, 2), 0.1), values)
    assert "missing input" not in capfd.readouterr().out


class Slave3:
    """An FMI 3.0 instance with its log messages collected."""

    def __init__(self, path: Path, tmp: Path, **instantiate):
        self.md = read_model_description(str(path))
        self.messages: list[str] = []
        self.fmu = FMU3Slave(guid=self.md.guid, unzipDirectory=extract(str(path), str(tmp)),
                             modelIdentifier=self.md.coSimulation.modelIdentifier,
                             instanceName="fmi3")
        self.callback = fmi3LogMessageCallback(
            lambda env, status, category, message: self.messages.append(message.decode()))
        self.fmu.instantiate(logMessage=self.callback, **instantiate)
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}


def test_time_is_the_communication_point_and_cannot_be_set(fmus3, tmp_path):
    s = Slave3(fmus3["SmoothShaper"], tmp_path)
    s.fmu.enterInitializationMode(startTime=1.7e9)
    s.fmu.exitInitializationMode()
    t = 1.7e9
    for k in range(1, 4):
        s.fmu.doStep(t, TS)
        t = 1.7e9 + k * TS
    assert s.fmu.getFloat64([s.vr["time"]]) == [1.7e9 + 3 * TS]
    with pytest.raises(Exception):
        s.fmu.setFloat64([s.vr["time"]], [0.0])
    assert any("independent variable" in m for m in s.messages)


def test_states_move_between_fmi3_and_fmi2(fmus, fmus3, tmp_path):  # noqa: F811
    """A state serialised by the FMI 3.0 FMU loads into the FMI 2.0 one of the same build (both
    tag it with the model's guid) and the two continue bit for bit."""
    from test_fmu_smoothshaper import slave
    s3 = Slave3(fmus3["SmoothShaper"], tmp_path / "3")
    s3.fmu.enterInitializationMode()
    s3.fmu.exitInitializationMode()
    u3, y3 = s3.vr["u"], s3.vr["y"]
    for k in range(40):
        s3.fmu.setFloat64([u3], [float(np.sin(0.3 * k))])
        s3.fmu.doStep(k * TS, TS)
    blob = s3.fmu.serializeFMUState(s3.fmu.getFMUState())
    s2 = slave(extract(str(fmus["SmoothShaper"]), str(tmp_path / "2")))
    s2.setupExperiment(startTime=0.0)
    s2.enterInitializationMode()
    s2.exitInitializationMode()
    s2.setFMUstate(s2.deSerializeFMUstate(blob))
    for k in range(40, 80):
        u = float(np.sin(0.3 * k))
        s3.fmu.setFloat64([u3], [u])
        s3.fmu.doStep(k * TS, TS)
        s2.setReal([u3], [u])
        s2.doStep(k * TS, TS)
        assert s2.getReal([y3]) == s3.fmu.getFloat64([y3])


def test_fmi3_refusals_name_what_is_wrong(fmus3, tmp_path):
    with pytest.raises(Exception):
        Slave3(fmus3["SmoothShaper"], tmp_path / "event", eventModeUsed=True)
    s = Slave3(fmus3["MultiAxisGenerator"], tmp_path / "ma")
    target = s.vr["target"]
    with pytest.raises(Exception):      # an array's later element is no FMI 3.0 variable
        s.fmu.setFloat64([target + 1], [0.0])
    with pytest.raises(Exception):      # nValues must be the array's 8 values
        s.fmu.setFloat64([target], [0.0, 1.0])
    s.fmu.setFloat64([target], [0.1] * 8)
    assert s.fmu.getFloat64([target], nValues=8) == [0.1] * 8
    with pytest.raises(Exception):
        s.fmu.enterEventMode()
    text = "\n".join(s.messages)
    assert "element of an array variable" in text and "nValues = 2" in text
    assert "no event mode" in text


def test_smoothshaper_retune_in_step_mode_equals_fmi2(fmus, fmus3, tmp_path):  # noqa: F811
    """The stages' tunable parameters are variability="tunable" in FMI 3.0 and set in Step
    Mode as in FMI 2.0 (checked at set, applied at the next communication point): the FMI 3.0
    run with two retunes, one of them during the switch of the first, equals the FMI 2.0 run
    bit for bit, and a retune beyond the stage's memory is refused naming the variable."""
    from test_fmu_smoothshaper import slave
    md = read_model_description(str(fmus3["SmoothShaper"]))
    tunable = {v.name: v.variability for v in md.modelVariables if v.name.startswith("stage[1].")}
    assert tunable["stage[1].wn"] == "tunable" and tunable["stage[1].kind"] == "fixed"
    reals = {"retune_max_delay": 0.05, "stage[0].T": 0.0153, "stage[1].wn": 200.0,
             "stage[1].zeta": 0.05}
    ints = {"stage[0].kind": 0, "stage[1].kind": 4}
    s3 = Slave3(fmus3["SmoothShaper"], tmp_path / "3")
    s2 = slave(extract(str(fmus["SmoothShaper"]), str(tmp_path / "2")))
    s3.fmu.enterInitializationMode()
    s2.setupExperiment(startTime=0.0)
    s2.enterInitializationMode()
    for name, value in reals.items():
        s3.fmu.setFloat64([s3.vr[name]], [value])
        s2.setReal([s3.vr[name]], [value])
    for name, value in ints.items():
        s3.fmu.setInt32([s3.vr[name]], [value])
        s2.setInteger([s3.vr[name]], [value])
    s3.fmu.exitInitializationMode()
    s2.exitInitializationMode()
    u, y, wn = s3.vr["u"], s3.vr["y"], s3.vr["stage[1].wn"]
    plan = {100: 150.0, 104: 260.0}
    for k in range(400):
        x = min(max((k - 20) * 0.004, 0.0), 1.0)
        if k in plan:
            s3.fmu.setFloat64([wn], [plan[k]])
            s2.setReal([wn], [plan[k]])
        s3.fmu.setFloat64([u], [x])
        s2.setReal([u], [x])
        s3.fmu.doStep(k * TS, TS)
        s2.doStep(k * TS, TS)
        assert s3.fmu.getFloat64([y, s3.vr["lag"]]) == s2.getReal([y, s3.vr["lag"]])
    with pytest.raises(Exception):
        s3.fmu.setFloat64([wn], [1.0])   # a ZV at 1 rad/s lasts far beyond retune_max_delay
    assert "stage[1].wn" in s3.messages[-1] and "retune_max_delay" in s3.messages[-1]
    assert s3.fmu.getFloat64([wn]) == [260.0]


@pytest.mark.parametrize("Ts", [1.7976931348623157e308, 2.0 ** 967 * (1 + 2.0 ** -52)])
def test_every_model_refuses_a_Ts_above_SMS_TS_MAX_naming_it(fmus3, Ts):
    """2^53 Ts (the longest time a state holds) must stay finite: every FMI 3.0 model refuses
    Ts > SMS_TS_MAX = 2^967 at ExitInitializationMode, the logger naming Ts and the bound."""
    from fmpy import simulate_fmu
    from fmpy.fmi1 import FMICallException
    for name, path in fmus3.items():
        messages = []
        with pytest.raises(FMICallException):
            simulate_fmu(str(path), start_values={"Ts": Ts}, stop_time=1e-2,
                         logger=lambda *a: messages.append(a[-1].decode()))
        assert any(f"Ts = {Ts!r}" in m and "(SMS_TS_MAX)" in m for m in messages), (name,
                                                                                 messages)


def test_smoothshaper_retune_narrowing_below_the_held_input_is_refused(fmus3, tmp_path):
    """FMI 3.0: fmi3SetFloat64 of a tunable parameter whose retune would narrow the range below
    the held u returns fmi3Error naming it and the values; the instance runs on unchanged."""
    from test_fmu_retune import DAMPED, HEAVY, LARGE_U, message_range, narrowed_range
    s3, twin = (Slave3(fmus3["SmoothShaper"], tmp_path / name) for name in ("a", "b"))
    for s in (s3, twin):
        s.fmu.enterInitializationMode()
        for name, value in {**DAMPED, "u": LARGE_U}.items():
            if isinstance(value, int):
                s.fmu.setInt32([s.vr[name]], [value])
            else:
                s.fmu.setFloat64([s.vr[name]], [value])
        s.fmu.exitInitializationMode()
    u, y, sigma = s3.vr["u"], s3.vr["y"], s3.vr["stage[0].sigma"]
    for k in range(120):
        if k == 40:
            with pytest.raises(Exception):
                s3.fmu.setFloat64([sigma], [HEAVY])
            assert "stage[0].sigma = -15000" in s3.messages[-1]
            assert message_range(s3.messages[-1]) == narrowed_range()
            assert s3.fmu.getFloat64([sigma]) == [-30.0]
        for s in (s3, twin):
            s.fmu.setFloat64([u], [LARGE_U * (1.0 - 0.004 * k)])
            s.fmu.doStep(k * TS, TS)
        assert s3.fmu.getFloat64([y]) == twin.fmu.getFloat64([y])
