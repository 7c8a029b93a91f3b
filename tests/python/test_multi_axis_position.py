# SPDX-License-Identifier: Apache-2.0
"""The multi-axis generator's position limits (qmin[i], qmax[i]) in every sync mode: random
campaigns (smoothshaper.bench.multi_position) with no sample outside, every limit held at every
sample (docs/sampled-limits.md), every axis landing exactly, the per-axis modes' plans equal
bit for bit to those without limits where these stay inside, and then within one sample of
ruckig's rounded duration where ruckig's own trajectory stays inside (ruckig does not hold
position limits); C equal to the NumPy reference (phase, independent: the multi-axis
reference; none: each axis the single-axis reference under its limits); a property test; the
refusals naming the axis with the generator unchanged; the saved state. Full-size campaigns
(10,000 cases per mode and precision) are ``long``."""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from smoothshaper.bench import multi_position as mp
from smoothshaper.errors import ParameterError
from smoothshaper.multi_axis import MultiAxisGenerator
from smoothshaper.reference.multi_axis import multi_axis_reference

U = {"double": 2.0 ** -53, "float": 2.0 ** -24}
LIM = dict(vmax=[1.0, 2.0, 0.5], amax=[10.0, 4.0, 5.0], jmax=[100.0, 50.0, 40.0])


def _assert_campaign(s):
    assert s["cases"] > 0
    assert not s["failures"], s["failures"][:2]     # direct plans bit-equal to unlimited ones
    assert s["outside"] == 0 and s["not_landed"] == 0
    assert max(s["over"], default=0) <= 1


@pytest.mark.parametrize("precision,cases", [("double", 30), ("float", 12)])
@pytest.mark.parametrize("mode", mp.MODES)
def test_campaign_draw(mode, precision, cases):
    pytest.importorskip("ruckig")
    _assert_campaign(mp.campaign(mode, cases, seed=20, precision=precision))


@pytest.mark.long
@pytest.mark.parametrize("precision", ["double", "float"])
@pytest.mark.parametrize("mode", mp.MODES)
def test_campaign_full(mode, precision):
    pytest.importorskip("ruckig")
    _assert_campaign(mp.campaign(mode, 10000, seed=1, precision=precision))


def _staircase(rng, lo, hi, n_targets, hold):
    rows = [rng.uniform(lo, hi) for _ in range(n_targets)]
    return np.repeat(np.array(rows), hold, axis=0)


@pytest.mark.parametrize("sync", ["phase", "independent"])
def test_phase_and_independent_equal_the_reference_and_stay_inside(sync):
    """Staircases that change mid-motion (where the axes would blend and, towards a limit,
    overshoot): every sample inside exactly, C equal to the multi-axis reference to 1e-12 of
    each limit and of the largest position (as without limits), each move from rest to rest."""
    rng = np.random.default_rng(5)
    lo, hi = np.array([-0.3, 0.0, -1.0]), np.array([0.4, 1.5, -0.2])
    targets = _staircase(rng, lo, hi, 8, 180)
    targets = np.vstack([targets, np.tile(targets[-1], (2500, 1))])
    g = MultiAxisGenerator(Ts=1e-3, sync=sync, qmin=lo, qmax=hi, **LIM)
    out = g.process(targets)
    assert not g.busy
    assert np.all(out[:, :, 0] >= lo) and np.all(out[:, :, 0] <= hi)
    ref = multi_axis_reference(targets, Ts=1e-3, sync=sync, qmin=lo, qmax=hi, **LIM)
    for m, lim in enumerate([np.abs(out[:, :, 0]).max(axis=0) + 1e-300, *map(np.array, LIM.values())]):
        assert np.all(np.abs(out[:, :, m] - ref[:, :, m]) <= 1e-12 * lim), m
    # without limits the same staircase blends and passes a limit (what the rule prevents)
    free = MultiAxisGenerator(Ts=1e-3, sync=sync, **LIM).process(targets)
    assert np.any(free[:, :, 0] < lo) or np.any(free[:, :, 0] > hi)


def test_none_equals_each_axis_under_the_single_axis_reference():
    """sync="none": each axis plans alone by the single-axis rule, so each equals the
    single-axis NumPy reference under its own limits (to 1e-9 of the scale, as the
    single-axis generator's test holds it), retargets mid-motion that brake, rest and move."""
    from smoothshaper.time_optimal import _run
    rng = np.random.default_rng(9)
    lo, hi = np.array([-0.3, 0.0, -1.0]), np.array([0.4, 1.5, -0.2])
    targets = _staircase(rng, lo, hi, 10, 150)
    targets = np.vstack([targets, np.tile(targets[-1], (3000, 1))])
    g = MultiAxisGenerator(Ts=1e-3, sync="none", qmin=lo, qmax=hi, **LIM)
    q0 = np.array([0.0, 0.0, -0.2])
    assert np.all(g.q0 == q0)    # at 0, or at the limit nearer 0 when 0 lies outside
    out = g.process(targets)
    assert np.all(out[:, :, 0] >= lo) and np.all(out[:, :, 0] <= hi)
    for i in range(3):
        ref = _run(targets[:, i], vmax=LIM["vmax"][i], amax=LIM["amax"][i], jmax=LIM["jmax"][i],
                   Ts=1e-3, q0=q0[i], qlim=(lo[i], hi[i]))[0]
        scale = np.array([np.abs(out[:, i, 0]).max() + 1, LIM["vmax"][i], LIM["amax"][i]])
        assert np.all(np.abs(out[:, i, :3] - ref[:, :3]) <= 1e-9 * scale), i


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_property_every_sample_inside_every_mode(data):
    """Random limits, start states and retargets in every mode and precision: no sample
    outside [qmin, qmax] (exactly), v, a, j within their limits to 32 u, the end exactly on
    the last target."""
    sync = data.draw(st.sampled_from(["phase", "independent", "time", "time_if_necessary",
                                      "none"]))
    precision = data.draw(st.sampled_from(["double", "float"]))
    n = data.draw(st.integers(1, 3))
    lo = np.array([data.draw(st.floats(-2.0, 0.0)) for _ in range(n)])
    hi = lo + np.array([data.draw(st.floats(0.05, 2.0)) for _ in range(n)])
    lim = {k: v[:n] for k, v in LIM.items()}
    g = MultiAxisGenerator(Ts=1e-3, sync=sync, qmin=lo, qmax=hi, precision=precision,
                           q0=(lo + hi) / 2, **lim)
    if sync in ("time", "time_if_necessary", "none"):
        v0 = np.array([data.draw(st.floats(-1.0, 1.0)) * lim["vmax"][i] * 0.5 for i in range(n)])
        try:
            g.start((lo + hi) / 2, v0, np.zeros(n))
        except ParameterError as e:
            assert e.parameter.startswith(("qmin", "qmax"))
    rows = []
    for _ in range(data.draw(st.integers(1, 4))):
        x = np.array([data.draw(st.floats(lo[i], hi[i])) for i in range(n)])
        rows += [x] * data.draw(st.integers(1, 400))
    rows += [rows[-1]] * 4000
    out = g.process(np.array(rows))
    real = np.float32 if precision == "float" else np.float64
    assert np.all(out[:, :, 0] >= lo.astype(real)) and np.all(out[:, :, 0] <= hi.astype(real))
    for m, key in ((1, "vmax"), (2, "amax"), (3, "jmax")):
        assert np.all(np.abs(out[:, :, m]) <= np.array(lim[key]) * (1 + 32 * U[precision]))
    assert np.all(out[-1, :, 0] == np.array(rows[-1]).astype(real))


def _state_equal(g, before):
    assert np.array_equal(g.get_state(), before)


def test_refusals_name_the_axis_and_leave_the_generator_unchanged():
    lo, hi = [-1.0, 0.0, -1.0], [1.0, 1.0, 1.0]
    g = MultiAxisGenerator(Ts=1e-3, sync="time", qmin=lo, qmax=hi, **LIM)
    before = g.get_state()
    with pytest.raises(ParameterError, match=r"^qmax: positions\[0, 1\]") as e:
        g.process_targets([[0.0, 1.5, 0.0]])
    assert e.value.status == -56
    with pytest.raises(ParameterError, match=r"^qmin: targets\[0, 1\]"):
        g.process([[0.0, -0.5, 0.0]])
    with pytest.raises(ParameterError, match=r"^velocities\[0, 2\]"):
        g.process_targets([[0.0, 0.5, 0.0]], velocities=[[0.0, 0.0, 0.1]])
    # axis 1 at 0.9 moving up at 2: its brake passes qmax = 1 (the stop needs 0.5+ more)
    with pytest.raises(ParameterError, match=r"^qmax: q\[1\] = 0.9.*would pass qmax\[1\]") as e:
        g.start([0.0, 0.9, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 0.0], positions=[0.0, 0.5, 0.0])
    assert e.value.status == -56
    with pytest.raises(ParameterError, match=r"^qmin: q\[0\] = -1.5 .*is outside"):
        g.start([-1.5, 0.0, 0.0], [0.0] * 3, [0.0] * 3)
    with pytest.raises(ParameterError, match=r"^q0"):
        g.reset([0.0, 2.0, 0.0])
    _state_equal(g, before)
    with pytest.raises(ParameterError, match=r"^qmax\[1\]"):
        MultiAxisGenerator(Ts=1e-3, qmin=[0, 1.0, 0], qmax=[1, 0.5, 1], **LIM)
    with pytest.raises(ParameterError, match=r"^qmax"):
        MultiAxisGenerator(Ts=1e-3, qmin=lo, **LIM)


def test_a_stretched_synchronised_motion_that_would_cross_brakes_rests_and_moves():
    """Axis 1 from q = 0.5 moving up at 1.5 towards 0.9, synchronised (time) to axis 0's 3.2 s
    move: its motion stretched to 3.2 s peaks at 1.24, above qmax = 0.95; the brake stays
    inside (it rests near 0.84), so the axis brakes, rests and moves to 0.9 with what is left
    of the common duration, still arriving with axis 0; every sample inside."""
    kw = dict(Ts=1e-3, sync="time", vmax=[1.0, 2.0], amax=[10.0, 4.0], jmax=[100.0, 50.0])
    g = MultiAxisGenerator(qmin=[None, -1.0], qmax=[None, 0.95], **kw)
    free = MultiAxisGenerator(**kw)
    for gen in (g, free):
        gen.start([0.0, 0.5], [0.0, 1.5], [0.0, 0.0], positions=[3.0, 0.9])
    assert g.axis_arrival == free.axis_arrival == (3200, 3200)
    out = g.process_targets(np.tile([3.0, 0.9], (3205, 1)))
    ref = free.process_targets(np.tile([3.0, 0.9], (3205, 1)))
    assert ref[:, 1, 0].max() > 1.2 and out[:, 1, 0].max() <= 0.95
    rest = np.flatnonzero((out[:, 1, 1] == 0) & (out[:, 1, 2] == 0))
    assert 0 < rest[0] < 1000 and out[rest[0], 1, 0] < 0.9     # braked to rest short of it
    assert np.all(out[3199:, :, 0] == [3.0, 0.9]) and np.any(out[3198, :, 1] != 0)


def test_saved_state_carries_the_limits():
    kw = dict(Ts=1e-3, sync="time", **LIM)
    g = MultiAxisGenerator(qmin=[-1.0, 0.0, -1.0], qmax=[1.0, 1.0, 1.0], **kw)
    g.process_targets(np.tile([0.5, 0.5, 0.5], (50, 1)))
    other = MultiAxisGenerator(qmin=[-1.0, 0.0, -1.0], qmax=[1.0, 2.0, 1.0], **kw)
    with pytest.raises(ParameterError, match=r"qmax\[1\]"):
        other.set_state(g.get_state())
    twin = MultiAxisGenerator(qmin=[-1.0, 0.0, -1.0], qmax=[1.0, 1.0, 1.0], **kw)
    twin.set_state(g.get_state())
    a = g.process_targets(np.tile([0.5, 0.5, 0.5], (2000, 1)))
    b = twin.process_targets(np.tile([0.5, 0.5, 0.5], (2000, 1)))
    assert np.array_equal(a, b)
