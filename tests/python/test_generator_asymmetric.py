# SPDX-License-Identifier: Apache-2.0
"""The generator with asymmetric limits (vmin, amin): every sample within [vmin, vmax] and
[amin, amax], C equal to the NumPy reference, the refusals naming the parameter with the
generator unchanged, and the saved state's identity. The campaigns against ruckig
(``asym_*`` in smoothshaper.bench.targets) run in tests/python/test_generator_targets.py."""
from __future__ import annotations

import pickle

import numpy as np
import pytest

from smoothshaper.bench import targets as bt
from smoothshaper.errors import ParameterError
from smoothshaper.trajectory import Generator, generator_reference

from generator_sequences import pad, sequence

pytest.importorskip("ruckig")

# a vertical axis: fast up, slow down; braking downwards gently
LIM = dict(vmax=1.0, amax=10.0, jmax=100.0, vmin=-0.25, amin=-2.5)


@pytest.mark.parametrize("profile,mode", [("polynomial", {}), ("damped", dict(wn=60.0, zeta=0.05))])
def test_c_equals_the_reference_with_asymmetric_limits(profile, mode):
    """C and the NumPy reference to 1e-9 of the scale (as for symmetric limits,
    docs/sampled-limits.md), the jerk but at the odd breakpoint within rounding of a sample;
    every sample of both within the bounds exactly (v and a are held to them)."""
    rng = np.random.default_rng(7)
    for _ in range(4):
        # 12000 samples: 2 units down at 0.25 unit/s
        pos, vel, acc, itf, stop, tmin = pad(sequence(rng, 14, **LIM), 12000, 0.3)
        kw = dict(Ts=1e-3, profile=profile, **LIM, **mode)
        y = Generator(**kw).process(pos, velocity=vel, acceleration=acc, interface=itf,
                                    stop=stop, minimum_duration=tmin)
        ref = generator_reference(pos, velocity=vel, acceleration=acc, interface=itf, stop=stop,
                                  minimum_duration=tmin, **kw)
        scale = np.array([np.max(np.abs(y[:, 0])) + 1, 1.0, 10.0])
        assert np.all(np.abs(y[:, :3] - ref[:, :3]) <= 1e-9 * scale)
        assert np.mean(np.abs(y[:, 3] - ref[:, 3]) > 1e-9 * 100.0) <= 0.01
        assert y[-1, 0] == 0.3 and np.all(y[-1, 1:] == 0)
        for out in (y, ref):
            assert LIM["vmin"] <= out[:, 1].min() and out[:, 1].max() <= LIM["vmax"]
            assert LIM["amin"] <= out[:, 2].min() and out[:, 2].max() <= LIM["amax"]
            assert np.abs(out[:, 3]).max() <= LIM["jmax"] * (1 + 2.0 ** -48)


@pytest.mark.parametrize("precision", ["double", "float"])
def test_sampled_differences_keep_each_bound_on_its_side(precision):
    """Up and down through the whole range from rest: the backward differences of the
    sampled position stay within [vmin, vmax] and [amin, amax] after the rounding floor of
    docs/sampled-limits.md (2^i 16 u S / Ts^i), and both bounds are reached."""
    Ts, u = 1e-3, bt.UNIT_ROUNDOFF[precision]
    x = np.r_[np.full(1500, 1.0), np.full(6000, -0.2), np.full(1500, 0.0)]
    y = Generator(Ts=Ts, precision=precision, **LIM).process(x)
    q = np.r_[0.0, y[:, 0]]
    S = float(np.max(np.abs(q))) + 1.0
    for i, lo, hi in ((1, LIM["vmin"], LIM["vmax"]), (2, LIM["amin"], LIM["amax"])):
        d = np.diff(q, i) / Ts ** i
        floor = 2.0 ** i * 16 * u * S / Ts ** i
        assert d.min() >= lo - floor and d.max() <= hi + floor, (i, d.min(), d.max())
        assert d.min() <= lo * 0.99 and d.max() >= hi * 0.99   # each bound is reached
    assert y[-1, 0] == 0.0 and np.all(y[-1, 1:] == 0)


def test_asymmetric_limits_refused_naming_the_parameter():
    base = dict(vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-3)
    for kwargs, name, words in [
        (dict(vmin=0.5), "vmin", "< 0"), (dict(vmin=np.nan), "vmin", "finite"),
        (dict(amin=2.0), "amin", "< 0"), (dict(amin=-np.inf), "amin", "finite"),
        (dict(vmin=-0.5, profile="trigonometric"), "vmin", "symmetric"),
        (dict(amin=-5.0, profile="trigonometric"), "amin", "symmetric"),
        (dict(vmin=-1e-200), "vmin", "reach vmin"),
        (dict(vmin=-1e308), "vmin", "over 16"),
        # reaching vmin would take 1e299 s: the acceleration bound named, as for vmax/amax
        (dict(vmin=-1e300), "amin", "vmin/amin = 1e+299 s, so reaching vmin"),
    ]:
        with pytest.raises(ParameterError) as info:
            Generator(**base, **kwargs)
        assert info.value.parameter == name, (kwargs, info.value)
        assert words in str(info.value), str(info.value)
    # the symmetric bound given explicitly is the default
    assert np.array_equal(Generator(**base, vmin=-1.0, amin=-10.0).get_state(),
                          Generator(**base).get_state())
    Generator(**base, vmin=-1.0, profile="trigonometric")


def test_targets_and_states_beyond_a_lower_bound_are_refused_unchanged():
    g = Generator(Ts=1e-3, **LIM)
    g.process(np.full(300, 0.4))
    before = g.get_state()
    n = 10
    for kwargs, name, words in [
        (dict(targets=np.zeros(n), velocity=-0.3), "velocity", "[vmin, vmax] = [-0.25, 1.0]"),
        (dict(velocity=np.full(n, -0.3)), "velocity", "sample 0"),
        (dict(targets=np.zeros(n), acceleration=np.r_[np.zeros(4), -3.0, np.zeros(5)]),
         "acceleration", "sample 4"),
        # reaching zero acceleration from 5 at 100: 0.125 unit/s lower, below vmin
        (dict(targets=np.zeros(n), velocity=-0.2, acceleration=5.0), "acceleration", "[amin"),
    ]:
        with pytest.raises(ParameterError) as info:
            g.process(**kwargs)
        assert info.value.parameter == name, (kwargs, info.value)
        assert words in str(info.value), str(info.value)
        assert np.array_equal(g.get_state(), before)
    for kwargs, name in [(dict(q=0.0, v=-0.3), "v"), (dict(q=0.0, a=-3.0), "a"),
                         (dict(q=0.0, target=0.0, velocity=-0.5), "velocity")]:
        with pytest.raises(ParameterError) as info:
            g.start_from(**kwargs)
        assert info.value.parameter == name, (kwargs, info.value)
        assert np.array_equal(g.get_state(), before)
    with pytest.raises(ParameterError, match="a plan of this generator can start from"):
        g.start_from(0.0, -0.24, -2.4)       # braking from there passes -0.25: -0.2688
    assert np.array_equal(g.get_state(), before)
    g.start_from(0.0, -0.2, -1.0)            # brakes to -0.205: within vmin, accepted


def test_saved_state_names_the_lower_bounds():
    """A state of asymmetric limits loads only into the same ones; the message names vmin or
    amin; a round trip continues bit-exactly."""
    kw = dict(vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-3)
    g = Generator(**kw, vmin=-0.25, amin=-2.5)
    g.process(np.full(700, -0.3))
    state = g.get_state()
    with pytest.raises(ParameterError, match=r"state is from vmin=-0.25 \(this Generator: "
                                             r"vmin=-1.0\)"):
        Generator(**kw).set_state(state)
    with pytest.raises(ParameterError, match="amin=-2.5"):
        Generator(**kw, vmin=-0.25).set_state(state)
    h = Generator(**kw, vmin=-0.25, amin=-2.5)
    h.set_state(state)
    p = pickle.loads(pickle.dumps(g))             # the lower bounds travel with a pickle
    assert (p.vmin, p.amin) == (-0.25, -2.5)
    x = np.full(900, 0.5)
    y = g.process(x)
    assert np.array_equal(h.process(x), y) and np.array_equal(p.process(x), y)


def _reference_case(case, Ts):
    """The campaign's case through C and the NumPy reference (time_optimal._run from the
    same start state): both (n, 4) outputs."""
    from smoothshaper import time_optimal as to
    feature = bt.ASYMMETRIC[case["feature"]]
    lim = dict(vmax=case["vmax"], amax=case["amax"], jmax=case["jmax"], vmin=case["vmin"],
               amin=case["amin"])
    g = Generator(Ts=Ts, **lim)
    itf = {"stop": to.STOP, "velocity": to.VELOCITY}.get(feature, to.POSITION)
    goal = to.canonical_target(itf, case["position"], case["velocity"], case["acceleration"],
                               **lim)
    if feature == "stop":
        g.start_from(case["q0"], case["v0"], case["a0"])
    elif feature == "velocity":
        g.start_from(case["q0"], case["v0"], case["a0"], interface="velocity",
                     velocity=case["velocity"], acceleration=case["acceleration"])
    else:
        g.start_from(case["q0"], case["v0"], case["a0"], target=case["position"],
                     velocity=case["velocity"], acceleration=case["acceleration"])
    n = g.arrival + 8
    y = g.process(np.full(n, case["position"]), velocity=case["velocity"],
                  acceleration=case["acceleration"], interface="velocity"
                  if feature == "velocity" else "position", stop=feature == "stop")
    ref, _, _ = to._run(np.full(n, case["position"]), Ts=Ts, velocity=np.full(n, goal[2]),
                        acceleration=np.full(n, goal[3]), interface=np.full(n, itf),
                        start=(case["q0"], case["v0"], case["a0"], goal), **lim)
    return y, ref


@pytest.mark.parametrize("feature", sorted(bt.ASYMMETRIC))
def test_campaign_cases_equal_the_reference(feature):
    """Random campaign cases (limits over four decades, vmin and amin 0.1 to 10 times the
    negated upper bounds, random start states and targets): C equals the reference to 1e-9 of
    each column's scale (max |q| + 1 for q, the limits for v, a), the jerk but at the odd
    breakpoint within a rounding of a sample."""
    rng = np.random.default_rng([5, bt.FEATURES.index(feature)])
    for _ in range(40):
        case = bt.draw_case(rng, feature)
        T = bt._ruckig(case)
        if not T:
            continue
        Ts = T / 10.0 ** rng.uniform(1, 2.5)
        y, ref = _reference_case(case, Ts)
        scale = np.array([np.max(np.abs(ref[:, 0])) + 1, max(case["vmax"], -case["vmin"]),
                          max(case["amax"], -case["amin"])])
        assert np.all(np.abs(y[:, :3] - ref[:, :3]) <= 1e-9 * scale), case
        assert np.mean(np.abs(y[:, 3] - ref[:, 3]) > 1e-9 * case["jmax"]) <= 0.05, case
