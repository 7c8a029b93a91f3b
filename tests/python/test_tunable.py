# SPDX-License-Identifier: Apache-2.0
"""TunableChain (C sms_tunable_chain) against the NumPy definition of a retuned stage
(reference.switched: each input increment through the stage active when it arrived), for every
family, over random configurations, switch instants and moves (hypothesis); the switch's jump
bound and the new filter after both lengths; state, copy and refusals.

Tolerances: the contract between the C core and the reference (docs/numerics.md: 1e-12
relative in double, 1e-5 in float) relative to the signal's magnitude, times the larger l1 norm
G of the two stages' impulse responses (each term of the realisation's sums is at most G times
the signal; G is 1 for most stages). The fixed stages themselves use up to 170 u of it (a
bounded rectangular stage of 2.00001 samples); tests/c/test_tunable.c measures the switch's own
error against the definition at 12 u (double) and 9 u (float).
"""
import numpy as np
import pytest
from hypothesis import given, strategies as st

import smoothshaper as sms
from smoothshaper import reference as ref

Ts = 1e-3
REL = {"double": 1e-12, "float": 1e-5}
SHAPER_KINDS = ("zv", "zvd", "zvdd", "ei", "ei2", "ei3", "mzv")


@st.composite
def configs(draw, family):
    """A random stage of a family (smoother, shaper, notch) valid at Ts, 2 to 60 samples long."""
    if family == "smoother":
        kind = draw(st.sampled_from(("rectangular", "harmonic", "damped_harmonic",
                                     "exponential")))
        nu = draw(st.floats(2.0, 60.0))
        timing = draw(st.sampled_from(("exact", "paper", "bounded")
                                      if kind in ("rectangular", "exponential")
                                      else ("exact", "paper")))
        extra = {"sigma": -draw(st.floats(0.0, 80.0))} if kind in ("damped_harmonic",
                                                                  "exponential") else {}
        stage = getattr(sms, kind)(T=nu * Ts, timing=timing, **extra)
        try:
            sms.Chain([stage], Ts=Ts)
        except sms.ParameterError:   # exact timing's zero above Nyquist: a whole length
            stage = getattr(sms, kind)(T=round(nu) * Ts, timing=timing, **extra)
        return stage
    if family == "shaper":
        return sms.shaper(draw(st.sampled_from(SHAPER_KINDS)), wn=draw(st.floats(150.0, 750.0)),
                          zeta=draw(st.floats(0.0, 0.2)),
                          timing=draw(st.sampled_from(("exact", "paper"))))
    return sms.notch(wn=draw(st.floats(100.0, 1000.0)), zeta=draw(st.floats(0.0, 0.1)),
                     notch_pole_zeta=draw(st.floats(0.3, 1.8)),
                     discretization=draw(st.sampled_from(("tustin", "matched"))))


FAMILIES = ("smoother", "shaper", "notch")


def move(seed: int, n: int, rest: float) -> np.ndarray:
    """Piecewise-constant velocity from rest (random slopes, pauses) plus a few small steps."""
    rng = np.random.default_rng(seed)
    v = np.repeat(np.where(rng.random(n // 37 + 1) < 0.25, 0.0, rng.uniform(-0.05, 0.05,
                                                                           n // 37 + 1)), 37)[:n]
    kicks = np.where(rng.random(n) < 0.02, rng.uniform(-0.01, 0.01, n), 0.0)
    return rest + np.cumsum(v) + kicks


def gain(*stages) -> float:
    """The largest l1 norm of the stages' impulse responses (a notch's over 2000 samples)."""
    return max(np.sum(np.abs(ref.impulse_response(s, Ts=Ts, length=2000 if s.kind in
                                                  sms.stages.NOTCHES else None)))
               for s in stages)


def run(stages_in_order, x, switch_at, *, precision="double", rest=0.0, capacity=None):
    """One tunable stage retuned at the given samples, or as soon after as its previous switch
    has ended; returns the output, the chain and the samples the retunes took effect at."""
    first, *rest_stages = stages_in_order
    chain = sms.TunableChain([first], Ts=Ts, precision=precision,
                             capacity=[capacity or list(stages_in_order)])
    chain.reset(rest)
    out, start, taken = [], 0, []
    for at, stage in zip(switch_at, rest_stages):
        out.append(chain.process(x[start:max(at, start)]))
        start = max(at, start)
        while chain.switching[0]:
            out.append(chain.process(x[start:start + 1]))
            start += 1
        chain.retune(0, stage)
        taken.append(start)
    out.append(chain.process(x[start:]))
    return np.concatenate(out), chain, taken


@pytest.mark.parametrize("precision", ["double", "float"])
@pytest.mark.parametrize("fam_b", FAMILIES)
@pytest.mark.parametrize("fam_a", FAMILIES)
@given(data=st.data())
def test_switch_equals_definition(fam_a, fam_b, precision, data):
    """Against the definition; the jump at the switch; the new filter after both lengths."""
    a, b = data.draw(configs(fam_a)), data.draw(configs(fam_b))
    n0 = data.draw(st.integers(40, 250))
    rest = data.draw(st.floats(-10.0, 10.0))
    x = move(data.draw(st.integers(0, 2 ** 31)), 400, rest)
    if precision == "float":       # the C float build sees the input rounded to float
        x = x.astype(np.float32).astype(np.float64)
        rest = float(np.float32(rest))
    y, _, _ = run([a, b], x, [n0], precision=precision, rest=rest)
    tol = REL[precision] * np.max(np.abs(x)) * gain(a, b)
    want = ref.switched([a, b], x, Ts=Ts, switch_at=[n0], rest=rest)
    assert np.max(np.abs(y - want)) <= tol
    # the jump against keeping the old filter: (h_B[0] - h_A[0]) dx[n0], below one sample's motion
    old = ref.filter(a, x - rest, Ts=Ts) + rest
    h0 = [ref.impulse_response(s, Ts=Ts, length=1)[0] for s in (a, b)]
    motion = abs(x[n0] - x[n0 - 1])
    assert abs(y[n0] - old[n0]) <= abs(h0[1] - h0[0]) * motion + tol
    # FIR: from n0 + max(L_A, L_B) - 2 on, the new filter as if it had always run
    if fam_a != "notch" and fam_b != "notch":
        L = max(ref.impulse_response(s, Ts=Ts).size for s in (a, b))
        new = ref.filter(b, x - rest, Ts=Ts) + rest
        assert np.max(np.abs(y[n0 + L - 2:] - new[n0 + L - 2:]), initial=0.0) <= tol


@given(data=st.data())
def test_several_switches(data):
    """Three configurations of any families, each switch after the previous one has ended."""
    stages = [data.draw(configs(f)) for f in data.draw(
        st.lists(st.sampled_from(FAMILIES), min_size=3, max_size=3))]
    x = move(data.draw(st.integers(0, 2 ** 31)), 1500, 0.0)
    y, _, taken = run(stages, x, [150, 450])
    tol = REL["double"] * np.max(np.abs(x)) * gain(*stages)
    assert np.max(np.abs(y - ref.switched(stages, x, Ts=Ts, switch_at=taken))) <= tol


def test_split_blocks_and_state_mid_switch():
    """Any split into blocks gives the same bits; a state saved during a switch, loaded into a
    chain built with other stages (same capacity), continues bit for bit."""
    a, b = sms.rectangular(T=0.0304), sms.shaper("ei", wn=220.0, zeta=0.03)
    x = move(7, 600, 1.5)
    whole, _, _ = run([a, b], x, [200], capacity=[a, b], rest=1.5)
    chain = sms.TunableChain([a], Ts=Ts, capacity=[[a, b]])
    chain.reset(1.5)
    parts = [chain.process(x[:57]), chain.process(x[57:200])]
    chain.retune(0, b)
    parts.append(chain.process(x[200:205]))
    assert chain.switching == (True,)
    saved = chain.get_state()
    parts.append(chain.process(x[205:]))
    assert np.array_equal(np.concatenate(parts), whole)
    other = sms.TunableChain([sms.rectangular(T=0.005)], Ts=Ts, capacity=[[a, b]])
    other.set_state(saved)
    assert other.stages[0].kind == "ei" and other.switching == (True,)
    assert np.array_equal(other.process(x[205:]), whole[205:])
    twin = chain.copy()
    assert np.array_equal(twin.process(x), chain.process(x))


def test_state_mid_notch_switch_into_a_chain_at_rest():
    """A state saved while a retuned notch fades, loaded into a chain built with other stages:
    its notch is rebuilt in the old configuration, at rest, so the retune to the active one
    begins no switch, and the saved part is longer than that stage's count (the old notch's
    values): the next stage's part is still found, the switch goes on and the output continues
    bit for bit."""
    a, b = sms.notch(wn=200.0, notch_pole_zeta=0.7), sms.notch(wn=260.0, notch_pole_zeta=0.7)
    s = sms.shaper("zv", wn=300.0)
    x = move(11, 800, 5.0)
    chain = sms.TunableChain([a, s], Ts=Ts, capacity=[[a, b], None])
    chain.reset(5.0)
    chain.process(x[:200])
    chain.retune(0, b)
    chain.process(x[200:203])
    assert chain.switching == (True, False)
    saved = chain.get_state()
    other = sms.TunableChain([sms.notch(wn=500.0, notch_pole_zeta=0.7), s], Ts=Ts,
                             capacity=[[a, b], None])
    other.set_state(saved)
    assert other.stages[0] == b and other.switching == (True, False)
    assert np.array_equal(other.process(x[203:]), chain.process(x[203:]))


def test_chain_retunes_its_middle_stage():
    """Stages in series: retuning stage 1 of three equals the reference chain of the fixed
    stages around the switched one."""
    s0, s2 = sms.rectangular(T=0.0155), sms.notch(wn=900.0, notch_pole_zeta=0.5)
    a, b = sms.shaper("zvd", wn=300.0, zeta=0.05), sms.shaper("zvd", wn=240.0, zeta=0.05)
    x = move(3, 700, 0.0)
    chain = sms.TunableChain([s0, a, s2], Ts=Ts, capacity=[None, b, None])
    y = np.concatenate([chain.process(x[:300]), (chain.retune(1, b), chain.process(x[300:]))[1]])
    u = ref.filter(s0, x, Ts=Ts)
    want = ref.filter(s2, ref.switched([a, b], u, Ts=Ts, switch_at=[300]), Ts=Ts)
    assert np.max(np.abs(y - want)) <= REL["double"] * np.max(np.abs(x))
    assert chain.stages[1] == b


def test_refusals_change_nothing():
    a, b = sms.shaper("zv", wn=300.0), sms.rectangular(T=0.01)
    chain = sms.TunableChain([a], Ts=Ts, capacity=[[a, b]])
    chain.process(np.linspace(0.0, 1.0, 50))
    before = chain.get_state()
    with pytest.raises(sms.ParameterError) as e:
        chain.retune(0, sms.shaper("zv", wn=100.0))        # longer than declared
    assert e.value.parameter == "stage" and "capacity" in str(e.value)
    with pytest.raises(sms.ParameterError) as e:
        chain.retune(1, b)
    assert e.value.parameter == "index"
    with pytest.raises(sms.ParameterError) as e:
        chain.retune(0, "zv")
    assert e.value.parameter == "stage"
    with pytest.raises(sms.ParameterError) as e:
        chain.retune(0, sms.shaper("zv", wn=4000.0))       # above Nyquist at Ts
    assert e.value.parameter == "wn"
    assert np.array_equal(chain.get_state(), before)
    chain.retune(0, b)
    busy = chain.get_state()
    with pytest.raises(sms.ParameterError) as e:
        chain.retune(0, a)
    assert e.value.parameter == "index" and "still switching" in str(e.value)
    assert np.array_equal(chain.get_state(), busy)
    left = ref.impulse_response(a, Ts=Ts).size - 2      # the old ZV's length minus 2
    assert chain.switch_left(0) == left
    chain.process(np.ones(left - 1))
    assert chain.switching == (True,) and chain.switch_left(0) == 1
    chain.process(np.ones(1))
    assert chain.switching == (False,)
    chain.retune(0, a)
    with pytest.raises(sms.ParameterError) as e:
        sms.TunableChain([a], Ts=Ts, capacity=[a, b])
    assert e.value.parameter == "capacity"
    with pytest.raises(sms.ParameterError) as e:
        chain.process([0.0, np.nan])
    assert e.value.parameter == "u"
    with pytest.raises(sms.ParameterError) as e:
        chain.set_state(before[:-1])
    assert e.value.parameter == "state"
    small = sms.TunableChain([a], Ts=Ts)
    with pytest.raises(sms.ParameterError) as e:
        small.set_state(before)
    assert e.value.parameter == "state" and "capacity" in str(e.value)


def test_input_max_during_a_switch_divides_the_uncapped_limit():
    """Two moving averages, stage 1 switching: each limit is REAL_MAX / 2 (sum |g| = 1) and
    R_1 = 1 + 2 G_0 = 3 (G_0 = 1), so the range stays at input_max() (REAL_MAX / 6 is far
    above it), where capping each stage first gave input_max() / 3."""
    from smoothshaper.filters import input_max
    chain = sms.TunableChain([sms.rectangular(T=0.01), sms.rectangular(T=0.005)], Ts=1e-3,
                             capacity=[None, sms.rectangular(T=0.02)])
    chain.process(np.zeros(30))
    chain.retune(1, sms.rectangular(T=0.02))
    chain.process([1.0])
    assert chain.switching == (False, True)
    assert chain.input_max == input_max("double")
    y = chain.process(np.where(np.arange(40) % 2, 1.0, -1.0) * input_max("double"))
    assert np.all(np.isfinite(y))
