# SPDX-License-Identifier: Apache-2.0
"""Kinematic chains keep their bounds at every sample, for any Ts: the backward differences of
a step of h through Chain(kinematic(..., Ts=Ts), Ts=Ts) stay within vmax, amax, jmax, ...
(docs/sampled-limits.md). Tolerance: 1e-9 relative plus the rounding of the samples
themselves, 2**i * 8 * eps * |h| / Ts**i for the i-th difference (eps of the precision)."""
import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from smoothshaper import design
from smoothshaper.filters import Chain, ParameterError
from smoothshaper.stages import Stage

EPS = {"double": np.finfo(np.float64).eps, "float": np.finfo(np.float32).eps}


def sampled_ratios(stages, Ts, h, limits, precision="double"):
    """max |diff(q, i)| / Ts**i / limits[i-1] beyond the rounding floor, i = 1..n."""
    n_samples = sum(int(math.ceil(s.T / Ts)) + 1 for s in stages) + 4
    q = Chain(stages, Ts=Ts, precision=precision).process(np.full(n_samples, float(h)))
    q = np.concatenate([[0.0], np.asarray(q, dtype=np.float64)])
    out = []
    for i, L in enumerate(limits, 1):
        floor = 2.0 ** i * 8 * EPS[precision] * abs(h) / Ts ** i
        out.append((np.abs(np.diff(q, i)).max() / Ts ** i - floor) / L)
    return out


def test_reported_cases_keep_every_bound():
    L = [250.0, 5000.0, 2e5]
    for Ts in (0.025 / 10.5, 0.16 / 10.5, 0.16 / 1000.5):
        cont = design.kinematic(h=40, vmax=250, amax=5000, jmax=2e5)
        grid = design.kinematic(h=40, vmax=250, amax=5000, jmax=2e5, Ts=Ts)
        assert max(sampled_ratios(grid, Ts, 40, L)) <= 1 + 1e-9
        if Ts < 0.01:
            # the continuous lengths with exact timing are what exceeded (1.17 jmax)
            assert max(sampled_ratios(cont, Ts, 40, L)) > 1.0001
        for g in grid:
            assert abs(g.T / Ts - round(g.T / Ts)) <= 1e-9 * g.T / Ts
        price = (design.duration(grid) - design.duration(cont)) / Ts
        assert 0 <= price < len(L)       # under one sample per stage
        if Ts == 0.025 / 10.5:   # the numbers docs/sampled-limits.md quotes for this case
            assert [round(g.T / Ts) for g in grid] == [68, 22, 10]
            assert np.round(sampled_ratios(grid, Ts, 40, L), 3).tolist() == [0.988, 0.943, 0.99]


limits_strategy = st.tuples(
    st.floats(-3, 3), st.floats(-3, 3), st.floats(-3, 3), st.floats(-3, 3), st.floats(-3, 3),
    st.integers(1, 4), st.sampled_from(["polynomial", "trigonometric"]), st.floats(0.5, 3.5),
    st.booleans(), st.sampled_from(["double", "float"]))


@settings(max_examples=80, deadline=None)
@given(limits_strategy)
def test_every_sample_within_bounds(case):
    lh, lv, la, lj, ls, n, profile, lsamples, negative, precision = case
    h = (-1 if negative else 1) * 10.0 ** lh
    limits = [10.0 ** lv, 10.0 ** (la + 1), 10.0 ** (lj + 2), 10.0 ** (ls + 3)][:n]
    kw = dict(vmax=limits[0], amax=limits[1] if n > 1 else None,
              jmax=limits[2] if n > 2 else None, higher=tuple(limits[3:]), profile=profile)
    cont = design.kinematic(h=h, **kw)
    Ts = design.duration(cont) / 10.0 ** lsamples     # 3 to 3000 samples, off the grid
    grid = design.kinematic(h=h, Ts=Ts, **kw)
    ratios = sampled_ratios(grid, Ts, h, limits, precision)
    assert max(ratios) <= 1 + 1e-9, ratios
    if precision == "float":
        # At fine Ts the rounding floor of a float difference can exceed its bound, so the
        # check above can pass vacuously there; what carries the guarantee is the per-sample
        # rounding the floor assumes (8 eps |h|): the float output is the double output (whose
        # differences are checked exactly) within it. Measured at most 3.8 u |h|.
        n_samples = sum(int(math.ceil(s.T / Ts)) + 1 for s in grid) + 4
        step = np.full(n_samples, float(h))
        q_float = Chain(grid, Ts=Ts, precision="float").process(step)
        q_double = Chain(grid, Ts=Ts).process(step)
        assert np.max(np.abs(q_float - q_double)) <= 8 * EPS["float"] * abs(h)
    ref = design.kinematic_reference(h=h, Ts=Ts, **kw)
    for a, b in zip(grid, ref):
        assert a.kind == b.kind
        # same samples, except where a continuous length sits on a ceil boundary
        assert abs(a.T - b.T) <= 1e-9 * a.T or abs(a.T - b.T) <= Ts * (1 + 1e-9)


@settings(max_examples=30, deadline=None)
@given(st.floats(-2, 2), st.floats(0.02, 0.45), st.floats(0.5, 1.5), st.booleans(),
       st.sampled_from(["polynomial", "trigonometric", "damped"]))
def test_mode_tuned_stage_keeps_its_zero_and_the_bounds(lh, zeta, period_ratio, odd, profile):
    """A last stage tuned to a mode keeps its exact length (zero on the mode) and the design
    bounds the jerk with its largest sampled tap: both hold."""
    h, L = 10.0 ** lh, [1.0, 10.0, 200.0]
    zeta = zeta if profile == "damped" else 0.0
    cont = design.kinematic(h=h, vmax=1, amax=10, jmax=200)
    wn = 2 * math.pi / (cont[-1].T * period_ratio)
    Ts = cont[-1].T / (7.3 if odd else 23.7)
    try:
        grid = design.kinematic(h=h, vmax=1, amax=10, jmax=200, profile=profile, wn=wn,
                                zeta=zeta, Ts=Ts)
    except ParameterError as exc:     # mode above Nyquist for this grid
        assert exc.parameter == "wn"
        return
    wd = wn * math.sqrt(1 - zeta ** 2)
    Tm = (3 if profile == "trigonometric" else 2) * math.pi / wd
    assert grid[-1].T == pytest.approx(grid[-1].k * Tm, rel=1e-12)
    assert max(sampled_ratios(grid, Ts, h, L)) <= 1 + 1e-9


def _tuned_price(h, limits, profile, wn, zeta, Ts):
    """(grid chain, price in samples): the grid chain's stages with the tuned one counted by
    its taps, against the continuous optimum with the same mode."""
    kw = dict(vmax=limits[0], amax=limits[1] if len(limits) > 1 else None,
              jmax=limits[2] if len(limits) > 2 else None, higher=tuple(limits[3:]),
              profile=profile, wn=wn, zeta=zeta)
    cont = design.kinematic(h=h, **kw)
    grid = design.kinematic(h=h, Ts=Ts, **kw)
    taps = Chain(grid[-1], Ts=Ts).length
    price = (sum(g.T for g in grid[:-1]) + taps * Ts - design.duration(cont)) / Ts
    return grid, price


@settings(max_examples=60, deadline=None)
@given(st.floats(-2, 2), st.integers(1, 4), st.floats(0.3, 3.0), st.floats(0.5, 2.5),
       st.sampled_from(["polynomial", "damped"]), st.floats(0.0, 0.3))
def test_mode_tuned_bound_stage_price(lh, n, period_ratio, lsamples, profile, zeta):
    """A rectangular or exponential stage that is both a bound and tuned to a mode: bounded
    taps (no tap above the continuous peak density), so the design's density holds on the
    grid and the price is the rounding, not a longer chain: under 2 samples for the stage's
    own taps (floor(nu) + 2 for a length of nu samples, the floor) plus under a sample per
    box before it (the overlap search with the tuned stage's exact top difference): n + 1
    in all. Every bound holds at every sample, and the reference agrees."""
    if profile == "damped" and n < 2:
        n = 2
    h, limits = 10.0 ** lh, [1.0, 10.0, 200.0, 1e4][:n]
    base = design.kinematic(h=h, vmax=1, amax=10 if n > 1 else None,
                            jmax=200 if n > 2 else None, higher=(1e4,) if n > 3 else ())
    wn = 2 * math.pi / (base[-1].T * period_ratio)
    Ts = design.duration(base) / 10.0 ** lsamples
    zeta = zeta if profile == "damped" else 0.0
    try:
        grid, price = _tuned_price(h, limits, profile, wn, zeta, Ts)
    except ParameterError as exc:     # mode above Nyquist for this grid
        assert exc.parameter == "wn"
        return
    assert grid[-1].timing == "bounded" or grid[-1].T / Ts == pytest.approx(
        round(grid[-1].T / Ts), rel=1e-9)
    assert max(sampled_ratios(grid, Ts, h, limits)) <= 1 + 1e-9
    assert price < n + 1 + 1e-9, price
    kw = dict(vmax=limits[0], amax=limits[1] if n > 1 else None,
              jmax=limits[2] if n > 2 else None, higher=tuple(limits[3:]))
    ref = design.kinematic_reference(h=h, Ts=Ts, profile=profile, wn=wn, zeta=zeta, **kw)
    for a, b in zip(grid, ref):
        assert (a.kind, a.k, a.timing) == (b.kind, b.k, b.timing)
        assert abs(a.T - b.T) <= 1e-9 * a.T or abs(a.T - b.T) <= Ts * (1 + 1e-9)


def test_mode_tuned_bound_stage_reported_case():
    """The case that cost 38 % with exact timing (its largest tap 6.2/nu at a mode near
    Nyquist): 951.9/945.7 samples continuous became 1313/1305; with bounded taps the lengths
    stay within a sample or two."""
    kw = dict(h=7.024, vmax=7693, amax=611.1, jmax=9.139e5, wn=2.681e4, zeta=0.05)
    Ts = 1.13e-4
    grid, price = _tuned_price(kw["h"], [7693, 611.1, 9.139e5], "polynomial", kw["wn"],
                               kw["zeta"], Ts)
    cont = design.kinematic(**kw)
    assert [round(g.T / Ts, 1) for g in cont[:2]] == [951.9, 945.7]
    assert price < 4      # n + 1 for three bounds
    assert max(sampled_ratios(grid, Ts, kw["h"], [7693, 611.1, 9.139e5])) <= 1 + 1e-9


@pytest.mark.parametrize("samples", [23.7, 100.3])
def test_one_bound_tuned_half_sine_takes_the_next_multiple(samples):
    """Alone, a tuned half sine is the velocity stage: where its sampled peak (exact timing)
    exceeds vmax, the design takes the next odd multiple instead of refusing (it named Ts and
    2^52 samples before), in C and in the reference."""
    T1 = design.kinematic(h=1.0, vmax=1.0, profile="trigonometric")[0].T
    kw = dict(h=1.0, vmax=1.0, profile="trigonometric", wn=3 * math.pi / T1, Ts=T1 / samples)
    grid = design.kinematic(**kw)
    assert grid[0].k == 3
    assert max(sampled_ratios(grid, kw["Ts"], 1.0, [1.0])) <= 1 + 1e-9
    assert design.kinematic_reference(**kw) == grid


@pytest.mark.parametrize("nu", [2.08, 2.5, 3.3, 5.5, 10.5, 20.2, 50.5])
def test_bounded_taps_need_their_extra_sample(nu):
    """Why the tuned stage costs one sample more than exact timing: no FIR of floor(nu) + 1
    non-negative taps summing to 1 with the zero on the mode keeps every tap <= 1/nu (the
    linear program's least largest tap is above 1/nu), while floor(nu) + 2 taps do."""
    from scipy.optimize import linprog
    phi = 2 * math.pi / nu

    def least_peak(M):
        i = np.arange(M)
        a_eq = np.array([np.r_[np.ones(M), 0], np.r_[np.cos(phi * i), 0],
                         np.r_[np.sin(phi * i), 0]])
        res = linprog(np.r_[np.zeros(M), 1], A_ub=np.hstack([np.eye(M), -np.ones((M, 1))]),
                      b_ub=np.zeros(M), A_eq=a_eq, b_eq=[1, 0, 0], bounds=(0, None),
                      method="highs")
        assert res.status == 0
        return res.x[-1] * nu

    assert least_peak(int(nu) + 1) > 1 + 1e-6
    assert least_peak(int(nu) + 2) <= 1
    taps = Chain(Stage("rectangular", T=nu * 1e-3, timing="bounded"), Ts=1e-3).taps()
    assert taps.size == int(nu) + 2 and taps.max() * nu <= 1 + 1e-12


@pytest.mark.parametrize("kwargs, parameter, words", [
    (dict(h=1e308, vmax=1e-10), "vmax", ["h/vmax = 1e+318 s", "1e+308", "1e-10"]),
    (dict(h=1e-300, vmax=1e100), "vmax", ["h/vmax = 1e-400 s", "shorter"]),
    (dict(h=1e60, vmax=1e70, amax=1e-5), "amax", ["vmax/amax", "1e+70"]),
    (dict(h=1, vmax=1, amax=1, jmax=1e300), "jmax", ["amax/jmax", "shorter"]),
    (dict(h=40, vmax=250, amax=5000, jmax=2e5, Ts=1e-300), "Ts", ["2^52", "vmax=250"]),
    (dict(h=40, vmax=250, amax=5000, jmax=2e5, wn=5000.0, Ts=1e-3), "wn", ["Nyquist"]),
])
def test_extreme_inputs_name_the_cause(kwargs, parameter, words):
    with pytest.raises(ParameterError) as exc:
        design.kinematic(**kwargs)
    assert exc.value.parameter == parameter
    for w in words:
        assert w in str(exc.value)
    if "wn" not in kwargs:   # a design without a mode never blames a mode multiple
        assert "multiple" not in str(exc.value)


def test_extreme_bounds_answer_at_once():
    """Six, seven and eight bounds spanning 1e-300 .. 1e300: a refusal, not a long search;
    feasible extreme chains (ratios 1e7 per order) are designed, all lengths finite."""
    for n in (6, 7, 8):
        with pytest.raises(ParameterError):
            design.kinematic(h=1, vmax=1e300, amax=1e-300, jmax=1e300,
                             higher=[1e-300 if i % 2 else 1e300 for i in range(n - 3)])
        stages = design.kinematic(h=1e-20, vmax=1.0, amax=1e7, jmax=1e14,
                                  higher=[10.0 ** (7 * i) for i in range(3, n)])
        assert all(math.isfinite(s.T) and s.T > 0 for s in stages)


def _grid_price(h, lim, Ts, profile="polynomial"):
    n = len(lim)
    kw = dict(vmax=lim[0], amax=lim[1] if n > 1 else None, jmax=lim[2] if n > 2 else None,
              higher=tuple(lim[3:]), profile=profile)
    cont = design.kinematic(h=h, **kw)
    grid = design.kinematic(h=h, Ts=Ts, **kw)
    return (design.duration(grid) - design.duration(cont)) / Ts, cont, grid


def price_bar(n, profile, shortest_stage_samples):
    """The price a grid design keeps to, in samples: one per stage; with a half-sine last
    stage (trigonometric) the floor of whole-sample half sines on top (test_half_sine_floor):
    one more sample when a continuous stage is shorter than a sample, else 3 - pi/2 - 1."""
    if profile != "trigonometric":
        return n
    return n + (1.0 if shortest_stage_samples < 1 else 2 - math.pi / 2)


@settings(max_examples=80, deadline=None)
@given(lh=st.floats(-3, 3), ls=st.lists(st.floats(-3, 3), min_size=8, max_size=8),
       n=st.integers(1, 8), lt=st.floats(0.0, 1.0),
       profile=st.sampled_from(["polynomial", "trigonometric"]))
def test_grid_price_at_most_one_sample_per_stage(lh, ls, n, lt, profile):
    """Designed on the grid, a chain of up to eight bounds costs at most one sample per stage
    over the continuous optimum, at any Ts; a trigonometric chain up to the floor of sampled
    half sines more (price_bar). Measured, not proven, from five bounds on: the search is
    bounded (docs/sampled-limits.md gives the measured prices). No lower bound: a chain
    whose copies overlap can be shorter than the continuous optimum (a negative price)."""
    h = 10.0 ** lh
    lim = [10.0 ** ls[i] * 10.0 ** i for i in range(n)]
    _, cont, _ = _grid_price(h, lim, 1.0, profile)
    Ts = design.duration(cont) / 10.0 ** (0.5 + 3 * lt)
    price, _, grid = _grid_price(h, lim, Ts, profile)
    bar = price_bar(n, profile, min(s.T for s in cont) / Ts)
    assert price <= bar + 1e-9, (price, [s.T / Ts for s in cont], [g.T / Ts for g in grid])


def test_half_sine_floor():
    """The floor of a trigonometric chain on the grid, against the count that proves it: a
    half sine of N samples has N - 1 non-zero taps (the first is sin 0), so boxes of N_k and a
    half sine of N move over N_0 + ... + N_(n-1) - n samples, each at most vmax Ts: the total
    is at least h/(vmax Ts) + n. With vmax at its bound and the other stages far shorter than
    a sample (here h/(vmax Ts) = 571.01, the half sine 4e-5 samples) that is 574 samples,
    2.99 over the continuous optimum where the bar of one sample per stage would be 2. The
    design reaches the floor, and every two-stage chain one sample shorter exceeds vmax.
    One bound, the half sine just over pi/2 samples: h/(vmax Ts) just over 1, so N >= 3
    samples, 3 - pi/2 = 1.43 over."""
    h, lim, Ts = 3.1020361616803642, [0.0026908609927207227, 53.70598447766265], 2.018881504301415
    price, cont, grid = _grid_price(h, lim, Ts, "trigonometric")
    N = [round(g.T / Ts) for g in grid]
    assert sum(N) == math.ceil(h / (lim[0] * Ts)) + 2 == 574
    assert price == pytest.approx(2.989, abs=1e-3)
    assert max(sampled_ratios(grid, Ts, h, lim)) <= 1 + 1e-9
    for n_sine in range(2, 8):
        short = [Stage("rectangular", T=(573 - n_sine) * Ts), Stage("harmonic", T=n_sine * Ts)]
        assert sampled_ratios(short, Ts, h, lim)[0] > 1 + 1e-6
    Ts = 1.0
    h, vmax = 1.0 + 1e-6, 1.0        # continuous: pi/2 h/vmax = 1.5708 samples
    grid = design.kinematic(h=h, vmax=vmax, profile="trigonometric", Ts=Ts)
    assert grid[0].T == 3.0
    assert grid[0].T - design.kinematic(h=h, vmax=vmax, profile="trigonometric")[0].T == (
        pytest.approx(3 - math.pi / 2, abs=1e-5))
    assert sampled_ratios([Stage("harmonic", T=2.0)], Ts, h, [vmax])[0] > 1 + 1e-7


def test_half_sine_peak_equals_the_samples():
    """The exact top difference of boxes followed by a half sine (design._half_sine_peak, the
    phasor sweep between the copies' ends) equals max |sum_S sign_S sin(pi (m - sigma_S)/N)|
    evaluated sample by sample."""
    rng = np.random.default_rng(11)
    for _ in range(60):
        boxes = sorted(rng.integers(1, 40, size=rng.integers(1, 6)).tolist(), reverse=True)
        N = int(rng.integers(2, 60))
        coeff = design._signed_sums(boxes)
        m = np.arange(sum(boxes) + N + 1)
        f = sum(v * np.where((m >= s) & (m <= s + N), np.sin(np.pi * (m - s) / N), 0.0)
                for s, v in coeff.items())
        assert design._half_sine_peak(boxes, N) == pytest.approx(np.abs(f).max(), abs=1e-12)


def test_trigonometric_stages_overlap_where_they_cancel():
    """Five bounds, the trigonometric profile, three tight stages above a stage at its bound
    (continuous 8.18, 4.09, 2.04, 1.02, 1.02 samples). The rule "each stage at least the
    stages after it" costs 15.6 samples (16, 8, 4, 2, 2); with the exact top difference of
    the half sine the fourth box may end inside it: 8, 4, 2, 1, 2 costs 0.65, every sampled
    difference within its bound, the reference agreeing."""
    h = 0.08036352747993378
    lim = [879.5229501069148, 4083.080640470341, 12857.538291960438, 222366.7571626746,
           38.02802175993449]
    Ts = 0.1359806188156874
    price, cont, grid = _grid_price(h, lim, Ts, "trigonometric")
    assert [round(g.T / Ts) for g in grid] == [8, 4, 2, 1, 2]
    assert price == pytest.approx(0.646, abs=1e-3)
    assert max(sampled_ratios(grid, Ts, h, lim)) <= 1 + 1e-9
    ref = design.kinematic_reference(h=h, vmax=lim[0], amax=lim[1], jmax=lim[2],
                                     higher=tuple(lim[3:]), profile="trigonometric", Ts=Ts)
    assert [round(r.T / Ts) for r in ref] == [8, 4, 2, 1, 2]


def test_sub_sample_stages_overlap_within_the_bar():
    """Four bounds where the last three stages last 1e-5 of a sample. Under the rule "each
    stage at least as long as the stages after it" every chain costs about five samples over
    the continuous optimum (exhaustive over every chain within three samples of the
    ceilings); letting copies of the stages overlap where they cancel (the exact count test of
    docs/sampled-limits.md) the design costs four, one per stage, and every sampled difference
    stays within its bound (checked through the Chain, not through the test)."""
    import itertools
    h = 100.71119125350725
    lim = [0.006020693715312491, 9.538809140168473, 50.1540522121824, 1430.6710659883863]
    Ts = 2090.7316420179104
    price, cont, grid = _grid_price(h, lim, Ts)
    assert price <= 4.0
    assert max(sampled_ratios(grid, Ts, h, lim)) <= 1 + 1e-9
    N = [round(g.T / Ts) for g in grid]
    ref = design.kinematic_reference(h=h, vmax=lim[0], amax=lim[1], jmax=lim[2],
                                     higher=(lim[3],), Ts=Ts)
    assert [round(r.T / Ts) for r in ref] == N

    def structured(M):
        below = M[-1]
        for i in range(2, -1, -1):
            if M[i] < below:
                return False
            below += M[i]
        prod = 1.0
        for i in range(3):
            prod *= M[i]
            if h / (prod * Ts ** (i + 1)) > lim[i] * (1 + 1e-12):
                return False
        return h / (prod * Ts ** 3) / M[3] / Ts <= lim[3] * (1 + 1e-12)
    base = [math.ceil(s.T / Ts) for s in cont]
    best = min(sum(M) for M in itertools.product(*(range(1, b + 4) for b in base))
               if structured(M))
    assert best - design.duration(cont) / Ts > 4.99
    assert sum(N) < best


@settings(max_examples=40, deadline=None)
@given(lh=st.floats(-3, 3), ls=st.lists(st.floats(-3, 3), min_size=8, max_size=8),
       n=st.integers(5, 8), lsamples=st.floats(0.5, 2.0),
       profile=st.sampled_from(["polynomial", "trigonometric"]))
def test_five_to_eight_bounds_every_sample_within_bounds(lh, ls, n, lsamples, profile):
    """Five to eight bounds, both profiles: every sampled difference within its bound (the
    chains of the overlap search included); the reference's placement on the grid
    (design._on_grid, from the C core's continuous lengths: the reference's nested bisection
    is too slow for many tight stages) gives the same samples."""
    h = 10.0 ** lh
    lim = [10.0 ** ls[i] * 10.0 ** i for i in range(n)]
    _, cont, _ = _grid_price(h, lim, 1.0, profile)
    Ts = design.duration(cont) / 10.0 ** lsamples
    price, cont, grid = _grid_price(h, lim, Ts, profile)
    assert max(sampled_ratios(grid, Ts, h, lim)) <= 1 + 1e-9
    ref = design._on_grid([s.T for s in cont], Ts, h, lim,
                          harmonic_last=profile == "trigonometric")
    assert [round(g.T / Ts) for g in grid] == [round(t / Ts) for t in ref]


def test_five_bounds_tight_stages_round_together():
    """Five bounds, three tight stages above a stage at its bound: rounding each stage on its
    own (ceilings lifted by the structure) cost 13.7 samples; the search that lets copies
    overlap where they cancel takes a sample from the second stage and gives it to the fourth
    (1398, 698, 350, 344, 6: the second is shorter than the stages after it, 698 < 700) and
    keeps 1.7 samples, every sampled difference within its bound, the NumPy reference
    agreeing sample for sample."""
    h = 0.8359411203020277
    lim = [1.3938247390973661, 297.17187056386626, 42.27817492302489, 7.027818042549363,
           1323.3393628839408]
    Ts = 0.0010035394681245516
    price, cont, grid = _grid_price(h, lim, Ts)
    assert [round(g.T / Ts) for g in grid] == [1398, 698, 350, 344, 6]
    assert price == pytest.approx(1.66, abs=0.01)
    assert max(sampled_ratios(grid, Ts, h, lim)) <= 1 + 1e-9
    ref = design.kinematic_reference(h=h, vmax=lim[0], amax=lim[1], jmax=lim[2],
                                     higher=tuple(lim[3:]), Ts=Ts)
    assert [round(r.T / Ts) for r in ref] == [1398, 698, 350, 344, 6]


@pytest.mark.parametrize("profile, h, lim, Ts, N, price", [
    ("polynomial", 0.051266164244901845,
     [0.022735659897553082, 0.08488369518529298, 31730.21889887176, 2752.7354035772173,
      23.009295194656396, 80743151.27571084, 4997.3472255695115, 280481.3685582115],
     0.002296086096794187, [983, 309, 153, 78, 38, 21, 11, 8], 3.105),
    ("trigonometric", 0.007317046314114021,
     [0.0038359527609021183, 705.6354308976337, 65776.35312034035, 156350.93389273074,
      134414.15849044826, 4836.294157042807, 44558973.113622],
     0.0007434929427981372, [2566, 283, 142, 71, 36, 34, 2], 3.423)])
def test_a_search_budget_per_pair_of_first_two_lengths(profile, h, lim, Ts, N, price):
    """Tight stages below the first (eight polynomial bounds: 982, 308, 154, 77, 38, 19, 11.5,
    7.8 samples; seven trigonometric ones) where a second length one sample short of its
    ceiling cannot work: with one budget per first length the search spent it all below that
    choice and the design cost 9.1 samples (the polynomial one) and 11.4 (the trigonometric
    one, the half sine's overlap test without that budget); with one per pair of first two
    lengths 3.1 and 3.4, every sampled difference within its bound, the reference agreeing."""
    got, cont, grid = _grid_price(h, lim, Ts, profile)
    assert [round(g.T / Ts) for g in grid] == N
    assert got == pytest.approx(price, abs=1e-3)
    assert max(sampled_ratios(grid, Ts, h, lim)) <= 1 + 1e-9
    ref = design._on_grid([s.T for s in cont], Ts, h, lim,
                          harmonic_last=profile == "trigonometric")
    assert [round(t / Ts) for t in ref] == N
