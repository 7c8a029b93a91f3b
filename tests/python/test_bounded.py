# SPDX-License-Identifier: Apache-2.0
"""Bounded work and finite results through Python and the SmoothShaper FMU: requests too large
are refused at once naming the parameter and the limit, designs and identifications are finite
or refused, saved states carry their configuration, and T below Ts is refused everywhere.

The wall-clock bounds below are three to six orders of magnitude above the measured times
(microseconds to milliseconds) and far below the old proportional-to-T/Ts times (11 s at
T/Ts = 1e9, hours at 1e12): they tell O(1) from O(T/Ts), not fast from slow."""
from __future__ import annotations

import math
import shutil
import sys
import time

import numpy as np
import pytest

from smoothshaper import filters, fmi, stages, trajectory
from smoothshaper.filters import Chain, ParameterError, identify_from_peaks, input_max
from smoothshaper.reference import filtering as ref_filtering, shapers as ref_shapers
from smoothshaper.reference import smoothers as ref_smoothers
from smoothshaper.stages import Stage
from fmu_builds import fmu_build_dir

O1_SECONDS = 2.0


def refused_fast(fn, parameter, exc=ParameterError):
    t0 = time.perf_counter()
    with pytest.raises(exc) as info:
        fn()
    elapsed = time.perf_counter() - t0
    assert elapsed < O1_SECONDS, f"refusal took {elapsed:.3g} s"
    if parameter is not None:
        assert getattr(info.value, "parameter", parameter) == parameter
        assert str(info.value).startswith(parameter)
    return info.value


# ---------------------------------------------------------------- O(1) refusals, stated limit

def test_bspline_of_a_million_seconds_at_a_microsecond_is_refused_naming_T():
    err = refused_fast(lambda: trajectory.BSpline(degree=3, T=1e6, Ts=1e-6), "T")
    assert str(filters.MAX_BUFFER_REALS) in str(err)
    refused_fast(lambda: trajectory.bspline_reference([0.0, 1.0, 2.0], degree=3, T=1e6,
                                                       Ts=1e-6), "T")


@pytest.mark.parametrize("nu", [1e9, 1e12, 1e15])
@pytest.mark.parametrize("kind", stages.SMOOTHERS)
def test_long_smoothers_are_refused_at_once_with_the_limit(kind, nu):
    stage = Stage(kind, T=nu * 1e-6 * (1 + 1e-7), sigma=-0.1)
    err = refused_fast(lambda: Chain(stage, Ts=1e-6), "T")
    assert str(filters.MAX_BUFFER_REALS) in str(err)
    refused_fast(lambda: ref_smoothers.smoother_taps(stage, Ts=1e-6), None, ValueError)


def test_oversized_requests_are_parameter_errors_not_memory_errors():
    chain = Chain(stages.rectangular(T=0.01), Ts=1e-3)
    refused_fast(lambda: chain.impulse_response(10**13), "n")
    refused_fast(lambda: ref_filtering.impulse_response(stages.notch(wn=10.0), Ts=1e-3,
                                                        length=10**13), None, ValueError)
    refused_fast(lambda: ref_shapers.shaper_taps(stages.shaper("zvd", wn=1e-9), Ts=1e-3),
                 None, ValueError)
    refused_fast(lambda: Chain(stages.shaper("zvd", wn=1e-9), Ts=1e-3), "wn")


@pytest.mark.parametrize("kind", stages.SMOOTHERS)
def test_stage_for_a_nearly_critical_mode_is_designed_at_once(kind):
    # T = k Td or k 1.5 Td is 1.4e7..2.1e7 samples: accepted by the core in microseconds,
    # beyond a Chain's memory limit only for the longest.
    stage = filters.design_for_mode(kind, wn=100.0, zeta=0.99999999999)
    t0 = time.perf_counter()
    chain = Chain(stage, Ts=1e-2)        # 1.4e5..2.1e5 samples
    assert time.perf_counter() - t0 < O1_SECONDS
    y = chain.process(np.ones(10))
    assert np.isfinite(y).all()


# ---------------------------------------------------------------- never OK with non-finite

@pytest.mark.parametrize("tolerance", [1e-200, 1e-300, 5e-324])
def test_two_hump_ei_with_tiny_tolerance_is_finite(tolerance):
    stage = stages.shaper("ei2", wn=200.0, zeta=0.05, tolerance=tolerance)
    taps = Chain(stage, Ts=1e-3).taps()
    assert np.isfinite(taps).all() and math.isclose(taps.sum(), 1.0, rel_tol=1e-14)
    ref = ref_shapers.shaper_taps(stage, Ts=1e-3)
    assert np.isfinite(ref).all()
    np.testing.assert_allclose(taps, ref, atol=1e-12)


@pytest.mark.parametrize("t1, p1, t2, p2", [
    (0.0, 1.0, 1e-300, 0.5), (0.0, 1.0, 1e300, 0.5), (-sys.float_info.max, 1.0,
                                                      sys.float_info.max, 0.5),
    (0.0, sys.float_info.max, 1.0, 5e-324), (0.0, 1.0, 1.0, 1.0 - 2.0**-53),
])
def test_two_peaks_give_a_finite_mode_or_name_the_parameter(t1, p1, t2, p2):
    try:
        mode = identify_from_peaks(t1=t1, p1=p1, t2=t2, p2=p2)
    except ParameterError as exc:
        assert exc.parameter in ("t2", "p2")
        return
    assert all(math.isfinite(v) for v in mode)
    assert mode.wn > 0 and 0.0 <= mode.zeta < 1.0


def test_peaks_too_close_for_double_name_t2():
    with pytest.raises(ParameterError) as info:
        identify_from_peaks(t1=0.0, p1=1.0, t2=5e-324, p2=0.5)
    assert info.value.parameter == "t2"


@pytest.mark.parametrize("precision", filters.PRECISIONS)
def test_inputs_at_the_stated_bound_stay_finite_and_the_state_loads(precision):
    chain = Chain([stages.damped_harmonic(T=0.0173, sigma=-3.0), stages.rectangular(T=0.0101),
                   stages.shaper("ei2", wn=90.0, zeta=0.1), stages.notch(wn=300.0, zeta=0.01),
                   stages.exponential(T=0.02, sigma=-50.0)], Ts=1e-3, precision=precision)
    m = chain.input_max
    # no stage here has a large internal gain; in float the notch's gain bound (about 20)
    # takes a little off the exponential smoother's range behind it
    assert input_max(precision) / 10 < m <= input_max(precision)
    rng = np.random.default_rng(7)
    chain.reset(-m)
    for u in (np.where(np.arange(3000) % 7 < 3, m, -m), rng.choice([m, -m], 3000),
              rng.uniform(-m, m, 3000)):
        y = chain.process(u)
        assert np.isfinite(y).all()
        chain.set_state(chain.get_state())          # every state a run produces loads again
    with pytest.raises(ParameterError, match=r"^u ") as info:
        chain.process([0.0, np.nextafter(m, math.inf) * 1.000001])
    assert "input_max" in str(info.value).lower()
    with pytest.raises(ParameterError, match=r"^x "):
        chain.step(-2.0 * m)


@pytest.mark.parametrize("precision", filters.PRECISIONS)
@pytest.mark.parametrize("decay,N", [(-19.0, 2), (-19.0, 7), (-50.0, 40), (-80.0, 2)])
def test_heavily_damped_harmonic_smoothers_state_a_finite_range_and_keep_it(precision, decay, N):
    """The class the FMI fuzz campaign found (NaN after fmi2OK, a state that did not load):
    recursion gain about e^(-sigma Ts)/sin(pi/N), far above the margin SMS_INPUT_MAX leaves."""
    Ts = 1e-3
    chain = Chain([stages.damped_harmonic(T=N * Ts, sigma=decay / Ts),
                   stages.rectangular(T=5 * Ts)], Ts=Ts, precision=precision)
    m = chain.input_max
    assert 1.0 <= m < input_max(precision)
    chain.reset(-m)
    y = chain.process(np.where(np.arange(400) % 6 < 3, m, -m))
    assert np.isfinite(y).all()
    chain.set_state(chain.get_state())
    with pytest.raises(ParameterError, match=r"^u ") as info:
        chain.process([min(1.01 * m, input_max(precision))])
    assert "input_max" in str(info.value)


def test_a_sigma_leaving_no_unit_input_range_is_refused_naming_sigma():
    with pytest.raises(ParameterError, match=r"^sigma ") as info:
        Chain([stages.damped_harmonic(T=2e-3, sigma=-720e3)], Ts=1e-3)
    assert "internal gain" in str(info.value)


# ---------------------------------------------------------------- state identity

def _chain(**change):
    kw = dict(T=0.02, sigma=-2.0, precision="double", kind="damped_harmonic", Ts=1e-3)
    kw.update(change)
    return Chain([Stage(kw["kind"], T=kw["T"], sigma=kw["sigma"]),
                  stages.shaper("zvd", wn=90.0, zeta=0.1)], Ts=kw["Ts"],
                 precision=kw["precision"])


@pytest.mark.parametrize("change, field", [
    (dict(kind="exponential"), "stages[0].kind"), (dict(sigma=-2.5), "stages[0].sigma"),
    (dict(T=0.0201), "stages[0].T"), (dict(precision="float"), "precision"),
    (dict(Ts=1.0001e-3), "Ts"),
])
def test_state_from_another_configuration_says_which_field_differs(change, field):
    source = _chain()
    source.process(np.sin(np.arange(500) * 0.1))
    state = source.get_state()
    target = _chain(**change)
    target.process(np.cos(np.arange(50) * 0.3))
    before = target.get_state()
    assert before.size == state.size or field in ("stages[0].T", "Ts")
    with pytest.raises(ParameterError, match=r"^state is from another configuration") as info:
        target.set_state(state)
    assert field + " differs" in str(info.value) or (field == "precision"
                                                      and "precision differs" in str(info.value))
    np.testing.assert_array_equal(target.get_state(), before)


def test_state_header_layout_and_version():
    chain = _chain()
    state = chain.get_state()
    assert state[0] == filters.STATE_TAG and state[1] == filters.STATE_VERSION
    assert state[3] == 1e-3 and state[4] == 2
    newer = state.copy()
    newer[1] = filters.STATE_VERSION + 1
    with pytest.raises(ParameterError, match="version"):
        chain.set_state(newer)


# ---------------------------------------------------------------- one rule for tiny T

@pytest.mark.parametrize("ratio", [1e-12, 1e-9, 0.5, 1.0 - 2e-9])
@pytest.mark.parametrize("kind", stages.SMOOTHERS)
@pytest.mark.parametrize("timing", stages.TIMINGS)
def test_T_below_Ts_is_refused_by_C_and_reference(kind, timing, ratio):
    if timing == "bounded" and "harmonic" in kind:
        return      # no such stage (Stage refuses it, naming timing)
    stage = Stage(kind, T=ratio * 1e-3, timing=timing)
    with pytest.raises(ParameterError, match=r"^T ") as info:
        Chain(stage, Ts=1e-3)
    assert info.value.parameter == "T"
    with pytest.raises(ValueError, match=r"^T "):
        ref_smoothers.smoother_taps(stage, Ts=1e-3)


def test_T_within_the_grid_tolerance_of_Ts_is_one_sample_everywhere():
    stage = Stage("rectangular", T=(1.0 - 5e-10) * 1e-3)
    np.testing.assert_array_equal(Chain(stage, Ts=1e-3).taps(), [1.0])
    np.testing.assert_array_equal(ref_smoothers.smoother_taps(stage, Ts=1e-3), [1.0])
    assert trajectory.BSpline(degree=2, T=(1.0 - 5e-10) * 1e-3, Ts=1e-3).N == 1
    with pytest.raises(ValueError, match=r"^T "):
        trajectory.BSpline(degree=2, T=0.5e-3, Ts=1e-3)


# ---------------------------------------------------------------- the FMU's initialisation

@pytest.fixture(scope="module")
def smoothshaper_dir(tmp_path_factory):
    fmpy = pytest.importorskip("fmpy", reason="fmpy is needed to import the FMUs")
    if shutil.which("cmake") is None:
        pytest.skip("cmake is needed to build the FMUs")
    fmus = fmi.build_fmus(fmu_build_dir())
    return fmpy.extract(str(fmus["SmoothShaper"]), str(tmp_path_factory.mktemp("ssb")))


def _init(unzipdir, stage_values):
    from fmpy import read_model_description
    from fmpy.fmi2 import FMU2Slave
    md = read_model_description(unzipdir)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=unzipdir,
                    modelIdentifier=md.coSimulation.modelIdentifier, instanceName="b")
    fmu.instantiate()
    fmu.setupExperiment(startTime=0.0)
    fmu.enterInitializationMode()
    for name, value in stage_values.items():
        (fmu.setInteger if isinstance(value, int) else fmu.setReal)([vr[name]], [value])
    return fmu, vr


@pytest.mark.parametrize("nu", [1e13, 1e15])
def test_fmu_refuses_a_chain_far_beyond_its_memory_at_once(smoothshaper_dir, nu):
    # 8e13 bytes and more: sized in closed form, refused by the allocator (or the address
    # range) at once, never designed sample by sample.
    from fmpy.fmi1 import FMICallException
    values = fmi.start_values([stages.harmonic(T=nu * 1e-6 + 0.37e-6)], Ts=1e-6)
    fmu, _ = _init(smoothshaper_dir, values)
    t0 = time.perf_counter()
    with pytest.raises(FMICallException):
        fmu.exitInitializationMode()
    assert time.perf_counter() - t0 < O1_SECONDS
    fmu.freeInstance()


@pytest.mark.parametrize("ratio", [1e-9, 0.5])
def test_fmu_refuses_T_below_Ts(smoothshaper_dir, ratio):
    from fmpy.fmi1 import FMICallException
    values = fmi.start_values([stages.rectangular(T=ratio * 1e-3)], Ts=1e-3)
    fmu, _ = _init(smoothshaper_dir, values)
    with pytest.raises(FMICallException):
        fmu.exitInitializationMode()
    fmu.freeInstance()


def test_fmu_two_hump_ei_with_tiny_tolerance_outputs_finite(smoothshaper_dir):
    values = fmi.start_values([stages.shaper("ei2", wn=200.0, zeta=0.05,
                                                    tolerance=1e-250)], Ts=1e-3)
    fmu, vr = _init(smoothshaper_dir, values)
    fmu.exitInitializationMode()
    out = []
    for i in range(100):
        fmu.setReal([vr["u"]], [1.0])
        fmu.doStep(i * 1e-3, 1e-3)
        out.append(fmu.getReal([vr["y"]])[0])
    assert np.isfinite(out).all() and out[-1] == pytest.approx(1.0, rel=1e-14)
    fmu.terminate()
    fmu.freeInstance()
