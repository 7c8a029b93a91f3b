# SPDX-License-Identifier: Apache-2.0
"""Zero lag and aligned axes (smoothshaper.align, MultiAxisGenerator(align=True)) against the
NumPy definitions (reference.lag, reference.delay): lags of every family, a constant-speed
segment through a centred chain equal to the unshaped one to rounding, aligned straight moves
on the line at constant speed to rounding (and before: millimetres off), the B-spline's
via-points at their own instants once advanced, refusals.

Tolerances: positions are compared to 16 u of their magnitude (u the unit roundoff: the
chain's own sums, the fractional delay's interpolation, the lag's rounding times the speed).
"""
import warnings

import numpy as np
import pytest

import smoothshaper as sms
from smoothshaper import align, reference as ref
from smoothshaper.trajectory import BSpline, MultiAxisGenerator

Ts = 1e-3
U = {"double": 2.0 ** -53, "float": 2.0 ** -24}
FAMILIES = [
    sms.rectangular(T=0.0403), sms.harmonic(T=0.031), sms.for_mode("damped_harmonic", wn=123.7,
                                                                   zeta=0.1),
    sms.for_mode("exponential", wn=300.0, zeta=0.1), sms.rectangular(T=0.02545, timing="bounded"),
    sms.shaper("zvd", wn=250.0, zeta=0.05), sms.shaper("ei", wn=400.0, zeta=0.02),
    sms.shaper("mzv", wn=300.0, zeta=0.1), sms.notch(wn=500.0, zeta=0.02, notch_pole_zeta=0.5),
    sms.notch(wn=800.0, discretization="tustin"),
]


@pytest.mark.parametrize("stage", FAMILIES, ids=lambda s: s.kind)
def test_lag_matches_the_definition(stage):
    D = ref.lag(stage, Ts=Ts)
    assert align.lag(stage, Ts=Ts) == pytest.approx(D * Ts, rel=1e-13)
    assert sms.Chain([stage], Ts=Ts).lag == pytest.approx(D * Ts, rel=1e-13)
    # what a ramp comes out with, after the transient
    x = 0.01 * np.arange(4000)
    y = sms.Chain([stage], Ts=Ts).process(x)
    assert np.max(np.abs(y[-500:] - 0.01 * (np.arange(3500, 4000) - D))) <= 16 * U["double"] * 40


@pytest.mark.parametrize("precision", ["double", "float"])
@pytest.mark.parametrize("stages", [FAMILIES[:1], FAMILIES[5:7], [FAMILIES[2], FAMILIES[8]],
                                    [FAMILIES[1], FAMILIES[4], FAMILIES[7]]],
                         ids=["rectangular", "zvd+ei", "damped+notch", "three"])
def test_centred_constant_speed_equals_the_input(stages, precision):
    """The acceptance: a constant-speed segment through a centred chain equals the unshaped
    segment to rounding; the same as the definition (reference chain, then the reference
    delay, shifted by the look-ahead)."""
    x = np.concatenate([np.full(300, 2.0), 2.0 + 0.013 * np.arange(1800),
                        np.full(600, 2.0 + 0.013 * 1799)])
    yc = align.centred(stages, x, Ts=Ts, precision=precision)
    L = sms.Chain(stages, Ts=Ts).length
    inside = slice(300 + L + 5, 2100 - L - 5)      # the chain's whole window on the segment
    scale = np.max(np.abs(x))
    if all(s.kind not in sms.stages.NOTCHES for s in stages):
        assert np.max(np.abs(yc[inside] - x[inside])) <= 16 * U[precision] * scale
    else:   # the notch's transient decays geometrically: far into the segment
        assert np.max(np.abs(yc[1500:2000] - x[1500:2000])) <= 16 * U[precision] * scale
    D = ref.lag(stages, Ts=Ts)
    A = align.lookahead(D * Ts, Ts=Ts)
    y = ref.filter(stages, np.concatenate([x, np.full(A, x[-1])]) - x[0], Ts=Ts) + x[0]
    want = ref.delay(y, samples=A - D)[A:]
    assert np.max(np.abs(yc - want)) <= 1e-12 * scale if precision == "double" else True
    assert yc[-1] == pytest.approx(x[-1], abs=16 * U[precision] * scale)


def straight(n: int, d, speed: float) -> np.ndarray:
    """A straight move p(t) = s(t) d from rest at the origin: constant speed, then rest."""
    s = np.minimum(np.arange(n) * speed, 1.0)
    return np.outer(s, d)


def off_line(q: np.ndarray, d) -> np.ndarray:
    u = np.asarray(d, dtype=float) / np.linalg.norm(d)
    return np.linalg.norm(q - np.outer(q @ u, u), axis=1)


def test_aligned_axes_stay_on_the_line():
    """Different chains per axis: before, the path leaves the line at constant speed by
    v |D_i - D_j|; aligned, by rounding; the same as the definition per axis."""
    lists = [[FAMILIES[5], FAMILIES[0]], [FAMILIES[6]], None]
    d = [1.2, -0.8, 0.5]
    x = straight(3000, d, 1 / 2000)
    before = np.column_stack([sms.Chain(s, Ts=Ts).process(x[:, i]) if s else x[:, i]
                              for i, s in enumerate(lists)])
    y, lag = align.aligned(lists, x, Ts=Ts)
    cruise = slice(200, 1900)
    assert np.max(off_line(before[cruise], d)) > 1e-3
    assert np.max(off_line(y[cruise], d)) <= 16 * U["double"] * 1.5
    common, pads = align.align(lists, Ts=Ts)
    assert lag == common and max(pads) == pytest.approx(common)
    for i, s in enumerate(lists):
        col = ref.filter(s, x[:, i], Ts=Ts) if s else x[:, i]
        want = ref.delay(col, samples=pads[i] / Ts)
        assert np.max(np.abs(y[:, i] - want)) <= 1e-12 * 1.5
    yc, _ = align.aligned(lists, x, Ts=Ts, centred=True)
    assert np.max(np.abs(yc[cruise] - x[cruise])) <= 16 * U["double"] * 1.5


@pytest.mark.parametrize("precision", ["double", "float"])
def test_multi_axis_generator_aligned(precision):
    """align=True: each axis equals the unaligned generator's axis delayed by its pad (the
    definition), and the constant-speed part of a straight move stays on the line."""
    sx = [sms.shaper("zvd", wn=2 * np.pi * 12, zeta=0.05), sms.rectangular(T=0.0205)]
    sy = [sms.shaper("ei", wn=2 * np.pi * 31, zeta=0.02)]
    kw = dict(vmax=[0.5] * 3, amax=[5.0] * 3, jmax=[200.0] * 3, Ts=Ts, stages=[sx, sy, []],
              precision=precision)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        plain, aligned = MultiAxisGenerator(**kw), MultiAxisGenerator(**kw, align=True)
    targets = np.tile([1.2, -0.8, 0.5], (3500, 1))
    a, p = aligned.process(targets), plain.process(targets)
    common, pads = align.align([sx, sy, []], Ts=Ts)
    assert aligned.lag == pytest.approx(common, rel=1e-13) and plain.lag == aligned.lag
    tol = 16 * U[precision] * 1.5
    for i in range(3):
        for m in range(4):
            want = ref.delay(p[:, i, m], samples=pads[i] / Ts, rest=0.0)   # reset at 0
            scale = max(1.0, np.max(np.abs(p[:, i, m])))
            assert np.max(np.abs(a[:, i, m] - want)) <= 16 * U[precision] * scale
    d = [1.2, -0.8, 0.5]
    assert np.max(off_line(p[600:2300, :, 0], d)) > 1e-2
    assert np.max(off_line(a[600:2300, :, 0], d)) <= tol
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        twin = MultiAxisGenerator(**kw, align=True)
    back = np.tile([0.1, 0.3, -0.2], (800, 1))
    aligned.process(back[:400])
    twin.set_state(aligned.get_state())
    assert np.array_equal(twin.process(back[400:]), aligned.process(back[400:]))


def test_bspline_advanced_passes_via_points_at_their_instants():
    """The B-spline's look-ahead is k0 samples: advanced by it, via-point i is passed at
    sample (i - 1) N, its own instant."""
    b = BSpline(degree=3, T=0.02, Ts=Ts)
    via = np.array([0.0, 0.5, 2.0, 1.0, 3.0, 3.0])
    y = b.interpolate(via, extra=4)[:, 0]
    centred = y[b.k0:]
    at = b.pass_samples(via.size) - b.k0
    assert np.array_equal(at, (np.arange(1, via.size - 1) - 1) * b.N)
    assert np.max(np.abs(centred[at] - via[1:-1])) <= 1e-12 * 3   # as test_bspline.py


def test_refusals():
    with pytest.raises(sms.ParameterError) as e:
        align.lookahead(-1.0, Ts=Ts)
    assert e.value.parameter == "lag_seconds"
    with pytest.raises(sms.ParameterError) as e:
        align.delay(np.ones(5), samples=-0.5)
    assert e.value.parameter == "samples"
    with pytest.raises(sms.ParameterError) as e:
        align.delay([0.0, np.inf], samples=1.5)
    assert e.value.parameter == "x"
    with pytest.raises(sms.ParameterError) as e:
        align.aligned([None], np.zeros((4, 2)), Ts=Ts)
    assert e.value.parameter == "stage_lists"
    with pytest.raises(sms.ParameterError) as e:
        MultiAxisGenerator(vmax=1.0, amax=1.0, jmax=1.0, Ts=Ts, align="yes")
    assert e.value.parameter == "align"
    assert align.lag([], Ts=Ts) == 0.0 and align.lookahead(0.003, Ts=Ts) == 3
    assert np.array_equal(align.delay(np.arange(6.0), samples=2.0), [0, 0, 0, 1, 2, 3])
