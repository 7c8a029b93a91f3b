# SPDX-License-Identifier: Apache-2.0
"""Reference shapers and notches: published designs, exact and paper timing, biquads."""
import math

import numpy as np
import pytest
import scipy.signal
from hypothesis import given
from hypothesis import strategies as st

import smoothshaper as sm
from smoothshaper import reference as ref
from smoothshaper.reference._checks import on_grid

SHAPERS = ["zv", "zvd", "zvdd", "zvn", "ei", "ei2", "mzv", "ei3", "gmzv"]


def K_of(zeta, scale=1.0):
    return math.exp(-scale * zeta * math.pi / math.sqrt(1 - zeta * zeta))


@pytest.mark.parametrize("zeta", [0.0, 0.05, 0.3, 0.7])
def test_zv_family_amplitudes_are_the_published_ones(zeta):
    wn = 10.0
    K = K_of(zeta)
    Td = 2 * math.pi / (wn * math.sqrt(1 - zeta * zeta))
    for kind, amps in [("zv", [1, K]), ("zvd", [1, 2 * K, K * K]),
                       ("zvdd", [1, 3 * K, 3 * K * K, K ** 3])]:
        A, t = ref.shaper_impulses(sm.shaper(kind, wn=wn, zeta=zeta))
        np.testing.assert_allclose(A, np.array(amps) / sum(amps), rtol=1e-14)
        np.testing.assert_allclose(t, 0.5 * Td * np.arange(len(amps)), rtol=1e-14)


@pytest.mark.parametrize("zeta", [0.0, 0.1, 0.5])
def test_mzv_is_the_firmware_formula(zeta):
    wn = 2 * math.pi * 40
    K = K_of(zeta, 0.75)
    a1 = 1 - 1 / math.sqrt(2)
    amps = np.array([a1, (math.sqrt(2) - 1) * K, a1 * K * K])
    Td = 2 * math.pi / (wn * math.sqrt(1 - zeta * zeta))
    A, t = ref.shaper_impulses(sm.shaper("mzv", wn=wn, zeta=zeta))
    np.testing.assert_allclose(A, amps / amps.sum(), rtol=1e-14)
    np.testing.assert_allclose(t, [0, 0.375 * Td, 0.75 * Td], rtol=1e-14)


@given(n=st.integers(1, 8), zeta=st.floats(0.0, 0.9), re=st.floats(-5, 5), im=st.floats(-50, 50))
def test_zvn_continuous_transfer_is_the_nth_power_of_zv(n, zeta, re, im):
    wn = 7.0
    s = complex(re, im)
    Td = 2 * math.pi / (wn * math.sqrt(1 - zeta * zeta))
    K = K_of(zeta)
    expected = ((1 + K * np.exp(-s * Td / 2)) / (1 + K)) ** n
    got = ref.continuous_transfer(sm.shaper("zvn", wn=wn, zeta=zeta, order=n), s)
    # The impulse sum cancels: rounding scales with the sum of the terms' magnitudes.
    magnitude = ((1 + K * abs(np.exp(-s * Td / 2))) / (1 + K)) ** n
    assert abs(got - expected) <= 1e-12 * max(1.0, magnitude)


@pytest.mark.parametrize("V", [0.02, 0.05, 0.1])
def test_undamped_ei_has_residual_V_at_the_mode_and_zeros_beside_it(V):
    stage = sm.shaper("ei", wn=1.0, tolerance=V)
    A, t = ref.shaper_impulses(stage)
    np.testing.assert_allclose(A, [(1 + V) / 4, (1 - V) / 2, (1 + V) / 4], rtol=1e-15)
    assert abs(ref.continuous_transfer(stage, 1j)) == pytest.approx(V, rel=1e-12)
    # |H(j w)| = |(1+V)/2 cos(pi w) + (1-V)/2| vanishes where cos(pi w) = -(1-V)/(1+V)
    w0 = math.acos(-(1 - V) / (1 + V)) / math.pi
    assert abs(ref.continuous_transfer(stage, 1j * w0)) < 1e-15
    assert abs(ref.continuous_transfer(stage, 1j * (2 - w0))) < 1e-15


@pytest.mark.parametrize("V", [0.03, 0.05])
def test_undamped_two_hump_ei_has_two_humps_of_height_V(V):
    stage = sm.shaper("ei2", wn=1.0, tolerance=V)
    r = np.linspace(0.6, 1.4, 400001)
    res = np.abs(ref.continuous_transfer(stage, 1j * r))
    inner = (r > 0.75) & (r < 1.25)
    peaks = scipy.signal.argrelmax(np.where(inner, res, 0))[0]
    assert len(peaks) == 2
    np.testing.assert_allclose(res[peaks], V, rtol=1e-6)      # grid step 2e-6 near a maximum
    assert res[np.argmin(abs(r - 1))] < 1e-12


@pytest.mark.parametrize("V", [0.05, 0.2])
def test_undamped_three_hump_ei_has_three_humps_of_height_V(V):
    """Singhose et al. (1997) closed form: with c = cos(pi w/wn), |H| = |A3 + 2 A2 c +
    2 A1 (2c^2 - 1)|: V at the mode and -V at the vertex c* = -A2/(4 A1) on either side."""
    stage = sm.shaper("ei3", wn=1.0, tolerance=V)
    A, t = ref.shaper_impulses(stage)
    a1 = (1 + 3 * V + 2 * math.sqrt(2 * V * (V + 1))) / 16
    np.testing.assert_allclose(A, [a1, (1 - V) / 4, (1 + V) / 2 - 2 * a1, (1 - V) / 4, a1],
                               rtol=1e-14)
    np.testing.assert_allclose(t / (2 * math.pi), [0, 0.5, 1, 1.5, 2], rtol=1e-15)
    ws = math.acos(-A[1] / (4 * A[0])) / math.pi
    r = np.linspace(ws, 2 - ws, 20001)
    res = np.abs(ref.continuous_transfer(stage, 1j * r))
    peaks = scipy.signal.argrelmax(np.r_[0, res, 0])[0] - 1
    assert len(peaks) == 3
    np.testing.assert_allclose(res[peaks], V, rtol=1e-9)
    assert res.max() <= V * (1 + 1e-12)


@pytest.mark.parametrize("zeta", [0.0, 0.1, 0.5])
def test_generalised_mzv_with_three_impulses_over_three_quarters_is_mzv(zeta):
    g = ref.shaper_impulses(sm.shaper("gmzv", wn=40.0, zeta=zeta))
    m = ref.shaper_impulses(sm.shaper("mzv", wn=40.0, zeta=zeta))
    np.testing.assert_allclose(g[0], m[0], rtol=1e-13)
    np.testing.assert_allclose(g[1], m[1], rtol=1e-15)


@pytest.mark.parametrize("n", range(3, 10))
def test_generalised_mzv_is_the_firmware_least_squares_design(n):
    """n equally spaced impulses over D Td; the amplitudes satisfy the normal equations of the
    firmware's system (sum A = 1, zeros at wd (1 + i/tau)): M^T M A is a constant vector."""
    for D in (0.55, 0.75, 0.45 * (n - 1)):
        A, t = ref.shaper_impulses(sm.shaper("gmzv", wn=2 * math.pi, order=n, duration=D))
        np.testing.assert_allclose(t, D * np.arange(n) / (n - 1), rtol=1e-14)
        assert np.all(A >= 0) and A.sum() == pytest.approx(1, abs=1e-15)
        tau = D * (n - 2) / (n - 2 * D - 1)
        w = 2 * math.pi * (1 + np.arange(n - 1)[:, None] / tau) * t
        M = np.vstack([np.ones(n), np.cos(w), np.sin(w)])
        g = M.T @ (M @ A)
        np.testing.assert_allclose(g, g[0], rtol=1e-12)


def test_generalised_mzv_rejects_bad_order_and_duration():
    with pytest.raises(ValueError, match="order"):
        sm.shaper("gmzv", wn=10.0, order=2)
    with pytest.raises(ValueError, match="duration"):
        sm.shaper("gmzv", wn=10.0, order=3, duration=1.0)
    with pytest.raises(ValueError, match="duration"):        # negative least-squares impulse
        ref.shaper_impulses(sm.shaper("gmzv", wn=10.0, order=5, duration=0.3))
    with pytest.raises(sm.ParameterError, match="duration") as err:
        sm.Chain([sm.shaper("gmzv", wn=10.0, order=5, duration=0.3)], Ts=1e-3)
    assert err.value.parameter == "duration"


def test_damped_designs_carry_the_undamped_vector_sum():
    """A_m e^{-p t_m} = c B_m e^{-j wd t_m}: the residual at the damped mode is the undamped
    design's residual times c = 1/sum_m B_m e^{-zeta wn t_m} (module docstring)."""
    wn, zeta, V = 3.0, 0.2, 0.05
    for kind in ("ei", "ei2", "mzv", "ei3", "gmzv"):
        damped = sm.shaper(kind, wn=wn, zeta=zeta, tolerance=V)
        undamped = sm.shaper(kind, wn=1.0, tolerance=V)
        A, t = ref.shaper_impulses(damped)
        B, u = ref.shaper_impulses(undamped)
        c = 1 / np.sum(B * np.exp(-zeta * wn * t))
        p = ref.mode_pole(wn, zeta)
        assert ref.continuous_transfer(damped, p) == pytest.approx(
            c * complex(ref.continuous_transfer(undamped, 1j)), abs=1e-14)


# ---------------------------------------------------------------- discrete timing

@given(kind=st.sampled_from(SHAPERS), wn_Ts=st.floats(0.01, 2.5), zeta=st.floats(0.0, 0.8),
       order=st.integers(1, 8))
def test_exact_timing_gives_dc_gain_one_and_the_continuous_value_at_the_mode(kind, wn_Ts, zeta,
                                                                              order):
    Ts = 1e-3
    if kind == "gmzv":      # 3..9 impulses over 0.75 .. 3 damped periods
        order += 1
        stage = sm.shaper(kind, wn=wn_Ts / Ts, zeta=zeta, order=max(order, 3),
                          duration=0.375 * (max(order, 3) - 1))
    else:
        stage = sm.shaper(kind, wn=wn_Ts / Ts, zeta=zeta, order=order)
    h = ref.impulse_response(stage, Ts=Ts)
    p = ref.mode_pole(stage.wn, zeta)
    zp = np.exp(p * Ts)
    scale = np.abs(h).sum() * abs(zp) ** -(h.size - 1)
    assert abs(h.sum() - 1) < 1e-12
    Hd = ref.discrete_transfer(stage, zp, Ts=Ts)
    assert abs(Hd - ref.continuous_transfer(stage, p)) < 1e-12 * scale


@given(n=st.integers(2, 8), wn_Ts=st.floats(0.01, 2.5), zeta=st.floats(0.0, 0.8))
def test_exact_zvn_is_the_nth_power_of_the_exact_zv(n, wn_Ts, zeta):
    Ts = 1e-3
    zv = sm.shaper("zv", wn=wn_Ts / Ts, zeta=zeta)
    zvn = sm.shaper("zvn", wn=wn_Ts / Ts, zeta=zeta, order=n)
    z = np.exp(1j * np.linspace(0, math.pi, 50)) * 1.01
    np.testing.assert_allclose(ref.discrete_transfer(zvn, z, Ts=Ts),
                               ref.discrete_transfer(zv, z, Ts=Ts) ** n, rtol=0, atol=1e-12)


def test_exact_split_touches_only_the_support():
    """Off-grid ZV impulse at mu = Td/(2 Ts): taps outside {0, m0, m0+1} are zero and the
    correction is the least-norm one (orthogonal to the null space of the constraints)."""
    Ts, wn = 1e-3, 40.0
    stage = sm.shaper("zv", wn=wn)
    mu = math.pi / wn / Ts
    m0 = math.floor(mu)
    h = ref.impulse_response(stage, Ts=Ts)
    assert h.size == m0 + 2
    assert np.all(h[1:m0] == 0)
    base = np.zeros(m0 + 2)
    base[0], base[m0], base[m0 + 1] = 0.5, 0.5 * (1 - (mu - m0)), 0.5 * (mu - m0)
    d = (h - base)[[0, m0, m0 + 1]]
    zinv = np.exp(-1j * wn * Ts * np.array([0, m0, m0 + 1]))
    G = base @ np.exp(-1j * wn * Ts * np.arange(m0 + 2))
    # sum d = 0 and sum d z_p^-i = H_c(p) - G(z_p) = -G (ZV: H_c(p) = 0)
    C = np.vstack([np.ones(3), zinv.real, zinv.imag])
    np.testing.assert_allclose(C @ d, [0.0, -G.real, -G.imag], atol=1e-15)


def test_on_grid_impulses_need_no_correction_and_match_paper_timing():
    Ts = 1e-3
    wn = math.pi / (25 * Ts)                    # Td/2 = 25 samples exactly
    for kind in ("zv", "zvd", "zvdd"):
        exact = ref.impulse_response(sm.shaper(kind, wn=wn), Ts=Ts)
        paper = ref.impulse_response(sm.shaper(kind, wn=wn, timing="paper"), Ts=Ts)
        np.testing.assert_array_equal(exact, paper)
        assert np.count_nonzero(exact) == {"zv": 2, "zvd": 3, "zvdd": 4}[kind]


def test_paper_timing_rounds_each_continuous_impulse():
    Ts, wn = 1e-3, 2 * math.pi * 7.3
    stage = sm.shaper("zvdd", wn=wn, timing="paper")
    A, t = ref.shaper_impulses(stage)
    h = ref.impulse_response(stage, Ts=Ts)
    expected = np.zeros(h.size)
    for a, tm in zip(A, t):
        expected[int(math.floor(tm / Ts + 0.5))] += a
    np.testing.assert_array_equal(h, expected)
    assert abs(ref.discrete_transfer(stage, np.exp(ref.mode_pole(wn, 0) * Ts), Ts=Ts)) > 1e-4


def test_shaper_mode_must_be_below_nyquist():
    with pytest.raises(ValueError, match="^wn "):
        ref.impulse_response(sm.shaper("zv", wn=4000.0), Ts=1e-3)


# ---------------------------------------------------------------- notch

@pytest.mark.parametrize("xi1, xi2", [(0.0, 0.7), (0.05, 0.5), (0.1, 1.0), (0.1, 2.5)])
def test_tustin_notch_equals_scipy_prewarped_bilinear(xi1, xi2):
    wn, Ts = 200.0, 1e-3
    b, a = ref.notch_coefficients(sm.notch(wn=wn, zeta=xi1, notch_pole_zeta=xi2,
                                           discretization="tustin"), Ts=Ts)
    fs = wn / (2 * math.tan(wn * Ts / 2))          # scipy uses s = 2 fs (z-1)/(z+1)
    bs, as_ = scipy.signal.bilinear([1, 2 * xi1 * wn, wn * wn], [1, 2 * xi2 * wn, wn * wn], fs)
    np.testing.assert_allclose(b, bs / as_[0], rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(a, as_ / as_[0], rtol=1e-12, atol=1e-15)
    z = np.exp(1j * wn * Ts)                        # prewarping: depth xi1/xi2 exactly at wn
    stage = sm.notch(wn=wn, zeta=xi1, notch_pole_zeta=xi2, discretization="tustin")
    assert abs(ref.discrete_transfer(stage, z, Ts=Ts)) == pytest.approx(xi1 / xi2, abs=1e-12)
    assert abs(ref.discrete_transfer(stage, 1.0, Ts=Ts) - 1) < 1e-12


@pytest.mark.parametrize("xi1, xi2", [(0.0, 0.7), (0.05, 0.5), (0.1, 1.0), (0.1, 2.5)])
def test_matched_notch_has_zeros_on_the_sampled_mode_and_dc_gain_one(xi1, xi2):
    wn, Ts = 200.0, 1e-3
    stage = sm.notch(wn=wn, zeta=xi1, notch_pole_zeta=xi2)
    b, a = ref.notch_coefficients(stage, Ts=Ts)
    zp = np.exp(ref.mode_pole(wn, xi1) * Ts)
    assert abs(np.polyval(b, zp)) < 1e-12 * abs(b).sum()   # b0 z^2 + b1 z + b2
    poles = np.roots(a)
    s_poles = np.roots([1, 2 * xi2 * wn, wn * wn])
    np.testing.assert_allclose(np.sort_complex(poles), np.sort_complex(np.exp(s_poles * Ts)),
                               rtol=1e-7)                    # np.roots of a double root
    assert abs(ref.discrete_transfer(stage, 1.0, Ts=Ts) - 1) < 1e-12


def test_notch_impulse_response_and_filter_match_scipy_lfilter():
    stage = sm.notch(wn=300.0, zeta=0.02, notch_pole_zeta=0.6)
    Ts = 1e-3
    b, a = ref.notch_coefficients(stage, Ts=Ts)
    x = np.random.default_rng(1).normal(size=500)
    np.testing.assert_allclose(ref.filter(stage, x, Ts=Ts), scipy.signal.lfilter(b, a, x),
                               rtol=0, atol=1e-12)
    imp = ref.impulse_response(stage, Ts=Ts, length=64)
    np.testing.assert_allclose(imp, scipy.signal.lfilter(b, a, np.eye(1, 64)[0]), atol=1e-15)
    with pytest.raises(ValueError, match="^length "):
        ref.impulse_response(stage, Ts=Ts)


def test_integer_test_threshold_is_1e_9_relative():
    assert on_grid(3.0 + 1e-10) == 3 and on_grid(3.0 + 1e-8) is None
