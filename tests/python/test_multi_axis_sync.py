# SPDX-License-Identifier: Apache-2.0
"""The multi-axis generator's Time, TimeIfNecessary, None and per-axis synchronisation from
any start state, against ruckig (smoothshaper.bench.multi_sync): the arrival at most one
sample after ruckig's duration rounded up to the grid (past a blocked duration: its discrete
one plus one), every reported value within the limits to 32 u, every backward difference of
every axis's sampled position within its bound after the rounding floor of
docs/sampled-limits.md, the synchronised axes on one arrival sample, each axis exactly on its
target state there. Full-size campaigns (10,000 cases per mode and precision) are ``long``.
Then the refusals, the saved state and the rest path."""
from __future__ import annotations

import numpy as np
import pytest

from smoothshaper.bench import multi_sync as ms
from smoothshaper.errors import ParameterError
from smoothshaper.multi_axis import MultiAxisGenerator

pytest.importorskip("ruckig")


def _assert_campaign(summary):
    assert summary["cases"] > 0
    assert not summary["failures"], summary["failures"][:2]
    assert summary["not_landed"] == 0 and summary["not_synchronised"] == 0
    assert max(summary["over"], default=0) <= 1


@pytest.mark.parametrize("precision,cases", [("double", 60), ("float", 25)])
@pytest.mark.parametrize("feature", ms.FEATURES)
def test_campaign_draw(feature, precision, cases):
    _assert_campaign(ms.campaign(feature, cases, seed=20, precision=precision))


@pytest.mark.long
@pytest.mark.parametrize("precision", ["double", "float"])
@pytest.mark.parametrize("feature", ms.FEATURES)
def test_campaign_full(feature, precision):
    _assert_campaign(ms.campaign(feature, 10000, seed=1, precision=precision))


def _gen(sync="time", **kw):
    return MultiAxisGenerator(vmax=[1.0, 2.0, 0.5], amax=[2.0, 3.0, 1.0], jmax=[10.0, 20.0, 5.0],
                              Ts=1e-3, sync=sync, **kw)


def test_time_lands_every_axis_on_one_sample_on_a_curved_path():
    g = _gen()
    g.start([0.0, 0.2, -0.1], [0.5, -1.0, 0.0], [0.0, 1.0, 0.0],
            positions=[1.0, -0.5, 0.3], velocities=[0.0, 0.5, 0.0])
    N = g.arrival
    arrive = list(g.axis_arrival)
    assert arrive == [N] * 3
    out = g.process_targets(np.tile([1.0, -0.5, 0.3], (N + 5, 1)),
                            velocities=np.tile([0.0, 0.5, 0.0], (N + 5, 1)))
    assert out[N - 1, 0, 0] == 1.0 and out[N - 1, 2, 0] == 0.3
    assert out[N - 1, 1, 0] == -0.5 and out[N - 1, 1, 1] == 0.5
    assert np.all(out[N - 2, [0, 2], 1] != 0)       # nobody waiting at its target before N
    # the path is not a straight line: the axes' progress fractions differ mid-move
    frac = (out[N // 2, :, 0] - [0.0, 0.2, -0.1]) / (np.array([1.0, -0.5, 0.3]) - [0.0, 0.2, -0.1])
    assert np.ptp(frac) > 0.05


def test_none_and_time_if_necessary_leave_rest_targets_to_themselves():
    starts = ([0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0])
    arrivals = {}
    for sync in ("time", "time_if_necessary", "none"):
        g = _gen(sync)
        g.start(*starts, positions=[1.0, 0.01, 0.3], velocities=[0.0, 0.5, 0.0])
        arrivals[sync] = list(g.axis_arrival)
    assert len(set(arrivals["time"])) == 1
    assert arrivals["none"][0] == arrivals["time_if_necessary"][0]    # a rest target: its own
    assert arrivals["none"][1] < arrivals["time_if_necessary"][1]     # moving: synchronised
    assert arrivals["time_if_necessary"][1] == max(arrivals["none"])
    # per-axis selection: axis 1 alone, the others in time
    g = _gen("time")
    g.start(*starts, positions=[1.0, 0.01, 0.3], velocities=[0.0, 0.5, 0.0],
            axis_sync=[None, "none", "time"])
    got = list(g.axis_arrival)
    assert got[1] == arrivals["none"][1] and got[0] == got[2] == max(arrivals["none"][::2])


def test_minimum_duration_stretches_the_synchronised_axes():
    g = _gen()
    g.start([0.0] * 3, [0.0] * 3, [0.0] * 3, positions=[0.1, 0.1, 0.1], minimum_duration=2.5)
    assert g.arrival == 2500
    out = g.process_targets(np.full((2510, 3), 0.1), minimum_duration=2.5)
    assert np.all(out[2499:, :, 0] == 0.1) and np.all(out[2499:, :, 1:] == 0)
    assert np.all(out[2497, :, 0] != 0.1)


@pytest.mark.parametrize("kw,name", [
    (dict(velocities=[[0.0, 2.5, 0.0]]), "velocities[0, 1]"),
    (dict(accelerations=[[0.0, 0.0, 1.5]]), "accelerations[0, 2]"),
    (dict(accelerations=[[1.9, 0.0, 0.0]], velocities=[[0.9, 0.0, 0.0]]), "accelerations[0, 0]"),
    (dict(axis_sync=["time", "phase", None]), "axis_sync[1]"),
    (dict(minimum_duration=-1.0), "minimum_duration"),
])
def test_a_bad_target_is_refused_naming_it_and_changes_nothing(kw, name):
    g = _gen()
    g.start([0.0, 0.2, -0.1], [0.5, -1.0, 0.0], [0.0, 1.0, 0.0], positions=[1.0, -0.5, 0.3])
    g.process_targets([[1.0, -0.5, 0.3]] * 10)
    before = g.get_state()
    with pytest.raises(ParameterError) as e:
        g.process_targets([[1.0, -0.5, 0.3]], **kw)
    assert e.value.parameter == name and str(e.value).startswith(name)
    assert np.array_equal(g.get_state(), before)


@pytest.mark.parametrize("args,name", [
    (([0.0, np.nan, 0.0], [0.0] * 3, [0.0] * 3), "q[1]"),
    (([0.0] * 3, [0.0, 0.0, 0.6], [0.0] * 3), "v[2]"),
    (([0.0] * 3, [0.9, 0.0, 0.0], [1.9, 0.0, 0.0]), "a[0]"),   # brakes beyond vmax
])
def test_start_refuses_a_state_no_plan_can_leave(args, name):
    g = _gen()
    before = g.get_state()
    with pytest.raises(ParameterError) as e:
        g.start(*args, positions=[1.0, 1.0, 1.0])
    assert e.value.parameter == name
    assert np.array_equal(g.get_state(), before)
    with pytest.raises(ParameterError) as e:
        _gen("phase").start([0.0] * 3, [0.0] * 3, [0.0] * 3)
    assert e.value.parameter == "sync"


@pytest.mark.parametrize("precision", ["double", "float"])
def test_saved_state_continues_bit_for_bit(precision):
    g = _gen(precision=precision)
    g.start([0.0, 0.2, -0.1], [0.5, -1.0, 0.0], [0.0, 1.0, 0.0], positions=[1.0, -0.5, 0.3],
            velocities=[0.2, 0.0, -0.1])
    g.process_targets([[1.0, -0.5, 0.3]] * 300, velocities=[[0.2, 0.0, -0.1]] * 300)
    twin = _gen(precision=precision)
    twin.set_state(g.get_state())
    rows = np.r_[np.tile([1.0, -0.5, 0.3], (400, 1)), np.tile([-1.0, 0.5, 0.0], (8000, 1))]
    assert np.array_equal(g.process_targets(rows), twin.process_targets(rows))
    assert not g.busy and g.arrival == 0


def test_process_is_step_target_with_rest_positions():
    a, b = _gen(), _gen()
    rows = np.r_[np.tile([1.0, -0.5, 0.3], (700, 1)), np.tile([0.2, 0.5, -0.3], (2500, 1))]
    assert np.array_equal(a.process(rows), b.process_targets(rows))
