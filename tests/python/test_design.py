# SPDX-License-Identifier: Apache-2.0
"""Kinematic design: ruckig's time-optimal duration, bounds of the sampled trajectory, seed 001
check values, C vs the independent reference, parameter errors."""
import copy
import dataclasses
import math
import pickle
import re
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import event, given, settings, strategies as st

ruckig = pytest.importorskip("ruckig")
from smoothshaper import design, stages  # noqa: E402


def ruckig_duration(h, v, a, j):
    otg = ruckig.Ruckig(1)
    inp = ruckig.InputParameter(1)
    inp.current_position = [0.0]
    inp.target_position = [h]
    inp.max_velocity = [v]
    inp.max_acceleration = [a]
    inp.max_jerk = [j]
    traj = ruckig.Trajectory(1)
    assert otg.calculate(inp, traj) == ruckig.Result.Working
    return traj.duration


def chain_derivative_peak(h, T, i, n_points=64):
    """Exact peak of |q^(i)| (1 <= i <= n) of a step h through rectangular stages T, in
    rational arithmetic (no cancellation):
    q^(i)(t) = h / prod(T) * sum over subsets S of (-1)^|S| (t - sum_S T)_+^(n-i) / (n-i)!.
    Continuous derivatives (i < n) are evaluated on a grid plus every breakpoint; the
    piecewise-constant top derivative at the midpoint of every interval between breakpoints
    wider than 1e-12 of the duration (T1 = T2 + T3 holds only to rounding when a bound is
    unreachable, which can leave a sliver of ~1e-17 s where two jerk pulses touch)."""
    n = len(T)
    Tq = [Fraction(x) for x in T]
    shifts = []
    for mask in range(1 << n):
        shifts.append((sum((Tq[b] for b in range(n) if mask >> b & 1), Fraction(0)),
                       -1 if bin(mask).count("1") % 2 else 1))
    total = sum(Tq)
    breaks = sorted({s for s, _ in shifts})
    if i < n:
        ts = {total * Fraction(k, n_points) for k in range(n_points + 1)} | set(breaks)
    else:
        ts = {(a + b) / 2 for a, b in zip(breaks, breaks[1:]) if b - a > total * Fraction(1, 10 ** 12)}
    scale = Fraction(h) / math.prod(Tq) / math.factorial(n - i)
    peak = Fraction(0)
    for t in ts:
        acc = Fraction(0)
        for shift, sign in shifts:
            x = t - shift
            if n - i == 0:
                acc += sign if x >= 0 else 0
            elif x > 0:
                acc += sign * x ** (n - i)
        peak = max(peak, abs(acc * scale))
    return peak


decades = st.floats(min_value=-3.0, max_value=3.0)


@given(lh=decades, lv=decades, la=decades, lj=decades)
def test_double_s_duration_equals_ruckig(lh, lv, la, lj):
    h, v, a, j = 10 ** lh, 10 ** lv, 10 ** (la + 1), 10 ** (lj + 2)
    stages = design.kinematic(h=h, vmax=v, amax=a, jmax=j)
    T = [s.T for s in stages]
    assert [s.kind for s in stages] == ["rectangular"] * 3
    assert sum(T) == pytest.approx(ruckig_duration(h, v, a, j), rel=1e-9)
    # the sampled trajectory stays within every bound (exact rational evaluation at a grid and
    # at every breakpoint) and the largest bound-relative peak is reached (time-optimality)
    ratios = [chain_derivative_peak(h, T, i) / Fraction(b) for i, b in enumerate((v, a, j), 1)]
    assert max(ratios) <= 1 + Fraction(1, 10 ** 12)
    assert ratios[0] >= 1 - Fraction(1, 10 ** 12) or ratios[1] >= 1 - Fraction(1, 10 ** 12) \
        or ratios[2] >= 1 - Fraction(1, 10 ** 12)
    assert T[0] >= T[1] + T[2] - 1e-12 * T[0] and T[1] >= T[2] * (1 - 1e-12)


@given(lh=decades, lv=decades, la=decades, lj=decades, ls=decades,
       profile=st.sampled_from(["polynomial", "trigonometric"]))
def test_c_matches_reference_any_order(lh, lv, la, lj, ls, profile):
    kw = dict(h=10 ** lh, vmax=10 ** lv, amax=10 ** la, jmax=10 ** lj, higher=(10 ** ls,),
              profile=profile)
    c = [s.T for s in design.kinematic(**kw)]
    ref = [s.T for s in design.kinematic_reference(**kw)]
    assert c == pytest.approx(ref, rel=1e-9)


@given(lh=decades, n=st.integers(1, 4), slack=st.lists(st.floats(0.0, 2.0), min_size=4,
       max_size=4), lt=decades, profile=st.sampled_from(["polynomial", "trigonometric"]))
def test_every_bound_reached_gives_the_quotients(lh, n, slack, lt, profile):
    """Where every stage lasts at least the sum of those below it (vmax reached, and every
    bound below it), the lengths are the quotients h/L_0, L_0/L_1, ..., c L_{n-2}/L_{n-1}
    (c = 1, or pi/2 for a harmonic last stage): the values of the recursion's closed form
    there, bit for bit (the C core computes them directly in that regime), and the
    reference's. Slack 0 puts a stage exactly at the regime's edge."""
    c = 1.0 if profile == "polynomial" else 0.5 * math.pi
    T = [10.0 ** lt]                            # the last stage, then upwards
    for u in slack[:n - 1]:
        T.insert(0, sum(T) * (1.0 + u))
    h = 10.0 ** lh
    L = [h / T[0]]                              # the bounds that give these lengths
    for k in range(1, n):
        L.append(L[-1] / T[k] * (c if k == n - 1 else 1.0))
    if n == 1:
        L = [c * h / T[0]]
    q = [c * h / L[0]] if n == 1 else \
        [h / L[0]] + [L[k - 1] / L[k] for k in range(1, n - 1)] + [c * L[n - 2] / L[n - 1]]
    kw = dict(h=h, vmax=L[0], amax=L[1] if n > 1 else None, jmax=L[2] if n > 2 else None,
              higher=tuple(L[3:]), profile=profile)
    got = [s.T for s in design.kinematic(**kw)]
    rest, regime = q[-1], True                  # the sums from the bottom, as the C core adds
    for k in reversed(range(n - 1)):
        regime &= q[k] >= rest
        rest = q[k] + rest
    if regime:
        assert got == q
    assert got == pytest.approx([s.T for s in design.kinematic_reference(**kw)], rel=1e-9)


@settings(max_examples=15, deadline=None)   # the reference tries all 10,000 multiples
@given(lv=st.floats(-4, -2), la=st.floats(1, 4), lj=st.floats(0, 3), n=st.integers(2, 3),
       lp=st.floats(-2.5, 0.5), zeta=st.sampled_from([0.0, 0.05]), grid=st.booleans())
def test_mode_multiple_search_skips_only_multiples_that_cannot_win(lv, la, lj, n, lp, zeta,
                                                                    grid):
    """With a rectangular stage tuned to a mode, the C search skips the multiples whose chain
    must last at least k Tm + h/vmax (longer than the best found; a short tuned box leaves
    the velocity to the other boxes). Where that skips the most, h/vmax far above the other
    stages and a mode period far below the last stage, the multiple and the lengths equal
    those of the reference, which tries every multiple."""
    kw = dict(h=1.0, vmax=10 ** lv, amax=10 ** la, jmax=10 ** lj if n == 3 else None)
    last = design.kinematic(**kw)[-1].T
    kw.update(wn=2 * math.pi / (last * 10 ** lp), zeta=zeta)
    if grid:
        kw["Ts"] = last * 10 ** lp / 7.3   # seven samples and a fraction per mode period
    c = design.kinematic(**kw)
    ref = design.kinematic_reference(**kw)
    assert [s.k for s in c] == [s.k for s in ref]
    assert [s.T for s in c] == pytest.approx([s.T for s in ref], rel=1e-9)


def test_seed_001_check_values():
    T = [s.T for s in design.kinematic(h=40, vmax=250, amax=5000, jmax=200000)]
    assert T == pytest.approx([0.16, 0.05, 0.025], rel=1e-14)
    assert sum(T) == pytest.approx(0.235, rel=1e-14)
    one = design.kinematic(h=40, vmax=250, profile="trigonometric")
    assert one[0].kind == "harmonic" and one[0].T == pytest.approx(0.2513, abs=5e-5)
    two = [s.T for s in design.kinematic(h=40, vmax=250, amax=5000, profile="trigonometric")]
    assert two == pytest.approx([0.16, 0.0785], abs=5e-5)
    three = design.kinematic(h=40, vmax=250, amax=5000, jmax=200000, profile="trigonometric")
    assert [s.T for s in three] == pytest.approx([0.16, 0.05, 0.0393], abs=5e-5)
    assert three[-1].kind == "harmonic"


def test_mixed_time_frequency_seed_001_sec_5_2():
    # T1 = h/v, T2 = v/a, last stage on the mode: 2 pi / 260.4 = 0.0241 s (the paper prints 0.0209)
    stages = design.kinematic(h=40, vmax=250, amax=5000, jmax=1e6, wn=260.4)
    assert [s.T for s in stages] == pytest.approx([0.16, 0.05, 2 * math.pi / 260.4], rel=1e-14)
    assert stages[-1].k == 1


def test_damped_jerk():
    stages = design.kinematic(h=40, vmax=250, amax=5000, jmax=200000, profile="damped",
                              wn=122.0, zeta=0.1)
    last = stages[-1]
    wd = 122.0 * math.sqrt(1 - 0.01)
    assert last.kind == "exponential" and last.sigma == pytest.approx(-12.2)
    assert last.T == pytest.approx(last.k * 2 * math.pi / wd, rel=1e-14)
    ref = design.kinematic_reference(h=40, vmax=250, amax=5000, jmax=200000, profile="damped",
                                     wn=122.0, zeta=0.1)
    assert [s.T for s in stages] == pytest.approx([s.T for s in ref], rel=1e-12)
    # peak jerk = acceleration level * peak density of the exponential stage <= jmax
    rho = -last.sigma / -math.expm1(last.sigma * last.T)
    assert 40 / (stages[0].T * stages[1].T) * rho <= 200000 * (1 + 1e-12)


@pytest.mark.parametrize("kwargs, name", [
    (dict(h=0.0, vmax=1), "h"),
    (dict(h=float("nan"), vmax=1), "h"),
    (dict(h=1, vmax=-1), "vmax"),
    (dict(h=1, vmax=1, amax=0), "amax"),
    (dict(h=1, vmax=1, jmax=5), "amax"),
    (dict(h=1, vmax=1, amax=1, jmax=float("inf")), "jmax"),
    (dict(h=1, vmax=1, amax=1, profile="cubic"), "profile"),
    (dict(h=1, vmax=1, amax=1, profile="damped"), "wn"),
    (dict(h=1, vmax=1, amax=1, wn=-3), "wn"),
    (dict(h=1, vmax=1, amax=1, wn=3, zeta=1.0), "zeta"),
    (dict(h=1, vmax=1, amax=1, jmax=1, higher=(1,) * 6), "higher"),
    (dict(h=1, vmax=1, amax=1, jmax=1, higher=3.0), "higher"),
])
def test_errors_name_the_parameter(kwargs, name):
    with pytest.raises(ValueError, match=rf"^{name}\b"):
        design.kinematic(**kwargs)


def _outcome(fn, *args, **kwargs):
    """What a call gives: its stages (with repr and hashes), or its exception's type,
    message and parameter."""
    try:
        out = fn(*args, **kwargs)
    except Exception as e:  # noqa: BLE001 - compared, not swallowed
        return ("raised", type(e), str(e), getattr(e, "parameter", None))
    return ("ok", out, repr(out), [hash(s) for s in out], [type(s.T) for s in out])


_NUMBER_TYPES = (float, int, np.float64, np.float32, np.int64)


def _typed(value, kind):
    """``value`` as one of the number types users pass, where that type can hold it."""
    if kind is int:
        return int(round(value)) if math.isfinite(value) else value
    if kind is np.float32:
        return np.float32(value) if abs(value) < 1e38 else value
    if kind is np.int64:
        return np.int64(round(value)) if abs(value) < 9e18 else value
    return kind(value)


# Valid magnitudes over 12 decades, and every kind of invalid value the checks refuse.
valid = st.floats(-6.0, 6.0).map(lambda e: 10.0 ** e)
special = st.sampled_from([0.0, float("nan"), float("inf"), -float("inf"), 1e308, 1e-320,
                           -1.0])
numbers = st.one_of(valid, valid, valid, special) \
    .flatmap(lambda v: st.sampled_from(_NUMBER_TYPES).map(lambda k: _typed(v, k)))
odd = st.sampled_from([True, False, np.bool_(True), 1 + 0j, "1.0", 10 ** 400, -10 ** 400,
                       np.array(2.0), np.complex128(1.0), None, Fraction(1, 3)])
arguments = st.one_of(numbers, numbers, numbers, odd)


@settings(max_examples=500)
@given(h=st.one_of(numbers, numbers.map(lambda v: -v), odd), vmax=arguments,
       amax=st.one_of(st.none(), arguments), jmax=st.one_of(st.none(), arguments),
       profile=st.sampled_from(["polynomial", "trigonometric", "damped"] * 3
                               + ["Polynomial", "cubic", ["polynomial"]]),
       wn=st.one_of(st.none(), st.none(), arguments),
       zeta=st.one_of(st.floats(0.0, 0.99), st.sampled_from([0, 1.0, -0.1, np.float32(0.5)]),
                      odd),
       Ts=st.one_of(st.none(), st.none(), arguments),
       higher=st.sampled_from([()] * 6 + [[], np.array([]), np.array([1e9, 1e12])]))
def test_fast_path_equals_the_checked_path(h, vmax, amax, jmax, profile, wn, zeta, Ts, higher):
    """design.kinematic takes a fast path for plain numbers (float, int, NumPy float64,
    float32, int64) and at most three bounds; for any argument whatever (valid, out of range,
    not finite, huge ints, booleans, complex, text, arrays) it gives exactly what the fully
    checked path gives: equal stages with the same repr, hash and float lengths, or the same
    error with the same message and parameter."""
    fast = _outcome(design.kinematic, h=h, vmax=vmax, amax=amax, jmax=jmax, profile=profile,
                    wn=wn, zeta=zeta, Ts=Ts, higher=higher)
    checked = _outcome(design._kinematic_checked, h, vmax, amax, jmax, higher, profile, wn,
                       zeta, Ts)
    assert fast == checked


@given(lh=decades, lv=decades, la=decades, lj=decades, n=st.integers(1, 3),
       profile=st.sampled_from(design.PROFILES), grid=st.booleans(), mode=st.booleans(),
       lw=st.floats(-1.0, 3.0), zeta=st.floats(0.0, 0.9), kind=st.sampled_from(_NUMBER_TYPES))
def test_fast_path_is_taken_and_exact(lh, lv, la, lj, n, profile, grid, mode, lw, zeta, kind):
    """Valid plain numbers never reach the checked path (so the comparison above covers the
    fast path, with and without a mode), and the stages equal those of the checked path with
    every argument as a float: the C design sees the same doubles."""
    h = 10.0 ** lh
    kw = dict(vmax=10.0 ** lv, amax=10.0 ** la if n > 1 else None,
              jmax=10.0 ** lj if n > 2 else None)
    mode = mode or profile == "damped"
    typed = {k: None if v is None else _typed(v, kind) or kind(1) for k, v in kw.items()}
    h_typed = _typed(h, kind) or kind(1)
    wn = _typed(10.0 ** lw, kind) or kind(1) if mode else None
    zeta = _typed(zeta, kind) if mode and kind not in (int, np.int64) else 0.0
    floats = [None if v is None else float(v) for v in typed.values()]
    try:
        Ts = design.duration(design._kinematic_checked(
            float(h_typed), *floats, (), profile, wn and float(wn), float(zeta), None)) / 37.3 \
            if grid else None
        expected = design._kinematic_checked(float(h_typed), *floats, (), profile,
                                             wn and float(wn), float(zeta), Ts)
    except ValueError:   # no such design (damped with one bound, a mode above Nyquist, ...)
        return
    with pytest.MonkeyPatch.context() as m:
        m.setattr(design, "_kinematic_checked", None)   # calling it would raise TypeError
        fast = design.kinematic(h=h_typed, profile=profile, wn=wn, zeta=zeta, Ts=Ts, **typed)
    assert fast == expected and repr(fast) == repr(expected)
    # and both equal what the validating constructor builds from the same values
    assert fast == [stages.Stage(s.kind, T=s.T, sigma=s.sigma, k=s.k, timing=s.timing)
                    for s in fast]


def test_fast_path_threads():
    """Designs in four threads at once equal the checked path's, with and without a mode on
    a grid (the fast path lets other threads run during that longer design)."""
    import concurrent.futures
    rng = np.random.default_rng(7)
    cases = [dict(h=float(h), vmax=float(v), amax=float(a), jmax=float(j))
             for h, v, a, j in 10.0 ** rng.uniform(-2, 2, (400, 4))]
    for c in cases[::4]:
        T = design.duration(design.kinematic(**c))
        c.update(wn=float(2 * np.pi / T * rng.uniform(2, 20)), zeta=0.05, Ts=T / 300)
    expected = [design._kinematic_checked(c["h"], c["vmax"], c["amax"], c["jmax"], (),
                                          "polynomial", c.get("wn"), c.get("zeta", 0.0),
                                          c.get("Ts")) for c in cases]

    def run(offset):
        return all(design.kinematic(**cases[(i + offset) % len(cases)])
                   == expected[(i + offset) % len(cases)] for i in range(4 * len(cases)))
    with concurrent.futures.ThreadPoolExecutor(4) as pool:
        assert all(pool.map(run, range(0, 400, 100)))


def test_fast_path_reentrant_from_finalizers():
    """An allocation of the fast path can trigger a collection whose finalizers design on
    the same thread: each design keeps its own lengths and last stage."""
    import gc
    other = dict(h=3.0, vmax=7.0, amax=11.0, jmax=13.0, wn=5.0, zeta=0.2, profile="damped")

    class Designer:
        def __del__(self):
            finalized.append(design.kinematic(**other))

    def garbage():
        d = Designer()
        d.cycle = d   # only the collector frees it
    cases = [dict(h=1.0, vmax=0.5, amax=5.0, jmax=100.0),
             dict(h=1.0, vmax=0.5, amax=5.0, jmax=100.0, wn=30.0, zeta=0.05)]
    expected = [design._kinematic_checked(c["h"], c["vmax"], c["amax"], c["jmax"], (),
                                          "polynomial", c.get("wn"), c.get("zeta", 0.0), None)
                for c in cases]
    finalized = []
    threshold = gc.get_threshold()
    gc.collect()
    gc.set_threshold(1)
    try:
        for _ in range(20):
            for c, e in zip(cases, expected):
                garbage()
                assert design.kinematic(**c) == e
    finally:
        gc.set_threshold(*threshold)
    assert finalized   # the finalizers did design in between


def test_fast_path_keeps_reference_counts():
    """The C fast path neither leaks nor over-releases a reference: after many designs of
    every outcome (stages with each last-stage field, a fallback to the checked path, a
    refused design) the objects it uses and returns have their reference counts back."""
    import gc
    import sys
    watched = [stages.Stage, *stages.KINDS, *stages.TIMINGS, "polynomial", "damped", 0.05]
    calls = [dict(h=1.0, vmax=0.5, amax=5.0, jmax=100.0),
             dict(h=1.0, vmax=0.5, amax=5.0, jmax=100.0, wn=30.0, zeta=0.05, Ts=1e-3,
                  profile="damped"),
             dict(h=1.0, vmax=0.5, amax=5.0, jmax=100.0, wn=30.0, zeta=0.05,
                  profile="trigonometric"),
             dict(h=1.0, vmax=np.float32(0.5), amax=np.int64(5), jmax=100),
             dict(h=1.0, vmax=0.5, amax=5.0, jmax=100.0, higher=(1e4,))]
    for c in calls:   # warm every path (caches, interned names) before counting
        design.kinematic(**c)
    gc.collect()   # earlier tests' garbage holds Stage objects
    before = [sys.getrefcount(o) for o in watched]
    kept = [design.kinematic(**c) for c in calls for _ in range(1000)]
    del kept
    for _ in range(1000):
        with pytest.raises(design.ParameterError):
            design.kinematic(h=1.0, vmax=-0.5)
    gc.collect()
    assert [sys.getrefcount(o) for o in watched] == before


@given(kind=st.sampled_from(stages.SMOOTHERS), T=st.floats(1e-9, 1e9),
       sigma=st.one_of(st.just(0.0), st.floats(-1e6, -1e-9)), k=st.integers(0, 50))
def test_unchecked_stage_is_the_validated_stage(kind, T, sigma, k):
    """The Stage the design builds without re-validation (stages._UncheckedStage) is the one
    the constructor builds from the same values: same type, equal both ways, same hash, repr,
    every field with its type, frozen, and the same after pickle, copy, asdict and with_."""
    k = 2 * k + 1 if kind in ("harmonic", "damped_harmonic") else k + 1
    fast = stages._unchecked_stage(kind, T, sigma, k)
    ref = stages.Stage(kind, T=T, sigma=sigma, k=k)
    assert type(fast) is stages.Stage
    assert fast == ref and ref == fast and hash(fast) == hash(ref) and repr(fast) == repr(ref)
    for f in dataclasses.fields(stages.Stage):
        assert getattr(fast, f.name) == getattr(ref, f.name)
        assert type(getattr(fast, f.name)) is type(getattr(ref, f.name))
    assert fast.kind_index == ref.kind_index
    with pytest.raises(dataclasses.FrozenInstanceError):
        fast.T = 2 * T
    for twin in (pickle.loads(pickle.dumps(fast)), copy.copy(fast), copy.deepcopy(fast)):
        assert type(twin) is stages.Stage and twin == ref and repr(twin) == repr(ref)
    assert dataclasses.asdict(fast) == dataclasses.asdict(ref)
    assert fast.with_(T=2 * T) == ref.with_(T=2 * T)
    with pytest.raises(ValueError, match="T must be > 0"):   # with_ validates again
        fast.with_(T=-T)


@pytest.mark.parametrize("kwargs, name", [
    (dict(h=1e300, vmax=1e-250), "vmax"),
    (dict(h=1.0, vmax=1e200, amax=1e-200), "vmax"),
    (dict(h=1.0, vmax=1.0, amax=1.0, jmax=1e-70), "jmax"),
    (dict(h=1.0, vmax=1.0, amax=1e-70, Ts=1e-3), "amax"),
])
def test_fast_path_refusals_name_the_bound(kwargs, name):
    """Extreme ratios pass the fast path's plain-number test; the C design refuses them and
    the error still names the bound of the offending ratio."""
    with pytest.raises(ValueError, match=rf"\b{name}\b") as err:
        design.kinematic(**kwargs)
    assert err.value.parameter == name


# ----------------------------------------------------------------------------------------------
# Batch design
# ----------------------------------------------------------------------------------------------

def _lengths(**kw):
    return np.array([s.T for s in design.kinematic(**kw)])


@given(m=st.integers(1, 12), n=st.integers(1, 4), data=st.data(),
       profile=st.sampled_from(["polynomial", "trigonometric", "damped"]),
       grid=st.booleans(), mode=st.booleans(), lw=st.floats(-1.0, 2.0))
def test_batch_equals_the_scalar_design_bit_for_bit(m, n, data, profile, grid, mode, lw):
    """Every row of kinematic_lengths is the scalar design's lengths to the last bit, for
    every profile, with and without a mode and a grid, any sign of h; a problem the scalar
    design refuses is refused with the same error and its row."""
    n = max(n, 2) if profile == "damped" else n
    logs = np.array(data.draw(st.lists(st.lists(decades, min_size=n + 1, max_size=n + 1),
                                       min_size=m, max_size=m)))
    signs = np.array(data.draw(st.lists(st.sampled_from([-1.0, 1.0]), min_size=m, max_size=m)))
    h = signs * 10.0 ** logs[:, 0]
    bounds = 10.0 ** (logs[:, 1:] + 2 * np.arange(n))
    wn = 2 * math.pi * 10.0 ** lw if mode or profile == "damped" else None
    Ts = 10.0 ** lw / 1000.0 if grid else None

    def scalar(i):
        return dict(h=h[i], vmax=bounds[i, 0], amax=bounds[i, 1] if n > 1 else None,
                    jmax=bounds[i, 2] if n > 2 else None, higher=tuple(bounds[i, 3:]),
                    profile=profile, wn=wn, Ts=Ts)
    try:
        batch = design.kinematic_lengths(
            h=h, vmax=bounds[:, 0], amax=bounds[:, 1] if n > 1 else None,
            jmax=bounds[:, 2] if n > 2 else None, higher=list(bounds[:, 3:].T),
            profile=profile, wn=wn, Ts=Ts)
    except ValueError as e:
        i = int(re.search(r"\(row (\d+)\)$", str(e)).group(1))
        for k in range(i):                       # the rows before it are designed
            design.kinematic(**scalar(k))
        with pytest.raises(ValueError) as refused:
            design.kinematic(**scalar(i))
        assert str(e) == f"{refused.value} (row {i})"
        assert e.parameter == refused.value.parameter
        event("a problem refused")
        return
    assert batch.shape == (m, n) and batch.dtype == np.float64 and batch.flags.c_contiguous
    for i in range(m):
        assert batch[i].tobytes() == _lengths(**scalar(i)).tobytes()


def test_batch_broadcasts():
    """Scalars are shared, arrays broadcast (NumPy rules); the result has one row of n
    lengths per problem; ints and float32 are taken as their float64 values."""
    h = np.array([1.0, 10.0, 40.0])
    vmax = np.array([[100.0], [250.0]])
    out = design.kinematic_lengths(h=h, vmax=vmax, amax=5000, jmax=np.float32(2e5))
    assert out.shape == (2, 3, 3)
    for a in range(2):
        for b in range(3):
            assert out[a, b].tolist() == _lengths(h=h[b], vmax=vmax[a, 0], amax=5000.0,
                                                  jmax=float(np.float32(2e5))).tolist()
    assert design.kinematic_lengths(h=40, vmax=250, amax=5000, jmax=2e5).tolist() == \
        [0.16, 0.05, 0.025]
    assert design.kinematic_lengths(h=[], vmax=1.0, amax=2.0).shape == (0, 2)
    same = design.kinematic_lengths(h=[40, 40], vmax=[250, 250], amax=[5000, 5000],
                                    jmax=2e5, Ts=1e-3)
    assert (same == _lengths(h=40, vmax=250, amax=5000, jmax=2e5, Ts=1e-3)).all()
    h_in = np.array([1.0, 2.0])
    design.kinematic_lengths(h=h_in, vmax=1.0)
    assert h_in.tolist() == [1.0, 2.0]


@pytest.mark.parametrize("kwargs, name, text", [
    (dict(h=[1.0, 2.0, 3.0], vmax=[1.0, -1.0, 1.0]), "vmax", r"vmax must be > 0, got -1\.0 \(row 1\)$"),
    (dict(h=[1.0, 0.0], vmax=1.0), "h", r"^h must be non-zero.* \(row 1\)$"),
    (dict(h=[[1.0, float("nan")]], vmax=1.0), "h", r"^h must be finite, got nan \(index \(0, 1\)\)$"),
    (dict(h=[1.0, 1e300], vmax=1e-50, amax=1.0), "vmax", r"^vmax=1e-50 with h=1e\+300: h/vmax = .* \(row 1\)$"),
    # all scalars: one problem, no "(index ())" suffix
    (dict(h=1e308, vmax=1.0), "vmax", r"^vmax=1\.0 with h=1e\+308: h/vmax = .* closer together$"),
    (dict(h=1.0, vmax=[1.0, 1.0], amax=[1.0, float("inf")]), "amax", r"^amax must be finite.*\(row 1\)$"),
    (dict(h=[1.0, 2.0], vmax=[1.0, 2.0, 3.0]), "vmax", r"^vmax: shape \(3,\) does not broadcast"),
    (dict(h=[True], vmax=1.0), "h", r"^h must hold numbers, got a boolean array"),
    (dict(h=[1.0], vmax=[1 + 1j]), "vmax", "complex"),
    (dict(h=["1"], vmax=1.0), "h", "real numbers"),
    (dict(h=[[1.0], [1.0, 2.0]], vmax=1.0), "h", "^h must be an array of real numbers$"),
    (dict(h=1.0, vmax=1.0, jmax=[1.0]), "amax", r"^amax must be given when jmax is"),
    (dict(h=1.0, vmax=1.0, amax=1.0, jmax=1.0, higher=[1.0] * 6), "higher", "at most 8"),
    (dict(h=1.0, vmax=1.0, amax=1.0, higher=3.0), "higher", "sequence"),
    (dict(h=1.0, vmax=None), "vmax", "real numbers"),
    (dict(h=1.0, vmax=1.0, profile="cubic"), "profile", ""),
    (dict(h=1.0, vmax=1.0, amax=1.0, profile="damped"), "wn", ""),
    (dict(h=1.0, vmax=1.0, profile="damped", wn=3.0), "amax", ""),
    (dict(h=1.0, vmax=1.0, amax=1.0, wn=3.0, zeta=1.0), "zeta", ""),
    (dict(h=[1.0, 2.0], vmax=1.0, Ts=0.0), "Ts", r"^Ts must be > 0"),
    (dict(h=[1.0, 1e16], vmax=1.0, Ts=1e-3), "Ts", r"2\^52 samples.*\(row 1\)$"),
    (dict(h=[1.0, 2.0], vmax=1.0, amax=1.0, wn=1e4, Ts=1e-3), "wn", r"Nyquist.*\(row 0\)$"),
])
def test_batch_errors_name_the_parameter_and_the_problem(kwargs, name, text):
    """Each error names its parameter first (a ratio names the pair), and a refused problem
    its position."""
    with pytest.raises(ValueError, match=text or rf"^{name}\b") as err:
        design.kinematic_lengths(**kwargs)
    assert err.value.parameter == name
    assert re.match(rf"(h/)?{re.escape(name)}\b", str(err.value))


@pytest.mark.parametrize("kwargs, name", [
    (dict(vmax=1e308), "vmax"),        # ZeroDivisionError
    (dict(amax=5e-324), "amax"),       # ZeroDivisionError
    (dict(jmax=1e-308), "jmax"),       # ZeroDivisionError
    (dict(vmax=5e-324), "vmax"),       # named T
    (dict(Ts=5e-324), "Ts"),           # OverflowError from int(inf)
    (dict(Ts=1e-20), "Ts"),            # returned lengths off any grid of Ts
    (dict(wn=1e20, Ts=1e-3), "wn"),    # named T: the tuned stage's length, derived from wn
    (dict(wn=50.0, Ts=1e308), "wn"),
])
def test_the_reference_refuses_what_the_c_design_refuses(kwargs, name):
    """kinematic_reference has kinematic's contract: the same out-of-range arguments are the
    same parameter's error, at once, instead of a ZeroDivisionError or OverflowError."""
    kw = dict(h=0.1, vmax=1.0, amax=10.0, jmax=100.0)
    kw.update(kwargs)
    for func in (design.kinematic, design.kinematic_reference):
        with pytest.raises(design.ParameterError) as info:
            func(**kw)
        assert info.value.parameter == name, (func.__name__, str(info.value))
