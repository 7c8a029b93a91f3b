# SPDX-License-Identifier: Apache-2.0
"""SmoothShaper.fmu retuned while it runs and scheduled by its input s, in fmpy and libcosim:
a tunable parameter set at a communication point takes effect on the next tick, bit for bit
the Python TunableChain retuned there (the same C core); one set while the stage is still
switching waits until the switch ends, as the core's rule says; the lag output is the active
stages' lag; the scheduled shaper equals ScheduledShaper fed the same s; a state serialised in
the middle of a switch continues bit for bit; refusals name the variable and change nothing."""
from __future__ import annotations

import numpy as np
import pytest

fmpy = pytest.importorskip("fmpy", reason="fmpy is needed to import the FMUs")
from fmpy import extract  # noqa: E402
from fmpy.fmi1 import FMICallException  # noqa: E402

import smoothshaper as sms  # noqa: E402
from smoothshaper.scheduled import ScheduledShaper  # noqa: E402
from test_fmu_multi_axis import start as base_start  # noqa: E402
from test_fmu_smoothshaper import Logged, fmus, slave  # noqa: E402,F401

TS = 1e-3
ZV, RECT = 4, 0
SCHEDULED_ZV = 0   # schedule.kind codes: 0 zv, 1 zvd, 2 zvdd, 3 zvn
STAGES = {"stage[0].kind": RECT, "stage[0].T": 0.0153, "stage[1].kind": ZV,
          "stage[1].wn": 200.0, "stage[1].zeta": 0.05}
TABLE = [(0.0, 150.0, 0.02), (0.5, 190.0, 0.03), (1.0, 240.0, 0.05)]


@pytest.fixture(scope="module")
def ss_dir(fmus, tmp_path_factory):  # noqa: F811
    return extract(str(fmus["SmoothShaper"]), str(tmp_path_factory.mktemp("ssr")))


def start(fmu, values, u0=0.0):
    base_start(fmu, **{**values, "u": float(u0)})


def move(n=900):
    t = np.arange(n)
    return np.clip((t - 50) * 0.002, 0.0, 1.0) + 0.3 * np.clip((t - 500) * 0.004, 0.0, 1.0)


def test_retune_at_a_communication_point_equals_tunable_chain(ss_dir):
    u = move()
    fmu = slave(ss_dir)
    start(fmu, {**STAGES, "retune_max_delay": 0.05})
    chain = sms.TunableChain([sms.rectangular(T=0.0153), sms.shaper("zv", wn=200.0, zeta=0.05)],
                             Ts=TS, capacity=[None, sms.shaper("zv", wn=150.0, zeta=0.05)])
    plan = {300: 150.0, 305: 260.0, 650: 175.0}   # the second arrives during the switch
    y_fmu, y_py, lags = np.empty(u.size), np.empty(u.size), []
    waiting = None
    for i, ui in enumerate(u):
        if i in plan:
            fmu.setReal([fmu.vr["stage[1].wn"]], [plan[i]])
            waiting = sms.shaper("zv", wn=plan[i], zeta=0.05)
        if waiting is not None and not chain.switching[1]:   # applied when the switch allows
            chain.retune(1, waiting)
            waiting = None
        fmu.setReal([fmu.vr["u"]], [ui])
        fmu.doStep(i * TS, TS)
        y_fmu[i] = fmu.getReal([fmu.vr["y"]])[0]
        y_py[i] = chain.step(ui)
        lags.append((fmu.getReal([fmu.vr["lag"]])[0], chain.lag))
    fmu.terminate()
    fmu.freeInstance()
    assert np.array_equal(y_fmu, y_py)
    assert all(a == pytest.approx(b, rel=1e-13) for a, b in lags)
    assert lags[0][0] != lags[-1][0]                      # the lag follows the retunes


def test_retune_refusals_name_the_variable(ss_dir):
    logged = Logged()
    fmu = slave(ss_dir, logged=logged)
    start(fmu, STAGES)                                     # retune_max_delay = 0: fixed
    with pytest.raises(FMICallException):
        fmu.setReal([fmu.vr["stage[1].wn"]], [180.0])
    assert "stage[1].wn" in logged.messages[-1] and "retune_max_delay" in logged.messages[-1]
    fmu.terminate()
    fmu.freeInstance()
    fmu = slave(ss_dir, logged=logged)
    start(fmu, {**STAGES, "retune_max_delay": 0.02})
    with pytest.raises(FMICallException):                  # a ZV at 100 rad/s lasts 31 ms
        fmu.setReal([fmu.vr["stage[1].wn"]], [100.0])
    assert "retune_max_delay" in logged.messages[-1]
    with pytest.raises(FMICallException):
        fmu.setReal([fmu.vr["stage[1].zeta"]], [1.5])
    assert "stage[1].zeta" in logged.messages[-1]
    with pytest.raises(FMICallException):                  # kind stays fixed
        fmu.setInteger([fmu.vr["stage[1].kind"]], [5])
    assert fmu.getReal([fmu.vr["stage[1].wn"]])[0] == 200.0
    fmu.terminate()
    fmu.freeInstance()


def test_state_serialised_mid_switch_continues(ss_dir):
    u = move()
    fmu = slave(ss_dir)
    start(fmu, {**STAGES, "retune_max_delay": 0.05})
    out = []
    for i, ui in enumerate(u[:400]):
        if i == 300:
            fmu.setReal([fmu.vr["stage[1].wn"]], [150.0])
        fmu.setReal([fmu.vr["u"]], [ui])
        fmu.doStep(i * TS, TS)
    blob = fmu.serializeFMUstate(fmu.getFMUstate())
    twin = slave(ss_dir, name="twin")
    start(twin, {**STAGES, "retune_max_delay": 0.05})
    twin.setFMUstate(twin.deSerializeFMUstate(blob))
    for i, ui in enumerate(u[400:], 400):
        for f in (fmu, twin):
            f.setReal([f.vr["u"]], [ui])
            f.doStep(i * TS, TS)
        out.append((fmu.getReal([fmu.vr["y"]])[0], twin.getReal([twin.vr["y"]])[0]))
    assert all(a == b for a, b in out)
    for f in (fmu, twin):
        f.terminate()
        f.freeInstance()


def test_state_restored_after_a_retune_keeps_its_own_parameters(ss_dir):
    """A state saved before a retune, restored into the instance that has retuned since: the
    state's tunable values come back (stage[1].wn reads the saved 200, not the 150 set after)
    and the run continues bit for bit as a fresh instance that loads the same state. The
    restore into an instance of the state's own parameters copies that instance's built
    filters instead of designing them; the retuned instance's must not be copied over the
    state's values (its pending retune to 150 would then be applied on the next tick)."""
    u = move(700)
    fmu = slave(ss_dir)
    start(fmu, {**STAGES, "retune_max_delay": 0.05})
    for i, ui in enumerate(u[:300]):
        fmu.setReal([fmu.vr["u"]], [ui])
        fmu.doStep(i * TS, TS)
    blob = fmu.serializeFMUstate(fmu.getFMUstate())
    fmu.setReal([fmu.vr["stage[1].wn"]], [150.0])
    for i, ui in enumerate(u[300:350], 300):
        fmu.setReal([fmu.vr["u"]], [ui])
        fmu.doStep(i * TS, TS)
    twin = slave(ss_dir, name="twin")
    start(twin, {**STAGES, "retune_max_delay": 0.05})
    for f in (fmu, twin):
        f.setFMUstate(f.deSerializeFMUstate(blob))
        assert f.getReal([f.vr["stage[1].wn"]]) == [200.0]
    out = []
    for i, ui in enumerate(u[300:], 300):
        for f in (fmu, twin):
            f.setReal([f.vr["u"]], [ui])
            f.doStep(i * TS, TS)
        out.append((fmu.getReal([fmu.vr["y"]])[0], twin.getReal([twin.vr["y"]])[0],
                    fmu.getReal([fmu.vr["lag"]])[0], twin.getReal([twin.vr["lag"]])[0]))
    assert all(a == b and la == lb for a, b, la, lb in out)
    for f in (fmu, twin):
        f.terminate()
        f.freeInstance()


def schedule_values(table):
    values = {"schedule.kind": SCHEDULED_ZV, "schedule.points": len(table)}
    for j, (s, wn, zeta) in enumerate(table):
        values.update({f"schedule.value[{j}]": s, f"schedule.wn[{j}]": wn,
                       f"schedule.zeta[{j}]": zeta})
    return values


def test_scheduled_shaper_follows_the_input_s(ss_dir):
    """fmpy's simulate_fmu with inputs u and s: the outputs at the communication points equal
    ScheduledShaper on the ticks (inputs held over each step), bit for bit."""
    n = 800
    t = np.arange(n) * TS
    u = np.clip(t - 0.05, 0.0, None) * 0.8
    s = np.clip(u, 0.0, 1.0)
    signal = np.zeros(n, dtype=[("time", float), ("u", float), ("s", float)])
    signal["time"], signal["u"], signal["s"] = t, u, s
    values = {"stage[0].kind": -1, "stage[1].kind": -1, **schedule_values(TABLE)}
    r = fmpy.simulate_fmu(str(ss_dir), start_values=values, input=signal, stop_time=t[-1],
                          output_interval=TS, output=["y", "lag"])
    sh = ScheduledShaper("zv", TABLE, Ts=TS)
    sh.reset(u[0], s=s[0])
    want = np.r_[u[0], [sh.step(u[k], s[k]) for k in range(n - 1)]]   # fmpy: y(t_k+1)
    assert np.array_equal(np.asarray(r["y"]), want)
    assert np.asarray(r["lag"])[-1] > 0.0


def test_libcosim_retune_equals_fmpy(ss_dir, fmus):  # noqa: F811
    pytest.importorskip("libcosimpy", reason="libcosimpy is the second importer")
    from fmpy import read_model_description
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimManipulator import CosimManipulator
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave
    log_output_level(CosimLogLevel.ERROR)
    path = str(fmus["SmoothShaper"])
    vr = {v.name: v.valueReference for v in read_model_description(path).modelVariables}
    u = move(600)
    execution = CosimExecution.from_step_size(step_size=int(round(TS * 1e9)))
    index = execution.add_local_slave(local_slave=CosimLocalSlave(fmu_path=path, instance_name="s"))
    override = CosimManipulator.create_override()
    execution.add_manipulator(manipulator=override)
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer=observer)
    for name, value in {**STAGES, "retune_max_delay": 0.05}.items():
        ok = (execution.integer_initial_value(index, vr[name], value) if isinstance(value, int)
              else execution.real_initial_value(index, vr[name], float(value)))
        assert ok, name
    y = []
    for k, uk in enumerate(u):
        if k == 250:
            override.slave_real_values(index, [vr["stage[1].wn"]], [160.0])
        override.slave_real_values(index, [vr["u"]], [float(uk)])
        assert execution.step()
        y.append(observer.last_real_values(index, [vr["y"]])[0])
    fmu = slave(ss_dir)
    start(fmu, {**STAGES, "retune_max_delay": 0.05})
    ref = []
    for k, uk in enumerate(u):
        if k == 250:
            fmu.setReal([fmu.vr["stage[1].wn"]], [160.0])
        fmu.setReal([fmu.vr["u"]], [float(uk)])
        fmu.doStep(k * TS, TS)
        ref.append(fmu.getReal([fmu.vr["y"]])[0])
    fmu.terminate()
    fmu.freeInstance()
    assert np.array_equal(np.array(y), np.array(ref))


# An input smoother (every sample a tap), an SI shaper and user-defined impulses retunable in
# one chain: the smoother's slot holds the longest of its kind that retune_max_delay admits;
# the impulses run as built (their fields are fixed, a wn set on them changes nothing).
FAMILIES = {"stage[0].kind": 15, "stage[0].wn": 2 * np.pi * 40.0, "stage[0].zeta": 0.1,
            "stage[1].kind": 22, "stage[1].order": 3,
            **{f"stage[1].amplitude[{i}]": a for i, a in enumerate((0.3, 0.5, 0.2))},
            **{f"stage[1].time[{i}]": t for i, t in enumerate((0.0, 0.0042, 0.0091))},
            "stage[2].kind": 21, "stage[2].wn": 180.0, "stage[2].order": 5,
            "stage[2].duration": 1.4, "stage[2].tolerance": 0.05, "retune_max_delay": 0.06}


def families_chain(smoother_wn, si_wn):
    return [sms.input_smoother("smooth_zv", wn=smoother_wn, zeta=0.1),
            sms.impulse_shaper(amplitudes=[0.3, 0.5, 0.2], times=[0.0, 0.0042, 0.0091]),
            sms.shaper("si", wn=si_wn, zeta=0.0, order=5, duration=1.4, tolerance=0.05)]


def test_new_families_retune_and_restore(ss_dir):
    u = move()
    fmu = slave(ss_dir)
    start(fmu, FAMILIES)
    slow = 2 * np.pi * 12.0            # the smooth_zv kernel at 12 Hz lasts 55 ms < 60 ms
    chain = sms.TunableChain(families_chain(2 * np.pi * 40.0, 180.0), Ts=TS,
                             capacity=[sms.input_smoother("smooth_zv", wn=slow, zeta=0.1), None,
                                       sms.shaper("si", wn=150.0, order=5, duration=1.4,
                                                  tolerance=0.05)])
    plan = {200: ("stage[0].wn", slow), 210: ("stage[2].wn", 150.0), 220: ("stage[1].wn", 9.0)}
    y_fmu, y_py, lags, blob = np.empty(u.size), np.empty(u.size), [], None
    for i, ui in enumerate(u):
        if i in plan:
            name, value = plan[i]
            fmu.setReal([fmu.vr[name]], [value])
            if name != "stage[1].wn":       # impulses read no wn
                k = int(name[6])
                chain.retune(k, families_chain(value, value)[k])
        if i == 230:                        # the old SI (49 ms) still fading out
            assert chain.switching == (False, False, True)
            blob = fmu.serializeFMUstate(fmu.getFMUstate())
        fmu.setReal([fmu.vr["u"]], [ui])
        fmu.doStep(i * TS, TS)
        y_fmu[i] = fmu.getReal([fmu.vr["y"]])[0]
        y_py[i] = chain.step(ui)
        lags.append((fmu.getReal([fmu.vr["lag"]])[0], chain.lag))
    assert np.array_equal(y_fmu, y_py)
    assert all(a == pytest.approx(b, rel=1e-13) for a, b in lags)
    # a state saved mid-switch continues bit for bit in a twin configured alike
    twin = slave(ss_dir, name="twin")
    start(twin, FAMILIES)
    twin.setFMUstate(twin.deSerializeFMUstate(blob))
    for i, ui in enumerate(u[230:], 230):
        twin.setReal([twin.vr["u"]], [ui])
        twin.doStep(i * TS, TS)
        assert twin.getReal([twin.vr["y"]])[0] == y_fmu[i]
    for f in (fmu, twin):
        f.terminate()
        f.freeInstance()


def test_new_families_retune_refusals(ss_dir):
    logged = Logged()
    fmu = slave(ss_dir, logged=logged)
    start(fmu, FAMILIES)
    with pytest.raises(FMICallException):   # the kernel at 10 Hz lasts 66 ms > 60 ms
        fmu.setReal([fmu.vr["stage[0].wn"]], [2 * np.pi * 10.0])
    assert "stage[0].wn" in logged.messages[-1] and "retune_max_delay" in logged.messages[-1]
    fmu.terminate()
    fmu.freeInstance()
    # a state carries the parameters: an FMU configured with other impulses takes the saved
    # ones back (the impulses restored from them, not from the state's checksum)
    u = move(300)
    first = slave(ss_dir, name="a")
    start(first, FAMILIES)
    for i, ui in enumerate(u[:150]):
        first.setReal([first.vr["u"]], [ui])
        first.doStep(i * TS, TS)
    blob = first.serializeFMUstate(first.getFMUstate())
    other = slave(ss_dir, name="b")
    start(other, {**FAMILIES, "stage[1].amplitude[1]": 0.51})
    other.setFMUstate(other.deSerializeFMUstate(blob))
    assert other.getReal([other.vr["stage[1].amplitude[1]"]])[0] == 0.5
    for i, ui in enumerate(u[150:], 150):
        for f in (first, other):
            f.setReal([f.vr["u"]], [ui])
            f.doStep(i * TS, TS)
        assert other.getReal([other.vr["y"]])[0] == first.getReal([first.vr["y"]])[0]
    for f in (first, other):
        f.terminate()
        f.freeInstance()


# A damped harmonic smoother retuned to heavy damping (sigma T = -300): its range falls from
# SMS_INPUT_MAX = 1e305 to 2.7e299 (its gain c grows with e^(-sigma Ts)), below the input
# u = 1e301 the FMU holds.
DAMPED = {"stage[0].kind": 2, "stage[0].T": 0.02, "stage[0].sigma": -30.0,
          "stage[1].kind": -1, "retune_max_delay": 0.03}
HEAVY = -15000.0
LARGE_U = 1e301


def narrowed_range() -> float:
    """sms_stage_config_range() of the heavily damped smoother: the range of the one-stage
    chain once it is retuned, during the switch (the smaller of the two) and after it."""
    from smoothshaper.filters import _backend, _fill_config
    ffi, lib = _backend("double")
    config = ffi.new("sms_stage_config *")
    _fill_config(config, sms.damped_harmonic(T=0.02, sigma=HEAVY))
    x, g = ffi.new("double *"), ffi.new("double *")
    assert lib.sms_stage_config_range(config, TS, x, g) == 0
    return x[0]


def message_range(message: str) -> float:
    import re
    return float(re.search(r"input range would be (\S+) ", message).group(1))


def test_retune_narrowing_the_range_below_the_held_input_is_refused(ss_dir):
    """The retune is refused at the set, naming the parameter, its value, the range it would
    give and the held u; the FMU runs on unchanged (bit for bit a twin never asked), and its
    saved state loads into the twin."""
    bound = narrowed_range()
    assert 1e299 < bound < LARGE_U / 10
    logged = Logged()
    fmu, twin = slave(ss_dir, logged=logged), slave(ss_dir, name="twin")
    for f in (fmu, twin):
        start(f, DAMPED, u0=LARGE_U)
    u = LARGE_U * (1.0 - 0.5 * move(200))
    for i, ui in enumerate(u):
        if i == 80:
            with pytest.raises(FMICallException):
                fmu.setReal([fmu.vr["stage[0].sigma"]], [HEAVY])
            text = logged.messages[-1]
            assert "stage[0].sigma = -15000" in text and "u it holds" in text
            assert message_range(text) == bound
            assert f"{u[i - 1]:.17g}" in text                 # the u held
            assert fmu.getReal([fmu.vr["stage[0].sigma"]])[0] == -30.0
        for f in (fmu, twin):
            f.setReal([f.vr["u"]], [ui])
            f.doStep(i * TS, TS)
        assert fmu.getReal([fmu.vr["y"]]) == twin.getReal([twin.vr["y"]])
    blob = fmu.serializeFMUstate(fmu.getFMUstate())
    twin.setFMUstate(twin.deSerializeFMUstate(blob))
    for f in (fmu, twin):
        f.terminate()
        f.freeInstance()


def test_input_beyond_a_pending_retunes_range_is_refused(ss_dir):
    """With small inputs the retune is accepted; from the set on (pending, then switching, then
    done) u is held to the narrowed range, exactly: the bound itself is taken, the next double
    refused naming u; every state saved on the way loads again."""
    bound = narrowed_range()
    logged = Logged()
    fmu = slave(ss_dir, logged=logged)
    start(fmu, DAMPED, u0=0.5)
    fmu.setReal([fmu.vr["u"]], [LARGE_U])             # within the built range: ticked once,
    fmu.doStep(0.0, TS)                               # it is in the stages' memory
    fmu.setReal([fmu.vr["u"]], [0.5])
    fmu.doStep(TS, TS)
    with pytest.raises(FMICallException):
        fmu.setReal([fmu.vr["stage[0].sigma"]], [HEAVY])
    assert "largest input the stages' memory may hold" in logged.messages[-1]
    assert f"{LARGE_U:.17g}" in logged.messages[-1]
    fmu.terminate()
    fmu.freeInstance()
    fmu = slave(ss_dir, logged=logged)
    start(fmu, DAMPED, u0=0.5)
    fmu.setReal([fmu.vr["u"]], [LARGE_U])             # set but never ticked: not held
    fmu.setReal([fmu.vr["u"]], [0.5])
    fmu.doStep(0.0, TS)
    fmu.setReal([fmu.vr["stage[0].sigma"]], [HEAVY])
    for i in range(1, 60):                            # pending, switching (20 ticks), done
        with pytest.raises(FMICallException):
            fmu.setReal([fmu.vr["u"]], [np.nextafter(bound, np.inf)])
        assert "u = " in logged.messages[-1] and f"{bound:.17g}" in logged.messages[-1]
        fmu.setReal([fmu.vr["u"]], [bound if i % 2 else -0.5 * bound])
        fmu.doStep(i * TS, TS)
        assert np.isfinite(fmu.getReal([fmu.vr["y"]])[0])
        if i % 20 == 1:
            state = fmu.deSerializeFMUstate(fmu.serializeFMUstate(fmu.getFMUstate()))
            fmu.setFMUstate(state)
    assert fmu.getReal([fmu.vr["stage[0].sigma"]])[0] == HEAVY
    fmu.terminate()
    fmu.freeInstance()


def test_the_held_input_bound_forgets_an_input_once_the_memory_has(ss_dir):
    """A large input ticked once stays in the bound while the stages' memory can hold it (the
    narrowing retune is refused) and leaves it two memory spans later (the same retune is then
    taken): the span of DAMPED's smoother of 21 samples (its delay line, its two running sums
    restarted every window, plus a margin per stage) is below 100 ticks, so 2 spans < 200. A
    rest keeps the bound for good: at rest at LARGE_U, the retune stays refused."""
    logged = Logged()
    fmu = slave(ss_dir, logged=logged)
    start(fmu, DAMPED, u0=0.5)
    fmu.setReal([fmu.vr["u"]], [LARGE_U])
    fmu.doStep(0.0, TS)
    for i in range(1, 400):
        fmu.setReal([fmu.vr["u"]], [0.5])
        fmu.doStep(i * TS, TS)
        if i in (2, 15):          # LARGE_U is still in the smoother's window
            with pytest.raises(FMICallException):
                fmu.setReal([fmu.vr["stage[0].sigma"]], [HEAVY])
            assert "memory may hold" in logged.messages[-1]
    fmu.setReal([fmu.vr["stage[0].sigma"]], [HEAVY])          # taken
    for i in range(400, 460):
        fmu.setReal([fmu.vr["u"]], [0.5])
        fmu.doStep(i * TS, TS)
        assert np.isfinite(fmu.getReal([fmu.vr["y"]])[0])
    fmu.setFMUstate(fmu.deSerializeFMUstate(fmu.serializeFMUstate(fmu.getFMUstate())))
    fmu.terminate()
    fmu.freeInstance()
    fmu = slave(ss_dir, logged=logged)
    start(fmu, DAMPED, u0=LARGE_U)                            # the rest: kept by every slot
    for i in range(400):
        fmu.setReal([fmu.vr["u"]], [0.5])
        fmu.doStep(i * TS, TS)
    with pytest.raises(FMICallException):
        fmu.setReal([fmu.vr["stage[0].sigma"]], [HEAVY])
    assert "memory may hold" in logged.messages[-1]
    fmu.terminate()
    fmu.freeInstance()


def test_a_two_stage_switch_takes_inputs_up_to_sms_input_max(ss_dir):
    """Two moving averages switching: each stage's limit (REAL_MAX / 2) over R_1 = 3 is far
    above SMS_INPUT_MAX, so the chain's range stays SMS_INPUT_MAX during the switch (it was
    SMS_INPUT_MAX / 3, the stage's capped range over R_1): the retune with u = SMS_INPUT_MAX
    held is taken, and so is u = SMS_INPUT_MAX during the switch, every output finite."""
    from smoothshaper.filters import input_max
    top = input_max("double")
    fmu = slave(ss_dir)
    start(fmu, {"stage[0].kind": RECT, "stage[0].T": 0.01, "stage[1].kind": RECT,
                "stage[1].T": 0.005, "retune_max_delay": 0.03}, u0=top)
    fmu.doStep(0.0, TS)
    fmu.setReal([fmu.vr["stage[1].T"]], [0.02])
    for i in range(1, 40):
        fmu.setReal([fmu.vr["u"]], [top if i % 3 else -top])
        fmu.doStep(i * TS, TS)
        assert np.isfinite(fmu.getReal([fmu.vr["y"]])[0])
        if i % 10 == 0:
            fmu.setFMUstate(fmu.deSerializeFMUstate(fmu.serializeFMUstate(fmu.getFMUstate())))
    fmu.terminate()
    fmu.freeInstance()


def test_a_loaded_retunable_state_is_held_to_its_configurations_range(ss_dir):
    """DAMPED retuned to HEAVY has the range B = narrowed_range() < SMS_INPUT_MAX. A state it
    saved with inputs swinging to +-B loads; the same state with the stage's last input
    (the tunable's field 8 of its part, after y) forged to 2 B, within SMS_INPUT_MAX but beyond
    the configuration's range, is refused (it was checked against SMS_INPUT_MAX)."""
    import struct
    xxhash = pytest.importorskip("xxhash")
    bound = narrowed_range()
    logged = Logged()
    fmu = slave(ss_dir, logged=logged)
    start(fmu, {**DAMPED, "stage[0].sigma": HEAVY}, u0=0.0)
    for i in range(50):
        fmu.setReal([fmu.vr["u"]], [bound if i % 2 else -bound])
        fmu.doStep(i * TS, TS)
    blob = bytes(fmu.serializeFMUstate(fmu.getFMUstate()))
    fmu.setFMUstate(fmu.deSerializeFMUstate(blob))             # its own state loads
    last = struct.pack("<d", bound)                              # the last input ticked (i = 49)
    at = [o for o in range(0, len(blob) - 8, 8) if blob[o:o + 8] == last]   # doubles: 8-aligned
    dynamic = [o for o in at if struct.unpack_from("<d", blob, o - 8 * 9)[0]
               == fmu.getReal([fmu.vr["y"]])[0]]              # y opens the dynamic part
    assert len(dynamic) == 1
    forged = bytearray(blob)
    struct.pack_into("<d", forged, dynamic[0], 2.0 * bound)
    struct.pack_into("<Q", forged, len(forged) - 8, xxhash.xxh64_intdigest(bytes(forged[:-8])))
    with pytest.raises(FMICallException):
        fmu.deSerializeFMUstate(bytes(forged))
    assert "chain's range" in logged.messages[-1] and f"{bound:.17g}" in logged.messages[-1]
    fmu.terminate()
    fmu.freeInstance()
