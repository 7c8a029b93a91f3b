# SPDX-License-Identifier: Apache-2.0
"""Saved generator states carry their configuration's identity: a state of another
configuration is refused with a ParameterError naming the field that differs, the state of the
same configuration continues bit for bit (a run split by get_state/set_state equals the
one-shot run), and start_from() puts the generator into a motion state without hand-built
arrays."""
import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from smoothshaper.errors import ParameterError
from smoothshaper.trajectory import Generator

BASE = dict(vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-3)
MODE = dict(BASE, wn=60.0, zeta=0.1)


def _targets(n=600):
    k = np.arange(n)
    return np.where(k < 80, 0.02, np.where(k < 300, -0.015, 0.01 * (k % 3)))


def _split_equals_one_shot(config, split=170):
    x = _targets()
    one_shot = Generator(**config).process(x)
    first = Generator(**config)
    first.process(x[:split])
    second = Generator(**config)
    second.reset(3.0)                     # somewhere else entirely before loading
    second.set_state(first.get_state())
    rest = second.process(x[split:])
    assert np.array_equal(rest, one_shot[split:])


@pytest.mark.parametrize("config", [BASE, MODE, dict(BASE, profile="trigonometric"),
                                    dict(MODE, profile="damped"),
                                    dict(MODE, profile="trigonometric", precision="float")])
def test_the_same_configuration_continues_bit_for_bit(config):
    _split_equals_one_shot(config)


@pytest.mark.parametrize("base, change, field, theirs, ours", [
    (BASE, dict(vmax=2.0), "vmax", "1.0", "2.0"),
    (BASE, dict(amax=11.0), "amax", "10.0", "11.0"),
    (BASE, dict(jmax=100.00000000000001), "jmax", "100.0", "100.00000000000001"),
    (BASE, dict(profile="trigonometric"), "profile", "'polynomial'", "'trigonometric'"),
    (BASE, dict(Ts=2e-3), "Ts", "0.001", "0.002"),
    (BASE, dict(precision="float"), "precision", "'double'", "'float'"),
    (BASE, dict(wn=60.0), "wn", "0.0", "60.0"),            # and another length
    (MODE, dict(wn=None, zeta=0.0), "wn", "60.0", "0.0"),
    (MODE, dict(wn=61.0), "wn", "60.0", "61.0"),
    (MODE, dict(zeta=0.2), "zeta", "0.1", "0.2"),
    (MODE, dict(profile="damped"), "profile", "'polynomial'", "'damped'"),
])
def test_another_configuration_is_refused_naming_the_field(base, change, field, theirs, ours):
    source = Generator(**base)
    source.process(_targets(120))
    state = source.get_state()
    target = Generator(**dict(base, **change))
    target.process(np.full(30, -0.5))
    before = target.get_state()
    with pytest.raises(ParameterError) as err:
        target.set_state(state)
    assert err.value.parameter == "state" and isinstance(err.value, ValueError)
    assert str(err.value) == f"state is from {field}={theirs} (this Generator: {field}={ours})"
    assert err.value.status == {"vmax": -36, "amax": -37, "jmax": -38, "profile": -39,
                                "Ts": -25, "precision": -23, "wn": -30, "zeta": -31}[field]
    assert np.array_equal(target.get_state(), before)      # untouched


def test_q0_is_not_part_of_the_configuration():
    """q0 is only where reset() returns to; the state fully describes the motion."""
    a = Generator(**BASE, q0=1.0)
    b = Generator(**BASE, q0=-4.0)
    b.set_state(a.get_state())
    assert np.array_equal(a.process(_targets(200)), b.process(_targets(200)))


def test_not_a_generator_state():
    g = Generator(**BASE)
    s = g.get_state()
    with pytest.raises(ParameterError, match="^state is not a saved Generator state"):
        g.set_state(np.concatenate([[1.0], s[1:]]))
    newer = s.copy()
    newer[1] += 1
    with pytest.raises(ParameterError, match="^state has format version 3.0"):
        g.set_state(newer)
    other = s.copy()
    other[3] = 101.0
    with pytest.raises(ParameterError, match=r"^state is from a BSpline \(this is a Generator\)"):
        g.set_state(other)
    with pytest.raises(ParameterError, match="^state is truncated inside"):
        g.set_state(s[:4])
    with pytest.raises(ParameterError, match="^state does not match"):
        g.set_state(s[:-1])


@pytest.mark.parametrize("field", [3, 8])          # kind, profile: enumerations
@pytest.mark.parametrize("value", [np.nan, np.inf, -np.inf])
def test_a_non_finite_enumeration_field_is_named(field, value):
    """A NaN or inf in the kind or profile field of a saved state raised ValueError (or
    OverflowError) from int() while the message was being written."""
    g = Generator(**BASE)
    g.process(np.full(30, 0.5))
    s = g.get_state()
    bad = s.copy()
    bad[field] = value
    with pytest.raises(ParameterError, match="^state is from ") as info:
        g.set_state(bad)
    assert info.value.parameter == "state"
    assert np.array_equal(g.get_state(), s)


def test_layout_is_documented():
    g = Generator(**dict(BASE, profile="trigonometric"))
    s = g.get_state()
    assert s.size == 29
    # ... profile, wn, zeta, then vmin and amin in effect (symmetric: -vmax, -amax), then qmin
    # and qmax (0, 0: no position limits)
    assert list(s[:15]) == [5459283.0, 2.0, 8.0, 100.0, 1e-3, 1.0, 10.0, 100.0, 1.0, 0.0, 0.0,
                            -1.0, -10.0, 0.0, 0.0]
    # the target and the goal at rest on 0 (position interface, no minimum duration), the
    # plan from (0, 0, 0), k
    assert list(s[15:]) == [0.0] * 14


_limits = st.floats(min_value=0.05, max_value=50.0)


@settings(max_examples=25, deadline=None)
@given(vmax=_limits, amax=_limits, jmax=_limits,
       profile=st.sampled_from(["polynomial", "trigonometric"]),
       field=st.sampled_from(["vmax", "amax", "jmax", "Ts", None]),
       split=st.integers(min_value=1, max_value=400))
def test_random_configurations(vmax, amax, jmax, profile, field, split):
    """Random limits: the same configuration continues bit for bit from any sample; one
    field nudged by a relative 1e-9 is refused naming it."""
    config = dict(vmax=vmax, amax=amax, jmax=jmax * amax, Ts=1e-3, profile=profile)
    x = np.where(np.arange(500) < 200, vmax * 0.3, -vmax * 0.1)
    one_shot = Generator(**config).process(x)
    g = Generator(**config)
    g.process(x[:split])
    state = g.get_state()
    other = dict(config)
    if field is not None:
        other[field] = config[field] * (1 + 1e-9)
    h = Generator(**other)
    if field is None:
        h.set_state(state)
        assert np.array_equal(h.process(x[split:]), one_shot[split:])
    else:
        with pytest.raises(ParameterError, match=rf"^state is from {field}="):
            h.set_state(state)


@pytest.mark.parametrize("profile", ["polynomial", "trigonometric"])
def test_start_from_equals_a_replan_at_that_state(profile):
    """start_from(q, v, a, target=T) is the state right after a re-plan at a sample whose
    output was (q, v, a): both generators go on bit for bit."""
    g = Generator(**BASE, profile=profile)
    y = g.process(np.concatenate([np.full(90, 0.05), [-0.02]]))   # re-plans on the last sample
    q, v, a = y[-1, :3]
    assert v != 0 and a != 0
    after = g.process(np.full(400, -0.02))
    h = Generator(**BASE, profile=profile)
    h.start_from(q, v, a, target=-0.02)
    assert np.array_equal(h.process(np.full(400, -0.02)), after)


def test_start_from_with_a_mode_runs_through_the_stage():
    m = Generator(**MODE)
    m.start_from(0.01, 0.5, -2.0, target=-0.02)
    out = m.process(np.full(1000, -0.02))
    assert out[-1, 0] == -0.02 and out[-1, 1] == 0.0
    assert np.all(np.abs(out[:, 1]) <= MODE["vmax"] * (1 + 1e-12))
    assert np.all(np.abs(out[:, 2]) <= MODE["amax"] * (1 + 1e-12))


def test_start_from_refuses_a_state_no_plan_starts_from():
    g = Generator(**BASE)
    before = g.get_state()
    for kwargs, name in [(dict(q=0.0, v=1.5), "v"), (dict(q=0.0, a=-11.0), "a"),
                         (dict(q=float("nan")), "q"), (dict(q=0.0, target=float("inf")), "target"),
                         (dict(q=0.0, v=0.99, a=9.0), "a"),      # brakes beyond vmax
                         # a state at rest heading for a target no plan reaches in a double:
                         # the target, not a (it was named a)
                         (dict(q=0.0, target=1e308), "target"), (dict(q=0.0, target=1e20), "target"),
                         (dict(q=0.0, v=0.99, a=9.0, target=1e20), "a")]:
        with pytest.raises(ParameterError) as err:
            g.start_from(**kwargs)
        assert err.value.parameter == name
        assert np.array_equal(g.get_state(), before)


# -- MultiAxisGenerator ----------------------------------------------------------------------

def _multi(**change):
    from smoothshaper.multi_axis import MultiAxisGenerator
    return MultiAxisGenerator(**dict(dict(vmax=[1.0, 2.0], amax=10.0, jmax=100.0, Ts=1e-3),
                                     **change))


def _zv(wn):
    from smoothshaper import stages
    return stages.shaper("zv", wn=wn, zeta=0.0)


def _multi_targets(n=600):
    t = _targets(n)
    return np.stack([t, -2.0 * t], axis=1)


@pytest.mark.parametrize("change", [{}, dict(sync="independent"), dict(stages=[_zv(60.0)]),
                                    dict(stages=[[_zv(60.0)], []], precision="float")])
def test_multi_axis_continues_bit_for_bit(change, split=230):
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")           # different stages per axis warn
        x = _multi_targets()
        one_shot = _multi(**change).process(x)
        first = _multi(**change)
        first.process(x[:split])
        second = _multi(**change, q0=[0.5, -1.0])
        second.set_state(first.get_state())
        assert np.array_equal(second.process(x[split:]), one_shot[split:])


@pytest.mark.parametrize("base, change, expected", [
    ({}, dict(vmax=[1.0, 3.0]), "state is from vmax[1]=2.0 (this MultiAxisGenerator: vmax[1]=3.0)"),
    ({}, dict(amax=[10.0, 9.0]), "state is from amax[1]=10.0 (this MultiAxisGenerator: amax[1]=9.0)"),
    ({}, dict(jmax=[101.0, 100.0]), "state is from jmax[0]=100.0 (this MultiAxisGenerator: jmax[0]=101.0)"),
    ({}, dict(sync="independent"),
     "state is from sync='phase' (this MultiAxisGenerator: sync='independent')"),
    ({}, dict(vmax=[1.0, 2.0, 3.0]), "state is from axes=2 (this MultiAxisGenerator: axes=3)"),
    ({}, dict(Ts=2e-3), "state is from Ts=0.001 (this MultiAxisGenerator: Ts=0.002)"),
    ({}, dict(precision="float"),
     "state is from precision='double' (this MultiAxisGenerator: precision='float')"),
    ({}, dict(stages=[_zv(60.0)]),
     "state is from n_stages[0]=0 (this MultiAxisGenerator: n_stages[0]=1)"),
    (dict(stages=[_zv(60.0)]), dict(stages=[_zv(61.0)]),
     "state does not match this MultiAxisGenerator: a vibration stage differs (saved state is "
     "from another wn)"),
])
def test_multi_axis_refuses_another_configuration(base, change, expected):
    source = _multi(**base)
    source.process(_multi_targets(150))
    target = _multi(**change)
    before = target.get_state()
    with pytest.raises(ParameterError) as err:
        target.set_state(source.get_state())
    assert err.value.parameter == "state" and str(err.value) == expected
    assert np.array_equal(target.get_state(), before)
    with pytest.raises(ParameterError, match="^state does not match"):
        source.set_state(source.get_state()[:-1])


@settings(max_examples=20, deadline=None)
@given(axes=st.integers(min_value=1, max_value=4), data=st.data(),
       sync=st.sampled_from(["phase", "independent"]), split=st.integers(1, 300))
def test_multi_axis_random_configurations(axes, data, sync, split):
    """Random per-axis limits: the same configuration continues bit for bit; one axis's limit
    nudged by a relative 1e-9 is refused naming that axis and limit."""
    from smoothshaper.multi_axis import MultiAxisGenerator
    lims = {name: np.array(data.draw(st.lists(_limits, min_size=axes, max_size=axes)))
            for name in ("vmax", "amax", "jmax")}
    config = dict(lims, Ts=1e-3, sync=sync)
    x = np.outer(np.where(np.arange(400) < 150, 0.3, -0.1), lims["vmax"])
    one_shot = MultiAxisGenerator(**config).process(x)
    g = MultiAxisGenerator(**config)
    g.process(x[:split])
    h = MultiAxisGenerator(**config)
    h.set_state(g.get_state())
    assert np.array_equal(h.process(x[split:]), one_shot[split:])
    name = data.draw(st.sampled_from(["vmax", "amax", "jmax"]))
    axis = data.draw(st.integers(0, axes - 1))
    nudged = lims[name].copy()
    nudged[axis] *= 1 + 1e-9
    with pytest.raises(ParameterError, match=rf"^state is from {name}\[{axis}\]="):
        MultiAxisGenerator(**dict(config, **{name: nudged})).set_state(g.get_state())
