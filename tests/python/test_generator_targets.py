# SPDX-License-Identifier: Apache-2.0
"""The generator's targets beyond rest, against ruckig and the NumPy reference.

Campaigns (smoothshaper.bench.targets) per feature, from random states (rest targets, moving
targets, the velocity interface, the stop), double and float: the arrival at most one sample
after ruckig's duration rounded up to the grid (a moving target past a blocked duration:
within a sample of ruckig's discrete duration), every reported value within the limits to
32 u, every backward difference of the sampled position within its bound after the rounding
floor of docs/sampled-limits.md, the target state exactly on the arrival sample. The
full-size campaigns (10,000 cases per feature and precision) are ``long``; a fixed-seed draw
of each runs by default. Then C against the reference, and the refusals."""
from __future__ import annotations

import numpy as np
import pytest

from smoothshaper.bench import targets as bt
from smoothshaper.errors import ParameterError
from smoothshaper.trajectory import Generator, generator_reference

from generator_sequences import pad, sequence

pytest.importorskip("ruckig")


def _assert_campaign(summary):
    assert summary["cases"] > 0
    assert not summary["failures"], summary["failures"][:3]
    assert summary["not_landed"] == 0
    assert max(summary["over"], default=0) <= 1


@pytest.mark.parametrize("precision,cases", [("double", 120), ("float", 50)])
@pytest.mark.parametrize("feature", bt.FEATURES)
def test_campaign_draw(feature, precision, cases):
    _assert_campaign(bt.campaign(feature, cases, seed=20, precision=precision))


@pytest.mark.long
@pytest.mark.parametrize("precision", ["double", "float"])
@pytest.mark.parametrize("feature", bt.FEATURES)
def test_campaign_full(feature, precision):
    _assert_campaign(bt.campaign(feature, 10000, seed=1, precision=precision))


@pytest.mark.parametrize("profile,mode", [("polynomial", {}), ("trigonometric", {}),
                                          ("damped", dict(wn=60.0, zeta=0.05))])
def test_c_equals_the_reference_on_every_kind_of_target(profile, mode):
    """C and the NumPy reference to 1e-9 of the scale (docs/sampled-limits.md), the jerk but
    at the odd breakpoint within rounding of a sample (the two may take opposite sides)."""
    rng = np.random.default_rng(4)
    for _ in range(6):
        seq = sequence(rng, 14, profile=profile)
        pos, vel, acc, itf, stop, tmin = pad(seq, 3000, 0.3)
        kw = dict(vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-3, profile=profile, **mode)
        y = Generator(**kw).process(pos, velocity=vel, acceleration=acc, interface=itf,
                                    stop=stop, minimum_duration=tmin)
        ref = generator_reference(pos, velocity=vel, acceleration=acc, interface=itf, stop=stop,
                                  minimum_duration=tmin, **kw)
        scale = np.array([np.max(np.abs(y[:, 0])) + 1, 1.0, 10.0])
        assert np.all(np.abs(y[:, :3] - ref[:, :3]) <= 1e-9 * scale)
        assert np.mean(np.abs(y[:, 3] - ref[:, 3]) > 1e-9 * 100.0) <= 0.01
        assert y[-1, 0] == 0.3 and np.all(y[-1, 1:] == 0)


@pytest.mark.parametrize("vmax,amax,jmax,goal", [(1.0, 10.0, 100.0, -0.5), (2.0, 10.0, 50.0, -1.0),
                                                 (2.0, 10.0, 300.0, -0.5)])
def test_minimum_duration_given_on_the_ramp_into_the_cruise(vmax, amax, jmax, goal):
    """Only the minimum changes, on the last samples of the ramp into the cruise and the
    first of the cruise: the start's acceleration returns to zero on vmax to the rounding of
    the running plan, so the motion that ends farthest back cruises from there and the
    stretched motion exists (docs/design.md, "A minimum duration"). C arrives on the sample
    the minimum asks for (N samples after the one before the change, within a sample of
    rounding of N Ts) and equals the reference to 1e-9 of the scale; both rest on the target
    from there (the blend may reach it earlier and rest: its two motions' jerks cancel)."""
    Ts = 1e-3
    kw = dict(vmax=vmax, amax=amax, jmax=jmax, Ts=Ts)
    cruise = round((2 * amax / jmax + (vmax - amax ** 2 / jmax) / amax) / Ts)
    for k in range(cruise - 5, cruise + 2):
        g = Generator(**kw)
        g.process(np.full(k, goal))
        N = g.arrival + 500
        g.process(np.full(1, goal), minimum_duration=N * Ts)
        assert g.arrival in (N - 1, N), (k, g.arrival, N)
        n = k + N + 20
        tmin = np.r_[np.zeros(k), np.full(n - k, N * Ts)]
        y = Generator(**kw).process(np.full(n, goal), minimum_duration=tmin)
        ref = generator_reference(np.full(n, goal), minimum_duration=tmin, **kw)
        scale = np.array([abs(goal) + 1, 1.0, 10.0])
        assert np.all(np.abs(y[:, :3] - ref[:, :3]) <= 1e-9 * scale), k
        for out in (y, ref):
            assert np.all(out[k + N:, 0] == goal) and np.all(out[k + N:, 1:] == 0), k


def test_process_refuses_a_bad_target_naming_it_and_changes_nothing():
    g = Generator(vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-3)
    g.process(np.full(50, 0.4))
    before = g.get_state()
    n = 20
    bad = [
        (dict(targets=np.zeros(n), velocity=np.r_[np.zeros(5), 1.5, np.zeros(14)]), "velocity",
         "sample 5"),
        (dict(targets=np.zeros(n), velocity=0.93, acceleration=4.0), "acceleration",
         "sample 0"),
        (dict(targets=np.zeros(n), acceleration=np.full(n, 11.0)), "acceleration", "amax"),
        (dict(targets=np.zeros(n), interface="sideways"), "interface", "position"),
        (dict(targets=np.zeros(n), velocity=np.zeros(3)), "velocity", "length"),
        (dict(targets=np.zeros(n), stop=np.zeros(n)), "stop", "bool"),
        (dict(velocity=0.2, interface="position"), "targets", "position"),
        (dict(targets=np.r_[np.zeros(3), np.nan]), "targets", "finite"),
        (dict(targets=np.zeros(n), minimum_duration=np.r_[np.zeros(7), -0.1, np.zeros(12)]),
         "minimum_duration", "sample 7"),
        (dict(targets=np.zeros(n), minimum_duration=np.inf), "minimum_duration", "finite"),
        (dict(targets=np.zeros(n), minimum_duration=1e300), "minimum_duration", "2^50"),
    ]
    for kwargs, name, words in bad:
        with pytest.raises(ParameterError) as info:
            g.process(**kwargs)
        assert info.value.parameter == name, (kwargs, info.value)
        assert words in str(info.value), str(info.value)
        assert np.array_equal(g.get_state(), before)
    tg = Generator(vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-3, profile="trigonometric")
    with pytest.raises(ParameterError, match="^velocity at sample 0: 0.5: the trigonometric"):
        tg.process(np.zeros(3), velocity=0.5)
    with pytest.raises(ParameterError, match="^acceleration") as info:
        tg.process(velocity=np.full(3, 0.5), acceleration=1.0)
    with pytest.raises(ParameterError, match="^minimum_duration at sample 0: 0.5: the trig"):
        tg.process(np.zeros(3), minimum_duration=0.5)


def test_minimum_duration_stretches_the_move_onto_its_sample():
    """A rest-to-rest move of 0.297 s (trajectory.h) asked to last 1 s arrives on sample 1000
    exactly, within every limit; a minimum below the optimum changes nothing; the minimum is
    part of the target (the same target with another minimum re-plans from there)."""
    kw = dict(vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-3)
    fast = Generator(**kw).process(np.full(1200, 0.0819))
    y = Generator(**kw).process(np.full(1200, 0.0819), minimum_duration=1.0)
    at = np.flatnonzero((y[:, 0] == 0.0819) & np.all(y[:, 1:] == 0, axis=1))[0]
    assert at == 1000                        # the move starts on out[0]
    assert np.all(np.abs(y[:, 1:]) <= np.array([1.0, 10.0, 100.0]) * (1 + 2.0 ** -48))
    assert np.array_equal(Generator(**kw).process(np.full(1200, 0.0819), minimum_duration=0.1),
                          fast)
    g = Generator(**kw)
    g.start_from(0.0, 0.0, 0.0, target=0.5, minimum_duration=2.0)
    assert g.arrival == 2000
    g.process(np.full(10, 0.5), minimum_duration=2.0)        # held: no re-plan
    assert g.arrival == 1990
    g.process(np.full(1, 0.5), minimum_duration=0.0)         # changed: as fast as possible
    assert g.arrival < 1000
    with pytest.raises(ParameterError, match="^minimum_duration"):
        g.start_from(0.0, target=0.5, minimum_duration=np.nan)


def test_start_from_any_state_towards_every_kind_of_target():
    """The first sample after start_from continues the plan from (q, v, a): its backward
    difference stays within vmax; arrival counts down to the target state."""
    g = Generator(vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-3)
    g.start_from(0.2, 0.8, -3.0, target=-0.5, velocity=0.3, acceleration=1.0)
    n = g.arrival
    y = g.process(np.full(n, -0.5), velocity=0.3, acceleration=1.0)
    assert tuple(y[-1, :3]) == (-0.5, 0.3, 1.0) and g.arrival == 0
    assert abs(y[0, 0] - 0.2) / 1e-3 <= 1.0
    g.start_from(0.0, -0.6, 2.0)                       # default: brake to rest
    y = g.process(velocity=np.zeros(g.arrival + 5), stop=True)
    assert np.all(y[-5:, 1:] == 0) and np.all(y[-5:, 0] == y[-1, 0])
    g.start_from(0.0, 0.0, 0.0, interface="velocity", velocity=-0.4)
    y = g.process(velocity=np.full(g.arrival + 5, -0.4))
    assert np.all(y[-5:, 1] == -0.4) and np.all(y[-5:, 2:] == 0)
    before = g.get_state()
    for kwargs, name in [(dict(q=0.0, v=1.2), "v"), (dict(q=0.0, v=0.9, a=5.0), "a"),
                         (dict(q=0.0, target=0.0, velocity=2.0), "velocity"),
                         (dict(q=0.0, target=0.0, acceleration=20.0), "acceleration"),
                         (dict(q=0.0, interface="up"), "interface"),
                         (dict(q=0.0, interface="position"), "target"),
                         (dict(q=0.0, target=1e300), "target")]:
        with pytest.raises(ParameterError) as info:
            g.start_from(**kwargs)
        assert info.value.parameter == name, (kwargs, info.value)
        assert np.array_equal(g.get_state(), before)
