# SPDX-License-Identifier: Apache-2.0
"""Every C-backed object (Chain, TunableChain, ScheduledShaper, Generator, MultiAxisGenerator,
BSpline) is safe to share
between threads, copies and pickles into an independent object that continues bit-exactly,
and refuses a non-finite saved state (docs/python.md).

The thread tests feed the same block of input from several threads at once: whatever order
the calls run in, one call at a time is that block repeated, as one thread running them all
gives it, so the output blocks (in some order) and the final state must equal that thread's
exactly. Without a
lock the C core runs on one state from two threads and both differ (or a call never ends,
which the join's timeout turns into a failure)."""
from __future__ import annotations

import copy
import pickle
import threading

import numpy as np
import pytest

import smoothshaper as sms
from smoothshaper import ParameterError
from smoothshaper.multi_axis import MultiAxisGenerator
from smoothshaper.scheduled import ScheduledShaper
from smoothshaper.trajectory import BSpline, Generator
from smoothshaper.tunable import TunableChain

Ts = 1e-3
THREADS, CALLS, BLOCK = 4, 10, 20000


def chain(precision="double"):
    return sms.Chain([sms.harmonic(T=0.05), sms.shaper("zv", wn=100.0, zeta=0.05),
                      sms.notch(wn=300.0, zeta=0.02)], Ts=Ts, precision=precision)


def generator(precision="double"):
    return Generator(vmax=250.0, amax=5000.0, jmax=2e5, Ts=Ts, wn=100.0, zeta=0.05,
                     precision=precision)


def multi(precision="double"):
    return MultiAxisGenerator(vmax=[0.5, 0.4], amax=[5.0, 4.0], jmax=[200.0, 150.0], Ts=Ts,
                              stages=[sms.shaper("zv", wn=50.0, zeta=0.1)], precision=precision)


def tunable(precision="double"):
    """A chain caught in a retune: the saved state holds the fading old stage too."""
    c = TunableChain([sms.damped_harmonic(T=0.05, sigma=-20.0), sms.shaper("zv", wn=200.0)], Ts=Ts,
                     capacity=[None, sms.shaper("zvd", wn=80.0)], precision=precision)
    c.retune(1, sms.shaper("zvd", wn=90.0))
    return c


def scheduled(precision="double"):
    return ScheduledShaper("zvd", [(0.0, 150.0, 0.02), (0.5, 190.0, 0.03), (1.0, 240.0, 0.05)],
                           Ts=Ts, precision=precision)


#: The scheduled shaper's schedule: the input block's sample index mapped onto [0, 1].
def _scheduled_run(obj, block):
    return obj.process(block, np.linspace(0.0, 1.0, block.size))


def staircase(axes: int, scale: float):
    """Random targets held 500 samples each (a fixed draw)."""
    steps = np.random.default_rng(7).uniform(-scale, scale, size=(BLOCK // 500, axes))
    return np.repeat(steps, 500, axis=0)


# (factory, a block of input)
OBJECTS = {
    "Chain": (chain, np.random.default_rng(5).normal(size=BLOCK)),
    "TunableChain": (tunable, np.random.default_rng(6).normal(size=BLOCK)),
    "ScheduledShaper": (scheduled, np.random.default_rng(8).normal(size=BLOCK)),
    "Generator": (generator, staircase(1, 40.0)[:, 0]),
    "MultiAxisGenerator": (multi, staircase(2, 0.3)),
}
#: How each filters a block (the scheduled shaper also takes its schedule).
RUN = {"ScheduledShaper": _scheduled_run}
#: Filters of a single input that run 20000 samples too fast to meet another thread.
FAST = ("Chain", "TunableChain", "ScheduledShaper")


def run(name, obj, block):
    return RUN.get(name, lambda o, b: o.process(b))(obj, block)


def _hammer(obj, block, threads=THREADS, calls=CALLS, process=lambda o, b: o.process(b)):
    """Run ``calls`` blocks on ``obj`` from each of ``threads`` threads at once; the outputs."""
    outputs, errors = [], []
    start = threading.Barrier(threads)

    def work():
        try:
            start.wait()
            for _ in range(calls):
                outputs.append(process(obj, block))
        except Exception as exc:       # reported below, with the test's failure
            errors.append(exc)

    pool = [threading.Thread(target=work, daemon=True) for _ in range(threads)]
    for t in pool:
        t.start()
    for t in pool:
        t.join(timeout=120)
    assert not any(t.is_alive() for t in pool), "a thread never finished (the state is corrupt)"
    assert not errors, errors
    return outputs


@pytest.mark.parametrize("name", OBJECTS)
def test_shared_between_threads_is_one_call_at_a_time(name):
    factory, block = OBJECTS[name]
    calls = CALLS
    if name in FAST:     # filters 20000 samples too fast to meet another thread
        block, calls = np.tile(block, 10), 3
    shared, alone = factory(), factory()
    outputs = _hammer(shared, block, calls=calls, process=lambda o, b: run(name, o, b))
    expected = [run(name, alone, block) for _ in range(THREADS * calls)]
    assert np.array_equal(shared.get_state(), alone.get_state())

    assert sorted(b.tobytes() for b in outputs) == sorted(b.tobytes() for b in expected)


def test_bspline_shared_between_threads():
    """A B-spline filter's process() starts from rest every call: each call from each thread
    returns what it returns alone."""
    b = BSpline(degree=3, T=0.05, Ts=Ts, axes=2)
    x = np.cumsum(np.random.default_rng(3).normal(size=(BLOCK, 2)), axis=0)
    expected = BSpline(degree=3, T=0.05, Ts=Ts, axes=2).process(x)
    for y in _hammer(b, x, calls=10):
        assert np.array_equal(y, expected)


def test_step_reset_and_state_from_threads():
    """step, get_state and set_state interleaved from threads: every saved state is one the
    chain had (it loads again) and the chain ends consistent (each thread's get/set pair holds
    the chain's lock, which is re-entrant, so that no other thread's step falls between them)."""
    c = chain()
    c.process(np.ones(100))
    saved, errors = [], []

    def work(k):
        try:
            for i in range(200):
                c.step(1.0)
                if i % 50 == 0:
                    # get and set as one: between two separate calls another thread's step
                    # would be undone by set_state, and the chain would end short of the twin
                    with c._lock:
                        s = c.get_state()
                        saved.append(s)
                        c.set_state(s)
        except Exception as exc:
            errors.append(exc)

    pool = [threading.Thread(target=work, args=(k,), daemon=True) for k in range(THREADS)]
    for t in pool:
        t.start()
    for t in pool:
        t.join(timeout=120)
    assert not any(t.is_alive() for t in pool) and not errors, errors
    for s in saved:
        c.copy().set_state(s)
    twin = chain()
    twin.process(np.ones(100))
    for _ in range(THREADS * 200):
        twin.step(1.0)
    assert np.array_equal(c.get_state(), twin.get_state())


DUPLICATES = {"copy()": lambda o: o.copy(), "copy.copy": copy.copy, "deepcopy": copy.deepcopy,
              "pickle": lambda o: pickle.loads(pickle.dumps(o))}


@pytest.mark.parametrize("precision", ["double", "float"])
@pytest.mark.parametrize("how", DUPLICATES)
@pytest.mark.parametrize("name", OBJECTS)
def test_duplicates_are_independent_and_continue_bit_exactly(name, how, precision):
    factory, block = OBJECTS[name]
    original, reference = factory(precision), factory(precision)
    half, block = block[:BLOCK // 100], block[:BLOCK // 20]
    run(name, original, half)
    run(name, reference, half)
    twin = DUPLICATES[how](original)
    assert twin is not original and type(twin) is type(original)
    assert np.array_equal(twin.get_state(), original.get_state())
    y_twin = run(name, twin, block)            # the twin runs ahead ...
    assert np.array_equal(original.get_state(), reference.get_state())   # ... alone
    assert np.array_equal(y_twin, run(name, reference, block))
    assert np.array_equal(run(name, original, block), y_twin)


@pytest.mark.parametrize("how", DUPLICATES)
def test_bspline_duplicates(how):
    b = BSpline(degree=4, T=0.04, Ts=Ts, axes=3, precision="float")
    twin = DUPLICATES[how](b)
    assert (twin.degree, twin.axes, twin.N, twin.precision) == (4, 3, b.N, "float")
    x = np.random.default_rng(1).normal(size=(300, 3))
    assert np.array_equal(twin.process(x), b.process(x))


def test_duplicates_keep_the_diagnostic_counters():
    g = Generator(vmax=1.0, amax=1.0, jmax=1.0, Ts=Ts)
    with pytest.warns(sms.errors.DroppedTargetWarning):
        g.process([1e300, 1e300])
    for twin in (g.copy(), pickle.loads(pickle.dumps(g))):
        assert (twin.dropped, twin.refused) == (g.dropped, g.refused) == (1, True)


@pytest.mark.parametrize("name", OBJECTS)
@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_set_state_refuses_non_finite_values_everywhere(name, bad):
    """Every entry of a saved state (identity, plan, delay lines, stage states) set to a
    non-finite value is refused, naming ``state``, and the object is unchanged."""
    factory, block = OBJECTS[name]
    obj = factory()
    run(name, obj, block[:50])
    good = obj.get_state()
    for i in range(good.size):
        s = good.copy()
        s[i] = bad
        with pytest.raises(ParameterError) as info:
            obj.set_state(s)
        assert info.value.parameter == "state"
        assert np.array_equal(obj.get_state(), good)
