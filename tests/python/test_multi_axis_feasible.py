# SPDX-License-Identifier: Apache-2.0
"""The multi-axis generator's feasible limits and its drop rule. Limits: the C core (sms_multi_generator_reach) and the
independent NumPy reference (smoothshaper.reference.multi_axis.reach, derived from the
planner's arithmetic) accept the same limit sets and name the same axis and quantity when
they refuse, over the whole range of the type, in double and float, and at the bounds to
the neighbouring double; MultiAxisGenerator and multi_axis_reference then name the same
argument. Dropped targets: exactly the moves that cannot be represented (more than 2^52
samples, or a duration that overflows the precision), however far beyond the distance to
reach vmax they go."""
import math
import warnings
from collections import Counter

import numpy as np
import pytest

from smoothshaper.errors import DroppedTargetWarning, ParameterError
from smoothshaper.filters import _backend
from smoothshaper.multi_axis import MultiAxisGenerator
from smoothshaper.reference.multi_axis import multi_axis_reference, reach
from smoothshaper.time_optimal import reach as single_reach
from test_api import raises as _named  # noqa: E402

#: Every quantity the region can name (the single-axis region's, then the planner's own);
#: "the duration to reach vmax" (T >= MIN) needs limits that the others refuse first.
QUANTITIES = {"vmax", "amax", "jmax", "vmax*jmax", "vmax/amax", "sqrt(vmax/jmax)", "amax^2",
              "the distance to reach vmax", "amax/vmax", "jmax/vmax", "amax/h", "jmax/h",
              "the duration to reach vmax, squared", "(amax/h)^2"}


def c_reach(lim, Ts, precision):
    """(quantity or None, axis) from sms_multi_generator_reach."""
    ffi, lib = _backend(precision)
    cfg = ffi.new("sms_multi_generator_config *")
    cfg.n_axes = lim.shape[1]
    for i in range(lim.shape[1]):
        cfg.vmax[i], cfg.amax[i], cfg.jmax[i] = lim[:, i]
    info, axis = ffi.new("sms_generator_reach_info *"), ffi.new("size_t *")
    if lib.sms_multi_generator_reach(cfg, Ts, info, axis) == 0:
        return None, None
    quantity = ffi.string(info.quantity).decode()
    return quantity, None if quantity == "Ts" else int(axis[0])


def ref_reach(lim, Ts, precision):
    r = reach(lim[0], lim[1], lim[2], Ts, precision)
    return r["quantity"], r["axis"]


def draw(rng):
    """Limits (3, axes) and Ts: over the whole double range, over the float range, a
    plausible vmax with amax/vmax and jmax/vmax over many decades, or a plausible machine."""
    n = int(rng.integers(1, 5))
    mode = int(rng.integers(0, 4))
    if mode == 0:
        return 10.0 ** rng.uniform(-320, 308, size=(3, n)), 10.0 ** rng.uniform(-300, 300)
    if mode == 1:
        return 10.0 ** rng.uniform(-45, 40, size=(3, n)), 10.0 ** rng.uniform(-45, 40)
    v = 10.0 ** rng.uniform(-3, 3, n)
    if mode == 2:
        return (np.array([v, v * 10.0 ** rng.uniform(-20, 25, n),
                          v * 10.0 ** rng.uniform(-40, 45, n)]), 10.0 ** rng.uniform(-12, 1))
    a = v * 10.0 ** rng.uniform(-2, 4, n)
    return np.array([v, a, a * 10.0 ** rng.uniform(-2, 4, n)]), 10.0 ** rng.uniform(-6, -2)


def feasible(rng, axes, precision):
    """A random feasible set of ``axes`` axes (a plausible machine)."""
    while True:
        v = 10.0 ** rng.uniform(-3, 3, axes)
        a = v * 10.0 ** rng.uniform(-2, 4, axes)
        lim, Ts = np.array([v, a, a * 10.0 ** rng.uniform(-2, 4, axes)]), 10.0 ** rng.uniform(-6, -2)
        if c_reach(lim, Ts, precision)[0] is None:
            return lim, Ts


def usable(lim, Ts):
    return bool(np.all(np.isfinite(lim)) and np.all(lim > 0) and 0 < Ts < math.inf)


@pytest.mark.parametrize("precision", ["double", "float"])
def test_c_and_the_reference_refuse_the_same_limit_sets(precision):
    """4000 random limit sets of 1 to 4 axes: the same verdict, axis and quantity; every
    quantity of the region occurs (a sample that missed one would not test it)."""
    rng = np.random.default_rng(20261201 + (precision == "float"))
    seen, disagree = Counter(), []
    while sum(seen.values()) < 4000:
        lim, Ts = draw(rng)
        if not usable(lim, Ts):
            continue
        got, want = c_reach(lim, Ts, precision), ref_reach(lim, Ts, precision)
        seen[got[0]] += 1
        if got != want:
            disagree.append((lim.tolist(), Ts, got, want))
    assert not disagree, disagree[:5]
    assert seen[None] >= 100        # accepted sets too
    missing = QUANTITIES - set(seen)
    assert not missing, missing


@pytest.mark.parametrize("precision", ["double", "float"])
def test_the_verdicts_agree_at_the_bounds(precision):
    """A limit (or Ts) moved by bisection in log space from a refused to an accepted value
    until the two are neighbouring doubles: C and the reference agree on both, so each bound
    is the same to the last bit, whichever quantity it is."""
    rng = np.random.default_rng(7 + (precision == "float"))
    found = Counter()
    for _ in range(400):
        lim, Ts = draw(rng)
        if not usable(lim, Ts):
            continue
        ok_lim, ok_Ts = feasible(rng, lim.shape[1], precision)   # to move towards
        which = int(rng.integers(0, lim.size + 1))
        if c_reach(lim, Ts, precision)[0] is None:
            continue

        def at(x):
            if which == lim.size:
                return ok_lim, x
            m = ok_lim.copy()
            m.flat[which] = x
            return m, ok_Ts
        bad = Ts if which == lim.size else float(lim.flat[which])
        good = ok_Ts if which == lim.size else float(ok_lim.flat[which])
        if c_reach(*at(bad), precision)[0] is None:
            continue
        lo, hi = math.log(bad), math.log(good)
        for _ in range(200):
            mid = math.exp(0.5 * (lo + hi))
            x_lo, x_hi = math.exp(lo), math.exp(hi)
            if not min(x_lo, x_hi) < mid < max(x_lo, x_hi):
                break
            if c_reach(*at(mid), precision)[0] is None:
                hi = math.log(mid)
            else:
                lo = math.log(mid)
        x_bad, x_good = math.exp(lo), math.exp(hi)
        # walk to the neighbouring doubles of the switch
        step = math.inf if x_good > x_bad else -math.inf
        while math.nextafter(x_bad, step) != x_good and c_reach(*at(math.nextafter(
                x_bad, step)), precision)[0] is not None:
            x_bad = math.nextafter(x_bad, step)
        x_good = math.nextafter(x_bad, step)
        for x in (x_bad, x_good):
            assert c_reach(*at(x), precision) == ref_reach(*at(x), precision), (which, x)
        found[c_reach(*at(x_bad), precision)[0]] += 1
    assert len(found) >= 5, found     # bounds of at least five different quantities


@pytest.mark.parametrize("precision", ["double", "float"])
def test_the_generator_and_the_reference_name_the_same_argument(precision):
    """Refused random sets: MultiAxisGenerator and multi_axis_reference (double) raise
    ParameterError naming the same argument (``jmax[1]``, ``Ts``, ...)."""
    rng = np.random.default_rng(99)
    tried = 0
    while tried < 300:
        lim, Ts = draw(rng)
        if not usable(lim, Ts) or c_reach(lim, Ts, precision)[0] is None:
            continue
        tried += 1
        kw = dict(vmax=lim[0], amax=lim[1], jmax=lim[2], Ts=Ts)
        with pytest.raises(ParameterError) as c_error:
            MultiAxisGenerator(precision=precision, **kw)
        assert c_error.value.parameter == reach(**kw, precision=precision)["parameter"]
        if precision == "double":
            with pytest.raises(ParameterError) as ref_error:
                multi_axis_reference(np.zeros((2, lim.shape[1])), **kw)
            assert ref_error.value.parameter == c_error.value.parameter


def test_the_documented_example():
    """Reaching vmax on axis 1 takes 4 sqrt(vmax/jmax) = 4e150 s: both refuse, naming
    jmax[1] and the quantity."""
    kw = dict(vmax=[1.0, 1.0], amax=[1.0, 1e-30], jmax=[1.0, 1e-300], Ts=1e-3)
    r = reach(**kw)
    assert (r["axis"], r["quantity"], r["parameter"]) == (1, "sqrt(vmax/jmax)", "jmax[1]")
    assert r["duration"] == pytest.approx(4e150, rel=1e-12)
    with pytest.raises(ParameterError, match=r"axis 1: .*sqrt\(vmax/jmax\)") as e:
        multi_axis_reference(np.zeros((3, 2)), **kw)
    assert e.value.parameter == "jmax[1]"
    assert reach(vmax=[1.0, 2.0], amax=10.0, jmax=100.0, Ts=1e-3)["quantity"] is None


# ---------------------------------------------------------------- the drop rule

def run(x, precision="double", **kw):
    g = MultiAxisGenerator(precision=precision, **kw)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DroppedTargetWarning)
        return g.process(x), g


@pytest.mark.parametrize("sync", ["phase", "independent"])
def test_a_long_move_whose_unit_limits_underflow_is_planned(sync):
    """jmax/|d| = 1e-330 underflows to 0, but the move lasts 1e10 samples of Ts: planned (it
    was dropped while the landing formed the unit limits before deciding that the cruise
    reaches vmax), in C and in the reference alike."""
    kw = dict(vmax=[1.0, 2.0], amax=[1.0, 1.0], jmax=[1e-190, 1e-190], Ts=1e130, sync=sync)
    x = np.tile([1e140, -1e140], (3, 1))
    y, g = run(x, **kw)
    assert g.dropped == 0 and g.busy
    assert y[1, 0, 1] == 1.0 and y[1, 1, 1] == (-1.0 if sync == "phase" else -2.0)
    np.testing.assert_array_equal(y, multi_axis_reference(x, **kw))


@pytest.mark.parametrize("precision", ["double", "float"])
@pytest.mark.parametrize("factor, dropped", [(0.99, False), (1.01, True)])
def test_the_2_52_sample_boundary(precision, factor, dropped):
    """A move whose cruise alone lasts 0.99 or 1.01 times 2^52 samples: planned below,
    dropped above; the reference (double) alike."""
    kw = dict(vmax=[1.0, 2.0], amax=[10.0, 10.0], jmax=[100.0, 100.0], Ts=1e-3)
    x = np.tile([factor * 2.0 ** 52 * 1e-3, 0.0], (4, 1))
    y, g = run(x, precision, **kw)
    assert g.dropped == int(dropped) and (y[-1, 0, 1] > 0) != dropped
    if precision == "double":
        np.testing.assert_array_equal(y, multi_axis_reference(x, **kw))


@pytest.mark.parametrize("precision", ["double", "float"])
def test_only_unrepresentable_moves_are_dropped(precision):
    """Random feasible limit sets (over the whole range of the type) and rest-to-rest moves
    of h 2^k on every axis (h the axis's distance to reach vmax), k = 0 to as far as the
    displacement stays finite: a move is dropped exactly when it cannot be represented, i.e.
    when its cruise alone lasts more than 2^52 samples or its duration in seconds overflows
    the precision; every shorter move is planned, however far beyond h it goes."""
    rng = np.random.default_rng(5 + (precision == "float"))
    big = float(np.finfo(np.float32 if precision == "float" else np.float64).max)
    sets = planned = refused = 0
    while sets < 60:
        n = int(rng.integers(1, 4))
        span = 300 if precision == "double" else 36
        lim, Ts = 10.0 ** rng.uniform(-span, span, (3, n)), 10.0 ** rng.uniform(-span, span)
        if reach(lim[0], lim[1], lim[2], Ts, precision)["quantity"] is not None:
            continue
        sets += 1
        kw = dict(vmax=lim[0], amax=lim[1], jmax=lim[2], Ts=Ts,
                  sync=["phase", "independent"][sets % 2])
        one = [single_reach(*lim[:, i], Ts, "ramp", precision) for i in range(n)]
        h = np.array([r["distance"] for r in one])
        reach_time = max(r["duration"] for r in one)
        sign = rng.choice([-1.0, 1.0], n)
        for k in range(0, 1024, 3):
            with np.errstate(over="ignore"):
                d = h * math.ldexp(1.0, k) * sign
            if not np.all(np.abs(d) <= big):
                break
            cruise = float(np.max(np.abs(d) / lim[0]))      # seconds: a lower bound
            if cruise / Ts > 2.0 ** 55:   # the last step lands in (2^52, 2^55]
                break
            _, g = run(np.tile(d, (2, 1)), precision, **kw)
            if g.dropped:
                refused += 1
                assert cruise / Ts > 2.0 ** 52 or cruise > big, (kw, k)
            else:
                planned += 1
                assert (cruise + 2 * reach_time) / Ts <= 2.0 ** 52 * (1 + 1e-6), (kw, k)
    assert planned > 1000 and refused >= 30


# ---------------------------------------------------------------- durations at the extremes

@pytest.mark.parametrize("delta, v, a, j, T", [
    ([1e300], 1.0, 1e-300, 1e-300, 2e300),       # A = 1e-600 underflows: V reached at 1e300 s
    ([1e-300], 1.0, 1.0, 1.0, 4 * 0.5 ** (1 / 3) * 1e-100),   # jerk-limited: 4 cbrt(d/(2 j))
    ([1.0], 1e300, 1e300, 1e-300, 4 * 0.5 ** (1 / 3) * 1e100),
    ([1.0, 0.0], 1.0, 1.0, 1.0, 4 * 0.5 ** (1 / 3)),
])
def test_phase_duration_over_the_whole_range(delta, v, a, j, T):
    """The closed form in the path's time scales: finite whenever the duration is (it raised
    ZeroDivisionError or OverflowError when A^4/J^2 left the range of a double)."""
    from smoothshaper.reference.multi_axis import phase_duration
    assert phase_duration(delta, vmax=v, amax=a, jmax=j) == pytest.approx(T, rel=1e-14)
    assert phase_duration([1e300], vmax=1e-300, amax=1.0, jmax=1.0) == math.inf


def test_phase_duration_beyond_a_double_is_refused():
    """The public function names delta instead of returning inf (as the C library refuses
    with SMS_ERR_TOO_LONG); the NumPy reference keeps inf."""
    from smoothshaper.multi_axis import phase_duration
    for delta, v in (([1e300], 1e-300), ([1e-6, -0.5e-6], 4.9e-324)):
        with pytest.raises(ParameterError) as e:
            phase_duration(delta, vmax=v, amax=1.0, jmax=1.0)
        assert e.value.parameter == "delta" and "largest double" in str(e.value)


def test_multi_axis_move_broadcasts_limits_and_refuses_huge_moves_at_once():
    from smoothshaper.multi_axis import multi_axis_move
    m = multi_axis_move([0.0, 0.0], [1.0, 1.0], vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-3)
    assert m.profile.shape == (m.N + 1, 2, 4) and np.all(m.profile[-1, :, 0] == 1.0)
    with pytest.raises(ParameterError, match=r"1e\+303 samples") as e:
        multi_axis_move([0.0, 0.0], [1e300, 1.0], vmax=1.0, amax=10.0, jmax=100.0, Ts=1e-3)
    assert e.value.parameter == "target"


# -- malformed arguments: the shared checks, named, nothing changed ---------------------------

_LIMITS = dict(vmax=[1.0, 2.0], amax=[10.0, 10.0], jmax=[100.0, 100.0])




@pytest.mark.parametrize("bad", ["a", [1 + 1j, 2.0], [[1.0], [1.0, 2.0]], {"a": 1},
                                 [1, 10 ** 400], np.ones(2, dtype=bool)])
def test_multi_axis_arrays_go_through_the_shared_check(bad):
    """Text, complex, ragged, dict and 10**400 raised ValueError, TypeError or OverflowError
    from np.asarray(..., float64), or were cast (booleans as 0/1)."""
    from smoothshaper import multi_axis as ma
    g = MultiAxisGenerator(**_LIMITS, Ts=1e-3)
    g.process(np.ones((20, 2)))
    before = g.get_state()
    _named("targets", g.process, bad)
    assert np.array_equal(g.get_state(), before)
    _named("delta", ma.phase_duration, bad, **_LIMITS)
    _named("start", ma.multi_axis_move, bad, [1.0, 2.0], **_LIMITS, Ts=1e-3)
    _named("target", ma.multi_axis_move, [0.0, 0.0], bad, **_LIMITS, Ts=1e-3)
    _named("vmax", MultiAxisGenerator, vmax=bad, amax=1.0, jmax=1.0, Ts=1e-3)
    _named("targets", multi_axis_reference, bad, **_LIMITS, Ts=1e-3)
    _named("q0", multi_axis_reference, np.ones((5, 2)), **_LIMITS, Ts=1e-3, q0=bad)


def test_multi_axis_scalars_and_stages_are_named():
    from smoothshaper import multi_axis as ma
    for Ts in (10 ** 400, True, np.float32("nan"), "1e-3"):
        _named("Ts", MultiAxisGenerator, **_LIMITS, Ts=Ts)            # OverflowError; True was 1 s
    _named("amax", MultiAxisGenerator, vmax=[1.0, 2.0], amax=np.ones((3, 3)), jmax=1.0,
           Ts=1e-3)                                                  # named vmax ("9 axes")
    _named("stages", MultiAxisGenerator, **_LIMITS, Ts=1e-3, stages=0.5)   # TypeError
    _named("start", ma.multi_axis_move, [0.0, np.inf], [1.0, 2.0], **_LIMITS, Ts=1e-3)  # was q0
    _named("target", ma.multi_axis_move, [0.0, 0.0], [1.0, np.nan], **_LIMITS, Ts=1e-3)  # delta
    assert MultiAxisGenerator(**_LIMITS, Ts=np.float32(1e-3)).Ts == float(np.float32(1e-3))
    from smoothshaper import harmonic
    one = MultiAxisGenerator(**_LIMITS, Ts=1e-3, stages=harmonic(T=0.01))
    assert one.stages == [[harmonic(T=0.01)]] * 2
