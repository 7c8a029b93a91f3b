# SPDX-License-Identifier: Apache-2.0
"""Specified-insensitivity shapers, user-defined impulses and the input smoothers of
Klipper-derived firmware, in Python: the Stage checks, the closed forms against the NumPy
reference (independent derivations: Chebyshev series and brentq there, a cosine transform and
a closed-form band in C; exact polynomial algebra there, Gauss-Legendre in C), the pinned
residual at any Ts, the firmware's definitions, the CLI syntax and the FMU's refusals."""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import smoothshaper as sms
from smoothshaper import reference
from smoothshaper.cli.chain import parse_stage
from smoothshaper.filters import _backend, _fill_config
from smoothshaper.reference.input_smoothers import (input_smoother_taps, pinned_pole,
                                                    smoother_kernel, smoother_transfer)
from smoothshaper.reference.shapers import si_undamped
from smoothshaper.stages import INPUT_SMOOTHERS, Stage
from fmu_builds import fmu_build_dir

# T f of each kernel at zeta = 0 (shaper_defs.py: the first term of its t cubic, or constant)
SPANS = {"smooth_zv": 0.66471804, "smooth_mzv": 0.85165483, "smooth_ei": 0.96753911,
         "smooth_ei2": 1.14875, "smooth_zvd_ei": 1.475, "smooth_si": 1.245}


def c_transfer(stage: Stage, s: complex) -> complex:
    ffi, lib = _backend("double")
    config = ffi.new("sms_stage_config *")
    _fill_config(config, stage)
    re, im = ffi.new("double *"), ffi.new("double *")
    assert lib.sms_shaper_transfer(config, s.real, s.imag, re, im) == 0
    return complex(re[0], im[0])


def taps(stage: Stage, Ts: float) -> np.ndarray:
    chain = sms.Chain(stage, Ts=Ts)
    x = np.zeros(chain.length)
    x[0] = 1.0
    return chain.process(x)


# ---------------------------------------------------------------- SI

@pytest.mark.parametrize("V", [1e-3, 0.05, 0.4])
@pytest.mark.parametrize("n", [3, 5, 7, 9])
def test_si_closed_form_matches_the_reference(n, V):
    """C (cosine transform, closed-form band) and NumPy (Chebyshev series, brentq) agree to
    rounding; the response stays <= V over the band and equals V at its lower edge."""
    d = (n - 1) // 2
    for D in np.linspace(0.5 * d, d, 5):
        A, units, I = si_undamped(n, D, V)
        assert sms.si_insensitivity(order=n, duration=D, tolerance=V) == pytest.approx(I, abs=1e-14)
        c_A, c_t = reference.shaper_impulses(Stage("si", wn=2 * math.pi, order=n, duration=D,
                                                   tolerance=V))
        A_c = sms.Chain(Stage("si", wn=2 * math.pi, order=n, duration=D, tolerance=V), Ts=1e-3)
        assert A_c.length > 0
        assert np.all(A >= 0.0) and A.sum() == pytest.approx(1.0, abs=1e-15)
        w = np.linspace(1 - I / 2, 1 + I / 2, 801)           # wd = 1 in units of damped periods
        H = np.abs(np.exp(-2j * math.pi * np.outer(w, units)) @ A)
        assert H.max() <= V * (1 + 1e-12)
        assert H[0] == pytest.approx(V, rel=1e-12)


def test_si_contains_ei_ei3_and_zv():
    """SI over the widest spacing is EI (3 impulses) and the three-hump EI (5); 3 impulses over
    half a period is ZV (Singhose, Porter, Tuttle and Singer 1997 closed forms)."""
    wn, zeta = 230.0, 0.13
    for kind, n, D in (("ei", 3, 1.0), ("ei3", 5, 2.0)):
        A_si, t_si = reference.shaper_impulses(Stage("si", wn=wn, zeta=zeta, order=n, duration=D))
        A, t = reference.shaper_impulses(Stage(kind, wn=wn, zeta=zeta))
        np.testing.assert_allclose(A_si, A, rtol=0, atol=2e-15)
        np.testing.assert_allclose(t_si, t, rtol=1e-15)
    A_si, t_si = reference.shaper_impulses(Stage("si", wn=wn, zeta=zeta, order=3, duration=0.5))
    A, t = reference.shaper_impulses(Stage("zv", wn=wn, zeta=zeta))
    assert A_si[1] == 0.0
    np.testing.assert_allclose(A_si[[0, 2]], A, atol=2e-15)


@pytest.mark.parametrize("I", [0.05, 0.3, 0.6, 1.0, 1.3])
def test_si_design_is_the_shortest_for_the_band(I):
    n, D = sms.si_design(insensitivity=I)
    got = si_undamped(n, D, 0.05)[2]
    assert got >= I * (1 - 1e-12) or (n, D) == (3, 0.5)
    for other in (3, 5, 7, 9):                 # no other order reaches I sooner
        d = (other - 1) / 2
        shorter = D * (1 - 1e-9)
        if other != n and 0.5 * d <= shorter <= d:
            assert si_undamped(other, shorter, 0.05)[2] < I
    stage = sms.si_shaper(wn=300.0, zeta=0.05, insensitivity=I)
    assert (stage.kind, stage.order, stage.duration) == ("si", n, D)


def test_si_is_within_8_percent_of_the_free_time_optimum():
    """Equally spaced impulses cost little: the shortest shaper with free impulse times on a
    1/64-period grid that keeps |H| <= 5 % over the band (a linear program, scipy's HiGHS)
    is at most 8 % shorter than the SI design at the band widths of tests/README."""
    from scipy.optimize import linprog
    for I, ratio in ((0.2, 1.001), (0.6, 1.08)):
        n, D = sms.si_design(insensitivity=I)

        def feasible(span):
            t = np.arange(65) * span / 64
            w = np.linspace(1 - I / 2, 1 + I / 2, 40)
            phase = 2 * math.pi * np.outer(w, t)
            rows = [math.cos(a) * np.cos(phase) + math.sin(a) * np.sin(phase)
                    for a in 2 * math.pi * np.arange(16) / 16]
            res = linprog(np.zeros(65), A_ub=np.vstack(rows),
                          b_ub=np.full(16 * 40, 0.05 * math.cos(math.pi / 16)),
                          A_eq=np.ones((1, 65)), b_eq=[1.0], bounds=(0, None), method="highs")
            return res.status == 0
        assert not feasible(D / ratio)
        assert feasible(D * 1.001)


@pytest.mark.parametrize("kwargs, parameter", [
    (dict(order=4), "order"), (dict(order=11), "order"), (dict(order=5, duration=0.99), "duration"),
    (dict(order=5, duration=2.01), "duration"), (dict(tolerance=1.0), "tolerance"),
    (dict(tolerance=0.0), "tolerance"), (dict(zeta=1.0), "zeta"),
])
def test_si_stage_refuses(kwargs, parameter):
    with pytest.raises(ValueError, match=rf"^{parameter}"):
        Stage("si", **{"wn": 100.0, **kwargs})


def test_si_design_refuses():
    with pytest.raises(ValueError, match=r"^insensitivity"):
        sms.si_design(insensitivity=1.45)          # wider than nine impulses reach at 5 %
    with pytest.raises(ValueError, match=r"^insensitivity"):
        sms.si_design(insensitivity=-0.1)
    with pytest.raises(ValueError, match=r"^tolerance"):
        sms.si_design(insensitivity=0.3, tolerance=1.5)
    with pytest.raises(ValueError, match=r"^order"):
        sms.si_insensitivity(order=2**40, duration=1.0)


# ---------------------------------------------------------------- user-defined impulses

def test_impulses_equal_the_firmware_shaper_they_paste():
    """Klipper's mzv at 41 Hz, damping 0.1, as its shaper_defs.get_mzv_shaper impulses: the
    same continuous shaper as the mzv kind, and the same filter at paper timing."""
    f, zeta = 41.0, 0.1
    df = math.sqrt(1 - zeta * zeta)
    K, td, a1 = math.exp(-0.75 * zeta * math.pi / df), 1 / (f * df), 1 - 1 / math.sqrt(2)
    pasted = sms.impulse_shaper(amplitudes=[a1, (math.sqrt(2) - 1) * K, a1 * K * K],
                                times=[0.0, 0.375 * td, 0.75 * td], timing="paper")
    mzv = sms.shaper("mzv", wn=2 * math.pi * f, zeta=zeta, timing="paper")
    for a, b in zip(reference.shaper_impulses(pasted), reference.shaper_impulses(mzv)):
        np.testing.assert_allclose(a, b, rtol=4e-16, atol=1e-18)
    np.testing.assert_array_equal(taps(pasted, 1e-3), taps(mzv, 1e-3))


def test_impulses_keep_a_sampled_ramp_exact():
    """Exact timing splits each impulse linearly: sum 1 and the centroid sum A t, so a sampled
    ramp comes out as the continuous shaper's output (negative amplitudes and a delay too)."""
    stage = sms.impulse_shaper(amplitudes=[0.7, -0.2, 0.9, 0.1],
                               times=[0.0013, 0.0041, 0.0105, 0.0188])
    Ts = 1e-3
    t = np.arange(200) * Ts
    y = sms.Chain(stage, Ts=Ts).process(3 * t)
    want = sum(a / 1.5 * 3 * np.maximum(t - ti, 0.0) for a, ti in zip(stage.amplitudes, stage.times))
    np.testing.assert_allclose(y[20:], want[20:], rtol=0, atol=1e-14)
    h = reference.impulse_response(stage, Ts=Ts)
    assert h.sum() == pytest.approx(1.0, abs=1e-15)
    assert h @ np.arange(h.size) * Ts == pytest.approx(
        np.dot(stage.amplitudes, stage.times) / 1.5, rel=1e-14)


@pytest.mark.parametrize("kwargs, parameter", [
    (dict(amplitudes=[], times=[]), "amplitudes"),
    (dict(amplitudes=[1.0] * 10, times=list(range(10))), "amplitudes"),
    (dict(amplitudes=[0.5, 0.5], times=[0.0]), "times"),
    (dict(amplitudes=[0.5, math.nan], times=[0.0, 0.01]), r"amplitudes\[1\]"),
    (dict(amplitudes=[0.5, -0.5], times=[0.0, 0.01]), "amplitudes"),
    (dict(amplitudes=[0.5, 0.5], times=[-0.001, 0.01]), r"times\[0\]"),
    (dict(amplitudes=[0.5, 0.5], times=[0.01, 0.01]), r"times\[1\]"),
    (dict(amplitudes=[0.5, 0.5], times=[0.0, math.inf]), r"times\[1\]"),
    (dict(amplitudes="0.5,0.5", times=[0.0, 0.01]), "amplitudes"),
    (dict(amplitudes=[0.5, 0.5], times=[0.0, 0.01], timing="bounded"), "timing"),
])
def test_impulses_refuse(kwargs, parameter):
    with pytest.raises(ValueError, match=rf"^{parameter}"):
        sms.impulse_shaper(**kwargs)


def test_impulses_fields_are_for_impulses_only():
    with pytest.raises(ValueError, match=r"^amplitudes"):
        Stage("zv", wn=100.0, amplitudes=(1.0,), times=(0.0,))
    with pytest.raises(ValueError, match=r"^order"):
        Stage("impulses", amplitudes=(1.0, 1.0), times=(0.0, 0.01), order=3)
    stage = sms.impulse_shaper(amplitudes=[1, 2], times=[0, 0.01])
    assert (stage.order, stage.amplitudes, stage.times) == (2, (1.0, 2.0), (0.0, 0.01))


def test_impulses_state_is_refused_by_other_impulses():
    a = sms.Chain(sms.impulse_shaper(amplitudes=[0.25, 0.5, 0.25], times=[0, 0.005, 0.01]), Ts=1e-3)
    b = sms.Chain(sms.impulse_shaper(amplitudes=[0.25, 0.5, 0.2500001], times=[0, 0.005, 0.01]),
                  Ts=1e-3)
    a.process(np.arange(7.0))
    with pytest.raises(ValueError, match=r"^state"):
        b.set_state(a.get_state())
    c = sms.Chain(a.stages, Ts=1e-3)
    c.set_state(a.get_state())
    np.testing.assert_array_equal(c.process(np.ones(5)), a.process(np.ones(5)))


# ---------------------------------------------------------------- input smoothers

@pytest.mark.parametrize("kind", INPUT_SMOOTHERS)
def test_input_smoother_transfer_c_equals_reference(kind):
    """Gauss-Legendre (C) and exact series / antiderivative (NumPy) agree at the pinned point
    and along the frequency axis to the rounding of the terms they sum: up to
    sum_k |q_k| 2^-k (2.7e3 for smooth_ei) times a few eps."""
    stage = sms.input_smoother(kind, wn=2 * math.pi * 37.5, zeta=0.1)
    q, _ = smoother_kernel(stage)
    tol = 4 * np.finfo(float).eps * max(1.0, float(np.sum(np.abs(q) * 0.5 ** np.arange(q.size))))
    points = [pinned_pole(stage), 0.3 + 5j] + [1j * w for w in np.linspace(0.0, 4000.0, 41)]
    for s in points:
        assert abs(c_transfer(stage, s) - smoother_transfer(stage, s)) <= tol


@pytest.mark.parametrize("kind", INPUT_SMOOTHERS)
def test_input_smoother_kernel_is_the_firmware_one(kind):
    """The kernel of the source (zero at both ends, unit area, its duration t/f; the cubic in
    zeta for smooth_zv, smooth_mzv, smooth_ei), and the residual it was designed for at
    damping 0.1 (the source's default): < 1e-4 for the zero-vibration kernels, < 5 % for the
    EI ones, as e^{-zeta wn T} |H_c(p)| (the source's V)."""
    f, zeta = 40.0, 0.1
    stage = sms.input_smoother(kind, wn=2 * math.pi * f, zeta=zeta if kind in (
        "smooth_zv", "smooth_mzv", "smooth_ei") else 0.0)
    q, T = smoother_kernel(stage)
    P = np.polynomial.Polynomial(q)
    rounding = 4 * np.finfo(float).eps * float(np.sum(np.abs(q) * 0.5 ** np.arange(q.size)))
    # zero ends to the digits the source prints (about 10 significant: 1e-9 of the peak)
    assert abs(P(-0.5)) < 1e-9 and abs(P(0.5)) < 1e-9
    assert P.integ()(0.5) - P.integ()(-0.5) == pytest.approx(1.0, abs=rounding)
    if kind in ("smooth_zv", "smooth_mzv", "smooth_ei"):
        t = {"smooth_zv": [0.66471804, 0.0039585139, 0.33614293, 0.2157273],
             "smooth_mzv": [0.85165483, 0.0183642417, 0.39000898, 0.23209004],
             "smooth_ei": [0.96753911, 0.48592866, -7.2991788, 18.2075661]}[kind]
        assert T * f == pytest.approx(np.polynomial.polynomial.polyval(zeta, t), rel=1e-15)
    else:
        assert T * f == pytest.approx(SPANS[kind], rel=1e-15)
    wn = 2 * math.pi * f
    p = complex(-zeta * wn, wn * math.sqrt(1 - zeta * zeta))
    V = math.exp(-zeta * wn * T) * abs(smoother_transfer(stage, p))
    assert V < (0.05 if kind in ("smooth_ei", "smooth_ei2") else 1e-4)


@settings(max_examples=40, deadline=None)
@given(kind=st.sampled_from(INPUT_SMOOTHERS), periods=st.floats(5.0, 300.0),
       zeta=st.floats(0.0, 0.25))
def test_input_smoother_pins_its_residual_for_any_Ts(kind, periods, zeta):
    """H(e^{p Ts}) = H_c(p) at the pinned point, unit gain and the continuous centroid,
    whatever the sample period (here 5 to 300 samples per design period)."""
    Ts = 1e-4
    stage = sms.input_smoother(kind, wn=2 * math.pi / (periods * Ts), zeta=zeta)
    if smoother_kernel(stage)[1] < 4 * Ts:
        return
    h = taps(stage, Ts)
    p = pinned_pole(stage)
    k = np.arange(h.size)
    assert abs(h @ np.exp(-p * Ts * k) - smoother_transfer(stage, p)) <= 1e-12
    assert h.sum() == pytest.approx(1.0, abs=1e-13)
    q, T = smoother_kernel(stage)
    moment = T * (np.polynomial.Polynomial(q) * np.polynomial.Polynomial([0.5, 1.0])).integ()
    assert h @ k * Ts == pytest.approx(moment(0.5) - moment(-0.5), rel=1e-11)


@pytest.mark.parametrize("kind", INPUT_SMOOTHERS)
def test_input_smoother_float_follows_double(kind):
    stage = sms.input_smoother(kind, wn=2 * math.pi * 45.0, zeta=0.1)
    u = np.repeat(np.random.default_rng(3).normal(size=40), 25)
    yd = sms.Chain(stage, Ts=2e-4).process(u)
    yf = sms.Chain(stage, Ts=2e-4, precision="float").process(u)
    assert np.max(np.abs(yf - yd)) <= 1e-5 * np.max(np.abs(u)) * np.abs(taps(stage, 2e-4)).sum()
    np.testing.assert_allclose(taps(stage, 2e-4), input_smoother_taps(stage, Ts=2e-4),
                               rtol=0, atol=1e-12 * np.abs(input_smoother_taps(stage, Ts=2e-4)).max())


@pytest.mark.parametrize("make, parameter", [
    (lambda: sms.input_smoother("smooth_zv", wn=100.0, zeta=0.26), "zeta"),
    (lambda: sms.input_smoother("smooth_ei", wn=0.0), "wn"),
    (lambda: sms.input_smoother("zv", wn=100.0), "kind"),
    (lambda: Stage("smooth_mzv", wn=100.0, timing="paper"), "timing"),
    (lambda: sms.Chain(sms.input_smoother("smooth_zv", wn=2 * math.pi * 200), Ts=1e-3), "wn"),
    (lambda: sms.Chain(sms.input_smoother("smooth_si", wn=1e-9), Ts=1e-3), "wn"),
])
def test_input_smoother_refuses(make, parameter):
    with pytest.raises(ValueError, match=rf"^{parameter}"):
        make()


def test_input_smoother_alias_and_unread_zeta():
    assert sms.input_smoother("smooth_2hump_ei", wn=100.0).kind == "smooth_ei2"
    a = taps(sms.input_smoother("smooth_si", wn=300.0, zeta=0.0), 1e-3)
    b = taps(sms.input_smoother("smooth_si", wn=300.0, zeta=0.7), 1e-3)
    np.testing.assert_array_equal(a, b)


# ---------------------------------------------------------------- CLI and FMU

def test_cli_stage_syntax():
    s = parse_stage("impulses:amplitudes=[0.2, 0.5 0.3],times=[0,0.006,0.012],timing=paper")
    assert (s.amplitudes, s.times, s.timing) == ((0.2, 0.5, 0.3), (0.0, 0.006, 0.012), "paper")
    s = parse_stage("si:f=40,zeta=0.1,insensitivity=0.6")
    assert (s.kind, s.wn) == ("si", 2 * math.pi * 40) and (s.order, s.duration) == sms.si_design(
        insensitivity=0.6)
    assert parse_stage("smooth_2hump_ei:f=50").kind == "smooth_ei2"
    for bad in ("impulses:amplitudes=[0.5,0.5,times=[0,1]", "impulses:amplitudes=0.5",
                "impulses:amplitudes=[a,b],times=[0,1]", "si:wn=10,f=2",
                "si:f=40,insensitivity=0.5,order=5", "zv:f=40,insensitivity=0.5",
                "impulses:amplitudes=[1]],times=[0]"):
        with pytest.raises(ValueError, match=r"^stage"):
            parse_stage(bad)


def test_fmu_names_the_impulse_it_refuses(capfd):
    # fmpy's default logger (it prints; a logger= callback of simulate_fmu can crash a later
    # fmpy simulation in the same process once the call has failed)
    fmpy = pytest.importorskip("fmpy")
    import shutil
    from smoothshaper import fmi
    if shutil.which("cmake") is None:
        pytest.skip("cmake is needed to build the FMUs")
    path = fmi.build_fmus(fmu_build_dir())["SmoothShaper"]
    values = fmi.start_values([sms.impulse_shaper(amplitudes=[0.5, 0.5], times=[0.0, 0.01])],
                              Ts=1e-3)
    values["stage[0].time[1]"] = 0.0               # not above time[0]
    with pytest.raises(Exception):
        fmpy.simulate_fmu(str(path), start_values=values, stop_time=0.01, output_interval=1e-3,
                          validate=False)
    out = capfd.readouterr()
    assert "stage[0].time[1] = 0" in out.out + out.err


def test_tunable_chain_new_families():
    """TunableChain: an input smoother and an SI shaper retune and their state saved during the
    switch restores into another chain of the same capacity (the stages it reports are the
    saved ones, every SI field back); user-defined impulses run as built: a retune to or from
    them is refused naming ``stage``, their state restores from the chain's own stage."""
    Ts = 1e-3
    imp = sms.impulse_shaper(amplitudes=[0.3, 0.5, 0.2], times=[0.0, 0.0042, 0.0091])
    si_a = sms.shaper("si", wn=180.0, order=5, duration=1.4, tolerance=0.05)
    si_b = sms.shaper("si", wn=150.0, order=7, duration=2.2, tolerance=0.03)
    smooth_a = sms.input_smoother("smooth_mzv", wn=2 * np.pi * 40.0, zeta=0.1)
    smooth_b = sms.input_smoother("smooth_mzv", wn=2 * np.pi * 25.0, zeta=0.2)
    make = lambda: sms.TunableChain([smooth_a, imp, si_a], Ts=Ts,   # noqa: E731
                                    capacity=[smooth_b, None, si_b])
    chain = make()
    u = np.clip((np.arange(400) - 20) * 0.004, 0.0, 1.0)
    chain.process(u[:100])
    with pytest.raises(sms.ParameterError, match="impulses") as err:
        chain.retune(1, sms.shaper("zv", wn=200.0))
    assert err.value.parameter == "stage"
    with pytest.raises(sms.ParameterError, match="impulses") as err:
        chain.retune(0, imp)
    assert err.value.parameter == "stage" and chain.stages[0] == smooth_a
    chain.retune(0, smooth_b)
    chain.retune(2, si_b)
    chain.process(u[100:110])
    assert chain.switching == (True, False, True)
    state = chain.get_state()
    twin = make()
    twin.set_state(state)
    assert twin.stages == chain.stages == (smooth_b, imp, si_b)
    assert np.array_equal(twin.process(u[110:]), chain.process(u[110:]))
    assert twin.lag == chain.lag
