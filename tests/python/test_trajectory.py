"""Online generator: never beyond v/a/j for random staircases (reversals, steps every few
samples, tiny steps), exact arrival, C == NumPy reference (q, v, a and j, also with every jerk
jump on a sample instant, where both give the right limit), state round trip, errors."""
import math

import numpy as np
import pytest
from hypothesis import assume, given, strategies as st

from smoothshaper import trajectory as tr
from smoothshaper.filters import ParameterError

# Rounding allowance on the bounds: the output is a few products of numbers within the bounds.
BOUND_RTOL = {"double": 1e-12, "float": 1e-5}

steps = st.lists(st.tuples(st.floats(-5.0, 5.0), st.integers(1, 40),
                           st.booleans()), min_size=1, max_size=60)


def staircase(spec, hold_last):
    values, prev = [], 0.0
    for value, hold, tiny in spec:
        v = prev + 1e-7 * value if tiny else value   # tiny steps next to big jumps
        values += [v] * hold
        prev = v
    return np.array(values + [values[-1]] * hold_last)


@given(spec=steps, lv=st.floats(-1, 1), la=st.floats(0, 2), lj=st.floats(1, 3),
       profile_mode=st.sampled_from([("polynomial", {}), ("trigonometric", {}),
                                     ("damped", dict(wn=50.0, zeta=0.05)),
                                     ("polynomial", dict(wn=40.0)),
                                     ("trigonometric", dict(wn=90.0, zeta=0.02))]),
       precision=st.sampled_from(["double", "float"]))
def test_random_staircases_stay_bounded_and_arrive(spec, lv, la, lj, profile_mode, precision):
    vmax, amax, jmax = 10 ** lv, 10 ** la, 10 ** lj
    profile, mode = profile_mode
    try:
        g = tr.Generator(vmax=vmax, amax=amax, jmax=jmax, Ts=1e-3, profile=profile,
                         precision=precision, **mode)
    except ParameterError as exc:
        assume(exc.parameter not in ("amax", "jmax"))   # a tail stage shorter than a sample
        raise
    assume(g.tail_samples < 3000)
    # hold long enough for the worst case: finish the running segment (<= 10 units or Nc),
    # stop, wait Nc, travel back (<= 10 units or Nc), and let the tail settle (Nc)
    # (time-optimal: the velocity rise and fall, vmax/amax + amax/jmax each, instead of Nc)
    hold = 2 * int(10.0 / (vmax * 1e-3)) + 5 * g.tail_samples + 10 + \
        4 * int((vmax / amax + amax / jmax) / 1e-3)
    x = staircase(spec, hold)
    y = g.process(x)
    tol = 1 + BOUND_RTOL[precision]
    assert np.max(np.abs(y[:, 1])) <= vmax * tol
    assert np.max(np.abs(y[:, 2])) <= amax * tol
    assert np.max(np.abs(y[:, 3])) <= jmax * tol
    last = np.float32(x[-1]) if precision == "float" else x[-1]
    assert y[-1, 0] == last                      # exactly on the last via-point
    assert np.all(y[-1, 1:] == 0.0)


@given(spec=steps, profile=st.sampled_from(["polynomial", "trigonometric", "damped"]))
def test_c_matches_numpy_reference(spec, profile):
    kw = dict(vmax=1.0, amax=10.0, jmax=300.0, Ts=1e-3, profile=profile)
    if profile == "damped":
        kw.update(wn=60.0, zeta=0.05)
    x = staircase(spec, 500)
    y = tr.Generator(**kw).process(x)
    ref = tr.generator_reference(x, **kw)
    scale = np.array([5.0 + kw["vmax"] * 0.2, kw["vmax"], kw["amax"], kw["jmax"]])
    if profile == "polynomial":
        # time-optimal: a jerk jump within rounding of a sample may fall on either side in the
        # two implementations (whole samples plus fractions against float64 seconds)
        assert np.all(np.abs(y[:, :3] - ref[:, :3]) <= 1e-9 * scale[:3])
        assert np.mean(np.abs(y[:, 3] - ref[:, 3]) > 1e-9 * scale[3]) <= 0.01
        return
    assert np.all(np.abs(y - ref) <= 1e-11 * scale)


def test_single_move_is_time_optimal_and_reaches_the_bounds():
    g = tr.Generator(vmax=250.0, amax=5000.0, jmax=200000.0, Ts=1e-4)
    assert g.time_optimal
    y = g.process(np.full(4000, 40.0))
    arrive = np.flatnonzero((y[:, 0] == 40.0) & (y[:, 1] == 0.0))[0]
    assert arrive == 2350                       # 0.235 s, the ruckig duration of this move
    assert np.max(np.abs(y[:, 1:]), axis=0) == pytest.approx([250, 5000, 200000], rel=1e-9)


def test_reversal_waits_instead_of_doubling_acceleration():
    g = tr.Generator(vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-3)
    x = np.concatenate([np.full(300, 2.0), np.full(3000, -2.0)])
    y = g.process(x)
    assert np.max(np.abs(y[:, 2])) <= 10.0 * (1 + 1e-12)
    assert np.max(np.abs(y[:, 3])) <= 100.0 * (1 + 1e-12)
    assert y[-1, 0] == -2.0


def test_state_round_trip():
    g = tr.Generator(vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-3)
    g.process(np.full(150, 1.0))
    s = g.get_state()
    h = tr.Generator(vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-3)
    h.set_state(s)
    x = np.concatenate([np.full(100, 1.0), np.full(900, -0.5)])
    assert np.array_equal(g.process(x), h.process(x))
    with pytest.raises(ValueError, match="^state"):
        h.set_state(s[:-1])


@pytest.mark.parametrize("kwargs, name", [
    (dict(vmax=0.0, amax=1, jmax=1, Ts=1e-3), "vmax"),
    (dict(vmax=1, amax=float("nan"), jmax=1, Ts=1e-3), "amax"),
    (dict(vmax=1, amax=1, jmax=-1, Ts=1e-3), "jmax"),
    (dict(vmax=1, amax=1, jmax=1, Ts=0.0), "Ts"),
    (dict(vmax=1, amax=1e4, jmax=1e9, Ts=1e-3, profile="trigonometric"), "amax"),
    (dict(vmax=1, amax=1, jmax=1e9, Ts=1e-3, profile="trigonometric"), "jmax"),
    (dict(vmax=1, amax=1, jmax=1, Ts=1e-3, profile="damped"), "wn"),
    (dict(vmax=1, amax=1, jmax=1, Ts=1e-3, wn=5000.0), "wn"),
    (dict(vmax=1, amax=1, jmax=1, Ts=1e-3, wn=50.0, zeta=2.0), "zeta"),
])
def test_errors_name_the_parameter(kwargs, name):
    with pytest.raises(ValueError, match=rf"^{name}\b"):
        tr.Generator(**kwargs)


def test_non_finite_targets_rejected():
    g = tr.Generator(vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-3)
    before = g.get_state()
    with pytest.raises(ValueError, match="^targets"):
        g.process([0.0, float("nan")])
    assert np.array_equal(g.get_state(), before)


# Stage lengths that are whole multiples of Ts: every jump of the jerk falls on a sample
# instant, where both implementations must report the right limit (trajectory.h). (vmax, amax,
# jmax, Ts, n2, n3) with T2 = vmax/amax = n2 Ts, T3 = amax/jmax = n3 Ts; amax or jmax None:
# computed as vmax/(n2 Ts), amax/(n3 Ts), which round T2 or T3 an ulp off n Ts.
ON_GRID = [
    (1.0, 10.0, 200.0, 1e-3, 100, 50),            # validation.TRAJECTORY_LIMITS
    (1.0, 10.0, 100.0, 1e-3, 100, 100),           # T2 = T3
    (2.0, 8.0, 64.0, 1e-3, 250, 125),
    (1.0, 10.0, None, 1e-3, 100, 7),
    (1.0, None, None, 1e-4, 76, 25),
    (0.3, 30.0, None, 1e-4, 100, 33),
]


def on_grid_limits(vmax, amax, jmax, Ts, n2, n3):
    """The tail realisation (a rectangular last stage tuned to a mode of period T3 = n3 Ts)."""
    amax = vmax / (n2 * Ts) if amax is None else amax
    jmax = amax / (n3 * Ts) if jmax is None else jmax
    return dict(vmax=vmax, amax=amax, jmax=jmax, Ts=Ts, wn=2 * math.pi / (n3 * Ts))


def assert_c_equals_reference(kw, x):
    g = tr.Generator(**kw)
    y = g.process(x)
    ref = tr.generator_reference(x, **kw)
    scale = np.array([5.0 + kw["vmax"] * 0.2, kw["vmax"], kw["amax"], kw["jmax"]])
    err = np.abs(y - ref) / scale
    assert np.all(err <= 1e-11), (np.max(err, axis=0), np.flatnonzero(err[:, 3] > 1e-11))
    return g, y, ref


def test_validation_staircase_c_equals_reference_on_q_v_a_and_j():
    from smoothshaper import validation
    Ts = 1e-3
    x = validation.target_staircase(validation.communication_points(step=Ts, stop_time=1.5))
    g, _, _ = assert_c_equals_reference(dict(validation.TRAJECTORY_LIMITS, Ts=Ts), x)
    assert g.time_optimal


def jerk_right_limit(k, K, V, n2, n3, Ts):
    """Closed form of a single move of a polynomial tail: changes +V at tick 0 and -V at tick
    K; after a change, (l(s) - l(s - T2)) / T2 with l = 1/T3 on [0, T3), right limits."""
    def shape(m):
        return (((m >= 0) & (m < n3)).astype(float) - ((m >= n2) & (m < n2 + n3))) / (n2 * n3 * Ts * Ts)
    return V * (shape(k) - shape(k - K))


@pytest.mark.parametrize("case", ON_GRID)
def test_jerk_at_jumps_on_the_grid_is_the_right_limit(case):
    kw = on_grid_limits(*case)
    n2, n3, Ts = case[4], case[5], kw["Ts"]
    D = 0.7 * kw["vmax"]
    K = math.ceil(D / (kw["vmax"] * Ts))          # the segment length the generator rounds to
    x = np.full(K + n2 + n3 + 20, D)
    g, y, ref = assert_c_equals_reference(kw, x)
    assert g.tail_samples == n2 + n3
    k = np.arange(x.size)
    V = D / (K * Ts)
    expected = jerk_right_limit(k, K, V, n2, n3, Ts)
    left = jerk_right_limit(k - 1, K, V, n2, n3, Ts)    # the value just before each tick
    jumps = np.flatnonzero(np.abs(expected - left) > 0.1 * kw["jmax"])
    assert set(jumps) == {0, n3, n2, n2 + n3, K, K + n3, K + n2, K + n2 + n3}
    for out in (y, ref):
        assert np.all(np.abs(out[:, 3] - expected) <= 1e-12 * kw["jmax"])


@given(spec=steps, case=st.sampled_from(ON_GRID))
def test_c_matches_numpy_reference_with_stage_lengths_on_the_grid(spec, case):
    kw = on_grid_limits(*case)
    assert_c_equals_reference(kw, staircase(spec, 2 * (case[4] + case[5])))
