# SPDX-License-Identifier: Apache-2.0
"""ScheduledShaper (C sms_scheduled) against the NumPy definition (reference.scheduled: the
reference's exact-timing shaper of the interpolated mode at every update), over random
tables, inputs, schedules and update periods (hypothesis); a schedule that holds still gives
the fixed shaper; a constant input passes exactly; the plant campaign of the report (20 random
moves on a machine whose stiffness doubles along the travel); refusals.

Tolerances: the C core against the reference, docs/numerics.md's 1e-12 (double) and 1e-5
(float) relative to the signal, times the taps' l1 norm (the fixed shapers' contract; the
scheduled taps equal the fixed ones to 4e-15, tests/c/test_scheduled.c).
"""
import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import smoothshaper as sms
from smoothshaper import reference as ref
from smoothshaper.report import scheduled as campaign
from smoothshaper.filters import input_max
from smoothshaper.scheduled import ScheduledShaper

Ts = 1e-3
REL = {"double": 1e-12, "float": 1e-5}


@st.composite
def tables(draw):
    n = draw(st.integers(1, 5))
    values = np.cumsum(draw(st.lists(st.floats(0.05, 1.0), min_size=n, max_size=n)))
    rows = [(float(v), draw(st.floats(120.0, 700.0)), draw(st.floats(0.0, 0.15)))
            for v in values]
    return np.array(rows)


@settings(max_examples=40)
@given(table=tables(), kind=st.sampled_from(["zv", "zvd", "zvdd", "zvn"]),
       order=st.integers(1, 4), every=st.integers(1, 5), seed=st.integers(0, 2 ** 31),
       precision=st.sampled_from(["double", "float"]))
def test_equals_the_definition(table, kind, order, every, seed, precision):
    rng = np.random.default_rng(seed)
    n = 250
    x = np.cumsum(rng.uniform(-0.05, 0.05, n)) + 2.0
    lo, hi = table[0, 0], table[-1, 0]
    s = lo - 0.2 + (hi - lo + 0.4) * (0.5 + 0.5 * np.sin(np.arange(n) * rng.uniform(0.005, 0.05)))
    if precision == "float":
        x = x.astype(np.float32).astype(np.float64)
    sh = ScheduledShaper(kind, table, Ts=Ts, order=order, update_every=every,
                         precision=precision)
    sh.reset(2.0 if precision == "double" else float(np.float32(2.0)), s=s[0])
    y = sh.process(x, s)
    want = ref.scheduled(kind, table, x, s, Ts=Ts, order=order, update_every=every, rest=2.0)
    gain = max(np.sum(np.abs(ref.impulse_response(sms.shaper(kind, wn=wn, zeta=z, order=order
                                                             if kind == "zvn" else None), Ts=Ts)))
               for _, wn, z in table)
    assert np.max(np.abs(y - want)) <= REL[precision] * np.max(np.abs(x)) * gain


@pytest.mark.parametrize("kind", ["zv", "zvd", "zvdd"])
def test_schedule_held_still_is_the_fixed_shaper(kind):
    table = campaign.table()
    x = np.cumsum(np.random.default_rng(3).uniform(-0.01, 0.02, 800))
    for s in (0.0, 0.33, 0.5, 1.0, 1.7):
        sh = ScheduledShaper(kind, table, Ts=Ts)
        sh.reset(0.0, s=s)
        wn, zeta = sh.mode(s)
        fixed = sms.Chain([sms.shaper(kind, wn=wn, zeta=zeta)], Ts=Ts).process(x)
        assert np.max(np.abs(sh.process(x, s) - fixed)) <= 1e-13 * np.max(np.abs(x))
        assert sh.mode(s) == pytest.approx(ref.schedule_mode(table, s), rel=1e-13)


def test_constant_input_passes_exactly_under_any_schedule():
    sh = ScheduledShaper("zvd", campaign.table(), Ts=Ts)
    sh.reset(0.7, s=0.0)
    s = np.linspace(-0.5, 1.5, 3000)
    assert np.array_equal(sh.process(np.full(3000, 0.7), s), np.full(3000, 0.7))


def test_state_round_trip_and_refusals():
    table = campaign.table()
    sh = ScheduledShaper("zv", table, Ts=Ts, update_every=3)
    x = np.linspace(0.0, 1.0, 500)
    sh.process(x[:200], x[:200])
    saved = sh.get_state()
    twin = ScheduledShaper("zv", table, Ts=Ts, update_every=3)
    twin.set_state(saved)
    assert np.array_equal(twin.process(x[200:], x[200:]), sh.process(x[200:], x[200:]))
    with pytest.raises(sms.ParameterError) as e:
        ScheduledShaper("zv", table, Ts=Ts).set_state(saved)        # another update period
    assert e.value.parameter == "state"
    bad = [(0.0, 100.0, 0.0), (0.0, 120.0, 0.0)]
    for args, parameter in [((("ei"), table), "kind"), (("zv", bad), "table"),
                            (("zv", [(0.0, 5000.0, 0.0)]), "table"),
                            (("zv", [(0.0, 100.0, 1.0)]), "table"), (("zv", np.ones(3)), "table")]:
        with pytest.raises(sms.ParameterError) as e:
            ScheduledShaper(*args, Ts=Ts)
        assert e.value.parameter == parameter, args
    with pytest.raises(sms.ParameterError) as e:
        ScheduledShaper("zv", table, Ts=Ts, update_every=0)
    assert e.value.parameter == "update_every"
    with pytest.raises(sms.ParameterError) as e:
        sh.process(x[:5], x[:4])
    assert e.value.parameter == "schedule"



@pytest.mark.parametrize("precision", ["double", "float"])
def test_inputs_and_states_beyond_the_input_range_are_refused(precision):
    """x, rest and delay-line values beyond SMS_INPUT_MAX are refused naming the argument, with
    nothing changed (in float such an input would be an infinity in the delay line)."""
    limit = input_max(precision)
    sh = ScheduledShaper("zvd", campaign.table(), Ts=Ts, precision=precision)
    sh.process(np.linspace(0.0, 1.0, 50), 0.5)
    saved = sh.get_state()
    for call, parameter in [(lambda: sh.process([0.0, 2 * limit], 0.5), "x"),
                            (lambda: sh.step(-2 * limit, 0.5), "x"),
                            (lambda: sh.reset(2 * limit), "rest")]:
        with pytest.raises(sms.ParameterError) as e:
            call()
        assert e.value.parameter == parameter
        assert np.array_equal(sh.get_state(), saved)
    beyond = saved.copy()
    beyond[-1] = 2 * limit
    with pytest.raises(sms.ParameterError, match=rf"state\[{saved.size - 1}\]") as e:
        sh.set_state(beyond)
    assert e.value.parameter == "state" and np.array_equal(sh.get_state(), saved)


SECTION = campaign.build()


@pytest.mark.parametrize("claim", SECTION.claims, ids=lambda c: c.key)
def test_plant_campaign_claims(claim):
    """The task's acceptance: on every one of 20 random moves the scheduled ZV leaves at most
    1 % of the unshaped residual and less than the fixed mid-travel ZV."""
    assert claim.holds, (f"{claim.what}: ours {claim.ours!r} vs {claim.relation} "
                         f"{claim.expected!r} ({claim.reference})")


def test_plant_simulation_is_exact_for_a_fixed_mode():
    """With the stiffness held, simulate_varying_mode equals the exact ZOH of the LTI mode
    (plants.simulate_zoh of wn^2/(s^2 + 2 zeta wn s + wn^2))."""
    from smoothshaper import plants
    wn, zeta = 2 * math.pi * 25, 0.02
    u = np.r_[np.zeros(5), np.linspace(0, 1, 100), np.ones(300)]
    x, _ = plants.simulate_varying_mode(u, wn=np.full(u.size, wn), zeta=zeta, Ts=Ts, x0=(0, 0))
    p = plants.Plant(np.array([[0.0, 1.0], [-wn * wn, -2 * zeta * wn]]), np.array([0.0, wn * wn]),
                     np.array([1.0, 0.0]), 0.0)
    _, y = plants.simulate_zoh(p, u, Ts=Ts)
    assert np.max(np.abs(x[:-1] - y)) <= 1e-12
