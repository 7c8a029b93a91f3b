# SPDX-License-Identifier: Apache-2.0
"""Reference chain filtering: explicit state, block splitting, rest states, bad input."""
import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import smoothshaper as sm
from smoothshaper import reference as ref

TS = 1e-3


@st.composite
def stages(draw):
    kind = draw(st.sampled_from(["rectangular", "harmonic", "damped_harmonic", "exponential",
                                 "zv", "zvd", "ei", "ei2", "mzv", "notch"]))
    timing = draw(st.sampled_from(["exact", "paper"]))
    if kind in ("rectangular", "harmonic", "damped_harmonic", "exponential"):
        T = draw(st.floats(5.3, 60.0)) * TS
        sigma = draw(st.floats(-30.0, 0.0))
        kw = {"sigma": sigma} if kind in ("damped_harmonic", "exponential") else {}
        return getattr(sm, kind)(T=T, timing=timing, **kw)
    wn = draw(st.floats(0.05, 2.0)) / TS
    zeta = draw(st.floats(0.0, 0.5))
    if kind == "notch":
        return sm.notch(wn=wn, zeta=zeta, notch_pole_zeta=zeta + draw(st.floats(0.05, 1.5)),
                        discretization=draw(st.sampled_from(["matched", "tustin"])))
    return sm.shaper(kind, wn=wn, zeta=zeta, timing=timing)


@given(chain=st.lists(stages(), min_size=1, max_size=3),
       cuts=st.lists(st.integers(0, 300), max_size=4), seed=st.integers(0, 2 ** 31))
def test_blocks_with_explicit_state_equal_one_shot(chain, cuts, seed):
    x = np.random.default_rng(seed).normal(size=300) * 10
    whole = ref.filter(chain, x, Ts=TS)
    state = ref.filter_zi(chain, Ts=TS)
    parts, start = [], 0
    for stop in sorted(cuts) + [x.size]:
        y, state = ref.filter(chain, x[start:stop], Ts=TS, zi=state)
        parts.append(y)
        start = stop
    # FIR stages are the same dot products in the same order; a biquad continues from the
    # same four numbers: both are exact, only the convolution kernel's summation could differ
    np.testing.assert_allclose(np.concatenate(parts), whole, rtol=0,
                               atol=1e-13 * max(1.0, np.abs(whole).max()))


@given(chain=st.lists(stages(), min_size=1, max_size=3), x0=st.floats(-1e3, 1e3))
def test_rest_state_holds_its_value(chain, x0):
    y, _ = ref.filter(chain, np.full(50, x0), Ts=TS, zi=ref.filter_zi(chain, Ts=TS, x0=x0))
    np.testing.assert_allclose(y, x0, rtol=1e-12, atol=1e-12)


def test_fir_chain_equals_convolution_of_the_taps():
    chain = [sm.rectangular(T=0.0204), sm.harmonic(T=0.0117), sm.shaper("zvd", wn=150.0)]
    x = np.random.default_rng(0).normal(size=400)
    taps = np.ones(1)
    for s in chain:
        taps = np.convolve(taps, ref.impulse_response(s, Ts=TS))
    np.testing.assert_allclose(ref.filter(chain, x, Ts=TS), np.convolve(x, taps)[:x.size],
                               rtol=0, atol=1e-13)


def test_step_through_a_chain_reaches_the_target_after_its_length():
    chain = [sm.rectangular(T=0.16), sm.rectangular(T=0.05), sm.harmonic(T=0.0393)]
    y = ref.filter(chain, np.full(400, 40.0), Ts=TS)
    L = sum(ref.impulse_response(s, Ts=TS).size - 1 for s in chain) + 1
    np.testing.assert_allclose(y[L - 1:], 40.0, rtol=1e-13)
    assert abs(y[L - 2] - 40.0) > 1e-9


def test_state_is_the_past_inputs_oldest_first():
    stage = sm.rectangular(T=4 * TS)
    _, zf = ref.filter(stage, np.arange(10.0), Ts=TS, zi=ref.filter_zi(stage, Ts=TS))
    np.testing.assert_array_equal(zf[0], [7.0, 8.0, 9.0])


@pytest.mark.parametrize("call, name", [
    (lambda: ref.filter(sm.rectangular(T=0.01), [0.0, math.nan], Ts=TS), "x"),
    (lambda: ref.filter(sm.rectangular(T=0.01), np.zeros((2, 2)), Ts=TS), "x"),
    (lambda: ref.filter(sm.rectangular(T=0.01), [0.0], Ts=-1.0), "Ts"),
    (lambda: ref.filter([], [0.0], Ts=TS), "stages"),
    (lambda: ref.filter([sm.rectangular(T=0.01), "zv"], [0.0], Ts=TS), r"stages\[1\]"),
    (lambda: ref.filter(sm.rectangular(T=0.01), [0.0], Ts=TS, zi=[np.zeros(3)]), r"zi\[0\]"),
    (lambda: ref.filter(sm.rectangular(T=0.01), [0.0], Ts=TS, zi=[]), "zi"),
    (lambda: ref.filter_zi(sm.rectangular(T=0.01), Ts=TS, x0=math.inf), "x0"),
])
def test_bad_input_raises_value_error_naming_the_parameter(call, name):
    with pytest.raises(ValueError, match=rf"^{name} "):
        call()


def test_bad_state_leaves_the_callers_state_untouched():
    stage = sm.rectangular(T=0.005)
    zi = ref.filter_zi(stage, Ts=TS, x0=2.0)
    before = [z.copy() for z in zi]
    with pytest.raises(ValueError):
        ref.filter(stage, [1.0, math.nan], Ts=TS, zi=zi)
    _, zf = ref.filter(stage, [1.0], Ts=TS, zi=zi)
    for a, b in zip(zi, before):
        np.testing.assert_array_equal(a, b)                  # zi is copied, never mutated
    assert zf[0][-1] == 1.0


def _named_ref(parameter, func, *args, **kwargs):
    import warnings
    from smoothshaper import ParameterError
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(ParameterError) as info:
            func(*args, **kwargs)
    assert info.value.parameter == parameter, (info.value.parameter, str(info.value))


def test_reference_functions_name_bad_arguments():
    """s, z and t went through np.asarray (text a ValueError, None or NaN gave NaN); mode_pole
    raised OverflowError for 10**400 and took True as 1 rad/s; a t of NaN or a positive sigma
    returned NaN or overflowed; 40 moving averages summed 2^40 terms (a hang); a ragged T was a
    ValueError."""
    import smoothshaper as sms
    from smoothshaper import reference as ref
    st = sms.harmonic(T=0.05)
    for s in (["a"], [None], [np.nan], [1j, np.inf]):
        _named_ref("s", ref.continuous_transfer, st, s)
        _named_ref("z", ref.discrete_transfer, st, s, Ts=1e-3)
    _named_ref("z", ref.discrete_transfer, st, [0.0], Ts=1e-3)
    _named_ref("s", ref.continuous_transfer, st, [-1e300])
    _named_ref("wn", ref.mode_pole, 10 ** 400, 0.1)
    _named_ref("wn", ref.mode_pole, True, 0.1)
    _named_ref("t", ref.continuous_impulse_response, st, ["a"])
    _named_ref("t", ref.harmonic_trajectory, [0.0, np.nan], T=0.1)
    _named_ref("sigma", ref.exponential_trajectory, [0.0, 0.1], T=0.1, sigma=1e308)
    _named_ref("sigma", ref.damped_harmonic_trajectory, [0.0, 0.1], T=0.1, sigma=5.0)
    _named_ref("T", ref.rectangular_chain_trajectory, [0.1], T=[0.1] * 40)
    _named_ref("T", ref.rectangular_chain_trajectory, [0.1], T=[[0.1], [0.1, 0.2]])
    with np.errstate(all="raise"):                   # overflow on the way: no warning
        assert np.all(ref.rectangular_chain_trajectory([-1e300, 1e300], T=[0.1, 0.2]) >= 0)
    assert ref.mode_pole(np.float32(100.0), 0) == 100j
    assert ref.rectangular_chain_trajectory([0.05, 1.0], T=[0.1, 0.2])[1] == 1.0
