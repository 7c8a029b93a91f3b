# SPDX-License-Identifier: Apache-2.0
"""The trajectory benchmark: a smoke run (its timings are for reading, never asserted), ruckig's
discontinuity the benchmark steps around, and the arrival goal it measures (mid-motion and
rest to rest against ruckig), asserted on a seeded set of cases."""
import numpy as np
import pytest

pytest.importorskip("ruckig")


def test_quick_run_prints_every_figure(capsys):
    from smoothshaper.bench import trajectory as bench_trajectory
    assert bench_trajectory.main(["--quick"]) == 0
    out = capsys.readouterr().out
    for line in ("target changed mid-motion", "rest to rest", "Generator.process, double",
                 "Generator.process, float", "kinematic design", "grid price in samples, 3 bound(s)",
                 "Synchronization.Phase", "us/re-plan blended"):
        assert line in out


def test_ruckig_is_relaxed_where_its_duration_jumps():
    """A switch state on the ramp that ends a velocity change to vmax (braking velocity
    v + a|a|/(2 jmax) = vmax to the last bit): ruckig asked with vmax exactly plans a profile
    twice as long; relaxed by RUCKIG_RELAX it returns the optimum, which the planner and the
    generator reach (the benchmark's former 0.51 ratio was this comparison, not a shortcut)."""
    import ruckig
    import numpy as np
    from smoothshaper.bench.trajectory import RUCKIG_RELAX, _ruckig_duration
    from smoothshaper.time_optimal import plan_duration
    from smoothshaper.trajectory import Generator
    V, A, J = 0.23607371541684288, 3.4066933365820242, 38.626657267077285
    q, v, a, goal = 0.016206220050411654, 0.23431154949729, 0.36896227184440944, 1.0025747733685146
    assert abs(v + a * abs(a) / (2 * J) - V) <= 4e-16 * V
    ours = plan_duration(q, v, a, goal, vmax=V, amax=A, jmax=J)
    exact = _ruckig_duration(ruckig, q, v, a, goal, V, A, J, relax=0.0)
    relaxed = _ruckig_duration(ruckig, q, v, a, goal, V, A, J)
    assert exact > 1.9 * ours                      # ruckig's jump at the bound
    assert abs(relaxed - ours) <= 1e-9 * ours       # the optimum, to the relaxation
    assert RUCKIG_RELAX <= 1e-12
    # the generator started in that state arrives on the first sample at or after it
    Ts = 1e-3
    g = Generator(vmax=V, amax=A, jmax=J, Ts=Ts)
    g.start_from(q, v, a, target=goal)
    y = g.process(np.full(int(ours / Ts) + 5, goal))   # y[i] is (i + 1) Ts after that state
    rest = np.flatnonzero((y[:, 0] == goal) & (y[:, 1] == 0) & (y[:, 2] == 0))
    assert rest[0] + 1 == int(np.ceil(ours / Ts - 1e-9))
    assert np.abs(y[:, 1]).max() <= V * (1 + 1e-12)
    assert np.abs(y[:, 2]).max() <= A * (1 + 1e-12)


def test_arrival_after_a_mid_motion_target_meets_the_goal_and_rest_to_rest_is_on_the_grid():
    """The generator's goal against ruckig's time-optimal duration from the same state
    (docs/sampled-limits.md, "Time-optimal, from any state"): for a target changed mid-motion,
    arrival / optimum has a median at most 1.05 and a worst case at most 1.5, and is never
    below 1 (the planner forces the acceleration through zero at its peak velocity; ruckig may
    keep decelerating through a dip). Rest to rest the plan is ruckig's, so the arrival is its
    duration rounded up to the grid: the benchmark's Ts = T/2000 puts every duration on a
    sample to rounding (ruckig relaxed by 1e-12 of vmax, the plan within rounding of it), so
    the arrival is sample 2000 or 2001 and the ratio within one sample of 1. Seeded: the same
    200 cases every run."""
    from smoothshaper.bench.trajectory import arrival_ratios
    mid = arrival_ratios(200, seed=1, mid_motion=True)
    assert mid.size == 200
    assert np.median(mid) <= 1.05, np.median(mid)
    assert mid.max() <= 1.5, mid.max()
    assert mid.min() >= 1 - 1e-9, mid.min()
    rest = arrival_ratios(200, seed=1, mid_motion=False)
    samples = rest * 2000                        # the arrival sample: a whole number
    assert np.all(np.abs(samples - np.round(samples)) <= 1e-9), samples
    assert np.all((np.round(samples) == 2000) | (np.round(samples) == 2001)), samples
