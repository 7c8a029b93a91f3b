# SPDX-License-Identifier: Apache-2.0
"""B-spline filters: exact pass-through, C == NumPy reference, spectral zeros at k 2 pi / T,
and the residual-vibration drop with the degree on the seed 003 Cartesian robot (Table I)."""
import math

import numpy as np
import pytest
from hypothesis import given, strategies as st

from smoothshaper import plants
from smoothshaper import trajectory as tr

TS = 1e-3
# seed 003 Table I: (m [kg], d [N s/m], k [N/m]) for x, y, z
ROBOT = [(2.777, 4.0, 1e4), (6.25, 4.0, 1e4), (2.777, 4.0, 1e4)]


@given(p=st.integers(1, 7), N=st.integers(1, 30), M=st.integers(2, 15), axes=st.integers(1, 3),
       seed=st.integers(0, 2 ** 32 - 1))
def test_passes_through_every_via_point(p, N, M, axes, seed):
    via = np.random.default_rng(seed).uniform(-1, 1, (M, axes))
    b = tr.BSpline(degree=p, T=N * TS, Ts=TS, axes=axes)
    out = b.interpolate(via, extra=2)
    assert np.all(np.abs(out[b.pass_samples(M)] - via[1:-1]) <= 1e-12)
    assert np.all(np.abs(out[b.end_sample(M):] - via[-1]) <= 1e-12)   # rests on the last
    ctrl, ref, passes = tr.bspline_reference(via, degree=p, T=N * TS, Ts=TS)
    assert np.array_equal(passes, b.pass_samples(M))
    assert np.all(np.abs(b.control_points(via) - ctrl) <= 1e-10 * max(1.0, np.abs(ctrl).max()))
    assert np.all(np.abs(out[:ref.shape[0]] - ref) <= 1e-12)
    # the first sample leaves the rest at Q_0 by (C_1 - Q_0) / N^p
    assert np.all(np.abs(out[0] - (via[0] + (ctrl[min(1, M - 1)] - via[0]) / N ** p)) <= 1e-12)


@pytest.mark.parametrize("p", [1, 2, 3, 4, 5])
def test_spectrum_has_zeros_at_multiples_of_2pi_over_T(p):
    N = 40
    b = tr.BSpline(degree=p, T=N * TS, Ts=TS)
    impulse = np.zeros(p * N + 5)
    impulse[0] = 1.0
    h = b.process(impulse, rest=[0.0])[:, 0]
    k = np.arange(h.size)
    for harmonic in (1, 2, 3, 7):
        w = harmonic * 2 * math.pi / (N * TS)
        assert abs(np.sum(h * np.exp(-1j * w * k * TS))) <= 1e-13
    assert np.sum(h) == pytest.approx(1.0, abs=1e-14)


def test_period_from_modes():
    wn = [math.sqrt(k / m) for m, _, k in ROBOT]
    T = tr.bspline_period(wn=wn, Ts=TS)
    assert T >= 2 * math.pi / min(wn) and T - TS < 2 * math.pi / min(wn)
    with pytest.raises(ValueError, match="^wn"):
        tr.bspline_period(wn=[40.0, -1.0], Ts=TS)


def robot_path():
    """Via-points ~0.0454 m apart (seed 003) on straight lines with bends, all three axes moving."""
    corners = np.array([[0, 0, 0], [0.4, 0, 0.05], [0.4, 0.3, 0.1], [0.8, 0.3, 0.1],
                        [0.8, 0.6, 0.15]])
    pts = [corners[0]]
    for a, b in zip(corners[:-1], corners[1:]):
        n = int(round(np.linalg.norm(b - a) / 0.0454))
        pts += [a + (b - a) * i / n for i in range(1, n + 1)]
    return np.array(pts)


def spectral_residual(u, rest, pole):
    """Residual oscillation of a mode after a settled ZOH input u is proportional to
    |sum_k (u[k] - u[k-1]) e^{-p k Ts}| (the same factor for every input)."""
    du = np.diff(np.concatenate([[rest], u]))
    return abs(np.sum(du * np.exp(-pole * np.arange(u.size) * TS)))


def test_seed_003_robot_residual_vibration_drops_with_degree():
    via = robot_path()
    modes = [(math.sqrt(k / m), d / (2 * math.sqrt(k * m))) for m, d, k in ROBOT]
    T = tr.bspline_period(wn=[w for w, _ in modes], Ts=TS)
    rv = {}
    for p in (3, 4, 5):
        b = tr.BSpline(degree=p, T=T, Ts=TS, axes=3)
        out = b.interpolate(via, extra=3000)
        end = b.end_sample(len(via))
        # unfiltered reference: the via-points themselves as a staircase with the same spacing
        raw = b.staircase(via, out.shape[0])
        for a, ((m, d, k), (wn, zeta)) in enumerate(zip(ROBOT, modes)):
            plant = plants.cartesian_axis(m=m, d=d, k=k)
            x0 = plants.rest_state(plant, via[0, a])
            t, yf = plants.simulate_zoh(plant, out[:, a], Ts=TS, x0=x0)
            _, yu = plants.simulate_zoh(plant, raw[:, a], Ts=TS, x0=x0)
            rf = plants.residual_amplitude(t, yf, wn=wn, zeta=zeta, t_start=(end + 1) * TS)
            ru = plants.residual_amplitude(t, yu, wn=wn, zeta=zeta, t_start=(end + 1) * TS)
            rv[p, a] = rf / ru
            pole = complex(-zeta * wn, wn * math.sqrt(1 - zeta ** 2))
            predicted = (spectral_residual(out[:, a], via[0, a], pole) /
                         spectral_residual(raw[:, a], via[0, a], pole))
            assert rv[p, a] == pytest.approx(predicted, rel=1e-6, abs=1e-12)
    for a in range(3):
        # each extra degree multiplies the mode's component by |M_N(e^{p Ts})| < 1
        # (0.21 at wn = 1.5 w0 for x and z, ~0.006 at wn ~ w0 for y); the control points change
        # with p too, so require a clear drop rather than the bare factor
        assert rv[3, a] > rv[4, a] > rv[5, a]
        assert rv[5, a] < 0.5 * rv[4, a] < 0.25 * rv[3, a]
        assert rv[3, a] < 0.05                  # < 5 % of the unfiltered via-point staircase
    assert max(rv[p, 1] for p in (3, 4, 5)) < 1e-5   # y: w0 = 2 pi / T sits on its mode


@pytest.mark.parametrize("kwargs, name", [
    (dict(degree=0, T=0.1, Ts=TS), "degree"),
    (dict(degree=8, T=0.1, Ts=TS), "degree"),
    (dict(degree=3, T=0.1, Ts=TS, axes=4), "axes"),
    (dict(degree=3, T=1e-4, Ts=TS), "T"),
    (dict(degree=3, T=float("nan"), Ts=TS), "T"),
    (dict(degree=3, T=0.1, Ts=-1.0), "Ts"),
])
def test_errors_name_the_parameter(kwargs, name):
    with pytest.raises(ValueError, match=rf"^{name}\b"):
        tr.BSpline(**kwargs)


def test_bad_via_points():
    b = tr.BSpline(degree=3, T=0.02, Ts=TS, axes=2)
    with pytest.raises(ValueError, match="^via"):
        b.control_points([[0.0, 1.0]])
    with pytest.raises(ValueError, match="^via"):
        b.control_points([[0.0, 1.0], [float("nan"), 2.0]])
    with pytest.raises(ValueError, match="^via"):
        b.control_points([0.0, 1.0, 2.0])


def _refused(parameter, func, *args, **kwargs):
    from smoothshaper import ParameterError
    with pytest.raises(ParameterError) as info:
        func(*args, **kwargs)
    assert info.value.parameter == parameter, (info.value.parameter, str(info.value))
    assert str(info.value).startswith(parameter)
    return info.value


def test_bad_arguments_of_the_helpers_are_named():
    """pass_samples, end_sample, staircase, process(rest=) and interpolate(extra=) took any
    value: a TypeError, an IndexError, a hang building 10**400 pass samples, or NaN/inf
    output returned as a result."""
    b = tr.BSpline(degree=3, T=0.05, Ts=TS)
    for M in (np.nan, 1.5, "3", None, 1):
        _refused("M", b.pass_samples, M)
        _refused("M", b.end_sample, M)
    _refused("M", b.pass_samples, 10 ** 400)                     # refused at once, not built
    _refused("n_samples", b.staircase, [[0.0], [1.0]], -1)
    _refused("n_samples", b.staircase, [[0.0], [1.0]], np.inf)
    _refused("n_samples", b.staircase, [[0.0], [1.0]], 10 ** 400)
    _refused("control", b.staircase, [[0.0], [np.nan]], 10)
    _refused("control", b.staircase, [], 10)
    _refused("x", b.process, [])
    _refused("rest", b.process, np.ones(5), rest=np.nan)
    _refused("rest", b.process, np.ones(5), rest=[1.0, 2.0])
    _refused("extra", b.interpolate, [0.0, 1.0], extra=np.nan)
    _refused("extra", b.interpolate, [0.0, 1.0], extra=10 ** 400)
    assert np.array_equal(b.pass_samples(4), [b.k0, b.k0 + b.N])
    assert b.end_sample(np.int64(4)) == 2 * b.N + 3 * (b.N - 1)


@pytest.mark.parametrize("precision, big", [("double", 1.7e308), ("float", 1e39)])
def test_inputs_beyond_the_bound_are_refused_not_returned_as_nan(precision, big):
    b = tr.BSpline(degree=3, T=0.05, Ts=TS, precision=precision)
    exc = _refused("x", b.process, np.r_[np.full(100, -big), np.full(100, big)])
    assert "x[0]" in str(exc)
    _refused("via", b.interpolate, [0.0, big / 2, -big / 2, 0.0])
    y = b.process(np.r_[np.zeros(5), np.full(200, 1e30)])
    assert np.all(np.isfinite(y))


def test_bspline_period_and_reference_name_their_arguments():
    """bspline_period raised OverflowError/TypeError (10**400, complex) or warned on overflow;
    bspline_reference raised OverflowError from int(inf) for T/Ts beyond a float."""
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        _refused("wn", tr.bspline_period, wn=10 ** 400, Ts=TS)
        _refused("wn", tr.bspline_period, wn=1 + 1j, Ts=TS)
        _refused("wn", tr.bspline_period, wn=1e-308, Ts=TS)
        _refused("wn", tr.bspline_period, wn=5e-324, Ts=1e-300)
        _refused("T", tr.bspline_reference, [0.0, 1.0], degree=3, T=1e308, Ts=TS)
        _refused("T", tr.bspline_reference, [0.0, 1.0], degree=3, T=0.05, Ts=5e-324)
    assert tr.bspline_period(wn=[60.0, 200.0], Ts=TS) == 105 * TS
