# SPDX-License-Identifier: Apache-2.0
"""Exact rest through the Python API (the C core, double and float), a property over every FIR
family and random rests: after ``Chain.reset(rest)`` an input of ``rest`` comes out as ``rest``
bit for bit, and a constant after any history comes out as itself once the chain's length has
passed (the taps sum to 1, so the convolution of a constant is that constant; the C test
tests/c/test_exact_rest.c covers notches and mixed chains). A notch is IIR: only its reset is
checked here."""
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import smoothshaper as sms

TS = 1e-3

def _smoother(kind: str, n: float, sigma: float, timing: str) -> sms.Stage:
    if timing == "bounded" and kind not in ("rectangular", "exponential"):
        timing = "exact"    # bounded timing is for the rectangular and exponential families
    damped = {"sigma": sigma} if kind in ("damped_harmonic", "exponential") else {}
    return sms.Stage(kind, T=n * TS, timing=timing, **damped)


_smoothers = st.builds(
    _smoother, st.sampled_from(("rectangular", "harmonic", "damped_harmonic", "exponential")),
    st.floats(4.0, 300.0), st.floats(-40.0, -0.1), st.sampled_from(("exact", "paper", "bounded")))
_shapers = st.builds(
    lambda kind, wn_ts, zeta, timing: sms.shaper(kind, wn=wn_ts / TS, zeta=zeta, timing=timing),
    st.sampled_from(("zv", "zvd", "zvdd", "ei", "ei2", "ei3", "mzv")), st.floats(0.02, 1.0),
    st.floats(0.0, 0.3), st.sampled_from(("exact", "paper")))
_values = st.one_of(st.just(0.0), st.just(3.7), st.floats(-1e6, 1e6, allow_subnormal=False))


def _as(precision: str, v: float) -> float:
    return float(np.float32(v)) if precision == "float" else v


@settings(max_examples=200, deadline=None)
@given(stages=st.lists(st.one_of(_smoothers, _shapers), min_size=1, max_size=3),
       rest=_values, constant=_values, history=st.integers(0, 400),
       precision=st.sampled_from(("double", "float")), seed=st.integers(0, 2**32 - 1))
def test_a_constant_comes_out_exactly_once_the_length_has_passed(stages, rest, constant, history,
                                                                 precision, seed):
    chain = sms.Chain(stages, Ts=TS, precision=precision)
    rest, constant = _as(precision, rest), _as(precision, constant)
    chain.reset(rest)
    assert np.all(chain.process(np.full(chain.length + 5, rest)) == rest)
    noise = rest + np.random.default_rng(seed).uniform(-100.0, 100.0, history)
    chain.process(noise)
    y = chain.process(np.full(chain.length + 5, constant))
    assert np.all(y[chain.length - 1:] == constant)


@settings(max_examples=20, deadline=None)
@given(rest=_values, wn_ts=st.floats(0.05, 1.0), precision=st.sampled_from(("double", "float")),
       discretization=st.sampled_from(("matched", "tustin")))
def test_a_notch_reset_to_rest_outputs_rest(rest, wn_ts, precision, discretization):
    chain = sms.Chain([sms.notch(wn=wn_ts / TS, zeta=0.02, notch_pole_zeta=0.5,
                                 discretization=discretization)], Ts=TS, precision=precision)
    rest = _as(precision, rest)
    chain.reset(rest)
    assert np.all(chain.process(np.full(50, rest)) == rest)
