# SPDX-License-Identifier: Apache-2.0
"""Multi-axis generator: phase-synchronised rest-to-rest moves against ruckig (same arrival
sample, straight line, limits at every sample, duration), staircases with reversals and
mid-motion changes (limits, exact arrival, C == NumPy reference), independent axes, errors."""
import math
import sys
import os
import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings, strategies as st

from smoothshaper.errors import DroppedTargetWarning
from smoothshaper.filters import ParameterError
from smoothshaper.reference.multi_axis import multi_axis_reference, phase_duration
from smoothshaper.bench.trajectory import ruckig_phase
from smoothshaper.trajectory import MultiAxisGenerator, multi_axis_move

ruckig = pytest.importorskip("ruckig")

# MULTI_AXIS_EXAMPLES=500 pytest tests/python/test_multi_axis.py: the long random campaign
SETTINGS = dict(max_examples=int(os.environ.get("MULTI_AXIS_EXAMPLES", "20")), deadline=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])


@st.composite
def limits(draw, axes):
    """Per-axis limits spanning 4 orders of magnitude each."""
    e = st.floats(min_value=-2.0, max_value=2.0)
    v = np.array([10 ** draw(e) for _ in range(axes)])
    a = np.array([10 ** draw(e) for _ in range(axes)]) * v
    j = np.array([10 ** draw(e) for _ in range(axes)]) * a
    return v, a, j


def assert_within_limits(out, vmax, amax, jmax, Ts, q_before):
    """Reported v, a, j and backward differences dq/Ts, d2q/Ts^2, d3q/Ts^3 within the limits
    to 1e-9 relative (plus the rounding of q, a few ulps of the largest position)."""
    lim = np.stack([vmax, amax, jmax])                           # (3, axes)
    ratio = np.abs(out[:, :, 1:]) / lim.T[None]
    assert ratio.max() <= 1 + 1e-9, ratio.max()
    q = np.vstack([np.tile(q_before, (3, 1)), out[:, :, 0]])     # rest before the first sample
    ulp = 4 * np.finfo(float).eps * np.abs(q).max(axis=0)
    for order in (1, 2, 3):
        d = np.diff(q, n=order, axis=0) / Ts ** order
        allowed = lim[order - 1] * (1 + 1e-9) + 2 ** order * ulp / Ts ** order
        assert np.all(np.abs(d) <= allowed), (order, (np.abs(d) / allowed).max())


@settings(**SETTINGS)
@given(data=st.data(), axes=st.integers(2, 6))
def test_phase_rest_to_rest_matches_ruckig(data, axes):
    v, a, j = data.draw(limits(axes))
    start = np.array(data.draw(st.lists(st.floats(-10, 10), min_size=axes, max_size=axes)))
    delta = np.array(data.draw(st.lists(st.floats(-10, 10), min_size=axes, max_size=axes)))
    if np.abs(delta).max() < 1e-3:
        delta[0] = 1.0
    target = start + delta
    delta = target - start  # what the generator sees
    T = phase_duration(delta, vmax=v, amax=a, jmax=j)
    Ts = T / data.draw(st.floats(3.0, 600.0))
    nu = T / Ts
    gen = MultiAxisGenerator(vmax=v, amax=a, jmax=j, Ts=Ts, q0=start)
    n = int(math.ceil(nu)) + 3
    out = gen.process(np.tile(target, (n, 1)))
    # every axis arrives exactly, on the same sample, ceil(T/Ts) samples after the step
    at = (out[:, :, 0] == target) & np.all(out[:, :, 1:] == 0, axis=2)
    # a subnormal displacement moves below the resolution: its v underflows to 0 and q rounds
    # onto the target before the arrival (delta = [2, 5e-324] at T/Ts = 3: sample 2)
    moving = np.abs(delta) >= np.finfo(float).tiny
    first = [int(np.argmax(at[:, i])) for i in np.flatnonzero(moving)]
    assert len(set(first)) == 1 and np.all(at[first[0]:])
    N = first[0]
    near_integer = abs(nu - round(nu)) <= 1e-9 * nu
    assert N == math.ceil(nu) or (near_integer and abs(N - round(nu)) <= 1), (N, nu)
    # ruckig: same duration when it finds a phase-synchronised move, shorter (curved) otherwise
    T_ruckig, deviation = ruckig_phase(delta, v, a, j, samples=41)
    straight = deviation < 1e-9
    if straight:
        assert T == pytest.approx(T_ruckig, rel=1e-12, abs=0)
        assert N == math.ceil(T_ruckig / Ts) or near_integer
    else:
        assert T_ruckig <= T * (1 + 1e-12)
    # straight line: q - start parallel to delta, to 1e-12 of the move
    k = np.argmax(np.abs(delta))
    s = (out[:, k, 0] - start[k]) / delta[k]
    dev = np.abs(out[:, :, 0] - start - np.outer(s, delta)).max() / np.abs(delta).max()
    assert dev <= 1e-12
    assert_within_limits(out, v, a, j, Ts, start)
    ref = multi_axis_reference(np.tile(target, (n, 1)), vmax=v, amax=a, jmax=j, Ts=Ts, q0=start)
    for m, lim in enumerate([np.abs(out[:, :, 0]).max(axis=0) + 1e-300, v, a, j]):
        assert np.all(np.abs(out[:, :, m] - ref[:, :, m]) <= 1e-12 * lim), m


@st.composite
def staircases(draw):
    axes = draw(st.integers(1, 6))
    v, a, j = draw(limits(axes))
    Ts = 10 ** draw(st.floats(-4, -2))
    scale = v * Ts * np.array([10 ** draw(st.floats(0, 2.0)) for _ in range(axes)])
    steps = draw(st.lists(st.tuples(st.integers(1, 150),
                                    st.lists(st.floats(-1, 1), min_size=axes, max_size=axes)),
                          min_size=2, max_size=8))
    rows = [np.tile(np.array(t) * scale, (hold, 1)) for hold, t in steps]
    sync = draw(st.sampled_from(["phase", "independent"]))
    return np.vstack(rows), v, a, j, Ts, sync


@settings(**SETTINGS)
@given(case=staircases())
def test_staircase_limits_arrival_and_reference(case):
    targets, v, a, j, Ts, sync = case
    gen = MultiAxisGenerator(vmax=v, amax=a, jmax=j, Ts=Ts, sync=sync)
    out = gen.process(targets)
    tail = []
    while gen.busy:  # hold the last target until arrival
        tail.append(gen.process(targets[-1:]))
        assert len(tail) < 10 ** 6
    full_targets = np.vstack([targets] + [targets[-1:]] * len(tail))
    full = np.concatenate([out] + tail) if tail else out
    np.testing.assert_array_equal(full[-1, :, 0], targets[-1])
    np.testing.assert_array_equal(full[-1, :, 1:], 0)
    assert_within_limits(full, v, a, j, Ts, np.zeros(v.size))
    ref = multi_axis_reference(full_targets, vmax=v, amax=a, jmax=j, Ts=Ts, sync=sync)
    # same plan arithmetic and roots: C and reference agree to rounding (bit for bit on every
    # case tried); 1e-12 of each limit and of the largest position
    for m, lim in enumerate([np.abs(full[:, :, 0]).max(axis=0) + 1e-300, v, a, j]):
        assert np.all(np.abs(full[:, :, m] - ref[:, :, m]) <= 1e-12 * lim), m


def test_held_targets_land_exactly_mid_staircase():
    """Each target held long enough is reached exactly, on every axis, and stays there."""
    v, a, j = np.array([1.0, 2.0, 0.5]), np.array([10.0, 4.0, 20.0]), np.array([100.0, 50.0, 400.0])
    gen = MultiAxisGenerator(vmax=v, amax=a, jmax=j, Ts=1e-3)
    for target in ([1.0, -2.0, 0.5], [1.2, -1.0, 0.5], [-1.0, -1.0, -1.0]):
        out = gen.process(np.tile(target, (20000, 1)))
        assert not gen.busy
        np.testing.assert_array_equal(out[-1, :, 0], target)


def test_independent_axes_are_single_axis_generators():
    v, a, j = [1.0, 3.0], [5.0, 2.0], [50.0, 80.0]
    targets = np.repeat([[1.0, -2.0], [-0.5, 2.0], [0.3, 0.3]], [300, 700, 3000], axis=0)
    both = MultiAxisGenerator(vmax=v, amax=a, jmax=j, Ts=2e-3, sync="independent").process(targets)
    for i in range(2):
        one = MultiAxisGenerator(vmax=[v[i]], amax=[a[i]], jmax=[j[i]], Ts=2e-3).process(
            targets[:, i:i + 1])
        np.testing.assert_array_equal(both[:, i], one[:, 0])


def test_offline_move_design():
    m = multi_axis_move([0, 0, 0], [1, 2, -1], vmax=[1, 2, 3], amax=[10, 5, 20],
                        jmax=[100, 300, 50], Ts=1e-3)
    assert m.T == pytest.approx(phase_duration([1, 2, -1], vmax=[1, 2, 3], amax=[10, 5, 20],
                                               jmax=[100, 300, 50]), rel=1e-15)
    assert m.N == math.ceil(m.T / 1e-3 - 1e-9)
    np.testing.assert_array_equal(m.profile[-1, :, 0], [1, 2, -1])
    assert m.profile.shape == (m.N + 1, 3, 4)


def test_float_build_keeps_limits():
    v, a, j = [1.0, 2.0], [10.0, 5.0], [100.0, 300.0]
    targets = np.repeat([[1.0, -2.0], [-0.5, 2.0], [0.3, 0.3]], [300, 700, 5000], axis=0)
    out = MultiAxisGenerator(vmax=v, amax=a, jmax=j, Ts=1e-3, precision="float").process(targets)
    lim = np.array([v, a, j]).T
    # the arrival's rounding onto the grid and the roundings of the plan and of the evaluation:
    # 32 u (docs/multi-axis.md)
    assert (np.abs(out[:, :, 1:]) / lim[None]).max() <= 1 + 32 * 2.0 ** -24
    np.testing.assert_array_equal(out[-1, :, 0], np.float32([0.3, 0.3]))


@pytest.mark.parametrize("precision, u", [("double", 2.0 ** -53), ("float", 2.0 ** -24)])
def test_last_jerk_phase_on_a_sample_keeps_amax(precision, u):
    """A sample on the start of a transition's last jerk phase (fraction 1 - rho, which rounds
    by up to u/(2 rho) of that phase) reports at most amax, to the 32 u of the plan's and the
    evaluation's rounding. vmax = 1, amax = 10, jmax = 100 R, Ts = amax/jmax (the jerk phase,
    rho = 1/(R + 1)): the first transition's last jerk phase starts on sample R, the stop's one
    sample before the arrival, and the move lasts N samples less 8 u (no slack from the grid).
    With R = 1001, 1 - fl(1 - rho) exceeds rho by 130 eps in float and 112 eps in double: the
    evaluation by x against fl(1 - rho) reported amax (1 + 1.6e-5) and (1 + 2.6e-14) there."""
    R, N = 1001, 12000
    Ts = 10.0 / (100.0 * R)
    D = (N * Ts - (0.1 + Ts)) * (1 - 8 * u)
    targets = np.full((N + 2, 1), D)
    gen = MultiAxisGenerator(vmax=1.0, amax=10.0, jmax=100.0 * R, Ts=Ts, precision=precision)
    out = gen.process(targets)
    a = np.abs(out[:, 0, 2]) / 10.0
    assert a.max() <= 1 + 32 * u, a.max() - 1
    assert a[R] >= 1 - 1e-6 and a[N - 1] >= 1 - 1e-6  # on the peak, at both breakpoints
    assert np.all(out[N:, 0, 1:] == 0) and np.all(out[N:, 0, 0] == out[-1, 0, 0])  # arrival: N
    if precision == "double":
        ref = multi_axis_reference(targets, vmax=1.0, amax=10.0, jmax=100.0 * R, Ts=Ts)
        assert np.abs(ref[:, 0, 2]).max() / 10.0 <= 1 + 32 * u
        for m, lim in enumerate([abs(D), 1.0, 10.0, 100.0 * R]):
            assert np.all(np.abs(out[:, 0, m] - ref[:, 0, m]) <= 1e-12 * lim), m


@pytest.mark.parametrize("kwargs, parameter", [
    (dict(vmax=[1, -1, 1]), "vmax[1]"),
    (dict(amax=[1, 1, 0]), "amax[2]"),
    (dict(jmax=[1, float("nan"), 1]), "jmax[1]"),
    (dict(amax=[1, 1]), "amax"),
    (dict(Ts=0.0), "Ts"),
    (dict(Ts=sys.float_info.max), "Ts"),            # 2^53 Ts overflows: above SMS_TS_MAX
    (dict(Ts=math.ldexp(1.0, 967) * (1 + 2 ** -52)), "Ts"),  # just above SMS_TS_MAX = 2^967
    (dict(sync="sideways"), "sync"),
    (dict(vmax=[1] * 9, amax=1, jmax=1), "vmax"),
    (dict(q0=[0, float("inf"), 0]), "q0"),
])
def test_bad_input_names_the_parameter(kwargs, parameter):
    args = dict(vmax=[1, 1, 1], amax=[1, 1, 1], jmax=[1, 1, 1], Ts=1e-3)
    args.update(kwargs)
    with pytest.raises(ParameterError) as e:
        MultiAxisGenerator(**args)
    assert e.value.parameter == parameter


def test_targets_shape_and_values_checked():
    gen = MultiAxisGenerator(vmax=[1, 1], amax=[1, 1], jmax=[1, 1], Ts=1e-3)
    with pytest.raises(ParameterError, match="shape"):
        gen.process(np.zeros((5, 3)))
    with pytest.raises(ParameterError, match=r"targets\[2, 1\]"):
        gen.process(np.array([[0, 0], [0, 0], [0, np.nan]]))


def test_different_stages_per_axis_warn():
    from smoothshaper import stages
    zv = stages.shaper("zv", wn=30.0, zeta=0.05)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        MultiAxisGenerator(vmax=[1, 1], amax=[1, 1], jmax=[1, 1], Ts=1e-3, stages=[zv])
    with pytest.warns(UserWarning, match="bend straight lines"):
        MultiAxisGenerator(vmax=[1, 1], amax=[1, 1], jmax=[1, 1], Ts=1e-3, stages=[[zv], []])


@pytest.mark.parametrize("size", [1e-30, 1e-300, 2.2250738585072014e-311])
def test_tiny_moves_arrive_and_match_reference(size):
    """Tiny and subnormal displacements: limit ratios are capped, outputs stay finite."""
    targets = np.array([[0.0, 0.0]] + [[size, -size]] * 50)
    args = dict(vmax=[1.0, 2.0], amax=[1.0, 3.0], jmax=[1.0, 5.0], Ts=0.01)
    out = MultiAxisGenerator(**args).process(targets)
    ref = multi_axis_reference(targets, **args)
    assert np.all(np.isfinite(out))
    np.testing.assert_array_equal(out[-1, :, 0], [size, -size])
    np.testing.assert_allclose(out, ref, rtol=0, atol=1e-12 * size)


def _zv_and_smoother():
    from smoothshaper import stages
    return [stages.shaper("zv", wn=40.0, zeta=0.05), stages.rectangular(T=0.0173), stages.notch(wn=70.0, zeta=0.02)]


@pytest.mark.parametrize("sync", ["phase", "independent"])
def test_stages_in_c_equal_reference(sync):
    """Per-axis vibration stages run in C: q, v, a, j of every axis equal the NumPy reference
    (profile, then the reference chain per signal) to rounding, with the same stages on every
    axis and with different ones (which warn)."""
    from smoothshaper import stages
    v, a, j = [0.8, 0.5, 1.2], [6.0, 9.0, 4.0], [90.0, 200.0, 60.0]
    q0 = [0.05, -0.1, 0.0]
    targets = np.repeat([[0.3, 0.2, -0.25], [0.1, 0.35, 0.1], [-0.2, -0.1, 0.3]], [180, 120, 900],
                        axis=0)
    common = _zv_and_smoother()
    per_axis = [common, [stages.shaper("zvd", wn=25.0, zeta=0.1)], []]
    for chains in (common, per_axis):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            out = MultiAxisGenerator(vmax=v, amax=a, jmax=j, Ts=1e-3, sync=sync, q0=q0,
                                     stages=chains).process(targets)
        ref = multi_axis_reference(targets, vmax=v, amax=a, jmax=j, Ts=1e-3, sync=sync, q0=q0,
                                   stages=chains)
        for m, lim in enumerate([np.abs(ref[:, :, 0]).max(), v, a, j]):
            assert np.all(np.abs(out[:, :, m] - ref[:, :, m]) <= 1e-12 * np.asarray(lim)), m


@settings(**SETTINGS)
@given(data=st.data(), axes=st.integers(2, 6))
def test_same_stages_keep_lines_straight(data, axes):
    """The same stages on every axis: a rest-to-rest phase move stays on its segment to 1e-12 of
    the move, during the move and while the stages settle."""
    from smoothshaper import stages
    v, a, j = data.draw(limits(axes))
    start = np.array(data.draw(st.lists(st.floats(-10, 10), min_size=axes, max_size=axes)))
    delta = np.array(data.draw(st.lists(st.floats(-10, 10), min_size=axes, max_size=axes)))
    if np.abs(delta).max() < 1e-3:
        delta[0] = 1.0
    T = phase_duration(delta, vmax=v, amax=a, jmax=j)
    Ts = T / data.draw(st.floats(20.0, 400.0))
    wn = data.draw(st.floats(0.05, 0.5)) * math.pi / Ts
    kind = data.draw(st.sampled_from(["zv", "zvd", "ei", "mzv"]))
    chain = [stages.shaper(kind, wn=wn, zeta=data.draw(st.floats(0.0, 0.3)))]
    gen = MultiAxisGenerator(vmax=v, amax=a, jmax=j, Ts=Ts, q0=start, stages=chain)
    target = start + delta
    out = gen.process(np.tile(target, (int(T / Ts) + 200, 1)))
    delta = target - start
    k = np.argmax(np.abs(delta))
    s = (out[:, k, 0] - start[k]) / delta[k]
    dev = np.abs(out[:, :, 0] - start - np.outer(s, delta)).max() / np.abs(delta).max()
    assert dev <= 1e-12
    np.testing.assert_allclose(out[-1, :, 0], target, rtol=0, atol=1e-12 * np.abs(target).max())


def test_stage_errors_name_the_parameter():
    from smoothshaper import stages
    with pytest.raises(ParameterError) as e:
        MultiAxisGenerator(vmax=[1, 1], amax=[1, 1], jmax=[1, 1], Ts=1e-3,
                           stages=[stages.shaper("zv", wn=5000.0, zeta=0.0)])
    assert e.value.parameter == "wn"


@pytest.mark.parametrize("precision", ["double", "float"])
def test_unrepresentable_moves_are_dropped(precision):
    """Within feasible limits, a target whose move cannot be planned (|d| = 1e300 with
    vmax = 1: a cruise beyond 2^52 samples) is dropped like a non-finite one: every output
    stays finite, the axes keep their previous target, and the next representable target
    moves as usual; the reference drops it alike."""
    big = 1e300 if precision == "double" else 1e38
    args = dict(vmax=[1.0, 1.0], amax=[1e-3, 1.0], jmax=[1e-3, 1.0], Ts=1e-3)
    targets = np.array([[big, -big]] * 30 + [[0.0, 0.5]] * 5 + [[big, 0.5]] * 20
                       + [[0.0, 0.25]] * 4000)
    g = MultiAxisGenerator(precision=precision, **args)
    # counted once: the second [big, 0.5] arrives in the first velocity transition of axis
    # 1's move and changes before the move may blend, so it is never tried
    with pytest.warns(DroppedTargetWarning, match=r"1 target vector\(s\) dropped"):
        out = g.process(targets)
    assert g.dropped == 1 and g.refused == (False, False)
    with pytest.warns(DroppedTargetWarning, match=r"refused now: \{'target\[0\]'"):
        g.process(np.tile([big, 0.25], (3000, 1)))
    assert g.dropped == 2 and g.refused == (True, True)   # phase: the group together
    g.reset()
    assert g.dropped == 0 and g.refused == (False, False)
    assert np.all(np.isfinite(out))
    np.testing.assert_array_equal(out[:30], 0.0)   # dropped at rest: still at q0
    u = 2.0 ** -24 if precision == "float" else 2.0 ** -53
    assert np.all(np.abs(out[:, :, 1:]) <= np.array([[1.0, 1e-3, 1e-3], [1, 1, 1]])[None]
                  * (1 + 32 * u))
    if precision == "double":
        ref = multi_axis_reference(targets, **args)
        np.testing.assert_array_equal(out, ref)


@pytest.mark.parametrize("precision", ["double", "float"])
def test_limits_with_which_no_move_reaches_vmax_are_refused(precision):
    """Limits with which no move of an axis can reach its vmax are refused at construction,
    naming the axis, its limits and the quantity out of range (sms_multi_generator_reach);
    just inside each bound the limits are accepted."""
    def refused(**kw):
        with pytest.raises(ParameterError) as e:
            MultiAxisGenerator(precision=precision, **{"Ts": 1e-3, **kw})
        return e.value
    # the documented example on axis 1: reaching vmax takes 4 sqrt(vmax/jmax) = 4e150 s
    e = refused(vmax=[1.0, 1.0], amax=[1.0, 1e-30], jmax=[1.0, 1e-300])
    assert e.parameter == "jmax[1]" and "axis 1" in str(e) and "jmax[1]=1e-300" in str(e)
    if precision == "double":
        assert "sqrt(vmax/jmax) = 1e+150 s" in str(e) and "4e+150 s" in str(e)
    else:
        assert "smallest normal float" in str(e)
    # the planner's ratios (capped at 2^60) must stay below 2^56: both sides of the bound
    ratio = 2.0 ** 56
    for kw, name, quantity in [(dict(amax=[1.0, ratio], jmax=[1.0, 1.0]), "amax[1]", "amax/vmax"),
                               (dict(amax=[1.0, 1.0], jmax=[1.0, ratio]), "jmax[1]", "jmax/vmax")]:
        MultiAxisGenerator(precision=precision, vmax=[1.0, 1.0], Ts=1e-3,
                           **{k: [v[0], v[1] * (1 - 1e-6)] for k, v in kw.items()})
        e = refused(vmax=[1.0, 1.0], **{k: [v[0], v[1] * (1 + 1e-6)] for k, v in kw.items()})
        assert e.parameter == name and f"{quantity} = " in str(e) and "axis 1" in str(e)
    # the duration to reach vmax against 2^50 samples of Ts: Ts is named
    T = 2.0 * (1.0 / 5.0 + 5.0 / 100.0)
    MultiAxisGenerator(precision=precision, vmax=[1.0], amax=[5.0], jmax=[100.0],
                       Ts=T / 2.0 ** 50 * (1 + 1e-6))
    if precision == "double":
        e = refused(vmax=[1.0], amax=[5.0], jmax=[100.0], Ts=T / 2.0 ** 50 * (1 - 1e-6))
        assert e.parameter == "Ts" and "vmax/amax" in str(e) and "axis 0" in str(e)
    # a Ts beyond the precision's range next to a limit out of range: named, no crash
    if precision == "float":
        e = refused(vmax=[1.0, 1e-320], amax=[1.0, 1.0], jmax=[1.0, 1.0], Ts=1e300)
        assert e.parameter == "Ts" and str(e).startswith("Ts=1e+300: above 3.40282e+38")


def test_axis_count_and_state_identity_match_the_c_core():
    """The Python side's axis limit and the identity field names it reports a differing
    saved state by have one slot per C identity value (multi_generator.h)."""
    from smoothshaper import multi_axis
    from smoothshaper._state_identity import HEAD_FIELDS
    from smoothshaper.filters import _backend
    _, lib = _backend("double")
    assert MultiAxisGenerator.MAX_AXES == lib.SMS_MULTI_MAX_AXES
    assert len(HEAD_FIELDS + multi_axis._MULTI_IDENTITY_FIELDS) == lib.SMS_MULTI_IDENTITY_COUNT


def _first_transition_search():
    """tests/bench/multi_first_transition_search.py as a module (its planner from a crafted
    cruise and its adversarial families)."""
    import importlib.util
    path = os.path.join(os.path.dirname(__file__), "..", "bench",
                        "multi_first_transition_search.py")
    spec = importlib.util.spec_from_file_location("multi_first_transition_search", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


SEARCH = _first_transition_search()


@settings(suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow])
@given(n=st.integers(1, 4), precision=st.sampled_from(["double", "float"]), data=st.data())
def test_first_transition_keeps_the_limits_when_the_arrival_snaps_from_a_cruise(n, precision,
                                                                               data):
    """A move from a cruise at V (1 to 4 axes) whose candidate cruises at W, one axis at vmax,
    for a few eps of the move, with Ts putting the planned end just after a sample (rounded
    onto it: W rises by up to 2 GRID_TOL) or just before it (rounded up). The planned first
    transition's peaks stay within the limits to 2 (s - 1) <= 4 GRID_TOL = 16 u and rounding,
    and its first reported sample (the jerk phase) within 32 u (docs/multi-axis.md); they
    reached 40 u with the stretched jerk fraction (tests/c/test_multi_generator.c)."""
    bounds = SEARCH.snap_bounds(n)
    x = np.array([data.draw(st.floats(lo, hi), label=f"x{i}")
                  for i, (lo, hi) in enumerate(bounds)])
    try:
        case = SEARCH.snap_case(x, n, precision)
    except ParameterError:
        case = None
    assume(case is not None)
    planner, V0, target = case
    f = planner.plan(V0, target)
    assume(f is not None)
    v, a, j = planner.peaks(f)
    assert a <= 32 and j <= 32, (v, a, j)
    u = SEARCH.UNIT[precision]
    limits = [np.asarray(L, dtype=SEARCH.REAL[precision]).astype(float)
              for L in (planner.g.vmax, planner.g.amax, planner.g.jmax)]
    for i in range(3):
        assert np.all(np.abs(f["first"][:, i + 1]) <= limits[i] * (1 + 32 * u))
