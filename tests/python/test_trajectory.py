# SPDX-License-Identifier: Apache-2.0
"""Online generator: never beyond v/a/j for random staircases (reversals, steps every few
samples, tiny steps), exact arrival, C == NumPy reference for every profile with and without a
mode, the tuned stage (arrival, the mode's zero), the trigonometric rest-to-rest duration,
state round trip, errors."""
import math
import warnings

import numpy as np
import pytest
from hypothesis import assume, given, strategies as st

from smoothshaper import trajectory as tr
from smoothshaper.filters import ParameterError

# Reported v, a, j: within the limits to 32 u (u the unit roundoff of the build), the rounding
# of the plan's own values and of the tuned stage's average (docs/sampled-limits.md).
UNIT_ROUNDOFF = {"double": 2.0 ** -53, "float": 2.0 ** -24}
BOUND_RTOL = {p: 32 * u for p, u in UNIT_ROUNDOFF.items()}


def assert_sampled_limits(y, x, limits, Ts, precision, at_rest_before=True):
    """Backward differences of the sampled q over Ts^i within the limits (1 + 1e-9) beyond the
    rounding of the positions: 16 u S per sample, S the largest |q| or target, 2^i of them in
    a difference of order i (docs/sampled-limits.md). at_rest_before: the generator rested on
    y[0]'s plan start before the first sample (q = 0 there), else only differences within y."""
    u = UNIT_ROUNDOFF[precision]
    S = max(np.max(np.abs(y[:, 0])), np.max(np.abs(x)))
    q = np.r_[np.zeros(3), y[:, 0]] if at_rest_before else y[:, 0]
    for i, L in enumerate(limits, 1):
        d = np.abs(np.diff(q, i)[3 - i if at_rest_before else 0:]) / Ts ** i
        excess = np.max(d - 2.0 ** i * 16 * u * S / Ts ** i)
        assert excess <= L * (1 + 1e-9), (i, excess / L)

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
        assume(exc.parameter != "wn")   # a mode the grid cannot place
        raise
    # hold long enough for the worst case: stop, travel back (<= 10 units), the velocity rise
    # and fall (vmax/amax + (pi/2) amax/jmax each) and the stage (tail_samples)
    hold = 2 * int(10.0 / (vmax * 1e-3)) + 2 * g.tail_samples + 10 + \
        4 * int((vmax / amax + 2 * amax / jmax) / 1e-3)
    x = staircase(spec, hold)
    y = g.process(x)
    tol = 1 + BOUND_RTOL[precision]
    assert np.max(np.abs(y[:, 1])) <= vmax * tol
    assert np.max(np.abs(y[:, 2])) <= amax * tol
    assert np.max(np.abs(y[:, 3])) <= jmax * tol
    assert_sampled_limits(y, x, (vmax, amax, jmax), 1e-3, precision)
    last = np.float32(x[-1]) if precision == "float" else x[-1]
    assert y[-1, 0] == last                      # exactly on the last via-point
    assert np.all(y[-1, 1:] == 0.0)


@given(spec=steps, profile=st.sampled_from(["polynomial", "trigonometric", "damped"]))
def test_c_matches_numpy_reference(spec, profile):
    kw = dict(vmax=1.0, amax=10.0, jmax=300.0, Ts=1e-3, profile=profile)
    if profile == "damped":
        kw.update(wn=60.0, zeta=0.05)
    assert_c_equals_reference(kw, staircase(spec, 500))


def test_single_move_is_time_optimal_and_reaches_the_bounds():
    g = tr.Generator(vmax=250.0, amax=5000.0, jmax=200000.0, Ts=1e-4)
    assert g.time_optimal
    y = g.process(np.full(4000, 40.0))
    arrive = np.flatnonzero((y[:, 0] == 40.0) & (y[:, 1] == 0.0))[0]
    assert arrive == 2350                       # 0.235 s, the ruckig duration of this move
    assert np.max(np.abs(y[:, 1:]), axis=0) == pytest.approx([250, 5000, 200000], rel=1e-9)


def _direct_stop(v0, a0, jmax, shape):
    """Distance of the fastest stop from (v0, a0 < 0 <= v0 + a0|a0|/(2 J)) without reaching
    amax: a to zero at the mean jerk J, then the symmetric stop from `after`."""
    from smoothshaper.time_optimal import C3, mean_jerk
    J = mean_jerk(jmax, shape)
    d, after = -a0 / J, v0 + a0 * abs(a0) / (2 * J)
    return v0 * d + a0 * d * d / 2 + C3[shape] * J * d ** 3 + after * math.sqrt(J * after) / J


@pytest.mark.parametrize("precision", ["double", "float"])
@pytest.mark.parametrize("profile", ["polynomial", "trigonometric"])
def test_replan_just_beyond_the_direct_stop_is_continuous(profile, precision):
    """From v = 0.5, a = -2 (vmax 1, amax 10, jmax 100) to targets 2^-k beyond the direct stop:
    the peak velocity lies just above `after` = v + a|a|/(2 J), where the distance grows like
    the square root of vp - after, so neighbouring vp differ in distance by far more than the
    positions' rounding. The stop, anchored on the target, started that far from where the
    velocity change ended (a jump of q), or the target was dropped; a cruise at vp now covers
    it: nothing is dropped, every sample keeps the limits and the move lands."""
    shape = "cosine" if profile == "trigonometric" else "ramp"
    dA = _direct_stop(0.5, -2.0, 100.0, shape)
    for k in range(8, 53 if precision == "double" else 25, 2):
        target = dA * (1 + 2.0 ** -k)
        g = tr.Generator(vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-3, profile=profile,
                         precision=precision)
        g.start_from(0.0, 0.5, -2.0, target=dA)
        x = np.full(600, target)
        y = g.process(x)
        assert g.dropped == 0, k
        tol = 1 + BOUND_RTOL[precision]
        assert np.all(np.max(np.abs(y[:, 1:]), axis=0) <= np.array([1.0, 10.0, 100.0]) * tol)
        assert_sampled_limits(y, x, (1.0, 10.0, 100.0), 1e-3, precision, at_rest_before=False)
        last = np.float32(target) if precision == "float" else target
        assert y[-1, 0] == last and np.all(y[-1, 1:] == 0)


def test_reference_plan_parts_meet_just_beyond_the_direct_stop():
    """The NumPy reference's plan from the same state: each piece starts where the one before
    ends, to 8 u of the target (the jump was up to 1.3e8 u there)."""
    from smoothshaper.time_optimal import C3, _integrate, plan_to_rest
    for shape in ("ramp", "cosine"):
        dA = _direct_stop(0.5, -2.0, 100.0, shape)
        for k in range(8, 45, 2):
            goal = dA * (1 + 2.0 ** -k)
            pieces, starts = plan_to_rest(0.0, 0.5, -2.0, goal, vmax=1.0, amax=10.0,
                                          jmax=100.0, shape=shape)
            for i in range(1, len(pieces)):
                end = _integrate([pieces[i - 1]], *starts[i - 1], C3[shape])
                assert abs(end[0] - starts[i][0]) <= 8 * 2.0 ** -53 * goal, (shape, k, i)
                assert abs(end[1] - starts[i][1]) <= 8 * 2.0 ** -53, (shape, k, i)
            end = _integrate([pieces[-1]], *starts[-1], C3[shape])
            assert abs(end[0] - goal) <= 8 * 2.0 ** -53 * goal


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


def plan_excess(g, state):
    """The saved plan's start |v|/vmax, |a|/amax and brake velocity |v + a|a|/(2 J)|/vmax
    (J the shape's mean jerk), minus 1, in units of the precision's u; the limits as the
    precision holds them, as the C check compares them."""
    real = np.float32 if g.precision == "float" else np.float64
    plan = int(g._lib.SMS_GENERATOR_IDENTITY_COUNT)
    v = float(state[plan + g._lib.SMS_GENERATOR_STATE_V])
    a = float(state[plan + g._lib.SMS_GENERATOR_STATE_A])
    V, A = float(real(g.vmax)), float(real(g.amax))
    J = float(real(g.jmax) * real(0.63661977236758134)) if g.profile == "trigonometric" \
        else float(real(g.jmax))
    u = UNIT_ROUNDOFF[g.precision]
    return ((abs(v) / V - 1) / u, (abs(a) / A - 1) / u, (abs(v + a * abs(a) / (2 * J)) / V - 1) / u)


@given(spec=st.lists(st.tuples(st.floats(-5.0, 5.0), st.integers(1, 200), st.booleans()),
                    min_size=10, max_size=60),
       lv=st.floats(-1, 1), la=st.floats(0, 2), lj=st.floats(1, 3),
       Ts=st.sampled_from([1e-3, 1.3e-4, 4.7e-3]),
       profile_mode=st.sampled_from([("polynomial", {}), ("trigonometric", {}),
                                     ("damped", dict(wn=50.0, zeta=0.05)),
                                     ("trigonometric", dict(wn=90.0, zeta=0.02))]),
       chunks=st.lists(st.integers(1, 9), min_size=1, max_size=20),
       precision=st.sampled_from(["double", "float"]))
def test_every_state_the_generator_saves_loads_again(spec, lv, la, lj, Ts, profile_mode,
                                                     chunks, precision):
    """States saved after every few samples of a random staircase (mid-transition, at the peak
    velocity, in reversals) load into a twin: the state check (v, a and the brake velocity
    within the limits to 32 u, SMS_LIMIT_RTOL) is not tighter than the generator's rounding."""
    vmax, amax, jmax = 10 ** lv, 10 ** la, 10 ** lj
    profile, mode = profile_mode
    kw = dict(vmax=vmax, amax=amax, jmax=jmax, Ts=Ts, profile=profile, precision=precision,
              **mode)
    try:
        g, h = tr.Generator(**kw), tr.Generator(**kw)
    except ParameterError as exc:
        assume(exc.parameter != "wn")   # a mode the grid cannot place
        raise
    x = staircase(spec, 0)
    start, k, worst = 0, 0, (-np.inf,) * 3
    while start < x.size:
        n = chunks[k % len(chunks)]
        g.process(x[start:start + n])
        start, k = start + n, k + 1
        s = g.get_state()
        h.set_state(s)                           # raises ParameterError if refused
        assert np.array_equal(h.get_state(), s)
        worst = np.maximum(worst, plan_excess(g, s))
    assert np.all(worst <= 32), worst


@pytest.mark.parametrize("precision", ["double", "float"])
@pytest.mark.parametrize("profile", ["polynomial", "trigonometric"])
def test_a_state_beyond_the_limits_is_refused_and_the_generator_untouched(precision, profile):
    """v, a or the brake velocity beyond the limits by twice SMS_LIMIT_RTOL (32 u): set_state
    raises naming the state and changes nothing, start_from names v or a; at SMS_LIMIT_RTOL
    both accept. Limits of powers of two keep every value exact in float: a = amax/2 brakes
    over amax^2/(8 J) = 1/8 (polynomial, J = jmax)."""
    g = tr.Generator(vmax=1.0, amax=8.0, jmax=64.0, Ts=1e-3, profile=profile,
                     precision=precision)
    tol = float(g._lib.SMS_LIMIT_RTOL)
    assert tol == 32 * UNIT_ROUNDOFF[precision]
    g.process(np.full(30, 0.01))
    before = g.get_state()
    plan = int(g._lib.SMS_GENERATOR_IDENTITY_COUNT)
    for sign in (1.0, -1.0):
        for over, ok in ((2 * tol, False), (tol, True)):
            cases = [(sign * (1 + over), 0.0, "v"), (0.0, sign * 8.0 * (1 + over), "a")]
            if profile == "polynomial":
                cases.append((sign * (0.875 + over), sign * 4.0, "a"))
            for v, a, name in cases:
                s = before.copy()
                s[plan + g._lib.SMS_GENERATOR_STATE_V] = v
                s[plan + g._lib.SMS_GENERATOR_STATE_A] = a
                if ok:
                    g.set_state(s)
                    g.start_from(0.0, v, a)
                else:
                    with pytest.raises(ParameterError, match="^state") as exc:
                        g.set_state(s)
                    assert exc.value.parameter == "state"
                    assert np.array_equal(g.get_state(), before)
                    with pytest.raises(ParameterError) as exc:
                        g.start_from(0.0, v, a)
                    assert exc.value.parameter == name
                    assert np.array_equal(g.get_state(), before)
                g.set_state(before)


@pytest.mark.parametrize("precision", ["double", "float"])
def test_start_from_accepts_every_reported_sample(precision):
    """(q, v, a) of any sample the generator reported is a state start_from accepts, also where
    rounding put v or a above the limit (reversals every few samples at random limits)."""
    rng = np.random.default_rng(5)
    for _ in range(20):
        vmax, amax, jmax = (float(x) for x in 10 ** rng.uniform(-1, 1, 3) * [1, 10, 100])
        g = tr.Generator(vmax=vmax, amax=amax, jmax=jmax, Ts=rng.uniform(1e-4, 5e-3),
                         precision=precision)
        x = np.repeat(rng.uniform(-3, 3, 200) * vmax, rng.integers(1, 30, 200))
        y = g.process(x)
        h = tr.Generator(vmax=vmax, amax=amax, jmax=jmax, Ts=g.Ts, precision=precision)
        for i in np.argsort(-np.abs(y[:, 1]))[:10].tolist() + \
                np.argsort(-np.abs(y[:, 2]))[:10].tolist():
            h.start_from(*y[i, :3], target=x[i])


@pytest.mark.parametrize("kwargs, name", [
    (dict(vmax=0.0, amax=1, jmax=1, Ts=1e-3), "vmax"),
    (dict(vmax=1, amax=float("nan"), jmax=1, Ts=1e-3), "amax"),
    (dict(vmax=1, amax=1, jmax=-1, Ts=1e-3), "jmax"),
    (dict(vmax=1, amax=1, jmax=1, Ts=0.0), "Ts"),
    (dict(vmax=1, amax=1, jmax=1, Ts=1e-3, profile="cubic"), "profile"),
    (dict(vmax=1, amax=1, jmax=1, Ts=1e-3, profile="damped"), "wn"),
    (dict(vmax=1, amax=1, jmax=1, Ts=1e-3, wn=5000.0), "wn"),
    (dict(vmax=1, amax=1, jmax=1, Ts=1e-3, wn=50.0, zeta=2.0), "zeta"),
    # the tuned stage's length is derived from wn: a period beyond a float named T
    (dict(vmax=1, amax=1, jmax=1, Ts=1e-3, wn=1e-308), "wn"),
    (dict(vmax=1, amax=1, jmax=1, Ts=1e-3, wn=5e-324, profile="damped"), "wn"),
])
def test_errors_name_the_parameter(kwargs, name):
    with pytest.raises(ValueError, match=rf"^{name}\b"):
        tr.Generator(**kwargs)


@pytest.mark.parametrize("kwargs, name", [
    (dict(profile="damped", wn=0.0, zeta=0.1), "wn"),              # ZeroDivisionError
    (dict(profile="damped", wn=10 ** 400, zeta=0.1), "wn"),        # OverflowError
    (dict(profile="damped", wn="50", zeta=0.1), "wn"),             # TypeError
    (dict(profile="damped", wn=1e-308, zeta=0.1), "wn"),           # named T
    (dict(profile="damped", wn=50.0, zeta=2.0), "zeta"),           # math domain error
    (dict(profile="damped", wn=50.0, zeta=np.nan), "zeta"),        # named T
    (dict(profile="cubic", wn=50.0, zeta=0.1), "profile"),         # silently rectangular
])
def test_tuned_stage_names_its_arguments(kwargs, name):
    with pytest.raises(ParameterError, match=rf"^{name}\b") as info:
        tr.tuned_stage(**kwargs)
    assert info.value.parameter == name


def test_tuned_stage_is_unchanged_for_valid_modes():
    assert tr.tuned_stage("Polynomial", 50.0, 0.0).T == 2 * math.pi / 50.0
    stage = tr.tuned_stage("trigonometric", 50.0, 0.1)
    assert stage.kind == "damped_harmonic" and stage.T == 3 * math.pi / (50.0 * math.sqrt(0.99))


def test_non_finite_targets_rejected():
    g = tr.Generator(vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-3)
    before = g.get_state()
    with pytest.raises(ValueError, match="^targets"):
        g.process([0.0, float("nan")])
    assert np.array_equal(g.get_state(), before)


def assert_c_equals_reference(kw, x):
    """C against the NumPy reference: q, v, a to 1e-9 of their scale; the jerk may differ where
    a jump lies within rounding of a sample instant (the two implementations may then take
    opposite sides), on at most 1 % of the samples; through a tuned stage such a sample is
    spread over its taps: the output jerks then differ by at most the taps times the plans'
    jerk differences (the same comparison without the mode)."""
    from smoothshaper.reference.filtering import impulse_response
    g = tr.Generator(**kw)
    y = g.process(x)
    ref = tr.generator_reference(x, **kw)
    scale = np.array([5.0 + kw["vmax"] * 0.2, kw["vmax"], kw["amax"], kw["jmax"]])
    err = np.abs(y - ref) / scale
    assert np.all(err[:, :3] <= 1e-9), np.max(err, axis=0)
    if kw.get("wn"):
        taps = impulse_response(tr.tuned_stage(kw["profile"], kw["wn"], kw.get("zeta", 0.0)),
                                Ts=kw["Ts"])
        plain = {k: v for k, v in kw.items() if k not in ("wn", "zeta")}
        if plain["profile"] == "damped":
            plain["profile"] = "polynomial"
        _, y0, r0 = assert_c_equals_reference(plain, x)
        spread = np.convolve(np.abs(y0[:, 3] - r0[:, 3]), taps)[:x.size] / kw["jmax"]
        assert np.all(err[:, 3] <= spread + 1e-9)
    else:
        assert np.mean(err[:, 3] > 1e-9) <= 0.01
    return g, y, ref


def test_validation_staircase_c_equals_reference_on_q_v_a_and_j():
    from smoothshaper import fmi
    Ts = 1e-3
    x = fmi.target_staircase(fmi.communication_points(step=Ts, stop_time=1.5))
    g, _, _ = assert_c_equals_reference(dict(fmi.TRAJECTORY_LIMITS, Ts=Ts), x)
    assert g.time_optimal


MODES = [("polynomial", 40.0, 0.0), ("polynomial", 61.3, 0.0), ("damped", 60.0, 0.05),
         ("trigonometric", 90.0, 0.02), ("trigonometric", 70.0, 0.0)]


@given(spec=steps, mode=st.sampled_from(MODES), Ts=st.sampled_from([1e-3, 0.37e-3]))
def test_mode_stage_c_equals_reference(spec, mode, Ts):
    profile, wn, zeta = mode
    kw = dict(vmax=1.0, amax=10.0, jmax=300.0, Ts=Ts, profile=profile, wn=wn, zeta=zeta)
    assert_c_equals_reference(kw, staircase(spec, 800))


@pytest.mark.parametrize("profile, wn, zeta", MODES)
def test_mode_stage_rest_to_rest_zero_and_price(profile, wn, zeta):
    """A move through the tuned stage: the output rests exactly on the target L - 1 samples
    after the plan (the same generator without the mode) does; the stage's zero cancels the
    mode (the transform of the output's differences at z* = exp(s* Ts) vanishes to rounding,
    s* = -zeta wn + j wd); every bound holds and the taps are an average (non-negative, sum 1)."""
    from smoothshaper.reference.filtering import impulse_response
    Ts, H = 1e-3, 0.37
    kw = dict(vmax=1.0, amax=10.0, jmax=300.0, Ts=Ts, profile=profile)
    g = tr.Generator(wn=wn, zeta=zeta, **kw)
    g0 = tr.Generator(**dict(kw, profile="polynomial" if profile == "damped" else profile))
    taps = impulse_response(tr.tuned_stage(profile, wn, zeta), Ts=Ts)
    assert np.all(taps >= 0) and abs(taps.sum() - 1) <= 1e-14
    assert g.tail_samples == taps.size
    wd = wn * math.sqrt(1 - zeta ** 2)
    assert g.stage_duration == pytest.approx((3 if profile == "trigonometric" else 2) * math.pi / wd,
                                             rel=1e-15)
    x = np.full(3000, H)
    y, y0 = g.process(x), g0.process(x)

    def arrival(out):
        return np.flatnonzero((out[:, 0] == H) & np.all(out[:, 1:] == 0, axis=1))[0]
    assert arrival(y) == arrival(y0) + taps.size - 1
    assert np.all(y[arrival(y):, 0] == H)
    dq = np.diff(np.r_[0.0, y[:, 0]])
    s = complex(-zeta * wn, wd)
    z = np.exp(-s * Ts * np.arange(dq.size))
    assert abs(np.sum(dq * z)) <= 1e-12 * np.sum(np.abs(dq * z))
    assert np.all(np.max(np.abs(y[:, 1:]), axis=0) <= np.array([1.0, 10.0, 300.0]) * (1 + 1e-12))


def test_trigonometric_rest_to_rest_is_the_trigonometric_design():
    """Half-cosine transitions: a rest-to-rest move arrives on the first sample at or after
    the continuous trigonometric kinematic design's duration (h = 40, v = 250, a = 5000,
    j = 2e5: 0.16 + 0.05 + (pi/2) 0.025 s); the jerk peaks at jmax and never jumps."""
    from smoothshaper import design
    Ts = 1e-5
    T = design.duration(design.kinematic(h=40.0, vmax=250.0, amax=5000.0, jmax=2e5,
                                         profile="trigonometric"))
    assert T == pytest.approx(0.16 + 0.05 + math.pi / 2 * 0.025, rel=1e-12)
    g = tr.Generator(vmax=250.0, amax=5000.0, jmax=2e5, Ts=Ts, profile="trigonometric")
    y = g.process(np.full(30000, 40.0))
    arrive = np.flatnonzero((y[:, 0] == 40.0) & (y[:, 1] == 0))[0]
    assert arrive == math.ceil(T / Ts - 1e-9)
    assert np.max(np.abs(y[:, 1:3]), axis=0) == pytest.approx([250, 5000], rel=1e-9)
    # the jerk jmax sin(pi t/d) sampled: its peak within (pi Ts/d)^2/8 of jmax
    assert np.max(np.abs(y[:, 3])) == pytest.approx(2e5, rel=1e-6)
    d = math.pi / 2 * 5000.0 / 2e5           # the shortest full transition
    assert np.max(np.abs(np.diff(y[:, 3]))) <= 2e5 * math.pi * Ts / d * (1 + 1e-9)


@pytest.mark.parametrize("profile", ["polynomial", "trigonometric"])
def test_unrepresentable_move_is_dropped(profile):
    """vmax 1e6: a target 1e300 away would cruise 1e294 s, more than 2^52 samples; it is
    dropped (refused, counted once, one warning naming it), the output rests, the state
    round-trips; the next target runs and a new dropped one counts again."""
    kw = dict(vmax=1e6, amax=1e8, jmax=1e10, Ts=1e-3, profile=profile)
    g = tr.Generator(**kw)
    with pytest.warns(tr.DroppedTargetWarning, match=r"target 1e\+300: .*goal 0\.0"):
        y = g.process(np.full(50, 1e300))
    assert np.all(y == 0.0) and g.refused and g.dropped == 1
    h = tr.Generator(**kw)
    h.set_state(g.get_state())
    with pytest.warns(tr.DroppedTargetWarning):
        np.testing.assert_array_equal(h.process(np.full(5, 1e300)), g.process(np.full(5, 1e300)))
    assert g.dropped == 1       # still the same held target: not dropped again
    y = g.process(np.full(100, 5.0))
    assert y[-1, 0] == 5.0 and not g.refused and g.dropped == 1
    with pytest.warns(tr.DroppedTargetWarning, match="2 targets dropped in this block"):
        g.process(np.r_[np.full(3, -1e300), np.full(3, 1e300)])
    assert g.dropped == 3
    g.reset()
    assert not g.refused and g.dropped == 0


@pytest.mark.parametrize("kw, parameter, words", [
    (dict(vmax=1.0, amax=1e-30, jmax=1e-300), "jmax",
     ["jmax=1e-300, vmax=1.0", "sqrt(vmax/jmax) = 1e+150 s", "4e+150 s", "2^50"]),
    (dict(vmax=1.0, amax=1e-30, jmax=1e-300, profile="trigonometric"), "jmax",
     ["sqrt(pi vmax/(2 jmax)) = 1.25331e+150 s"]),
    (dict(vmax=1e300, amax=1e100, jmax=1e5), "amax", ["vmax/amax = 1e+200 s"]),
    (dict(vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-300), "Ts", ["Ts=1e-300", "4e+299 samples"]),
    (dict(vmax=1.7976931348623157e308, amax=9e-16, jmax=3e-14), "vmax", ["above 1.12356e+307"]),
    (dict(vmax=4.0, amax=1.0, jmax=1e307), "jmax", ["vmax*jmax = 4e+307 exceeds"]),
    (dict(vmax=1e150, amax=1e-150, jmax=1e150, Ts=1e290), "amax", ["amax^2 = 1e-300 is below"]),
    (dict(vmax=1e-100, amax=1e-100, jmax=1e-100, precision="float"), "vmax",
     ["below 1.17549e-38, the smallest normal float"]),
    (dict(vmax=1e13, amax=1.0, jmax=1.0, precision="float"), "amax", ["vmax/amax = 1e+13 s"]),
])
def test_infeasible_limits_are_refused_naming_the_quantity(kw, parameter, words):
    """Limits with which no plan can reach vmax: a ParameterError naming the arguments, their
    values and the derived quantity, in O(1)."""
    kw.setdefault("Ts", 1e-3)
    with pytest.raises(ParameterError) as info:
        tr.Generator(**kw)
    assert info.value.parameter == parameter
    for w in words:
        assert w in str(info.value), (w, str(info.value))


@pytest.mark.parametrize("precision", ["double", "float"])
def test_feasible_region_boundary(precision):
    """Both sides of the duration bound: reaching vmax takes 2 (vmax/amax + amax/jmax) =
    0.4 s; at Ts = 0.4 s / 2^50 (1 + 1e-6) the limits are accepted and that move (0.2 units)
    is planned, not dropped; at (1 - 1e-6) they are refused naming vmax/amax."""
    T = 2 * (1.0 / 5.0 + 5.0 / 100.0)
    g = tr.Generator(vmax=1.0, amax=5.0, jmax=100.0, Ts=T / 2.0 ** 50 * (1 + 1e-6),
                     precision=precision)
    g.process([1.0 * (1.0 / 5.0 + 5.0 / 100.0)])
    assert not g.refused and g.dropped == 0
    with pytest.raises(ParameterError, match="vmax/amax = 0.2 s"):
        tr.Generator(vmax=1.0, amax=5.0, jmax=100.0, Ts=T / 2.0 ** 50 * (1 - 1e-6),
                     precision=precision)


@pytest.mark.parametrize("vmax, amax, jmax, target", [
    (1e30, 1e32, 1e34, 1e305),
    (1.0, 10.0, 1e306, 1e305),
    (1e150, 1e152, 1e154, -1e307),
    (1e150, 1e152, 1e154, 1000.0),
    (1e-140, 1e-140, 1e-140, 1e-100),
])
def test_extreme_limits_keep_every_bound(vmax, amax, jmax, target):
    """Finite outputs within vmax, amax, jmax and the sampled velocity bound at every sample,
    for extreme but feasible limits and targets, whether the move is planned or dropped."""
    Ts = 1e-3
    g = tr.Generator(vmax=vmax, amax=amax, jmax=jmax, Ts=Ts)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", tr.DroppedTargetWarning)
        y = g.process(np.concatenate([np.full(400, target), np.full(400, -target)]))
    assert np.all(np.isfinite(y))
    tol = 1 + 1e-9
    assert np.all(np.abs(y[:, 1]) <= vmax * tol)
    assert np.all(np.abs(y[:, 2]) <= amax * tol)
    assert np.all(np.abs(y[:, 3]) <= jmax * tol)
    q = np.concatenate([[0.0], y[:, 0]])
    eps = np.finfo(float).eps
    dq = np.abs(np.diff(q))
    assert np.all(dq <= vmax * Ts * tol + 4 * eps * (np.abs(q[1:]) + np.abs(q[:-1])))


@pytest.mark.parametrize("target", [2.2250738585e-313, 5e-324, -3e-310])
@pytest.mark.parametrize("profile,mode", [("polynomial", {}), ("trigonometric", {}),
                                          ("damped", dict(wn=50.0, zeta=0.05))])
def test_a_subnormal_target_is_reached_not_dropped(target, profile, mode):
    # Below the smallest normal number the planner's relative meeting check underflows; such a
    # move is a subnormal position step (well within every bound), not an unrepresentable plan.
    g = tr.Generator(vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-3, profile=profile, **mode)
    y = g.process(np.full(3000, target))
    assert y[-1, 0] == target
    assert np.all(np.isfinite(y))


@pytest.mark.parametrize("precision", ["double", "float"])
def test_a_1000_s_move_arrives_on_time_within_vmax_over_every_second(precision):
    """Generator(vmax=1, amax=10, jmax=1000, Ts=1e-4) from 0 to 1000: about 1e7 samples. In
    float it used to arrive at 1004.08 s instead of 1000.11 s, and its mean speed over 1 s
    windows reached 1.22 vmax (a float time losing whole samples, a position summed sample by
    sample). Now every sample is computed afresh from the plan (docs/sampled-limits.md, "Float,
    any move length"): double arrives on ruckig's duration rounded up to the grid, float within
    the rounding of the duration itself (the C test's rule: |k - n| <= 1 + 8 u n for n = T/Ts
    samples, tests/c/test_generator.c), and both land exactly on the target."""
    vmax, amax, jmax, Ts, h = 1.0, 10.0, 1000.0, 1e-4, 1000.0
    # vmax and amax are reached (h >= vmax (vmax/amax + amax/jmax), vmax/amax >= amax/jmax):
    # the double-S duration is h/vmax + vmax/amax + amax/jmax = 1000.11 s
    T = h / vmax + vmax / amax + amax / jmax
    try:
        import ruckig
    except ImportError:
        pass
    else:
        otg, inp, traj = ruckig.Ruckig(1), ruckig.InputParameter(1), ruckig.Trajectory(1)
        inp.current_position, inp.target_position = [0.0], [h]
        inp.max_velocity, inp.max_acceleration, inp.max_jerk = [vmax], [amax], [jmax]
        otg.calculate(inp, traj)
        assert traj.duration == pytest.approx(T, rel=1e-12)
        T = traj.duration
    n = T / Ts
    expect = math.ceil(n * (1 - 1e-12))            # 10,001,100
    u = UNIT_ROUNDOFF[precision]
    y = tr.Generator(vmax=vmax, amax=amax, jmax=jmax, Ts=Ts, precision=precision).process(
        np.full(expect + 2000, h))
    arrive = np.flatnonzero((y[:, 0] == h) & (y[:, 1] == 0) & (y[:, 2] == 0))[0]
    if precision == "double":
        assert arrive == expect, (arrive, expect)
    else:
        assert n - 8 * u * n <= arrive <= n + 1 + 8 * u * n, (arrive, n)
    assert np.all(y[arrive:, 0] == h) and np.all(y[arrive:, 1:] == 0)
    tol = 1 + BOUND_RTOL[precision]
    assert np.all(np.max(np.abs(y[:, 1:]), axis=0) <= np.array([vmax, amax, jmax]) * tol)
    # mean speed over every window of 1 s (the generator rests at 0 before the first sample):
    # the exact trajectory's is within vmax; two stored positions of |q| <= h add u h each
    w = round(1.0 / Ts)
    q = np.r_[0.0, y[:, 0]]
    speed = np.abs(q[w:] - q[:-w]) / (w * Ts)
    assert np.max(speed) <= vmax + 2 * u * h / (w * Ts), (np.max(speed) - vmax) / u
