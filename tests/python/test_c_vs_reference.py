# SPDX-License-Identifier: Apache-2.0
"""The C core (through Chain) against the independent NumPy reference, on random stages,
chains and inputs.

Error measure: both implement y = h * u per stage (notches: the same biquad), so with
G = prod over stages of sum_i |h_stage[i]| (the l1 norm of each impulse response, the
infinity-norm gain of the stage) every output is bounded by G max|u|, and the rounding error
of either implementation is a small multiple of eps * (window length) * G max|u|. The
contract (docs/numerics.md, docs/exact-mode.md) is 1e-12 of that scale in double. The float module
rounds the input and every operation to float32 (eps 6e-8); docs/numerics.md's float target is
1e-5 of the same scale, which is what FLOAT_REL_TOL asserts for FIR stages. A notch is an IIR
biquad whose float32 coefficients move its poles by about eps/(wn Ts), relative to their
distance xi2 wn Ts from the unit circle: a relative response error up to
eps / (xi2 (wn Ts)^2) (first-order coefficient sensitivity), added per notch with a factor 4.
"""
import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import smoothshaper as sms
from smoothshaper import reference
from smoothshaper.stages import INPUT_SMOOTHERS, NOTCHES, SHAPERS, SMOOTHERS

DOUBLE_REL_TOL = 1e-12
FLOAT_REL_TOL = 1e-5
EPS32 = float(np.finfo(np.float32).eps)
# The core acceptance check: more examples than the suite default (about 5 s in all).
MANY = settings(max_examples=max(300, settings.default.max_examples))
NOTCH_TAIL = 20000          # samples of a notch's impulse response used for its l1 norm


@st.composite
def sample_periods(draw):
    return draw(st.sampled_from([1e-3, 5e-4, 2e-4, 1e-4, 2.5e-3]))


@st.composite
def smoother_stages(draw, Ts):
    kind = draw(st.sampled_from(SMOOTHERS))
    harmonic = "harmonic" in kind
    k = draw(st.sampled_from([1, 3] if harmonic else [1, 2, 3]))
    timing = draw(st.sampled_from(["exact", "paper"] if harmonic else ["exact", "paper", "bounded"]))
    if draw(st.booleans()):
        # On the grid; one sample of sin(pi t/T) is 0, so the harmonic families need N >= 2.
        nu = float(draw(st.integers(2 if harmonic else 1, 250)))
    else:
        # Off the grid, exact timing pins the zero w* = k 3pi/T (harmonic) or k 2pi/T, which
        # must lie below Nyquist: T/Ts > 3k or 2k (config.h).
        nu = draw(st.floats((3 if harmonic else 2) * k + 0.01, 250.0))
    T = nu * Ts
    fields = dict(T=T, k=k, timing=timing)
    if kind in ("damped_harmonic", "exponential"):
        fields["sigma"] = -draw(st.floats(0.0, 4.0)) / T
    return sms.Stage(kind, **fields)


@st.composite
def shaper_stages(draw, Ts):
    kind = draw(st.sampled_from(SHAPERS))
    zeta = draw(st.floats(0.0, 0.3))
    Td = draw(st.floats(3.0, 100.0)) * Ts           # damped period: 3 to 100 samples
    wn = 2 * math.pi / Td / math.sqrt(1 - zeta * zeta)
    fields = dict(wn=wn, zeta=zeta, timing=draw(st.sampled_from(["exact", "paper"])))
    if kind == "zvn":
        fields["order"] = draw(st.integers(1, 5))
    if kind in ("ei", "ei2", "ei3"):
        fields["tolerance"] = draw(st.floats(0.01, 0.2))
    if kind == "gmzv":
        fields["order"] = n = draw(st.integers(3, 9))
        # least squares: C (Householder) and NumPy agree to cond(M) eps; cond(M) < 600 here,
        # it grows to 1e12 as the duration approaches its limit (n - 1)/2
        fields["duration"] = draw(st.floats(0.55, max(0.6, 0.3 * (n - 1))))
    if kind == "si":
        fields["order"] = n = draw(st.sampled_from([3, 5, 7, 9]))
        fields["duration"] = draw(st.floats(0.25 * (n - 1), 0.5 * (n - 1)))
        fields["tolerance"] = draw(st.floats(0.01, 0.5))
    if kind == "impulses":
        n = draw(st.integers(1, 9))
        gaps = draw(st.lists(st.floats(0.05, 40.0), min_size=n, max_size=n))
        return sms.Stage(kind, amplitudes=draw(st.lists(st.floats(0.05, 2.0), min_size=n,
                                                        max_size=n)),
                         times=list(np.cumsum(gaps) * Ts - gaps[0] * Ts * draw(st.booleans())),
                         timing=fields["timing"])
    return sms.Stage(kind, **fields)


@st.composite
def input_smoother_stages(draw, Ts):
    kind = draw(st.sampled_from(INPUT_SMOOTHERS))
    zeta = draw(st.floats(0.0, 0.25))
    # the kernel spans 0.66 to 1.5 design periods and must span 4 samples: periods of 7 to 100
    wn = 2 * math.pi / (draw(st.floats(7.0, 100.0)) * Ts)
    return sms.input_smoother(kind, wn=wn, zeta=zeta)


@st.composite
def notch_stages(draw, Ts):
    kind = draw(st.sampled_from(NOTCHES))
    wn = draw(st.floats(0.01, 0.8)) * math.pi / Ts
    zeta = draw(st.floats(0.0, 0.3))
    return sms.Stage(kind, wn=wn, zeta=zeta, notch_pole_zeta=zeta + draw(st.floats(0.05, 1.5)))


@st.composite
def any_stage(draw, Ts):
    family = draw(st.sampled_from(["smoother", "smoother", "shaper", "notch", "input smoother"]))
    strategy = {"smoother": smoother_stages, "shaper": shaper_stages, "notch": notch_stages,
                "input smoother": input_smoother_stages}
    return draw(strategy[family](Ts))


@st.composite
def chains(draw, min_stages=1, max_stages=4):
    Ts = draw(sample_periods())
    n = draw(st.integers(min_stages, max_stages))
    return Ts, [draw(any_stage(Ts)) for _ in range(n)]


def _signal(seed: int, n: int) -> np.ndarray:
    """Steps of random heights over several decades plus noise: exercises every recursion."""
    rng = np.random.default_rng(seed)
    scale = 10.0 ** rng.uniform(-3, 3)
    hold = int(rng.integers(1, 60))
    steps = np.repeat(rng.normal(0, scale, size=n // hold + 1), hold)[:n]
    return steps + rng.normal(0, scale * rng.uniform(0, 0.1), size=n)


def _gain_bound(stages, Ts) -> float:
    g = 1.0
    for s in stages:
        length = NOTCH_TAIL if s.kind in NOTCHES else None
        g *= float(np.sum(np.abs(reference.impulse_response(s, Ts=Ts, length=length))))
    return g


def float_tolerance(stages, Ts) -> float:
    """FLOAT_REL_TOL plus the coefficient-sensitivity term of each notch (module docstring)."""
    return FLOAT_REL_TOL + sum(4 * EPS32 / (s.notch_pole_zeta * (s.wn * Ts) ** 2)
                               for s in stages if s.kind in NOTCHES)


def _assert_close(y, y_ref, u, stages, Ts, rel):
    scale = max(float(np.max(np.abs(u))), 1e-300) * _gain_bound(stages, Ts)
    err = float(np.max(np.abs(y - y_ref))) if y.size else 0.0
    assert err <= rel * scale, f"max error {err:.3g} > {rel:g} * {scale:.3g}"


def _every_kind():
    """One stage of each kind, on and off the sample grid, every timing."""
    out = []
    for kind in SMOOTHERS:
        cases = [(0.040, "exact"), (0.0437, "exact"), (0.0437, "paper")]
        if "harmonic" not in kind:
            cases += [(0.040, "bounded"), (0.0437, "bounded")]
        for T, timing in cases:
            sigma = -25.0 if kind in ("damped_harmonic", "exponential") else 0.0
            out.append(sms.Stage(kind, T=T, sigma=sigma, timing=timing))
    for kind in SHAPERS:
        for timing in ("exact", "paper"):
            if kind == "impulses":      # a firmware shaper pasted: ZVD at 57 Hz, off the grid
                out.append(sms.impulse_shaper(amplitudes=[0.25, 0.5, 0.25],
                                              times=[0.0, 0.00877, 0.01754], timing=timing))
                continue
            out.append(sms.Stage(kind, wn=71.3, zeta=0.08, order=3, timing=timing))
    out += [sms.input_smoother(kind, wn=71.3, zeta=0.08) for kind in INPUT_SMOOTHERS]
    out += [sms.Stage(kind, wn=210.0, zeta=0.03, notch_pole_zeta=0.4) for kind in NOTCHES]
    return out


@pytest.mark.parametrize("stage", _every_kind(), ids=lambda s: f"{s.kind}-{s.timing}-{s.T:g}")
@pytest.mark.parametrize("precision", ["double", "float"])
def test_every_kind_matches_reference(stage, precision):
    Ts = 1e-3
    u = _signal(7, 1500)
    y = sms.Chain(stage, Ts=Ts, precision=precision).process(u)
    tol = DOUBLE_REL_TOL if precision == "double" else float_tolerance([stage], Ts)
    _assert_close(y, reference.filter([stage], u, Ts=Ts), u, [stage], Ts, tol)


@MANY
@given(data=st.data())
def test_single_stage_of_every_family_matches_reference(data):
    Ts = data.draw(sample_periods())
    stage = data.draw(st.one_of(smoother_stages(Ts), shaper_stages(Ts), notch_stages(Ts),
                                input_smoother_stages(Ts)))
    chain = sms.Chain(stage, Ts=Ts)
    u = _signal(data.draw(st.integers(0, 2**32 - 1)),
                data.draw(st.integers(1, 3 * chain.length + 200)))
    _assert_close(chain.process(u), reference.filter([stage], u, Ts=Ts), u, [stage], Ts,
                  DOUBLE_REL_TOL)


@MANY
@given(data=st.data(), spec=chains(2, 4))
def test_random_chains_match_reference(data, spec):
    Ts, stages = spec
    chain = sms.Chain(stages, Ts=Ts)
    u = _signal(data.draw(st.integers(0, 2**32 - 1)),
                data.draw(st.integers(1, 2 * chain.length + 200)))
    _assert_close(chain.process(u), reference.filter(stages, u, Ts=Ts), u, stages, Ts,
                  DOUBLE_REL_TOL)


@MANY
@given(data=st.data(), spec=chains(1, 3))
def test_impulse_response_matches_reference_taps(data, spec):
    Ts, stages = spec
    chain = sms.Chain(stages, Ts=Ts)
    n = chain.length + 50
    impulse = np.zeros(n)
    impulse[0] = 1.0
    _assert_close(chain.impulse_response(n), reference.filter(stages, impulse, Ts=Ts), impulse,
                  stages, Ts, DOUBLE_REL_TOL)


@MANY
@given(data=st.data(), spec=chains(1, 4))
def test_split_processing_equals_one_shot(data, spec):
    Ts, stages = spec
    u = _signal(data.draw(st.integers(0, 2**32 - 1)), data.draw(st.integers(0, 1500)))
    whole = sms.Chain(stages, Ts=Ts).process(u)
    cuts = sorted(data.draw(st.lists(st.integers(0, u.size), max_size=6)))
    chain = sms.Chain(stages, Ts=Ts)
    parts = [chain.process(u[a:b]) for a, b in zip([0] + cuts, cuts + [u.size])]
    np.testing.assert_array_equal(np.concatenate(parts), whole)


@MANY
@given(data=st.data(), spec=chains(1, 4))
def test_state_save_restore_continues_bit_exactly(data, spec):
    Ts, stages = spec
    u = _signal(data.draw(st.integers(0, 2**32 - 1)), data.draw(st.integers(2, 1500)))
    cut = data.draw(st.integers(1, u.size - 1))
    a = sms.Chain(stages, Ts=Ts)
    a.process(u[:cut])
    saved = a.get_state()
    expected = a.process(u[cut:])
    b = sms.Chain(stages, Ts=Ts)
    b.set_state(saved)
    np.testing.assert_array_equal(b.process(u[cut:]), expected)


@MANY
@given(data=st.data(), spec=chains(1, 3))
def test_float_module_matches_reference_within_float_bound(data, spec):
    Ts, stages = spec
    chain = sms.Chain(stages, Ts=Ts, precision="float")
    u = _signal(data.draw(st.integers(0, 2**32 - 1)),
                data.draw(st.integers(1, 2 * chain.length + 200)))
    _assert_close(chain.process(u), reference.filter(stages, u, Ts=Ts), u, stages, Ts,
                  float_tolerance(stages, Ts))


@MANY
@given(data=st.data(), spec=chains(1, 3))
def test_reset_to_rest_matches_reference_rest_state(data, spec):
    Ts, stages = spec
    x0 = data.draw(st.floats(-1e3, 1e3))
    chain = sms.Chain(stages, Ts=Ts)
    chain.reset(x0)
    u = _signal(data.draw(st.integers(0, 2**32 - 1)), data.draw(st.integers(1, 800)))
    y_ref, _ = reference.filter(stages, u, Ts=Ts, zi=reference.filter_zi(stages, Ts=Ts, x0=x0))
    scale_u = np.concatenate([u, [x0]])
    _assert_close(chain.process(u), y_ref, scale_u, stages, Ts, DOUBLE_REL_TOL)
