# SPDX-License-Identifier: Apache-2.0
"""Feasible limits and dropped targets: the C generator and the independent NumPy reference
(smoothshaper.time_optimal) refuse the same limits, naming the same quantity, and drop the
same targets (a plan with a non-finite value or longer than 2^52 samples), with the same
outputs around them."""
import math
import warnings

import numpy as np
import pytest
from hypothesis import example, given, settings, strategies as st

from smoothshaper import trajectory as tr
from smoothshaper.filters import ParameterError
from smoothshaper.time_optimal import MAX_PLAN_SAMPLES, TS_MAX, _run, reach

PROFILES = [("polynomial", {}), ("trigonometric", {}), ("damped", dict(wn=40.0, zeta=0.05))]


def run_c(x, **kw):
    g = tr.Generator(**kw)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", tr.DroppedTargetWarning)
        y = g.process(x)
    return y, g


def compare(y, ref, x, kw):
    scale = np.array([np.max(np.abs(ref[:, 0])) + 1, kw["vmax"], kw["amax"]])
    assert np.all(np.abs(y[:, :3] - ref[:, :3]) <= 1e-9 * scale)


# a staircase of (kind, value, length): kind 0 a reachable target (in units of vmax), 1 one
# 1e300 away, 2 one whose cruise alone is 1.5 times 2^52 samples, 3 one at 0.5 times that
steps = st.lists(st.tuples(st.sampled_from([0, 0, 1, 2, 3]), st.floats(-0.3, 0.3),
                           st.integers(1, 200)), min_size=1, max_size=8)


@settings(max_examples=30, deadline=None)
@given(steps=steps, profile=st.sampled_from(PROFILES), sign=st.sampled_from([-1.0, 1.0]))
# the far target again on the last sample, mid-transition: not tried yet, so not refused
@example(steps=[(0, 0.28125, 110), (0, 0.0, 1), (1, 0.0, 116), (0, 0.0, 200), (1, 0.0, 1)],
         profile=("trigonometric", {}), sign=-1.0)
def test_c_and_the_reference_drop_the_same_targets(steps, profile, sign):
    name, mode = profile
    kw = dict(vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-3)
    far = MAX_PLAN_SAMPLES * kw["Ts"] * kw["vmax"]
    value = {0: lambda v: v, 1: lambda v: sign * 1e300, 2: lambda v: sign * 1.5 * far,
             3: lambda v: sign * 0.5 * far}
    x = np.concatenate([np.full(n, value[k](v)) for k, v, n in steps])
    y, g = run_c(x, profile=name, **mode, **kw)
    ref = tr.generator_reference(x, profile=name, **mode, **kw)
    compare(y, ref, x, kw)
    shape = "cosine" if name == "trigonometric" else "ramp"
    _, _, dropped = _run(x, shape=shape, **kw)
    assert g.dropped == int(dropped.sum())
    # refused: the target held now was dropped and has not changed since (a change, even back
    # to the same value, clears it; the new target may then wait for a state to start from)
    last = np.flatnonzero(dropped)[-1] if dropped.any() else None
    assert g.refused == (last is not None and bool(np.all(x[last:] == x[-1])))


@pytest.mark.parametrize("name, mode", PROFILES)
@pytest.mark.parametrize("factor, is_dropped", [(0.99, False), (1.01, True)])
def test_the_2_52_sample_boundary(name, mode, factor, is_dropped):
    """A move whose cruise alone lasts 0.99 or 1.01 times 2^52 samples (vmax 1, Ts 1 ms: a
    target 4.5e12 away): planned below, dropped above, in C and in the reference alike."""
    kw = dict(vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-3)
    x = np.full(300, factor * MAX_PLAN_SAMPLES * kw["Ts"] * kw["vmax"])
    y, g = run_c(x, profile=name, **mode, **kw)
    _, _, dropped = _run(x, shape="cosine" if name == "trigonometric" else "ramp", **kw)
    assert g.dropped == int(dropped.sum()) == int(is_dropped)
    assert np.all(y[1:, 1] > 0) != is_dropped
    compare(y, tr.generator_reference(x, profile=name, **mode, **kw), x, kw)


exponents = st.floats(-320, 308)


@settings(max_examples=300, deadline=None)
@given(ev=exponents, ea=exponents, ej=exponents, ets=st.floats(-300, 300),
       profile=st.sampled_from(["polynomial", "trigonometric"]),
       precision=st.sampled_from(["double", "float"]))
def test_c_and_the_reference_refuse_the_same_limits(ev, ea, ej, ets, profile, precision):
    """Random limits over the whole double range: the C core accepts exactly the limits the
    reference's region (reach()) accepts, and names the same quantity when it refuses."""
    vmax, amax, jmax, Ts = 10.0 ** ev, 10.0 ** ea, 10.0 ** ej, 10.0 ** ets
    if not all(0 < v < math.inf for v in (vmax, amax, jmax, Ts)):
        return
    if precision == "float" and not 1.2e-38 <= Ts <= 3.4e38:
        return   # Ts itself is refused before the limits (a sample period error)
    if not Ts <= TS_MAX:
        return   # Ts above SMS_TS_MAX is refused before the limits too (named Ts)
    expected = reach(vmax, amax, jmax, Ts, "cosine" if profile == "trigonometric" else "ramp",
                     precision)["quantity"]
    try:
        tr.Generator(vmax=vmax, amax=amax, jmax=jmax, Ts=Ts, profile=profile,
                     precision=precision)
        got = None
    except ParameterError as exc:
        got = str(exc)
    if expected is None:
        assert got is None, got
    elif expected in ("vmax", "amax", "jmax"):   # a limit itself: named with its value alone
        assert got is not None and got.startswith(f"{expected}=") and (
            ": below " in got or ": above " in got), (expected, got)
    else:
        assert got is not None and f": {expected} = " in got, (expected, got)


def test_the_reference_refuses_infeasible_limits_too():
    with pytest.raises(ParameterError, match=r"sqrt\(vmax/jmax\)"):
        tr.generator_reference(np.zeros(3), vmax=1.0, amax=1e-30, jmax=1e-300, Ts=1e-3)


@settings(max_examples=200, deadline=None)
@given(ev=exponents, ea=exponents, ej=exponents, ets=st.floats(-300, 300),
       profile=st.sampled_from(["polynomial", "trigonometric"]))
def test_the_reference_names_the_argument_the_generator_names(ev, ea, ej, ets, profile):
    """Refused limits: generator_reference names the same argument as the Generator (the
    limit the quantity is formed from, or Ts), e.g. amax for amax=1e-320, not vmax."""
    kw = dict(vmax=10.0 ** ev, amax=10.0 ** ea, jmax=10.0 ** ej, Ts=10.0 ** ets,
              profile=profile)
    if not all(0 < v < math.inf for k, v in kw.items() if k != "profile"):
        return
    try:
        tr.Generator(**kw)
        return
    except ParameterError as exc:
        expected = exc.parameter
    with pytest.raises(ParameterError) as got:
        tr.generator_reference(np.zeros(2), **kw)
    assert got.value.parameter == expected, (str(got.value), expected)
    for name in ("vmax", "amax", "jmax", "Ts"):
        assert f"{name}={kw[name]!r}" in str(got.value)


@pytest.mark.parametrize("Ts", [2.0 ** 967 * (1 + 2.0 ** -52), 1e300, 1.7976931348623157e308])
def test_a_Ts_above_the_largest_is_named_by_the_generator_and_the_reference(Ts):
    """Ts above SMS_TS_MAX = 2^967 (2^56 Ts must stay finite) is refused by both, naming Ts
    and its value, before limits that would be refused too (jmax = 1e308); 2^967 itself is
    taken by both."""
    for kw in (dict(vmax=1.0, amax=1.0, jmax=1.0), dict(vmax=1.0, amax=1.0, jmax=1e308)):
        with pytest.raises(ParameterError, match=r"2\^967") as c_err:
            tr.Generator(Ts=Ts, **kw)
        with pytest.raises(ParameterError, match=r"2\^967") as ref_err:
            tr.generator_reference(np.zeros(2), Ts=Ts, **kw)
        assert c_err.value.parameter == ref_err.value.parameter == "Ts"
        assert f"Ts={Ts!r}" in str(c_err.value) and f"Ts={Ts!r}" in str(ref_err.value)
    kw = dict(vmax=1.0, amax=1.0, jmax=1.0, Ts=TS_MAX)
    np.testing.assert_array_equal(tr.Generator(**kw).process(np.zeros(3)),
                                  tr.generator_reference(np.zeros(3), **kw))
