# SPDX-License-Identifier: Apache-2.0
"""The generator with position limits (qmin, qmax): every sample's q within them (the C
generator exactly, the NumPy reference to the rounding floor of docs/design.md, "Position
limits"), C equal to the reference, the refusals naming qmin/qmax with the generator unchanged,
and the durations against ruckig (whose Python package plans without its position limits:
compared where its motion stays inside, and else against its brake plus its move)."""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from smoothshaper.errors import ParameterError
from smoothshaper.trajectory import Generator, generator_reference

ruckig = pytest.importorskip("ruckig")

LIM = dict(vmax=1.0, amax=10.0, jmax=100.0)
U = {"double": 2.0 ** -53, "float": 2.0 ** -24}


def _floor(qmin, qmax, u):
    """How far an unrounded sample may pass a limit: the plan's extremes are checked to
    16 u (|qmin| + |qmax|), a sample's q carries 16 u of the largest |position|."""
    return 32 * u * (abs(qmin) + abs(qmax))


def _draw_limits(data):
    # on a grid of 2^-20: no target at the underflow of the planner's products (dropped)
    span = round(data.draw(st.floats(0.02, 3.0), label="span") * 2 ** 20) / 2 ** 20
    qmin = -round(span * data.draw(st.floats(0.0, 1.0), label="lower share") * 2 ** 20) / 2 ** 20
    return qmin, qmin + span


def _grid(x):
    return round(x * 2 ** 20) / 2 ** 20


def _draw_targets(data, qmin, qmax, Ts):
    pos, tmin = [], []
    for _ in range(data.draw(st.integers(1, 5), label="targets")):
        k = data.draw(st.integers(1, 200), label="hold")
        x = data.draw(st.one_of(st.just(qmin), st.just(qmax), st.floats(qmin, qmax).map(_grid)))
        m = data.draw(st.one_of(st.just(0.0), st.floats(0.0, 1.0)), label="minimum_duration")
        if pos and x == pos[-1]:
            # the same position with another minimum duration mid-motion: C and the reference
            # pick different stretched motions at the velocity bound, without limits too
            # (noted in the branch notes); not a question of the position limits
            m = tmin[-1]
        pos += [x] * k
        tmin += [m] * k
    tail = int((qmax - qmin + 2.5) / Ts) + 200   # a move across at vmax, the stretch, the stage
    return np.array(pos + [pos[-1]] * tail), np.array(tmin + [tmin[-1]] * tail)


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_every_sample_inside_and_c_equals_the_reference(data):
    """Random limits, rest position and staircases (targets on the limits too, minimum
    durations, retargets mid-motion): C within [qmin, qmax] exactly, the reference within
    the floor, both equal to 1e-9 of the scale as without limits (the jerk but at the odd
    breakpoint), the run ending exactly on its last target."""
    qmin, qmax = _draw_limits(data)
    profile, mode = data.draw(st.sampled_from([("polynomial", {}),
                                               ("damped", dict(wn=60.0, zeta=0.05))]))
    Ts = data.draw(st.sampled_from([1e-3, 7.3e-3]))
    pos, tmin = _draw_targets(data, qmin, qmax, Ts)
    q0 = data.draw(st.floats(qmin, qmax).map(_grid), label="q0")
    kw = dict(Ts=Ts, profile=profile, qmin=qmin, qmax=qmax, **LIM, **mode)
    y = Generator(q0=q0, **kw).process(pos, minimum_duration=tmin)
    ref = generator_reference(pos, position=q0, minimum_duration=tmin, **kw)
    assert qmin <= y[:, 0].min() and y[:, 0].max() <= qmax
    fl = _floor(qmin, qmax, U["double"])
    assert qmin - fl <= ref[:, 0].min() and ref[:, 0].max() <= qmax + fl
    scale = np.array([np.max(np.abs(y[:, 0])) + 1, 1.0, 10.0])
    assert np.all(np.abs(y[:, :3] - ref[:, :3]) <= 1e-9 * scale)
    assert np.mean(np.abs(y[:, 3] - ref[:, 3]) > 1e-9 * 100.0) <= 0.01
    assert y[-1, 0] == pos[-1] and np.all(y[-1, 1:] == 0)


def test_a_stretched_retarget_that_would_overshoot_brakes_then_moves():
    """Moving up (v = 0.21, a = 4.4 when the target changes), a target 0.11 below with a
    minimum duration of 1 s: the stretched motion (the convex combination of the two farthest
    motions of 1 s) first rises to 0.243; with qmax = 0.22 the generator brakes to rest
    (inside), waits for the sample and moves there, still on the sample the minimum duration
    asks for. C equal to the reference, every sample inside."""
    kw = dict(Ts=1e-3, **LIM)
    x = np.r_[np.full(44, -0.28), np.full(3000, 0.09)]
    m = np.r_[np.zeros(44), np.full(3000, 1.0)]
    free = Generator(**kw)
    free.start_from(0.18, -0.09, 8.9, target=-0.28)
    yf = free.process(x, minimum_duration=m)
    g = Generator(qmin=-1.0, qmax=0.22, **kw)
    g.start_from(0.18, -0.09, 8.9, target=-0.28)
    y = g.process(x, minimum_duration=m)
    assert yf[:, 0].max() > 0.24 and y[:, 0].max() <= 0.22
    assert np.array_equal(y[:44], yf[:44])         # the same until the retarget (to rounding on it)
    assert np.allclose(y[44, :3], yf[44, :3], rtol=1e-12, atol=0)
    rest = np.flatnonzero((y[44:, 1] == 0) & (y[44:, 2] == 0))
    assert 0 < rest[0] < 1000 and y[44 + rest[0], 0] > 0.2   # at rest near qmax, then moves
    last = lambda out: np.flatnonzero(out[:, 0] != 0.09)[-1] + 1
    assert last(y) == last(yf) == 44 + 1000          # on the sample of the minimum duration
    # the reference from the same state: its run with the sample before as a start
    from smoothshaper.time_optimal import POSITION, _run
    ref = _run(x, vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-3, minimum_duration=m,
               start=(0.18, -0.09, 8.9, (POSITION, -0.28, 0.0, 0.0, 0.0)),
               qlim=(-1.0, 0.22))[0]
    assert np.all(np.abs(y[:, :3] - ref[:, :3]) <= 1e-9 * np.array([2.0, 1.0, 10.0]))


def _ruckig(q, v, a, *, target=None, Ts):
    """ruckig's duration from (q, v, a) to the target at rest (None: to velocity 0), its
    lowest and highest position and where it ends."""
    inp = ruckig.InputParameter(1)
    inp.current_position, inp.current_velocity, inp.current_acceleration = [q], [v], [a]
    inp.max_velocity, inp.max_acceleration, inp.max_jerk = [1.0], [10.0], [100.0]
    if target is None:
        inp.control_interface = ruckig.ControlInterface.Velocity
        inp.target_velocity = [0.0]
    else:
        inp.target_position = [target]
    traj = ruckig.Trajectory(1)
    res = ruckig.Ruckig(1).calculate(inp, traj)
    assert res in (ruckig.Result.Working, ruckig.Result.Finished)
    # its reported extrema, and the trajectory sampled (ruckig 0.19.4's position_extrema miss
    # the peak from some states with an acceleration: (0.9375, 0.914, -2.45) to 0.68 reports
    # 0.9924, its samples reach 1.0022)
    ext = traj.position_extrema[0]
    p = np.array([traj.at_time(t)[0][0] for t in np.linspace(0.0, traj.duration, 4001)])
    p_end = traj.at_time(traj.duration)[0][0]
    return traj.duration, min(ext.min, p.min()), max(ext.max, p.max()), p_end


@settings(max_examples=150, deadline=None)
@given(q=st.floats(-1.0, 1.0), v=st.floats(-1.0, 1.0), a=st.floats(-10.0, 10.0),
       target=st.floats(-1.0, 1.0), qmax=st.floats(0.05, 1.2))
def test_start_states_against_ruckig(q, v, a, target, qmax):
    """From any state towards a target inside [-1, qmax]: refused (naming qmin or qmax, the
    generator unchanged) exactly when neither ruckig's time-optimal motion nor its brake to
    rest stays inside (to 1e-9); else every sample inside and the arrival within ruckig's
    duration rounded up plus one sample where ruckig's motion stays inside, else within its
    brake and its move from there, each rounded up, plus one sample each."""
    Ts, qmin = 1e-3, -1.0
    q, target = min(q, qmax), min(target, qmax)
    if abs(v + a * abs(a) / 200.0) > 1.0:
        a = 0.0
    g = Generator(Ts=Ts, qmin=qmin, qmax=qmax, **LIM)
    g.reset(0.0)
    before = g.get_state()
    T, lo, hi, _ = _ruckig(q, v, a, target=target, Ts=Ts)
    Tb, blo, bhi, pb = _ruckig(q, v, a, Ts=Ts)
    direct_in = lo >= qmin - 1e-9 and hi <= qmax + 1e-9
    brake_in = blo >= qmin - 1e-9 and bhi <= qmax + 1e-9
    try:
        g.start_from(q, v, a, target=target)
    except ParameterError as err:
        assert err.parameter in ("qmin", "qmax") and "qmin, qmax" in str(err)
        assert np.array_equal(g.get_state(), before)
        assert not (lo >= qmin + 1e-9 and hi <= qmax - 1e-9) and \
            not (blo >= qmin + 1e-9 and bhi <= qmax - 1e-9)
        return
    assert direct_in or brake_in
    n = g.arrival
    y = g.process(np.full(n + 5, target))
    assert qmin <= y[:, 0].min() and y[:, 0].max() <= qmax and y[-1, 0] == target
    if lo >= qmin + 1e-9 and hi <= qmax - 1e-9:
        assert n <= math.ceil(T / Ts - 1e-9) + 1
    else:
        Tm = _ruckig(pb, 0.0, 0.0, target=target, Ts=Ts)[0]
        assert n <= math.ceil(Tb / Ts - 1e-9) + math.ceil(Tm / Ts - 1e-9) + 2


def test_refusals_name_the_limit_and_change_nothing():
    base = dict(Ts=1e-3, **LIM)
    for kwargs, name, words in [
        (dict(qmin=1.0, qmax=-1.0), "qmax", "above qmin"),
        (dict(qmin=1.0, qmax=1.0), "qmax", "above qmin"),
        (dict(qmin=-1.0), "qmax", "given with qmin"),
        (dict(qmax=1.0), "qmin", "given with qmax"),
        (dict(qmin=np.nan, qmax=1.0), "qmin", "finite"),
        (dict(qmin=-1.0, qmax=np.inf), "qmax", "finite"),
        (dict(qmin=-1e308, qmax=1.0), "qmin", "over 16"),
        (dict(qmin=-1.0, qmax=1.0, profile="trigonometric"), "qmin", "linear-ramp"),
        (dict(qmin=-1.0, qmax=1.0, q0=2.0), "q0", "outside [qmin, qmax]"),
    ]:
        with pytest.raises(ParameterError) as info:
            Generator(**base, **kwargs)
        assert info.value.parameter == name and words in str(info.value), (kwargs, info.value)
    g = Generator(qmin=-1.0, qmax=2.0, **base)
    g.process(np.full(100, 1.5))
    before = g.get_state()
    for call, name, words in [
        (lambda: g.process(np.r_[np.full(5, 1.0), 2.5]), "qmax", "sample 5"),
        (lambda: g.process([-1.5], minimum_duration=0.2), "qmin", "below qmin"),
        (lambda: g.process([1.0], velocity=0.5), "velocity", "a target rests"),
        (lambda: g.process(None, velocity=0.5), "velocity", "a target rests"),
        (lambda: g.process([1.0], acceleration=1.0), "acceleration", "a target rests"),
        (lambda: g.reset(3.0), "position", "outside"),
        (lambda: g.start_from(2.5, 0.0, 0.0, target=1.0), "qmax", "outside"),
        (lambda: g.start_from(1.0, 0.0, 0.0, target=-3.0), "qmin", "outside"),
        (lambda: g.start_from(1.95, 1.0, 0.0, target=1.0), "qmax", "the brake to rest"),
    ]:
        with pytest.raises(ParameterError) as info:
            call()
        assert info.value.parameter == name and words in str(info.value), (name, info.value)
        assert np.array_equal(g.get_state(), before)


def test_the_reference_refuses_and_ignores_as_stated():
    with pytest.raises(ParameterError, match="position"):
        generator_reference([0.0], Ts=1e-3, qmin=0.5, qmax=1.0, **LIM)
    # a target outside is ignored by the reference (the Generator refuses the block)
    ref = generator_reference(np.r_[np.full(10, 0.5), np.full(10, 3.0)], Ts=1e-3, qmin=0.0,
                              qmax=1.0, position=0.2, **LIM)
    assert ref[:, 0].max() <= 1.0


@pytest.mark.parametrize("precision", ["double", "float"])
def test_saved_state_keeps_the_limits(precision):
    kw = dict(Ts=1e-3, qmin=-0.5, qmax=0.5, precision=precision, **LIM)
    g = Generator(**kw)
    g.process(np.full(40, 0.45))
    state = g.get_state()
    assert state[13] == -0.5 and state[14] == 0.5
    h = Generator(**kw)
    h.set_state(state)
    x = np.full(800, -0.4)
    assert np.array_equal(g.process(x), h.process(x))
    other = Generator(**{**kw, "qmax": 0.6})
    with pytest.raises(ParameterError, match="qmax"):
        other.set_state(state)
    with pytest.raises(ParameterError):
        Generator(Ts=1e-3, precision=precision, **LIM).set_state(state)
