"""Online generator: never beyond v/a/j for random staircases (reversals, steps every few
samples, tiny steps), exact arrival, C == NumPy reference, state round trip, errors."""
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
        assume(exc.parameter != "Ts")   # a tail stage shorter than one sample
        raise
    assume(g.tail_samples < 3000)
    # hold long enough for the worst case: finish the running segment (<= 10 units or Nc),
    # stop, wait Nc, travel back (<= 10 units or Nc), and let the tail settle (Nc)
    hold = 2 * int(10.0 / (vmax * 1e-3)) + 5 * g.tail_samples + 10
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
    assert np.all(np.abs(y - ref) <= 1e-11 * scale)


def test_single_move_is_time_optimal_and_reaches_the_bounds():
    g = tr.Generator(vmax=250.0, amax=5000.0, jmax=200000.0, Ts=1e-4)
    assert (g.T2, g.T3) == pytest.approx((0.05, 0.025), rel=1e-14)
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
    s = g.save_state()
    h = tr.Generator(vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-3)
    h.load_state(s)
    x = np.concatenate([np.full(100, 1.0), np.full(900, -0.5)])
    assert np.array_equal(g.process(x), h.process(x))
    with pytest.raises(ValueError, match="^state"):
        h.load_state(s[:-1])


@pytest.mark.parametrize("kwargs, name", [
    (dict(vmax=0.0, amax=1, jmax=1, Ts=1e-3), "vmax"),
    (dict(vmax=1, amax=float("nan"), jmax=1, Ts=1e-3), "amax"),
    (dict(vmax=1, amax=1, jmax=-1, Ts=1e-3), "jmax"),
    (dict(vmax=1, amax=1, jmax=1, Ts=0.0), "Ts"),
    (dict(vmax=1, amax=1e4, jmax=1e9, Ts=1e-3), "Ts"),
    (dict(vmax=1, amax=1, jmax=1, Ts=1e-3, profile="damped"), "wn"),
    (dict(vmax=1, amax=1, jmax=1, Ts=1e-3, wn=5000.0), "wn"),
    (dict(vmax=1, amax=1, jmax=1, Ts=1e-3, wn=50.0, zeta=2.0), "zeta"),
])
def test_errors_name_the_parameter(kwargs, name):
    with pytest.raises(ValueError, match=rf"^{name}\b"):
        tr.Generator(**kwargs)


def test_non_finite_targets_rejected():
    g = tr.Generator(vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-3)
    before = g.save_state()
    with pytest.raises(ValueError, match="^targets"):
        g.process([0.0, float("nan")])
    assert np.array_equal(g.save_state(), before)
