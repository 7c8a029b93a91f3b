# SPDX-License-Identifier: Apache-2.0
"""What a co-simulation master can throw at the FMUs: memory through its callbacks sized to the
chain, saved states sized to the chain, crafted or foreign states, another model's instance, a
held input over an enormous step. (Tick accounting under t += h hosts: tests/fmu/test_fmu_clock.c.)"""
from __future__ import annotations

import ctypes
import math
import re
import struct

import numpy as np
import pytest

fmpy = pytest.importorskip("fmpy", reason="fmpy is needed to import the FMUs")
xxhash = pytest.importorskip("xxhash", reason="xxhash recomputes the states' checksum")
from fmpy.fmi1 import FMICallException  # noqa: E402
from fmpy.fmi2 import (FMU2Slave, fmi2CallbackAllocateMemoryTYPE,  # noqa: E402
                       fmi2CallbackFreeMemoryTYPE)

from smoothshaper import fmi  # noqa: E402
from smoothshaper.filters import Chain  # noqa: E402
from smoothshaper.stages import harmonic, notch, rectangular, shaper  # noqa: E402
from test_fmu_smoothshaper import (CHAIN, Logged, configure, fmus, run, slave,  # noqa: E402,F401
                                   smoothshaper_dir)
from test_fmu_trajectory import start, trajectory_dir  # noqa: E402,F401
from test_fmu_multi_axis import multi_dir, multi_fmu  # noqa: E402,F401

TS = 1e-3


class Counted(Logged):
    """Logged callbacks whose allocator records every request (bytes)."""

    def __init__(self):
        super().__init__()
        self.sizes: list[int] = []
        libc = ctypes.CDLL(None)
        libc.calloc.restype = ctypes.c_void_p
        libc.calloc.argtypes = [ctypes.c_size_t, ctypes.c_size_t]
        libc.free.argtypes = [ctypes.c_void_p]

        def allocate(n, size):
            self.sizes.append(n * size)
            return libc.calloc(n, size)

        self.callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(allocate)
        self.callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(lambda p: libc.free(p))


def serialized(fmu) -> bytes:
    state = fmu.getFMUstate()
    blob = bytes(fmu.serializeFMUstate(state))
    fmu.freeFMUstate(state)
    return blob


def test_memory_comes_from_the_importer_sized_to_the_chain(smoothshaper_dir):
    sizes = {}
    for n in (10, 10000):
        log = Counted()
        fmu = slave(smoothshaper_dir, logged=log)
        configure(fmu, [rectangular(T=n * TS)])
        sizes[n] = max(log.sizes)
        fmu.freeInstance()
    assert sizes[10] < 16384                         # no fixed 65,536-sample (532 KB) line
    assert 8 * 10000 <= sizes[10000] <= 8 * 10000 + 4096


def test_saved_state_bytes_are_proportional_to_the_chain(smoothshaper_dir):
    size = {}
    for n in (10, 1000, 10000):
        fmu = slave(smoothshaper_dir)
        configure(fmu, [rectangular(T=n * TS)])
        size[n] = len(serialized(fmu))
        fmu.freeInstance()
    assert (size[10000] - size[1000]) * 990 == (size[1000] - size[10]) * 9000   # linear
    assert size[1000] - size[10] == 8 * 990          # one double per delay-line sample
    assert size[10] < 4096   # the header, every parameter (the schedule table's and the eight
    # stages' user impulses, 8 x 18 doubles, too) and the retunable stage's head (its
    # configurations' identities) around 10 delay-line samples: 3840 bytes


def test_a_02_hz_shaper_at_10_khz_runs_and_equals_the_library(smoothshaper_dir):
    # ZVDD for 0.2 Hz spans 1.5 periods = 75,000 samples at Ts = 0.1 ms (the old fixed
    # delay line held 65,536).
    Ts, step = 1e-4, 0.01
    stages = [shaper("zvdd", wn=2 * math.pi * 0.2)]
    t = fmi.communication_points(step=step, stop_time=12.0)
    u = fmi.test_input(t)
    y = fmi.simulate(smoothshaper_dir, stages, t, u, Ts=Ts)
    x, n_at = fmi.tick_inputs(t, u, Ts=Ts)
    chain = Chain(stages, Ts=Ts)
    assert chain.state_size > 75000
    chain.reset(u[0])
    expected = fmi.at_communication_points(chain.process(x), n_at, u[0])
    assert np.array_equal(y, expected)


# ---------------------------------------------------------------- crafted and foreign states

def clock_offset(blob: bytes) -> int:
    """Offset of the clock (u32 phase) in a serialised state: after magic, version, token, R."""
    glen = struct.unpack_from("<I", blob, 8)[0]
    return 12 + glen + 4


def patched(blob: bytes, offset: int, fmt: str, value) -> bytes:
    """The blob with one field replaced and the XXH64 checksum recomputed (a well-formed forgery)."""
    b = bytearray(blob)
    struct.pack_into(fmt, b, offset, value)
    struct.pack_into("<Q", b, len(b) - 8, xxhash.xxh64_intdigest(bytes(b[:-8])))
    return bytes(b)


def test_the_checksum_is_xxh64_of_the_bytes_before_it(stepped):
    """The format's checksum, computed by the FMU's own XXH64, equals the xxHash library's."""
    _, _, blob = stepped
    assert struct.unpack_from("<Q", blob, len(blob) - 8)[0] == xxhash.xxh64_intdigest(blob[:-8])
    # The dynamic part, u32 nS, zero bytes, nS doubles, puts the doubles at a multiple of 8.
    assert len(blob) % 8 == 0

    def dynamic_part_at(n):   # offset of the doubles if the blob holds n of them, else None
        at = len(blob) - 8 - 8 * n
        for start in range(at - 11, at - 3):   # u32 nS, then 0 to 7 zero bytes
            if start >= 0 and struct.unpack_from("<I", blob, start)[0] == n \
                    and not any(blob[start + 4:at]):
                return at
        return None
    assert any(dynamic_part_at(n) is not None for n in range(1, len(blob) // 8))


@pytest.fixture
def stepped(smoothshaper_dir):
    log = Logged()
    fmu = slave(smoothshaper_dir, logged=log)
    configure(fmu, CHAIN, u0=0.3)
    run(fmu, 0.0, np.linspace(0, 1, 50))
    yield fmu, log, serialized(fmu)
    fmu.freeInstance()


def test_a_state_whose_clock_disagrees_with_its_ticks_is_refused(stepped):
    fmu, log, blob = stepped
    at = clock_offset(blob)
    for offset, fmt, value in ((at + 12, "<d", 1e9),          # t = 1e9 s after 50 ticks
                               (at + 20, "<Q", 10 ** 12),     # 1e12 ticks at t = 0.05 s
                               (at + 28, "<d", 5 * TS)):      # since_tick beyond Ts
        with pytest.raises(FMICallException):
            fmu.deSerializeFMUstate(patched(blob, offset, fmt, value))
        assert "clock" in log.messages[-1] or "tick count" in log.messages[-1], log.messages[-1]
    # A consistent clock far away is fine: 1e12 ticks at t = 1e9 s, and the next 1 ms step
    # computes one tick (not 1e12).
    far = patched(patched(blob, at + 12, "<d", 1e9), at + 20, "<Q", 10 ** 12)
    fmu.setFMUstate(fmu.deSerializeFMUstate(far))
    fmu.setReal([fmu.vr["u"]], [0.7])
    fmu.doStep(1e9, TS)


def test_a_state_of_the_other_precision_is_refused(stepped):
    fmu, log, blob = stepped
    precision_at = clock_offset(blob) - 4
    assert struct.unpack_from("<I", blob, precision_at)[0] == 8
    with pytest.raises(FMICallException):
        fmu.deSerializeFMUstate(patched(blob, precision_at, "<I", 4))
    assert "other precision" in log.messages[-1]


def test_a_generator_state_beyond_its_limits_is_refused_with_the_reason(trajectory_dir):  # noqa: F811
    """A TrajectoryGenerator state whose saved output v or a, or whose plan's start v, a or
    brake velocity, lies beyond the limits by twice the reported values' tolerance
    (SMS_LIMIT_RTOL, 32 u) is refused by fmi2DeSerializeFMUstate, the logger saying why; the
    instance runs on as its twin. At the tolerance the state loads. Limits of powers of two:
    a = amax/2 brakes over amax^2/(8 jmax) = 1/8."""
    from smoothshaper import trajectory as tr
    from test_fmu_trajectory import run as run_tg
    limits = dict(vmax=1.0, amax=8.0, jmax=64.0)
    log = Logged()
    tg, twin = slave(trajectory_dir, "tg", logged=log), slave(trajectory_dir, "twin")
    for f in (tg, twin):
        start(f, target=0.3, **limits)
        run_tg(f, 0.0, [0.3] * 40)
    blob = tg.serializeFMUstate(tg.getFMUstate())
    g = tr.Generator(Ts=TS, **limits)
    tol, plan = float(g._lib.SMS_LIMIT_RTOL), 4 + int(g._lib.SMS_GENERATOR_IDENTITY_COUNT)
    plan_v, plan_a = plan + g._lib.SMS_GENERATOR_STATE_V, plan + g._lib.SMS_GENERATOR_STATE_A
    at = len(blob) - 8 - 8 * (4 + g.get_state().size)   # q, v, a, j, the generator's state
    assert struct.unpack_from("<d", blob, at + 8 * 4)[0] == g.get_state()[0]   # its state tag
    assert struct.unpack_from("<d", blob, at + 8)[0] == tg.getReal([tg.vr["v"]])[0]
    cases = [("its output v = ", {1: lambda o: 1 + o}),
             ("its output a = ", {2: lambda o: 8 * (1 + o)}),
             ("start v = ", {plan_v: lambda o: 1 + o, plan_a: lambda o: 0.0}),
             ("start v = ", {plan_v: lambda o: 0.0, plan_a: lambda o: 8 * (1 + o)}),
             ("start v = ", {plan_v: lambda o: 0.875 + o, plan_a: lambda o: 4.0})]
    for words, fields in cases:
        for over in (2 * tol, tol):
            forged = blob
            for index, value in fields.items():
                forged = patched(forged, at + 8 * index, "<d", value(over))
            if over == tol:
                tg.freeFMUstate(tg.deSerializeFMUstate(forged))
                continue
            with pytest.raises(FMICallException):
                tg.deSerializeFMUstate(forged)
            message = log.messages[-1]
            assert "does not fit" in message and words in message, message
            assert f"relative {tol:.3g}" in message, message
    targets = np.repeat([0.2, -0.5, 0.1], 150)
    assert np.array_equal(run_tg(tg, 0.04, targets), run_tg(twin, 0.04, targets))
    for f in (tg, twin):
        f.freeInstance()


def test_a_multi_axis_state_beyond_vmax_is_refused_with_the_reason(multi_dir):  # noqa: F811
    """A MultiAxisGenerator state whose axis's cruise velocity lies beyond its vmax by twice
    SMS_LIMIT_RTOL (32 u) is refused by fmi2DeSerializeFMUstate, the logger saying why; at the
    tolerance it loads."""
    from smoothshaper.multi_axis import MultiAxisGenerator
    from test_fmu_multi_axis import LIMITS, start as start_ma, start_values
    log = Logged()
    fmu = slave(multi_dir, "ma", logged=log)
    start_ma(fmu, **start_values(3, 0))
    for k in range(60):
        fmu.setReal([fmu.vr[f"target[{i}]"] for i in range(3)], [0.3, -0.2, 0.1])
        fmu.doStep(k * TS, TS)
    blob = fmu.serializeFMUstate(fmu.getFMUstate())
    g = MultiAxisGenerator(Ts=TS, **LIMITS[3])
    tol, identity = float(g._lib.SMS_LIMIT_RTOL), int(g._lib.SMS_MULTI_IDENTITY_COUNT)
    at = len(blob) - 8 - 8 * (4 * 3 + g.get_state().size)   # outputs, the generator's state
    W1 = at + 8 * (4 * 3 + identity + 4 * 3 + 1)             # axis 1's cruise velocity
    assert struct.unpack_from("<d", blob, at + 8 * 12)[0] == g.get_state()[0]   # state tag
    vmax = LIMITS[3]["vmax"][1]
    with pytest.raises(FMICallException):
        fmu.deSerializeFMUstate(patched(blob, W1, "<d", -vmax * (1 + 2 * tol)))
    message = log.messages[-1]
    assert "cruise velocity" in message and f"relative {tol:.3g}" in message, message
    fmu.freeFMUstate(fmu.deSerializeFMUstate(patched(blob, W1, "<d", -vmax * (1 + tol))))
    fmu.freeInstance()


ENTRY_POINTS = [
    ("fmi2DoStep", lambda f, c: f.fmi2DoStep(c, 0.05, TS, 1)),
    ("fmi2SetReal", lambda f, c: f.fmi2SetReal(c, (ctypes.c_uint32 * 1)(0), 1,
                                               (ctypes.c_double * 1)(5.0))),
    ("fmi2GetReal", lambda f, c: f.fmi2GetReal(c, (ctypes.c_uint32 * 1)(1), 1,
                                               (ctypes.c_double * 1)())),
    ("fmi2Reset", lambda f, c: f.fmi2Reset(c)),
    ("fmi2Terminate", lambda f, c: f.fmi2Terminate(c)),
    ("fmi2GetFMUstate", lambda f, c: f.fmi2GetFMUstate(c, ctypes.byref(ctypes.c_void_p()))),
]


@pytest.mark.parametrize("name,call", ENTRY_POINTS, ids=[e[0] for e in ENTRY_POINTS])
def test_another_models_instance_is_refused_and_untouched(smoothshaper_dir, trajectory_dir,  # noqa: F811
                                                          name, call):
    log = Logged()
    ss = slave(smoothshaper_dir, "ss")
    tg, twin = slave(trajectory_dir, "tg", logged=log), slave(trajectory_dir, "twin")
    for f in (tg, twin):
        start(f, target=0.2)
    with pytest.raises(FMICallException):
        call(ss, tg.component)
    assert "belongs to another FMU" in log.messages[-1]
    ss.fmi2FreeInstance(tg.component)           # void: must not free the other model's instance
    targets = np.repeat([0.2, 0.5, -0.1], 100)
    from test_fmu_trajectory import run as run_tg
    assert np.array_equal(run_tg(tg, 0.0, targets), run_tg(twin, 0.0, targets))
    for f in (ss, tg, twin):
        f.freeInstance()


def test_set_state_given_another_models_instance_never_writes(smoothshaper_dir, trajectory_dir):  # noqa: F811
    ss, tg = slave(smoothshaper_dir, "ss"), slave(trajectory_dir, "tg")
    start(tg, target=0.2, q0=0.2)   # at rest on its target: a step must leave q at 0.2
    state = ss.getFMUstate()
    with pytest.raises(FMICallException):
        ss.fmi2SetFMUstate(tg.component, state)  # used to copy 531,720 bytes over tg's block
    ss.freeFMUstate(state)
    tg.doStep(0.0, TS)
    assert tg.getReal([tg.vr["q"]])[0] == 0.2
    for f in (ss, tg):
        f.freeInstance()


# ---------------------------------------------------------------- held input over a huge step

@pytest.mark.parametrize("stages", [CHAIN, [rectangular(T=2000 * TS), harmonic(T=9 * TS)],
                                    [notch(wn=300.0, zeta=0.0, notch_pole_zeta=0.1)]],
                         ids=["M*S*ZVD*notch", "long M*S", "notch"])
def test_a_huge_step_over_a_held_input_equals_ticking_through_it(smoothshaper_dir, stages):
    # doStep(h = 1e9 s) is 1e12 ticks: once the chain has absorbed the held input its state is
    # a fixed point and the rest is skipped. Ticking one by one reaches the same bits.
    a, b = slave(smoothshaper_dir, "a"), slave(smoothshaper_dir, "b")
    for f in (a, b):
        configure(f, stages, u0=-0.4)
        run(f, 0.0, np.linspace(-1, 2, 30))
        f.setReal([f.vr["u"]], [1.25])
    a.doStep(0.03, 1e9)
    ya = a.getReal([a.vr["y"]])[0]
    yb = run(b, 0.03, np.full(5000, 1.25))[-1]  # one tick per step
    assert ya == yb and abs(ya - 1.25) <= 1e-12
    a.doStep(0.03 + 1e9, TS)                    # and it goes on from there
    assert a.getReal([a.vr["y"]])[0] == ya
    for f in (a, b):
        f.freeInstance()


def test_a_huge_step_of_the_generator_ends_at_rest_on_the_target(trajectory_dir):  # noqa: F811
    tg = slave(trajectory_dir)
    start(tg, target=0.0)
    tg.setReal([tg.vr["target"]], [0.75])
    tg.doStep(0.0, 1e9)
    assert tg.getReal([tg.vr[n] for n in "qvaj"]) == [0.75, 0.0, 0.0, 0.0]
    tg.freeInstance()


def test_the_fmpy_input_benchmark_runs(fmus):  # noqa: F811
    # Smoke test of tests/bench/fmu_input_bench.py (the full run prints 1e4/1e5/1e6 steps).
    import importlib.util
    from pathlib import Path
    path = Path(__file__).resolve().parents[1] / "bench" / "fmu_input_bench.py"
    spec = importlib.util.spec_from_file_location("fmu_input_bench", path)
    bench = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench)
    build_dir = Path(fmus["SmoothShaper"]).parents[1]
    assert bench.main(["--quick", "--build-dir", str(build_dir)]) == 0


def fmu_max_reals() -> int:
    """FMU_MAX_REALS, the per-instance state limit, read from its one definition (fmu_model.h)."""
    from pathlib import Path
    header = (Path(__file__).resolve().parents[2] / "fmu" / "fmu_model.h").read_text()
    shift = re.search(r"#define FMU_MAX_REALS \(\(size_t\)1 << (\d+)\)", header)
    assert shift, "FMU_MAX_REALS is no longer a power of two: update this test"
    return 1 << int(shift.group(1))


@pytest.mark.parametrize("T_over_Ts", [1e12, None], ids=["1e12 samples", "just over the limit"])
def test_an_oversized_chain_is_refused_at_exit_initialization(smoothshaper_dir, T_over_Ts):
    # The delay-line size is known in closed form: beyond the per-instance limit the chain is
    # refused at once, naming the parameter, the size and the limit; the instance stays in
    # initialization mode and takes a corrected T.
    limit = fmu_max_reals()
    T = (T_over_Ts or limit + 16) * TS
    log = Logged()
    fmu = slave(smoothshaper_dir, logged=log)
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    fmu.setReal([fmu.vr["stage[0].T"]], [T])
    with pytest.raises(FMICallException):
        fmu.exitInitializationMode()
    message = log.messages[-1]
    assert "stage[0].T = " in message and f"limit of {limit} reals" in message, message
    assert "shorten the stages" in message, message
    fmu.setReal([fmu.vr["stage[0].T"]], [(limit - 4096) * TS])   # under (with stage 1): accepted
    fmu.exitInitializationMode()
    fmu.doStep(0.0, TS)
    fmu.freeInstance()


def test_generators_beyond_the_state_limit_are_refused_naming_the_mode(trajectory_dir,  # noqa: F811
                                                                        multi_dir):
    # TrajectoryGenerator: the stage tuned to the mode holds 4 signals of one period 2 pi/wn.
    limit = fmu_max_reals()
    wn_over = 2 * math.pi / ((limit / 4 + 64) * TS)
    log = Logged()
    tg = slave(trajectory_dir, "tg", logged=log)
    with pytest.raises(FMICallException):
        start(tg, wn=wn_over)
    assert log.messages[-1].startswith("fmi2ExitInitializationMode: wn = "), log.messages[-1]
    assert f"limit of {limit} reals" in log.messages[-1] and "raise wn or Ts" in log.messages[-1]
    tg.freeInstance()
    # MultiAxisGenerator: every axis's stages count together (4 signals each); two axes with a
    # rectangular stage of half the limit each are one too many.
    ma = slave(multi_dir, "ma", logged=log)
    ma.setupExperiment(startTime=0.0)
    ma.enterInitializationMode()
    wn_half = 2 * math.pi / ((limit / 8 + 64) * TS)
    ma.setReal([ma.vr["Ts"]], [TS])
    ma.setInteger([ma.vr["axes"]], [2])
    for i in range(2):
        ma.setInteger([ma.vr[f"stage[0].kind[{i}]"]], [0])
        ma.setReal([ma.vr[f"stage[0].wn[{i}]"]], [wn_half])
    with pytest.raises(FMICallException):
        ma.exitInitializationMode()
    assert "stage[0].wn[0]" in log.messages[-1], log.messages[-1]
    assert f"limit of {limit} reals" in log.messages[-1] and "fewer stages or axes" in log.messages[-1]
    ma.freeInstance()
