# SPDX-License-Identifier: Apache-2.0
"""plants: exact ZOH simulation and the time-domain residual equal to |H(p)|."""
import math

import numpy as np
import pytest
import scipy.signal
from hypothesis import given, settings
from hypothesis import strategies as st

import smoothshaper as sm
from smoothshaper import analysis as an
from smoothshaper import plants
from smoothshaper import reference as ref
from test_api import raises as _named  # noqa: E402

# seed 000 experiment mode
SIGMA, WD, TS = -15.6539, 122.7185, 500e-6
WN = math.hypot(SIGMA, WD)
ZETA = -SIGMA / WN


def test_table1_two_mass_mode():
    p = plants.two_mass(J_l=0.23e-5, k_t=0.156, b_t=1e-5)
    wn = math.sqrt(0.156 / 0.23e-5)
    assert wn == pytest.approx(260.4, abs=0.05)
    zeta = 1e-5 / (2 * math.sqrt(0.156 * 0.23e-5))
    np.testing.assert_allclose(np.sort_complex(p.poles()),
                               np.sort_complex(np.roots([1, 2 * zeta * wn, wn * wn])), rtol=1e-12)


@pytest.mark.parametrize("make, num, den", [
    (lambda: plants.tracking_error(wn=30.0, zeta=0.1), [-1, 0, 0], [1, 6.0, 900.0]),
    (lambda: plants.mode(wn=30.0, zeta=0.1), [6.0, 900.0], [1, 6.0, 900.0]),
    (lambda: plants.cartesian_axis(m=2.0, d=3.0, k=800.0), [3.0, 800.0], [2.0, 3.0, 800.0]),
])
def test_state_space_realises_the_transfer_function(make, num, den):
    s = np.array([0.5j, 3 + 40j, -2 + 1j, 100j])
    np.testing.assert_allclose(make().transfer(s), np.polyval(num, s) / np.polyval(den, s),
                               rtol=1e-12)


def test_series_is_the_product():
    a, b = plants.mode(wn=30.0, zeta=0.1), plants.tracking_error(wn=80.0, zeta=0.02)
    s = np.array([1j, 7 + 25j, 90j])
    # the tracking error is -s^2/wn^2 near s = 0: compare to rounding of the factors
    np.testing.assert_allclose(plants.series(a, b).transfer(s), a.transfer(s) * b.transfer(s),
                               rtol=1e-12, atol=1e-15)


def test_simulate_zoh_equals_scipy_cont2discrete_and_dlsim():
    plant = plants.series(plants.mode(wn=200.0, zeta=0.05), plants.tracking_error(wn=90.0,
                                                                                    zeta=0.2))
    u = np.random.default_rng(3).normal(size=400)
    _, y = plants.simulate_zoh(plant, u, Ts=1e-3)
    sysd = scipy.signal.cont2discrete((plant.A, plant.B[:, None], plant.C[None, :],
                                       np.array([[plant.D]])), 1e-3, method="zoh")
    _, yd = scipy.signal.dlsim(sysd[:4] + (1e-3,), u)[:2]
    np.testing.assert_allclose(y, yd[:, 0], rtol=0, atol=1e-12 * np.abs(yd).max())


def test_simulate_zoh_intersample_values_equal_lsim_with_held_input():
    plant = plants.mode(wn=260.4, zeta=0.02)
    u = np.repeat([0.0, 1.0, 0.3, -2.0], 25)
    t, y = plants.simulate_zoh(plant, u, Ts=1e-3, oversample=8)
    _, ys, _ = scipy.signal.lsim((plant.A, plant.B[:, None], plant.C[None, :], plant.D),
                                 np.repeat(u, 8), t, interp=False)
    np.testing.assert_allclose(y, ys, rtol=0, atol=1e-9)


def measured_residual(stages, plant_mode, Ts, n=6000):
    """Time-domain residual ratio: filtered over unfiltered unit step, held by a ZOH."""
    plant = plants.tracking_error(wn=plant_mode[0], zeta=plant_mode[1])
    t, e_raw = plants.simulate_zoh(plant, np.ones(n), Ts=Ts)
    t, e_f = plants.simulate_zoh(plant, ref.filter(stages, np.ones(n), Ts=Ts), Ts=Ts)
    L = sum(ref.impulse_response(s, Ts=Ts).size for s in stages)
    t0 = (L + 2) * Ts                                   # the command has settled
    kw = dict(wn=plant_mode[0], zeta=plant_mode[1], t_start=t0)
    return (plants.residual_amplitude(t, e_f, **kw) / plants.residual_amplitude(t, e_raw, **kw))


@pytest.mark.parametrize("stages", [
    [sm.harmonic(T=3 * math.pi / WD)],                  # tuned to wd, not damped: ~10 %
    [sm.rectangular(T=1.1 * 2 * math.pi / WD)],         # mistuned by 10 %
    [sm.damped_harmonic(T=3 * math.pi / WD, sigma=SIGMA, timing="paper")],   # 0.27 %
    [sm.rectangular(T=0.02), sm.shaper("zv", wn=1.05 * WN, zeta=ZETA)],
])
def test_time_domain_residual_equals_the_transfer_at_the_pole(stages):
    """The fitted oscillation amplitude ratio is |H_d(e^{p Ts})|: the simulation is exact,
    so agreement is limited only by rounding in the fit (1e-7 relative is generous)."""
    expected = an.residual_vibration(stages, wn=WN, zeta=ZETA, Ts=TS)
    assert measured_residual(stages, (WN, ZETA), TS) == pytest.approx(expected, rel=1e-7)


def test_seed000_damped_harmonic_leaves_no_residual_in_the_time_domain():
    """Seed 000 Fig. 8 with exact timing at T/Ts = 153.6: residual at rounding level."""
    stages = [sm.damped_harmonic(T=3 * math.pi / WD, sigma=SIGMA)]
    assert measured_residual(stages, (WN, ZETA), TS) < 1e-9


def test_residual_amplitude_recovers_a_known_oscillation():
    t = np.linspace(0, 2, 4001)
    y = 0.7 + 3.0 * np.exp(-2 * t) * np.cos(40 * math.sqrt(1 - 0.05 ** 2) * t + 0.4)
    assert plants.residual_amplitude(t, y, wn=40.0, zeta=0.05, t_start=0.5) == pytest.approx(
        3.0, rel=1e-10)


@pytest.mark.parametrize("call, name", [
    (lambda: plants.mode(wn=-1.0), "wn"),
    (lambda: plants.tracking_error(wn=1.0, zeta=1.0), "zeta"),
    (lambda: plants.two_mass(J_l=0.0, k_t=1.0, b_t=0.0), "J_l"),
    (lambda: plants.two_mass(J_l=1.0, k_t=1.0, b_t=5.0), "b_t"),
    (lambda: plants.cartesian_axis(m=1.0, d=-1.0, k=1.0), "d"),
    (lambda: plants.simulate_zoh(plants.mode(wn=1.0), [0.0, math.nan], Ts=0.1), "u"),
    (lambda: plants.simulate_zoh(plants.mode(wn=1.0), [0.0], Ts=0.0), "Ts"),
    (lambda: plants.simulate_zoh(plants.mode(wn=1.0), [0.0], Ts=0.1, oversample=0), "oversample"),
    (lambda: plants.series(), "plants"),
])
def test_bad_arguments_raise_value_error_naming_the_parameter(call, name):
    with pytest.raises(ValueError, match=rf"^{name} "):
        call()


@settings(max_examples=25)
@given(kind=st.sampled_from(["rectangular", "harmonic", "zv", "ei", "mzv"]),
       detune=st.floats(0.7, 1.3), zeta=st.floats(0.0, 0.3), wn_Ts=st.floats(0.02, 0.3))
def test_time_domain_residual_equals_the_transfer_for_random_filters(kind, detune, zeta, wn_Ts):
    Ts = 1e-3
    wn = wn_Ts / Ts
    stage = sm.for_mode(kind, wn=detune * wn, zeta=zeta)
    expected = an.residual_vibration(stage, wn=wn, zeta=zeta, Ts=Ts)
    L = ref.impulse_response(stage, Ts=Ts).size
    n = L + int(8 * 2 * math.pi / (wn * Ts))              # eight periods after settling
    got = measured_residual([stage], (wn, zeta), Ts, n=n)
    assert got == pytest.approx(expected, rel=1e-6, abs=1e-9)




def test_a_plant_is_checked_when_it_is_made():
    """Plant took anything (None, text, NaN, a B of the wrong length): the failure came later
    from numpy.linalg, or a simulation of NaN."""
    A, B, C = np.array([[0.0, 1.0], [-1.0, -0.1]]), np.array([0.0, 1.0]), np.array([1.0, 0.0])
    _named("A", plants.Plant, None, B, C, 0.0)
    _named("A", plants.Plant, [1.0, 2.0], B, C, 0.0)
    _named("A", plants.Plant, A * np.nan, B, C, 0.0)
    _named("B", plants.Plant, A, [0.0, 1.0, 2.0], C, 0.0)
    _named("C", plants.Plant, A, B, ["a", "b"], 0.0)
    _named("D", plants.Plant, A, B, C, np.nan)
    _named("D", plants.Plant, A, B, C, None)
    p = plants.Plant(A.astype(int), B, C, 0)
    assert p.A.dtype == np.float64 and p.D == 0.0


def test_plant_functions_name_their_arguments():
    """NaN in, NaN out (rest_state, transfer), OverflowError or TypeError from float(), an
    IndexError for a y of another length, inf in A for wn = 1e308."""
    p = plants.mode(wn=10.0, zeta=0.1)
    for u0 in (np.nan, 10 ** 400, None, 1j):
        _named("u0", plants.rest_state, p, u0)
    for s in ([np.nan], [None], ["a"], [1j, np.inf]):
        _named("s", p.transfer, s)
    _named("wn", plants.mode, wn=1e308)
    _named("wn", plants.tracking_error, wn=1e308)
    _named("m", plants.cartesian_axis, m=1e-308, d=1.0, k=100.0)
    _named("Ts", plants.zoh_matrices, p, 1e308)
    _named("x0", plants.simulate_zoh, p, np.ones(5), Ts=1e-3, x0=[np.inf, 0.0])
    _named("oversample", plants.simulate_zoh, p, np.ones(5), Ts=1e-3, oversample=10 ** 400)
    t = np.arange(100) * 1e-2
    y = np.sin(10 * t)
    _named("y", plants.residual_amplitude, t, y[:50], wn=10.0, t_start=0.0)
    _named("t", plants.residual_amplitude, np.ones((10, 10)), y, wn=10.0, t_start=0.0)
    _named("t_start", plants.residual_amplitude, t, y, wn=10.0, t_start=None)
    assert plants.residual_amplitude(t, y, wn=10.0, t_start=0.0) == pytest.approx(1.0)
