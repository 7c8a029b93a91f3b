# SPDX-License-Identifier: Apache-2.0
"""Closed-form trajectories: rectangular chains (time-optimal profiles) and their samples."""
import math

import numpy as np
import pytest

import smoothshaper as sm
from smoothshaper import reference as ref

H, V, A, J = 40.0, 250.0, 5000.0, 200000.0
T = [H / V, V / A, A / J]                     # 0.16, 0.05, 0.025 s (Biagiotti & Melchiorri 2011a)


def test_rectangular_chain_reaches_its_limits_and_ends_at_the_optimal_duration():
    t = np.linspace(-0.01, 0.25, 260001)
    q = ref.rectangular_chain_trajectory(t, T=T, h=H)
    v = ref.rectangular_chain_trajectory(t, T=T, h=H, derivative=1)
    a = ref.rectangular_chain_trajectory(t, T=T, h=H, derivative=2)
    assert q[t <= 0].max() == 0 and np.all(q[t >= sum(T)] == H)
    assert q[t < sum(T) - 1e-6].max() < H
    assert v.max() == pytest.approx(V, rel=1e-12)
    assert a.max() == pytest.approx(A, rel=1e-9) and a.min() == pytest.approx(-A, rel=1e-9)
    np.testing.assert_allclose(np.gradient(q, t), v, atol=1e-6 * V)
    np.testing.assert_allclose(np.gradient(v, t)[10:-10], a[10:-10], atol=A * 0.01)


def test_sampled_chain_is_the_closed_form_shifted_by_half_samples():
    """Each rectangular stage (taps at delays 0..N-1) is the continuous average over the
    window, read by the midpoint rule, shifted by half a sample; the first one sees a sampled
    step and is exact one sample ahead. So for n stages the samples equal
    q(t + (n+1) Ts/2) up to a midpoint error O(Ts^2) (ratio 4 per halving of Ts), while
    q(t) itself is off by exactly (n+1)/2 Ts v_max while cruising."""
    errors = []
    for Ts in (1e-3, 5e-4, 2.5e-4):
        chain = [sm.rectangular(T=d) for d in T]
        n = int(round(0.3 / Ts))
        y = ref.filter(chain, np.full(n, H), Ts=Ts)
        k = np.arange(n)
        q_shift = ref.rectangular_chain_trajectory((k + 2) * Ts, T=T, h=H)
        q_plain = ref.rectangular_chain_trajectory(k * Ts, T=T, h=H)
        assert np.abs(y - q_plain).max() == pytest.approx(2 * Ts * V, rel=1e-9)
        errors.append(np.abs(y - q_shift).max())
    assert errors[0] / errors[1] == pytest.approx(4, rel=0.01)
    assert errors[1] / errors[2] == pytest.approx(4, rel=0.01)


def test_harmonic_and_damped_trajectories_agree_when_sigma_is_zero():
    t = np.linspace(0, 0.1, 101)
    np.testing.assert_allclose(ref.damped_harmonic_trajectory(t, T=0.1, sigma=0.0, h=3.0),
                               ref.harmonic_trajectory(t, T=0.1, h=3.0), atol=1e-15)
    np.testing.assert_allclose(ref.exponential_trajectory(t, T=0.1, sigma=0.0, h=3.0),
                               30.0 * t, atol=1e-14)


def test_seed001_harmonic_alone_duration():
    """Seed 001: the harmonic smoother alone for h = 40, v = 250 is T = pi h/(2 v) = 0.2513 s
    (peak velocity of h/2 (1 - cos(pi t/T)) is pi h/(2T))."""
    Tn = math.pi * H / (2 * V)
    assert Tn == pytest.approx(0.2513, abs=5e-5)
    t = np.linspace(0, Tn, 100001)
    v = np.gradient(ref.harmonic_trajectory(t, T=Tn, h=H), t)
    assert v.max() == pytest.approx(V, rel=1e-6)


@pytest.mark.parametrize("call, name", [
    (lambda: ref.harmonic_trajectory([0.0], T=0.0), "T"),
    (lambda: ref.damped_harmonic_trajectory([0.0], T=1.0, sigma=math.nan), "sigma"),
    (lambda: ref.rectangular_chain_trajectory([0.0], T=[1.0, -1.0]), r"T\[1\]"),
    (lambda: ref.rectangular_chain_trajectory([0.0], T=[1.0], derivative=1), "derivative"),
    (lambda: ref.exponential_trajectory([0.0], T=1.0, sigma=-1.0, h=math.inf), "h"),
])
def test_bad_arguments_raise_value_error_naming_the_parameter(call, name):
    with pytest.raises(ValueError, match=rf"^{name} "):
        call()
