# SPDX-License-Identifier: Apache-2.0
"""SmoothShaper.fmu through fmpy: model description, reference agreement for every family and
three kinds of communication step, FMU state (get/set, serialise), error handling, instances."""
from __future__ import annotations

import math
import shutil
from pathlib import Path

import numpy as np
import pytest

fmpy = pytest.importorskip("fmpy", reason="fmpy is needed to import the FMUs")
from fmpy import extract, read_model_description  # noqa: E402
from fmpy.fmi2 import FMU2Slave, fmi2CallbackFunctions, fmi2CallbackLoggerTYPE  # noqa: E402
from fmpy.fmi1 import FMICallException  # noqa: E402

from smoothshaper import fmi  # noqa: E402
from smoothshaper.stages import damped_harmonic, harmonic, notch, rectangular, shaper  # noqa: E402
from fmu_builds import fmu_build_dir  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
TS = 1e-3


@pytest.fixture(scope="session")
def fmus():
    if shutil.which("cmake") is None:
        pytest.skip("cmake is needed to build the FMUs")
    return fmi.build_fmus(fmu_build_dir())


@pytest.fixture(scope="session")
def smoothshaper_dir(fmus, tmp_path_factory):
    return extract(str(fmus["SmoothShaper"]), str(tmp_path_factory.mktemp("ss")))


def test_fmpy_finds_no_problem(fmus):
    for path in fmus.values():
        assert fmi.fmpy_problems(path) == []


CASES = fmi.validation_cases(TS)


@pytest.mark.parametrize("name,stages", CASES, ids=[c[0] for c in CASES])
@pytest.mark.parametrize("step", [TS, 7 * TS, 2.5 * TS], ids=["Ts", "7Ts", "2.5Ts"])
def test_fmu_equals_reference(fmus, name, stages, step):
    # Double rounding only: the FMU and the reference compute the same taps independently.
    *_, err, rel = fmi.compare(fmus["SmoothShaper"], stages, Ts=TS, step=step, stop_time=0.3)
    assert rel <= fmi.REL_TOL, (name, err)


# ---------------------------------------------------------------- low-level driving

class Logged:
    """fmpy callbacks that keep the FMU's log messages."""

    def __init__(self):
        self.messages: list[str] = []
        self.callbacks = fmi2CallbackFunctions()
        self.callbacks.logger = fmi2CallbackLoggerTYPE(self._log)
        self.callbacks.allocateMemory = fmpy.fmi2.defaultCallbacks.allocateMemory
        self.callbacks.freeMemory = fmpy.fmi2.defaultCallbacks.freeMemory

    def _log(self, env, name, status, category, message):
        self.messages.append(message.decode().replace("%%", "%"))


def vrs(unzipdir):
    md = read_model_description(unzipdir)
    return {v.name: v.valueReference for v in md.modelVariables}, md


def slave(unzipdir, name="ss", logged: Logged | None = None) -> FMU2Slave:
    names, md = vrs(unzipdir)
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=unzipdir,
                    modelIdentifier=md.coSimulation.modelIdentifier, instanceName=name)
    fmu.instantiate(callbacks=logged.callbacks if logged else None, loggingOn=logged is not None)
    if logged is not None:   # errors and warnings only: no call trace
        fmu.setDebugLogging(False, ["logCalls"])
    fmu.vr = names
    return fmu


def configure(fmu, stages, *, u0=0.0, Ts=TS):
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    for name, value in fmi.start_values(stages, Ts=Ts).items():
        if isinstance(value, int):
            fmu.setInteger([fmu.vr[name]], [value])
        else:
            fmu.setReal([fmu.vr[name]], [value])
    fmu.setReal([fmu.vr["u"]], [u0])
    fmu.exitInitializationMode()


def run(fmu, t0, u, step=TS):
    y = np.empty(len(u))
    for i, ui in enumerate(u):
        fmu.setReal([fmu.vr["u"]], [ui])
        fmu.doStep(t0 + i * step, step)
        y[i] = fmu.getReal([fmu.vr["y"]])[0]
    return y


CHAIN = [rectangular(T=17.3 * TS), harmonic(T=9 * TS), shaper("zvd", wn=2 * math.pi * 9, zeta=0.1),
         notch(wn=300.0, zeta=0.05, notch_pole_zeta=0.6)]
U = np.random.default_rng(4).uniform(-1, 2, 300)


def test_state_get_set_is_bit_identical(smoothshaper_dir):
    fmu = slave(smoothshaper_dir)
    configure(fmu, CHAIN, u0=0.3)
    run(fmu, 0.0, U[:100])
    state = fmu.getFMUstate()
    first = run(fmu, 0.1, U[100:])
    fmu.setFMUstate(state)
    again = run(fmu, 0.1, U[100:])
    assert np.array_equal(first, again)
    fmu.freeFMUstate(state)
    fmu.terminate()
    fmu.freeInstance()


def test_serialised_state_continues_identically_in_a_fresh_instance(smoothshaper_dir):
    a = slave(smoothshaper_dir, "a")
    configure(a, CHAIN, u0=-0.2)
    run(a, 0.0, U[:100])
    blob = a.serializeFMUstate(a.getFMUstate())
    expected = run(a, 0.1, U[100:])
    b = slave(smoothshaper_dir, "b")        # fresh: only instantiated, default parameters
    b.setFMUstate(b.deSerializeFMUstate(blob))
    assert np.array_equal(run(b, 0.1, U[100:]), expected)
    for f in (a, b):
        f.freeInstance()


def test_corrupted_truncated_or_foreign_blob_is_refused(smoothshaper_dir):
    log = Logged()
    fmu = slave(smoothshaper_dir, logged=log)
    configure(fmu, CHAIN)
    run(fmu, 0.0, U[:20])
    blob = bytes(fmu.serializeFMUstate(fmu.getFMUstate()))
    flipped = bytearray(blob)
    flipped[len(blob) // 2] ^= 0x10
    foreign = bytearray(blob)
    foreign[20] ^= 0x01                      # inside the instantiation token
    for bad in (bytes(flipped), blob[:-9], blob[:7], bytes(foreign), b"", b"SMSF" + b"\0" * 40):
        with pytest.raises(FMICallException):
            fmu.deSerializeFMUstate(bad)
    assert any("checksum" in m for m in log.messages)
    # The instance is unaffected and goes on as before.
    fmu.setFMUstate(fmu.deSerializeFMUstate(blob))
    fmu.freeInstance()


def test_two_instances_with_different_parameters_do_not_interact(smoothshaper_dir):
    a, b = slave(smoothshaper_dir, "a"), slave(smoothshaper_dir, "b")
    stages_a = [rectangular(T=12 * TS)]
    stages_b = [damped_harmonic(T=33.3 * TS, sigma=-20.0), shaper("ei", wn=150.0, zeta=0.05)]
    configure(a, stages_a, u0=1.0)
    configure(b, stages_b, u0=-1.0)
    ya, yb = np.empty(U.size), np.empty(U.size)
    for i, u in enumerate(U):                # interleaved, opposite inputs
        a.setReal([a.vr["u"]], [u])
        b.setReal([b.vr["u"]], [-u])
        a.doStep(i * TS, TS)
        b.doStep(i * TS, TS)
        ya[i], yb[i] = a.getReal([a.vr["y"]])[0], b.getReal([b.vr["y"]])[0]
    t = np.arange(U.size + 1) * TS
    for y, stages, u, rest in ((ya, stages_a, U, 1.0), (yb, stages_b, -U, -1.0)):
        # The value read after the step from t_k is the one recorded at t_{k+1}.
        ref = fmi.expected_output(stages, t, np.r_[u, u[-1]], Ts=TS, rest=rest)
        assert np.max(np.abs(y - ref[1:])) <= fmi.REL_TOL * np.max(np.abs(ref))
    for f in (a, b):
        f.freeInstance()


def test_bad_parameters_fail_at_exit_initialization_naming_the_variable(smoothshaper_dir):
    log = Logged()
    fmu = slave(smoothshaper_dir, logged=log)
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    with pytest.raises(FMICallException):
        fmu.setReal([fmu.vr["stage[1].T"]], [float("nan")])
    assert "stage[1].T must be finite" in log.messages[-1]
    fmu.setInteger([fmu.vr["stage[2].kind"]], [5])          # zvd
    fmu.setReal([fmu.vr["stage[2].zeta"]], [1.5])
    with pytest.raises(FMICallException):
        fmu.exitInitializationMode()
    assert "stage[2].zeta" in log.messages[-1]
    fmu.setReal([fmu.vr["stage[2].zeta"]], [0.1])           # still in initialization mode
    fmu.exitInitializationMode()
    with pytest.raises(FMICallException):                  # fixed parameter after init
        fmu.setReal([fmu.vr["Ts"]], [0.002])
    with pytest.raises(FMICallException):                  # unknown value reference
        fmu.getReal([99999])
    with pytest.raises(FMICallException):                  # wrong order
        fmu.enterInitializationMode()
    fmu.doStep(0.0, TS)
    with pytest.raises(FMICallException):                  # not the end of the last step
        fmu.doStep(0.5, TS)
    with pytest.raises(FMICallException):
        fmu.doStep(TS, -TS)
    fmu.reset()                                            # back to instantiated, defaults
    configure(fmu, [])
    assert run(fmu, 0.0, [2.0, 3.0]).tolist() == [2.0, 3.0]   # no stage: y is the held input
    fmu.freeInstance()


@pytest.mark.parametrize("model", ["SmoothShaper", "TrajectoryGenerator"])
def test_sources_rebuild_with_fmpy_compile(fmus, tmp_path, model):
    # fmpy compile reads <SourceFiles> and compiles with sources/ as the only include directory.
    from fmpy.build import build_platform_binary
    if model not in fmus:
        pytest.skip(f"{model}.fmu was not built")
    unzipdir = extract(str(fmus[model]), str(tmp_path / "src"))
    binary = Path(unzipdir) / "binaries" / "linux64" / f"{model}.so"
    binary.unlink()
    (tmp_path / "build").mkdir()
    # Debug (-O0): what is checked is that the listed sources build and run as the FMU does;
    # fmpy's default Release took 12 s of CPU for SmoothShaper, Debug 5 s.
    build_platform_binary(unzipdir, build_dir=tmp_path / "build", configuration="Debug")
    assert binary.is_file()
    t = fmi.communication_points(step=TS, stop_time=0.1)
    if model == "SmoothShaper":
        stages = [rectangular(T=10 * TS), shaper("zv", wn=100.0)]
        u = fmi.test_input(t)
        y = fmi.simulate(unzipdir, stages, t, u, Ts=TS)
        ref = fmi.expected_output(stages, t, u, Ts=TS)
    else:
        target = fmi.target_staircase(t)
        y = fmi.simulate_trajectory(unzipdir, t, target, Ts=TS, **fmi.TRAJECTORY_LIMITS)
        ref = fmi.expected_trajectory(t, target, Ts=TS, **fmi.TRAJECTORY_LIMITS)
        y, ref = y[:, :3], ref[:, :3]
    assert np.max(np.abs(y - ref)) <= fmi.REL_TOL * np.max(np.abs(ref))


@pytest.mark.parametrize("model", ["SmoothShaper", "TrajectoryGenerator"])
def test_only_fmi2_symbols_are_exported(fmus, tmp_path, model):
    nm = shutil.which("nm")
    if nm is None:
        pytest.skip("nm is needed to list the exported symbols")
    if model not in fmus:
        pytest.skip(f"{model}.fmu was not built")
    import subprocess
    unzipdir = extract(str(fmus[model]), str(tmp_path / "x"))
    so = Path(unzipdir) / "binaries" / "linux64" / f"{model}.so"
    out = subprocess.run([nm, "-D", "--defined-only", str(so)], capture_output=True, text=True,
                         check=True).stdout
    names = [line.split()[-1] for line in out.splitlines() if line.split()[-2] in "TDBR"]
    assert names and all(n.startswith("fmi2") for n in names), names


def test_fmutool_check_passes(fmus):
    pytest.importorskip("fmu_manipulation_toolbox", reason="fmu-manipulation-toolbox provides fmutool")
    for path in fmus.values():
        assert fmi.fmutool_problems(path) == []


@pytest.mark.parametrize("name,stages", CASES, ids=[c[0] for c in CASES])
def test_libcosim_sets_every_kind_and_equals_fmpy_bit_for_bit(fmus, name, stages):
    # libcosim ignores FMI Enumerations: the kinds are Integer codes, so every family is settable.
    pytest.importorskip("libcosimpy", reason="libcosimpy is the second importer")
    d_importers, d_reference = fmi.compare_importers(fmus["SmoothShaper"], stages, Ts=TS)
    assert d_importers == 0.0                   # same binary, same calls: same bits
    assert d_reference <= 4 * fmi.REL_TOL  # |y| <= ~4: the reference's rounding


def test_the_importer_cases_cover_every_stage_kind():
    assert {s.kind for _, stages in CASES for s in stages} == set(fmi.KIND_VALUES)


def test_every_choice_is_an_integer_code_with_bounds_and_names(fmus):
    for path in fmus.values():
        md = read_model_description(str(path))
        assert not md.typeDefinitions or all(t.type != "Enumeration" for t in md.typeDefinitions)
        for v in md.modelVariables:
            assert v.type in ("Real", "Integer"), v.name
            if v.name.endswith((".kind", ".design", ".timing")) or v.name == "profile":
                assert v.type == "Integer" and v.min is not None and v.max is not None, v.name
                codes = range(int(v.min), int(v.max) + 1)
                assert all(f"{c} = " in v.description for c in codes), v.description
    md = read_model_description(str(fmus["SmoothShaper"]))
    kind = next(v for v in md.modelVariables if v.name == "stage[0].kind")
    assert (int(kind.min), int(kind.max)) == (-1, len(fmi.KIND_VALUES) - 1)
    for name, code in fmi.KIND_VALUES.items():
        assert f"{code} = {name} " in kind.description


def test_inputs_are_continuous_outputs_have_no_direct_feedthrough(fmus):
    for path in fmus.values():
        md = read_model_description(str(path))
        inputs = [v for v in md.modelVariables if v.causality == "input"]
        # Real inputs are continuous; an Integer input (a choice) can only be discrete
        assert inputs and all(v.variability == ("continuous" if v.type == "Real" else "discrete")
                              for v in inputs)
        assert md.outputs and all(u.dependencies == [] for u in md.outputs)
        # at initialization the outputs are the rest point: computed from the input, or from
        # the rest positions q0[i] (MultiAxisGenerator)
        rest = [v for v in md.modelVariables if v.name.startswith("q0[")] or inputs
        assert all(u.dependencies and set(u.dependencies) <= set(rest)
                   for u in md.initialUnknowns)
        reals = [v for v in md.modelVariables if v.causality == "parameter" and v.type == "Real"
                 and v.name.split("[")[0] not in ("q0", "qmin", "qmax", "schedule.value")]
        # a rest position, position limits and a scheduling value (a position, a load) have no
        # natural bound
        assert all(v.min is not None or v.max is not None for v in reals)
        assert all(v.unit in (None, "s", "1/s", "rad/s", "1", "kg.m2", "N.m/rad", "N.m.s/rad",
                              "rad", "N.m") for v in md.modelVariables)
        # (a duration input, TrajectoryGenerator's minimum_duration, is in seconds)
        signals = [v for v in md.modelVariables if v.causality in ("input", "output")
                   and v.name != "minimum_duration"]
        assert all(v.unit == "s" for v in md.modelVariables if v.name == "minimum_duration")
        if md.modelName != "ServoDrive":   # a drive's signals are angles and torques
            assert all(v.unit is None for v in signals)   # any unit: the filters are linear
        else:
            assert all(v.unit in ("rad", "rad/s", "N.m") for v in signals)


def test_setting_u_does_not_change_y_before_the_next_step(smoothshaper_dir):
    fmu = slave(smoothshaper_dir)
    configure(fmu, [rectangular(T=3 * TS)], u0=0.0)
    run(fmu, 0.0, [1.0] * 5)
    before = fmu.getReal([fmu.vr["y"]])[0]
    fmu.setReal([fmu.vr["u"]], [-7.0])
    assert fmu.getReal([fmu.vr["y"]])[0] == before
    fmu.freeInstance()


@pytest.mark.parametrize("values,expected", [
    ({"Ts": -0.001}, "Ts = -0.001"),
    ({"stage[1].zeta": 1.5}, "stage[1].zeta = 1.5"),
    ({"stage[0].kind": 99}, "stage[0].kind = 99"),
    ({"stage[1].timing": 2}, "stage[1].timing = 2 (bounded) is for the rectangular (0) and"),
    ({"stage[0].timing": 3}, "stage[0].timing = 3 is not exact (0), paper (1) or bounded (2)"),
])
def test_errors_reach_the_logger_with_logging_off(fmus, capfd, values, expected):
    # fmpy's default simulate_fmu: debug logging off, its own logger prints to stdout.
    with pytest.raises(FMICallException):
        fmpy.simulate_fmu(str(fmus["SmoothShaper"]), stop_time=0.01, start_values=values,
                          validate=False)
    out = capfd.readouterr()
    assert expected in out.out + out.err


def test_fmpy_runs_of_the_package_drive_every_input(fmus, capsys):
    """fmi.run_fmpy gives fmpy a column for each scalar input the caller does not drive (held
    at its start value), so fmpy prints no "missing input" warning; the outputs equal a run
    that drives only the target."""
    from smoothshaper.fmi.simulate import run_fmpy
    from smoothshaper.trajectory import Generator
    t = np.arange(201) * 1e-3
    target = np.where(t < 0.05, 0.0, 0.2)
    capsys.readouterr()
    r = run_fmpy(fmus["TrajectoryGenerator"], t, {"target": target},
                 {"Ts": 1e-3, "vmax": 1.0, "amax": 10.0, "jmax": 100.0}, ["q"])
    assert "missing input" not in capsys.readouterr().out
    # fmpy records the outputs of the inputs at t_k at t_(k+1)
    ref = Generator(Ts=1e-3, vmax=1.0, amax=10.0, jmax=100.0).process(target)[:, 0]
    assert np.array_equal(r["q"][1:], ref[:-1])
