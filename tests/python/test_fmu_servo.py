# SPDX-License-Identifier: Apache-2.0
"""ServoDrive.fmu against the servo testbed (smoothshaper.servo): the defaults are the
testbed's, every controller agrees with it in fmpy for three communication steps (to ten times
the loop's own rounding sensitivity, smoothshaper.fmi.servo), libcosim equals fmpy bit for bit,
the rest at initialization is the closed form, invalid parameters are refused by name, long
steps hold in closed form, and FMU states continue bit for bit."""
from __future__ import annotations

import math

import numpy as np
import pytest

fmpy = pytest.importorskip("fmpy", reason="fmpy is needed to import the FMUs")
from fmpy import extract, read_model_description  # noqa: E402
from fmpy.fmi1 import FMICallException  # noqa: E402

from smoothshaper import servo  # noqa: E402
from smoothshaper.fmi import servo as fs  # noqa: E402
from smoothshaper.servo import presets  # noqa: E402
from test_fmu_smoothshaper import Logged, fmus, slave  # noqa: E402,F401

TS = presets.TS


@pytest.fixture(scope="module")
def fmu(fmus):  # noqa: F811
    return fmus["ServoDrive"]


@pytest.fixture(scope="module")
def unzipped(fmu, tmp_path_factory):
    return extract(str(fmu), str(tmp_path_factory.mktemp("servo")))


def test_the_defaults_are_the_testbeds(fmu):
    v = fs.default_parameters(fmu)
    plant = servo.elastic_servo()
    assert {k: v[k] for k in ("Jm", "Jl", "n", "Dm", "Kel", "Del")} == {
        k: servo.NOTES[k] for k in ("Jm", "Jl", "n", "Dm", "Kel", "Del")}
    assert v["Ts"] == TS and v["controller"] == 0
    assert fs.testbed(v).config == presets.pid(plant)
    # the TDO's nominal model defaults to the plant's motor: the same loop
    tdo = fs.testbed({**v, "controller": 1})
    assert np.array_equal(tdo.A, servo.Drive(plant, presets.pid_tdo(plant), Ts=TS).A)
    assert fs.testbed({**v, "controller": 3}).config == presets.lqg()
    # Poles travel as (wn, zeta): back to (re, im) they are the presets' to one rounding.
    pp = fs.testbed({**v, "controller": 2}).config
    want = presets.pole_placement()
    assert pp.wf == want.wf
    for got, ref in ((pp.poles, want.poles), (pp.observer_poles, want.observer_poles)):
        assert np.allclose(got, ref, rtol=4e-16, atol=0)


def test_the_choices_are_integer_codes_with_every_code_named(unzipped):
    md = read_model_description(unzipped)
    byname = {mv.name: mv for mv in md.modelVariables}
    for name, codes in (("controller", fs.CONTROLLERS), ("notch.at", ("none", "loop", "reference")),
                        ("notch.discretization", ("matched", "tustin"))):
        mv = byname[name]
        assert mv.type == "Integer" and (int(mv.min), int(mv.max)) == (0, len(codes) - 1)
        assert all(f"{i} = {c} (" in mv.description for i, c in enumerate(codes))
    assert [mv.name for mv in md.modelVariables if mv.causality == "output"] == list(fs.OUTPUTS)
    assert [mv.name for mv in md.modelVariables if mv.causality == "input"] == ["q_ref",
                                                                               "tau_load"]
    assert byname["q_ref"].unit == "rad" and byname["tau_m"].unit == "N.m"


CASES = fs.VALIDATION_CASES


@pytest.mark.parametrize("name,overrides", CASES, ids=[c[0] for c in CASES])
@pytest.mark.parametrize("step", [TS, 4 * TS, 2.5 * TS], ids=["Ts", "4Ts", "2.5Ts"])
def test_fmu_equals_the_testbed(fmu, name, overrides, step):
    c = fs.compare(fmu, overrides, step=step, stop_time=1.2)
    assert c.passed, (name, c.error, c.tolerance)
    # The tolerance is the loop's rounding, far below what any output moves: at most 1.2e-8
    # of its range (the LQG's torque, whose feed-forward sums terms of 1e2 N m), 1e-11 to 1e-10
    # for most.
    assert all(c.tolerance[n] <= 3e-8 * c.scale[n] for n in fs.OUTPUTS), c.tolerance


@pytest.mark.parametrize("code", [0, 3], ids=["pid", "lqg"])
def test_libcosim_equals_fmpy_bit_for_bit(fmu, code):
    pytest.importorskip("libcosimpy", reason="libcosimpy is the second importer")
    t = np.arange(1201) * TS
    q_ref, tau = fs.reference_input(t, Ts=TS, t_torque=0.4)
    start = {"controller": code}
    a = fs.simulate_servo(fmu, t, q_ref, tau, start)
    b = fs.simulate_servo(fmu, t, q_ref, tau, start, importer="libcosim")
    for name in fs.OUTPUTS:
        assert np.array_equal(a[name][1:], b[name][1:]), name


def configure(f, values: dict, *, q_ref=0.0, tau_load=0.0):
    f.setupExperiment(startTime=0.0)
    f.enterInitializationMode()
    for name, value in values.items():
        if isinstance(value, int):
            f.setInteger([f.vr[name]], [value])
        else:
            f.setReal([f.vr[name]], [value])
    f.setReal([f.vr["q_ref"], f.vr["tau_load"]], [q_ref, tau_load])
    f.exitInitializationMode()


def outputs(f) -> np.ndarray:
    return np.array(f.getReal([f.vr[n] for n in fs.OUTPUTS]))


@pytest.mark.parametrize("code", range(4), ids=fs.CONTROLLERS)
def test_it_rests_at_the_initial_inputs(unzipped, code):
    """Integral action: the motor sits at n q_ref and the load behind the spring's twist,
    n q_l = q_m - tau_l / (n K_el); the torque carries the load, tau_m = tau_l / n. The FMU
    solves (I - Acl) Z = Bcl w for its rest, so it holds it to that solve's forward error,
    cond(I - Acl) u max |Z| (cond from the testbed's loop: 6e5 for the P/PI cascade, 1.7e9 for
    the state feedback, whose integrator and reference model sit near z = 1)."""
    f = slave(unzipped)
    q0, tau0 = 0.3, 2.0
    values = {**fs.default_parameters(unzipped),
              "controller": code}
    configure(f, {"controller": code}, q_ref=q0, tau_load=tau0)
    drive = fs.testbed(values)
    M = np.eye(drive.order) - drive.A
    Z = np.linalg.solve(M, drive.B @ [q0, tau0])
    tol = np.linalg.cond(M, np.inf) * np.finfo(float).eps / 2 * np.max(np.abs(Z))
    p = servo.NOTES
    want = np.array([p["n"] * q0, 0.0, q0 - tau0 / (p["n"] ** 2 * p["Kel"]), 0.0, tau0 / p["n"]])
    for k in range(3):
        got = outputs(f)
        assert np.all(np.abs(got - want) <= tol * np.array([1, 1, 1 / p["n"], 1 / p["n"], 1])), \
            (k, got - want, tol)
        f.doStep(k * TS, TS)
    f.freeInstance()


BAD = [
    ({"Ts": 0.0}, "Ts = 0"),
    ({"Jm": -1.0}, "Jm = -1"),
    ({"Ts": 0.01}, "Ts = 0.01: too long for this plant"),
    ({"controller": 4}, "controller = 4"),
    ({"pid.wcp": 200.0}, "pid.wcp = 200: must be below pid.wcv"),
    ({"pid.wcv": 5000.0, "pid.wcp": 100.0}, "the closed loop is unstable"),
    ({"controller": 0, "notch.at": 1, "notch.wn": 7000.0}, "notch.wn = 7000"),
    ({"controller": 0, "notch.at": 3}, "notch.at = 3"),
    ({"controller": 1, "tdo.Tf": -1.0}, "tdo.Tf = -1"),
    ({"controller": 2, "place.zeta[0]": 1.0}, "place.zeta[0] = 1"),
    ({"controller": 2, "place.wn[1]": 148.49242404917499, "place.zeta[1]": 0.70710678118654746},
     "the two pole pairs must be distinct"),
    ({"controller": 2, "observer.real[1]": 800.0}, "observer.real[1] = 800"),
    ({"controller": 3, "lq.Q[0]": 0.0, "lq.Q[2]": 0.0, "lq.Q[4]": 0.0}, "lq.Q: every weight"),
    ({"controller": 3, "kalman.encoder_noise": 0.0}, "kalman.encoder_noise = 0"),
    ({"controller": 3, "wf": -1.0}, "wf = -1"),
]


@pytest.mark.parametrize("values,text", BAD, ids=[t for _, t in BAD])
def test_invalid_parameters_are_refused_naming_them(unzipped, values, text):
    log = Logged()
    f = slave(unzipped, logged=log)
    with pytest.raises(FMICallException):
        configure(f, values)
    assert text in log.messages[-1], log.messages[-1]
    f.freeInstance()


def test_a_long_step_holds_in_closed_form(unzipped):
    """A step of 20,000 ticks (beyond the 16,384 the model ticks one by one) advances the
    deviation from the rest by Acl^(n-1) and ticks once; against 20 steps of 1,000 ticks the
    outputs differ by the ticks' rounding, which grows at most linearly: 8 n u of the largest
    value (Ts = 10 us keeps the move's transient alive over the step)."""
    values = {"controller": 0, "Ts": 1e-5}
    a, b = slave(unzipped, "a"), slave(unzipped, "b")
    for f in (a, b):
        configure(f, values)
        f.setReal([f.vr["q_ref"]], [0.2])
    a.doStep(0.0, 20000 * 1e-5)
    for k in range(20):
        b.doStep(k * 1000 * 1e-5, 1000 * 1e-5)
    ya, yb = outputs(a), outputs(b)
    assert abs(ya[3]) > 1e-3                                 # the load still moves
    scale = np.array([100 * 0.2, 30.0, 0.2, 0.3, 1.0])
    assert np.all(np.abs(ya - yb) <= 8 * 20000 * np.finfo(float).eps * scale), (ya, yb)
    for f in (a, b):
        f.freeInstance()


def test_fmu_states_continue_bit_for_bit(unzipped):
    values = {"controller": 3}
    t = np.arange(400) * TS
    q_ref, tau = fs.reference_input(t, Ts=TS, t_move=0.01, t_torque=0.1)

    def run(f, k0, k1):
        y = []
        for k in range(k0, k1):
            f.setReal([f.vr["q_ref"], f.vr["tau_load"]], [q_ref[k], tau[k]])
            f.doStep(k * TS, TS)
            y.append(outputs(f))
        return np.array(y)

    a = slave(unzipped, "a")
    configure(a, values)
    run(a, 0, 150)
    state = a.getFMUstate()
    blob = a.serializeFMUstate(state)
    first = run(a, 150, 400)
    a.setFMUstate(state)
    assert np.array_equal(run(a, 150, 400), first)
    b = slave(unzipped, "b")                  # fresh: default parameters until the state loads
    b.setFMUstate(b.deSerializeFMUstate(blob))
    assert np.array_equal(run(b, 150, 400), first)
    a.freeFMUstate(state)
    for f in (a, b):
        f.freeInstance()


def test_a_shaper_on_the_locked_mode_cuts_the_pid_drives_load_overshoot(fmu):
    """What the FMU is for: the same trapezoid with and without a ZV on the locked mode
    (docs/servo.md: 6.86 % -> 4.65 % load velocity overshoot for the notes' first move)."""
    import smoothshaper as sms
    plant = servo.elastic_servo()
    wz, zeta = plant.modes()["w_z"], plant.modes()["zeta_z"]
    t = np.arange(3201) * TS
    step = np.where(t >= 0.01, math.radians(40.0), 0.0)
    h = math.radians(40.0) * 100.0
    v = (1200.0 * 0.5 - math.sqrt(1200.0 ** 2 * 0.25 - 4 * 1200.0 * h)) / 2   # cruise, motor side
    trapezoid = [sms.rectangular(T=h / v), sms.rectangular(T=v / 1200.0)]
    over = []
    for stages in (trapezoid, trapezoid + [sms.shaper("zv", wn=wz, zeta=zeta)]):
        q_ref = sms.Chain(stages, Ts=TS).process(step)
        y = fs.simulate_servo(fmu, t, q_ref, np.zeros_like(t), {"controller": 0})
        over.append(100 * (np.max(y["w_l"]) / (v / 100.0) - 1))
    assert over[0] == pytest.approx(6.86, abs=0.01) and over[1] == pytest.approx(4.65, abs=0.01)
