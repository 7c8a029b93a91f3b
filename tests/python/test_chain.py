# SPDX-License-Identifier: Apache-2.0
"""Chain (C-backed): construction errors, state handling, block/sample equivalence."""
import copy
import dataclasses
import gc
import math
import pickle

import numpy as np
import pytest

import smoothshaper as sms
from smoothshaper.filters import MAX_BUFFER_REALS, ParameterError

TS = 1e-3

# One valid stage of every kind, integer and non-integer T/Ts, both timings.
EXAMPLES = [
    sms.rectangular(T=0.02),
    sms.rectangular(T=0.0234),
    sms.rectangular(T=0.0234, timing="paper"),
    sms.harmonic(T=0.03),
    sms.harmonic(T=3 * math.pi / 100),
    sms.damped_harmonic(T=0.0377, sigma=-5.0),
    sms.exponential(T=0.05, sigma=-20.0),
    sms.exponential(T=0.0613, sigma=-20.0, k=2),
    sms.shaper("zv", wn=100.0, zeta=0.05),
    sms.shaper("zvd", wn=100.0, zeta=0.05),
    sms.shaper("zvdd", wn=150.0),
    sms.shaper("zvn", wn=120.0, zeta=0.1, order=4),
    sms.shaper("ei", wn=100.0, zeta=0.02, tolerance=0.05),
    sms.shaper("ei2", wn=100.0, zeta=0.02),
    sms.shaper("mzv", wn=100.0, zeta=0.05),
    sms.shaper("zv", wn=100.0, zeta=0.05, timing="paper"),
    sms.notch(wn=200.0, zeta=0.05, notch_pole_zeta=0.7, discretization="tustin"),
    sms.notch(wn=200.0, zeta=0.05, notch_pole_zeta=0.7),
]
IDS = [f"{s.kind}-{i}" for i, s in enumerate(EXAMPLES)]
RNG = np.random.default_rng(20261125)


def _signal(n, seed=0):
    rng = np.random.default_rng(seed)
    steps = np.repeat(rng.normal(0, 50, size=n // 25 + 1), 25)[:n]
    return steps + rng.normal(0, 1, size=n)


def _broken(stage, **fields):
    """A Stage carrying a value the Python validation would refuse, to reach the C checks."""
    stage = dataclasses.replace(stage)
    for name, value in fields.items():
        object.__setattr__(stage, name, value)
    return stage


# -- construction ---------------------------------------------------------------------------

@pytest.mark.parametrize("stage", EXAMPLES, ids=IDS)
def test_every_kind_builds_with_unit_dc_gain(stage):
    chain = sms.Chain(stage, Ts=TS)
    n = (chain.length if chain.is_fir else 0) + 3000
    y = chain.process(np.full(n, 2.5))
    assert y[-1] == pytest.approx(2.5, rel=1e-12)
    if chain.is_fir:
        h = chain.taps()
        assert h.size == chain.length
        assert h.sum() == pytest.approx(1.0, rel=1e-12)


@pytest.mark.parametrize("Ts", [0.0, -1e-3, math.nan, math.inf, "fast", None])
def test_bad_sample_period_names_Ts(Ts):
    with pytest.raises(ValueError, match=r"^Ts"):
        sms.Chain(sms.rectangular(T=0.02), Ts=Ts)


def test_Ts_is_keyword_only():
    with pytest.raises(TypeError):
        sms.Chain([sms.rectangular(T=0.02)], 1e-3)


@pytest.mark.parametrize("stage, Ts, parameter", [
    (sms.rectangular(T=0.0005), 1e-3, "T"),                         # T < Ts
    (sms.harmonic(T=0.0009), 1e-3, "T"),
    (sms.harmonic(T=0.0015), 1e-3, "T"),                            # harmonic needs N >= 2
    (sms.harmonic(T=0.0025), 1e-3, "T"),                            # pinned zero above pi/Ts
    (sms.rectangular(T=0.0051, k=3), 1e-3, "T"),
    (sms.shaper("zv", wn=4000.0), 1e-3, "wn"),                      # above pi/Ts = 3141.6
    (sms.notch(wn=3200.0), 1e-3, "wn"),
    (sms.rectangular(T=1e6), 1e-3, "T"),                            # delay line too long
    (sms.shaper("zv", wn=1e-9), 1e-3, "wn"),
    # Values the Python Stage refuses, forced through to check the C status mapping:
    (_broken(sms.rectangular(T=0.02), T=-1.0), 1e-3, "T"),
    (_broken(sms.exponential(T=0.02, sigma=-1.0), sigma=2.0), 1e-3, "sigma"),
    (_broken(sms.damped_harmonic(T=0.02, sigma=-1.0), sigma=math.nan), 1e-3, "sigma"),
    (_broken(sms.harmonic(T=0.03), k=2), 1e-3, "k"),
    (_broken(sms.rectangular(T=0.03), k=0), 1e-3, "k"),
    (_broken(sms.harmonic(T=0.03), k=2**40), 1e-3, "k"),
    (_broken(sms.shaper("zv", wn=100.0), zeta=1.0), 1e-3, "zeta"),
    (_broken(sms.shaper("zv", wn=100.0), wn=-5.0), 1e-3, "wn"),
    (_broken(sms.shaper("zvn", wn=100.0), order=9), 1e-3, "order"),
    (_broken(sms.shaper("zvn", wn=100.0), order=0), 1e-3, "order"),
    (_broken(sms.shaper("ei", wn=100.0), tolerance=1.5), 1e-3, "tolerance"),
    (_broken(sms.notch(wn=100.0, zeta=0.1), notch_pole_zeta=0.05), 1e-3, "notch_pole_zeta"),
])
def test_invalid_parameter_names_it(stage, Ts, parameter):
    with pytest.raises(ParameterError) as info:
        sms.Chain([sms.rectangular(T=0.01), stage], Ts=Ts)
    assert info.value.parameter == parameter
    assert str(info.value).startswith(parameter + " ")
    assert "stages[1]" in str(info.value)


def test_stage_constructors_name_the_parameter():
    for call, name in [(lambda: sms.rectangular(T=0), "T"),
                       (lambda: sms.exponential(T=1, sigma=1), "sigma"),
                       (lambda: sms.harmonic(T=1, k=2), "k"),
                       (lambda: sms.shaper("zv", wn=0), "wn"),
                       (lambda: sms.shaper("zv", wn=1, zeta=1), "zeta"),
                       (lambda: sms.shaper("zvn", wn=1, order=9), "order"),
                       (lambda: sms.shaper("ei", wn=1, tolerance=0), "tolerance"),
                       (lambda: sms.notch(wn=1, zeta=0.5, notch_pole_zeta=0.4), "notch_pole_zeta")]:
        with pytest.raises(ValueError, match=rf"^{name} "):
            call()


def test_delay_line_cap_is_far_above_real_use():
    # 2**28 samples at 1 kHz is 74 hours of delay: only nonsense durations hit the cap.
    assert MAX_BUFFER_REALS * 1e-3 > 24 * 3600


@pytest.mark.parametrize("stages", [[], [sms.rectangular(T=0.01)] * 17, "harmonic", [1.0]])
def test_bad_stage_list_names_stages(stages):
    with pytest.raises(ValueError, match=r"stages"):
        sms.Chain(stages, Ts=TS)


# -- state ----------------------------------------------------------------------------------

def _chain():
    return sms.Chain([sms.rectangular(T=0.0234), sms.harmonic(T=0.0311),
                      sms.shaper("zvd", wn=90.0, zeta=0.1),
                      sms.notch(wn=300.0, zeta=0.02)], Ts=TS)


def test_save_restore_continues_bit_exactly():
    u = _signal(900, seed=1)
    a = _chain()
    a.process(u[:417])
    saved = a.get_state()
    tail_a = a.process(u[417:])
    b = _chain()
    b.process(_signal(100, seed=9))           # some other history, then overwritten
    b.set_state(saved)
    np.testing.assert_array_equal(b.process(u[417:]), tail_a)
    a.state = saved                            # property form, back in time on the same chain
    np.testing.assert_array_equal(a.process(u[417:]), tail_a)


def test_state_is_a_float64_copy():
    chain = _chain()
    s = chain.state
    assert s.dtype == np.float64 and s.ndim == 1 and s.size == chain.state_size
    s[:] = 1e300                               # writing to the copy changes nothing
    np.testing.assert_array_equal(chain.state, _chain().state)


@pytest.mark.parametrize("bad", [
    np.zeros(3), "state", [[0.0]], None,
])
def test_wrong_state_names_state_and_changes_nothing(bad):
    chain = _chain()
    chain.process(_signal(300, seed=2))
    before = chain.get_state()
    with pytest.raises(ParameterError, match=r"^state") as info:
        chain.set_state(bad)
    assert info.value.parameter == "state"
    np.testing.assert_array_equal(chain.get_state(), before)


def test_state_from_another_chain_is_rejected_untouched():
    chain = _chain()
    chain.process(_signal(300, seed=3))
    before = chain.get_state()
    bad = before.copy()
    bad[-1] = math.nan
    with pytest.raises(ParameterError, match=r"^state"):
        chain.set_state(bad)
    np.testing.assert_array_equal(chain.get_state(), before)


def test_state_with_out_of_range_index_is_rejected_untouched():
    # Every entry replaced by a huge value: any ring index or counter in it is out of range.
    chain = _chain()
    chain.process(_signal(300, seed=4))
    before = chain.get_state()
    with pytest.raises(ParameterError, match=r"^state"):
        chain.set_state(np.full(before.size, 1e30))
    np.testing.assert_array_equal(chain.get_state(), before)


def test_bad_samples_leave_the_state_untouched():
    chain = _chain()
    chain.process(_signal(200, seed=5))
    before = chain.get_state()
    for bad in ([1.0, math.nan], [math.inf], np.ones((2, 2))):
        with pytest.raises(ValueError, match=r"^u "):
            chain.process(bad)
    for bad in (math.nan, "x", math.inf):
        with pytest.raises(ValueError, match=r"^x "):
            chain.step(bad)
    with pytest.raises(ValueError, match=r"^rest "):
        chain.reset(math.nan)
    np.testing.assert_array_equal(chain.get_state(), before)


def test_reset_puts_the_chain_at_rest():
    chain = _chain()
    chain.process(_signal(200, seed=6))
    chain.reset(3.25)
    y = chain.process(np.full(500, 3.25))
    np.testing.assert_allclose(y, 3.25, rtol=1e-12)


@pytest.mark.parametrize("duplicate", [lambda c: c.copy(), copy.copy, copy.deepcopy,
                                       lambda c: pickle.loads(pickle.dumps(c))],
                         ids=["copy", "copy.copy", "deepcopy", "pickle"])
def test_copies_are_independent_and_identical(duplicate):
    chain = _chain()
    chain.process(_signal(250, seed=7))
    twin = duplicate(chain)
    assert twin._memory is not chain._memory
    u = _signal(300, seed=8)
    np.testing.assert_array_equal(twin.process(u), chain.process(u))


def test_copy_owns_its_memory():
    """copy() duplicates the C instances and delay lines and points the copy at its own:
    it keeps filtering right after the original and its buffers are gone."""
    u = _signal(400, seed=9)
    reference = _chain()
    reference.process(u[:200])
    expected = reference.process(u[200:])
    chain = _chain()
    chain.process(u[:200])
    twin = chain.copy()
    assert twin._stage_mem != chain._stage_mem
    del chain
    gc.collect()
    junk = [np.random.default_rng(i).normal(size=10000) for i in range(20)]  # reuse freed memory
    np.testing.assert_array_equal(twin.process(u[200:]), expected)
    del junk


# -- processing -----------------------------------------------------------------------------

def test_split_blocks_and_steps_equal_one_shot():
    u = _signal(1200, seed=10)
    whole = _chain().process(u)
    chain = _chain()
    cuts = [0, 1, 2, 77, 78, 500, 1199, 1200]
    parts = [chain.process(u[a:b]) for a, b in zip(cuts[:-1], cuts[1:])]
    np.testing.assert_array_equal(np.concatenate(parts), whole)
    chain = _chain()
    np.testing.assert_array_equal([chain.step(v) for v in u], whole)


def test_process_accepts_any_array_like_and_does_not_modify_it():
    chain = _chain()
    u = _signal(64, seed=11)
    strided = np.repeat(u, 2)[::2]             # non-contiguous view
    assert not strided.flags.c_contiguous
    keep = strided.copy()
    y1 = chain.process(strided)
    np.testing.assert_array_equal(strided, keep)
    y2 = _chain().process(list(u))
    np.testing.assert_array_equal(y1, y2)
    assert y1.dtype == np.float64
    assert chain.process([]).shape == (0,)
    ints = _chain().process(np.arange(10))
    np.testing.assert_array_equal(ints, _chain().process(np.arange(10.0)))


def test_buffers_stay_alive_with_the_chain():
    expected = _chain().process(_signal(100, seed=12))
    chain = _chain()                           # only the Chain object refers to its buffers
    gc.collect()
    junk = [np.random.default_rng(i).normal(size=10000) for i in range(20)]  # reuse freed memory
    np.testing.assert_array_equal(chain.process(_signal(100, seed=12)), expected)
    del junk


def test_impulse_response_does_not_touch_the_state():
    chain = _chain()
    chain.process(_signal(150, seed=13))
    before = chain.get_state()
    h = chain.impulse_response(400)
    assert h.shape == (400,)
    np.testing.assert_array_equal(chain.get_state(), before)
    with pytest.raises(ValueError, match="n is required"):
        chain.impulse_response()
    with pytest.raises(ValueError, match="IIR"):
        chain.taps()
    with pytest.raises(ValueError, match=r"^n "):
        chain.impulse_response(0)


def test_float_precision_module_tracks_double():
    stages = [sms.rectangular(T=0.0234), sms.harmonic(T=0.0311), sms.shaper("zv", wn=90.0)]
    u = _signal(2000, seed=14)
    yd = sms.Chain(stages, Ts=TS).process(u)
    yf = sms.Chain(stages, Ts=TS, precision="float").process(u)
    assert np.max(np.abs(yf - yd)) <= 1e-5 * np.max(np.abs(u))
    with pytest.raises(ValueError, match="precision"):
        sms.Chain(stages, Ts=TS, precision="half")
    with pytest.raises(ValueError, match=r"^u "):
        sms.Chain(stages, Ts=TS, precision="float").process([1e39])


# -- C design and identification ------------------------------------------------------------

@pytest.mark.parametrize("kind", [k for k in sms.KINDS if k != "impulses"])
def test_c_design_for_mode_equals_python_for_mode(kind):
    c = sms.design_for_mode(kind, wn=123.0, zeta=0.07)
    py = sms.for_mode(kind, wn=123.0, zeta=0.07)
    assert c.kind == py.kind
    for field in ("T", "sigma", "wn", "zeta"):
        assert getattr(c, field) == pytest.approx(getattr(py, field), rel=1e-14, abs=0.0), field


@pytest.mark.parametrize("kwargs, parameter", [
    (dict(kind="zv", wn=-1.0), "wn"), (dict(kind="zv", wn=math.nan), "wn"),
    (dict(kind="zv", wn=10.0, zeta=1.0), "zeta"), (dict(kind="harmonic", wn=10.0, k=2), "k"),
    (dict(kind="rectangular", wn=10.0, k=0), "k"), (dict(kind="zv", wn=10.0, k=3), "k"),
])
def test_c_design_errors_name_the_parameter(kwargs, parameter):
    with pytest.raises(ValueError, match=rf"^{parameter}"):
        sms.design_for_mode(**kwargs)


def test_user_impulses_have_no_mode_to_design_for():
    for design in (sms.design_for_mode, sms.for_mode):
        with pytest.raises(ValueError, match=r"^kind"):
            design("impulses", wn=100.0)


def test_identify_from_peaks_matches_the_formula():
    m = sms.identify_from_peaks(t1=0.1, p1=2.0, t2=0.15, p2=1.5)
    assert m.wd == pytest.approx(2 * math.pi / 0.05, rel=1e-14)
    assert m.sigma == pytest.approx(math.log(0.75) / 0.05, rel=1e-14)
    assert m.zeta == pytest.approx(-m.sigma / m.wn, rel=1e-12)
    assert m.wn == pytest.approx(math.hypot(m.wd, m.sigma), rel=1e-12)
    with pytest.raises(ValueError, match=r"^t2"):
        sms.identify_from_peaks(t1=0.2, p1=2.0, t2=0.1, p2=1.5)
    with pytest.raises(ValueError, match=r"^p2"):
        sms.identify_from_peaks(t1=0.1, p1=1.0, t2=0.2, p2=1.5)


def test_identify_from_record_recovers_a_sampled_decay():
    wn, zeta, Ts = 80.0, 0.04, 1e-3
    wd = wn * math.sqrt(1 - zeta**2)
    t = np.arange(1500) * Ts
    x = 0.7 * np.exp(-zeta * wn * t) * np.cos(wd * t + 0.3)
    m = sms.identify_from_record(x, Ts=Ts)
    assert m.wn == pytest.approx(wn, rel=1e-6)
    assert m.zeta == pytest.approx(zeta, rel=1e-5)
    with pytest.raises(ValueError, match=r"^Ts"):
        sms.identify_from_record(x, Ts=0)
    with pytest.raises(ValueError, match=r"^x"):
        sms.identify_from_record(x[:3], Ts=Ts)


def test_notch_bandwidth_helper():
    xi2 = sms.notch_pole_zeta_from_bandwidth(wn=200.0, zeta=0.0, bandwidth=40.0)
    # Undamped-zero notch: the -3 dB band of (s^2+wn^2)/(s^2+2 xi2 wn s+wn^2) is 2 xi2 wn wide.
    assert xi2 == pytest.approx(40.0 / (2 * 200.0), rel=1e-9)
    with pytest.raises(ValueError, match=r"^bandwidth"):
        sms.notch_pole_zeta_from_bandwidth(wn=200.0, bandwidth=-1.0)
